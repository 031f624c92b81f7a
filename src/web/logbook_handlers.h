// Internal to web/: the climbers' logbook (issue 23; docs/web.md,
// "Logbook"): the tick API, the setters' review of held ticks, the logbook
// page and the blocks the route pages show. Bound to paths in server.cc.
#ifndef SB_WEB_LOGBOOK_HANDLERS_H_
#define SB_WEB_LOGBOOK_HANDLERS_H_

#include <nlohmann/json.hpp>
#include <string>

#include "app/logbook.h"
#include "app/types.h"
#include "web/handlers.h"

namespace sb::web {

void PostTick(Exchange& x);           // POST /api/routes/{id}/ticks
void GetRouteTicks(Exchange& x);      // GET /api/routes/{id}/ticks (setters)
void PostTickAccept(Exchange& x);     // POST /api/routes/{id}/ticks/{tick}/accept (setters)
void PostTickDiscard(Exchange& x);    // POST /api/routes/{id}/ticks/{tick}/discard (setters)
void GetRouteAscent(Exchange& x);     // GET /api/routes/{id}/ascent
void GetLogbook(Exchange& x);         // GET /api/logbook
void PageLogbook(Exchange& x);        // GET /logbook

// The ascent grade of a route (value, 80% interval, ticks) as HTML, for the
// route and variation pages ("" when it cannot be made; logged).
std::string AscentBlock(Exchange& x, const app::RouteView& route);
// The tick form of /r/{id} (with the ascent grade and, for the route's
// setters, its held ticks with accept/discard), placed before the survey.
std::string TickBlock(Exchange& x, const app::RouteView& route);
// The ascent grade as JSON: ticks, fitted, discipline and, when fitted,
// value, lo, hi (80%), grade, lo_grade, hi_grade, verdict, felt_votes,
// felt_median.
nlohmann::json AscentGradeJson(const app::AscentGrade& a);
// The ascent grade in words (HTML, escaped): "<strong>V4</strong> (80%: V3
// to V5) from 6 ticks", the felt median and the soft/sandbagged tag; with
// `with_ids` the elements carry the route page's ids (one per page).
// `lang`: the page's language (web/i18n.h).
std::string AscentText(const app::AscentGrade& a, bool with_ids, std::string_view lang = "en");
// A table cell (<td class="ascent">, data-ticks/value/lo/hi/verdict) with
// AscentText, for the wall pages and the report.
std::string AscentCell(const app::AscentGrade& a, std::string_view lang = "en");
// After a sign-in as `user_id`: moves the device cookie's ticks into the
// climber's logbook (failures are logged, never fail the sign-in).
void MergeDeviceTicks(Exchange& x, int64_t user_id);

}  // namespace sb::web

#endif  // SB_WEB_LOGBOOK_HANDLERS_H_
