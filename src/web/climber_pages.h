// Server-rendered pages of the climbers' side (issues 14 and 15): the
// feedback page behind every route card's QR code, the setter's view of a
// route's feedback and of their grade drift, and the study pages. Every
// piece of user text is escaped; numbers of the results page carry their
// exact value (data-v) and the JSON path of `study analyze --format json`
// (data-k). Pure; thread-safe.
#ifndef SB_WEB_CLIMBER_PAGES_H_
#define SB_WEB_CLIMBER_PAGES_H_

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "app/climber_feedback.h"
#include "app/studies_service.h"
#include "app/types.h"
#include "web/pages.h"

namespace sb::web {

// "/r/{id}": the questionnaire, felt grade and comment for one route or
// variation (the climber's earlier answers filled in), with the setter's
// grade, the climbers' consensus and the drift flag. `owner` adds links to
// the setter's views.
// `min_votes_shown` explains a withheld consensus. `tick_block` (HTML, the
// logbook's tick form, issue 23) comes before the survey.
std::string FeedbackPageHtml(const PageViewer& v, const app::FeedbackPage& page, bool owner,
                             int min_votes_shown, const std::string& tick_block = "");
// "/r/{id}/responses": the route owner's view of its feedback.
std::string SetterFeedbackHtml(const PageViewer& v, const app::SetterView& view,
                               int min_votes_shown);
// The block the route and variation pages show: the setter's grade, the
// climbers' consensus, the drift flag and the links to /r/{id} (and, for
// the owner, to the answers and the drift report).
std::string ConsensusHtml(const app::GradeSummary& grade, int64_t route_id, bool owner,
                          int min_votes_shown, std::string_view lang = "en");
// "/drift": a setter's grades against the climbers' consensus, per route.
std::string DriftPageHtml(const PageViewer& v, const app::DriftReport& report);
// "/studies": the viewer's studies (or a log-in prompt).
std::string StudiesPageHtml(const PageViewer& v, const std::vector<app::Study>& studies);
// "/studies/new" and "/studies/{id}/edit": the study editor over the routes
// the viewer can see; `study` = nullopt for a new one. `routes` is the first
// page of `total` (the page's search box and "More routes" fetch the rest
// from /api/routes); each route shows its gym (`gym_names`), wall, setter
// and date so routes sharing a name can be told apart.
std::string StudyEditorHtml(const PageViewer& v, const std::vector<app::RouteView>& routes,
                            const std::optional<app::Study>& study, int64_t total = -1,
                            const std::map<int64_t, std::string>& gym_names = {});
// "/s/{id}": the climbers' one-page response under neutral labels.
std::string StudyFormHtml(const PageViewer& v, const app::StudyForm& form);
// "/studies/{id}": the owner's results. `drop`/`censor` echo the censoring
// asked for; `error` explains a refused one ("" when none).
std::string StudyResultsHtml(const PageViewer& v, const app::StudyResults& results,
                             const std::string& drop, bool censor, const std::string& error);

}  // namespace sb::web

#endif  // SB_WEB_CLIMBER_PAGES_H_
