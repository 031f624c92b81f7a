// Server-rendered HTML pages of the web app. Each returns a complete HTML
// document; every piece of user text is escaped. Pure; thread-safe.
#ifndef SB_WEB_PAGES_H_
#define SB_WEB_PAGES_H_

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "app/gyms.h"
#include "app/routes.h"
#include "app/types.h"
#include "plan/card.h"
#include "plan/plan.h"
#include "web/i18n.h"

namespace sb::web {

// Who is looking: a logged-in user (with the session's CSRF token, put in a
// <meta> tag for the scripts) or nobody.
struct PageViewer {
  bool logged_in = false;
  int64_t user_id = 0;
  std::string username;
  std::string csrf;
  // A head setter or setter of some gym (issue 31): the setters' navigation
  // (New route, Vary, Studies, Drift, Import) is theirs; climbers, accounts in
  // no gym and visitors do not see it.
  bool setter = false;
  // The page's language (issue 32, web/i18n.h): "en", "de" or "fr" — the
  // account's, else the browser's Accept-Language, else the gym's default.
  std::string lang = "en";
  // Issue 31: the viewer's gyms and the one their pages write to (0: none).
  // A member of two or more gyms gets the header's gym switcher; every page
  // carries the gym in <meta name="sb-gym"> for the scripts' writes.
  std::vector<app::Gym> gyms;
  int64_t gym = 0;
  // The gym the page belongs to (0: none; then `gym` too): the switcher goes
  // to the chosen gym's same page (a gym's page, else its gym page).
  int64_t page_gym = 0;
};

// "/": one page of the route list (server-side search, filters, sort and
// paging; `query` is echoed into the form and the paging links).
std::string RouteListPage(const PageViewer& v, const app::RoutePage& page,
                          const app::RouteQuery& query);
// "/login" or (signup) "/signup": the account form.
std::string LoginPage(const PageViewer& v, bool signup);
// What the route form offers (issue 31): the gym the route is (to be) in
// when the viewer sets in it, its walls (each with the scale it reads grades
// in: `wall_scales`, wall id -> scale name; `scale_labels`, a gym scale's
// name -> its labels), circuits and members. Empty without a gym: the form
// of a personal route (name, grade, colour, setters, moves).
struct RouteFormData {
  std::optional<app::Gym> gym;
  std::vector<app::Wall> walls;
  std::map<int64_t, std::string> wall_scales;
  std::map<std::string, std::vector<std::string>> scale_labels;
  std::vector<app::Circuit> circuits;
  std::vector<app::Member> members;
  // A new route's wall chosen beforehand (issue 31: "/routes/new?wall=" from
  // a wall page); nullopt: none.
  std::optional<int64_t> wall;
};
// "/routes/new" and "/routes/{id}/edit" (`route` = nullopt for a new route):
// the route form (name, wall, grade, circuit/colour, setters, state, date,
// notes, moves one per line with the grammar's reading beside each) and the
// CRDL text as the advanced view, kept in sync by app.js; both post to
// /api/routes with `form`'s gym.
std::string EditorPage(const PageViewer& v, const std::optional<app::RouteView>& route,
                       const RouteFormData& form = {});
// "/routes/{id}". `can_change` = the viewer may edit and delete it (the
// ownership rule, app::IsOwner). `readings[i]` = how the grammar read move i
// ("" when it does not parse; an empty vector when the grammar is not
// available). Crux moves are marked.
// `discipline` describes the route's discipline ("bouldering (from its wall)").
std::string RoutePage(const PageViewer& v, const app::RouteView& route, bool can_change,
                      const std::vector<std::string>& readings = {},
                      const std::string& discipline = "");
// "/vary": `chosen` = the routes named in the URL, in that order (always
// shown and chosen); `missing` = ids named there the viewer cannot see;
// `found` = the first page of the picker's search for `find`.
std::string VaryPage(const PageViewer& v, const std::vector<app::RouteView>& chosen,
                     const std::vector<int64_t>& missing, const app::RoutePage& found,
                     const std::string& find);
// "/variations/{id}": the route plan (crux moves marked). `smoothing_note`
// explains missing smoothing ("" when none is needed).
// The page is the route card when printed (plan/card.h: same rows, marks,
// legend and parameters as the server PDF and SVG; `card.url` for the QR).
// `can_change`: the viewer may edit it (app::Routes::CanChange): "Edit".
std::string PlanPage(const PageViewer& v, const app::RouteView& record, const plan::RoutePlan& plan,
                     const std::string& smoothing_note, const plan::CardInfo& card,
                     bool can_change = false);
// "/import": CRDL and CSV import, CSV export links.
std::string ImportPage(const PageViewer& v);
// The page frame every page shares (head, navigation, footer) around
// `body` (HTML, not escaped); `title` is escaped. For the pages of other
// files (climber_pages.cc).
std::string PageLayout(const PageViewer& v, const std::string& title, const std::string& body,
                       const std::string& page_class = "");
// A colour as pages show it (issue 32): a swatch and its name
// (plan::ColourLabel), escaped; a colour no table knows is its name only
// (no empty box); "" for "".
// `lang`: the page's language (a known single colour word and a hex code's
// nearest name in it, web/i18n.h ColourLabelIn).
std::string ColourHtml(const std::string& colour, std::string_view lang = "en");
// A route state's words on every page (issue 31, one place): "draft",
// "planned", "on the wall", "stripped (archive)", in `lang`; any other text
// as it is.
std::string StateLabel(std::string_view lang, std::string_view state);
// An error page for `status` with a message (escaped).
std::string ErrorPage(const PageViewer& v, int status, const std::string& message);

}  // namespace sb::web

#endif  // SB_WEB_PAGES_H_
