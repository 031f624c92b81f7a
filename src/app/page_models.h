// What the gym's pages show (issue 31, "move page models into app so
// handlers only decode and render"): one call per page returns its content
// already permission-checked (the services' rules: Gyms::Get, GetWall,
// Routes::Search's visibility, Routes::CanChange), costed and admitted by the
// work budget before the work (issue 34: the cost is counted first through
// app::ReadCosts and charged to app::Services::renders), and, where a page
// is kept (app::RenderCache), read from or kept in the cache at the gym's
// stamp. The web layer decodes the request, calls one function and renders
// the model; the kept parts are rendered through a callback the web layer
// gives, so what is kept (and when it is dropped) is decided here.
//
//   int retry = 0;
//   Result<app::WallPageModel> m = app::WallPage(services, viewer, id, lang, RenderTables, &retry);
//   if (!m.ok()) ... 404 / 429 with Retry-After `retry` ...
//   html = Page(m->gym, m->wall, *m->tables);
//
// A refusal by the work budget is kResourceExhausted with
// *retry_after_seconds set (> 0 when waiting helps), as
// WorkBudget::Admit's. Every function is thread-safe (the services are).
#ifndef SB_APP_PAGE_MODELS_H_
#define SB_APP_PAGE_MODELS_H_

#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "app/dashboard.h"
#include "app/services.h"
#include "app/types.h"
#include "base/status.h"

namespace sb::app {

// What the wall page's route tables are made from (rendered by the caller,
// then kept per viewer and language at the gym's stamp).
struct WallRoutes {
  const Gym* gym = nullptr;    // the wall's gym; not owned
  const Wall* wall = nullptr;  // not owned
  // The routes on the wall `viewer` sees, current first (issue 31): planned,
  // set, the drafts the viewer sees, stripped, each newest set first; at
  // most options.limits.wall_page_rows (stripped routes are the first left
  // out, so the page's buttons cover the routes on the wall).
  std::vector<RouteView> routes;
  // How many routes the wall holds for `viewer` (more than `routes` when the
  // page is truncated: its buttons then change only the routes shown).
  int64_t total = 0;
  // Each route's ascent grade by id (one cached fit of the gym); empty when
  // the fit failed (then the tables are not kept).
  std::map<int64_t, AscentGrade> ascents;
  bool ascents_ok = false;
  WallAge age;        // the wall's age and due flag (WallAgeOf)
  std::string today;  // today's date (UTC), the "set all planned today" button's
};

// Renders the wall page's route tables. Called at most once per WallPage,
// while the work budget's slot is held.
using WallTablesRenderer = std::function<std::string(const WallRoutes&)>;

// The wall page (/walls/{id}).
struct WallPageModel {
  Gym gym;    // read each time (a rename moves no data version), with the viewer's role
  Wall wall;  // likewise
  // The route tables (kept or just rendered); never null.
  std::shared_ptr<const std::string> tables;
};

// The wall page of wall `wall_id` for `v`, its tables rendered by `render`
// in language `lang` (part of what is kept). Members of the wall's gym only
// (kNotFound "no wall N" / "no gym N" otherwise, as Gyms::GetWall and
// Gyms::Get). The route tables are kept per (wall, viewer, language) at the
// gym's stamp (the gym's data version and the day, read before the routes):
// a kept text is returned without reading or charging anything; otherwise
// the routes are listed, then the listing's rows (list_per_row) and the
// ascent fit this reader would make (fit_per_tick per tick of the gym per
// discipline listed, 0 when the kept fit is current; bounded by the
// caller's per-request cap, as ReadCosts::AscentCost) are charged to `v` on
// the gym's share before the fit is read (issue 34).
// Tables made without their ascent grades (the fit failed) are not kept.
// Errors: as above, kResourceExhausted from the work budget (with
// *retry_after_seconds), the store's.
Result<WallPageModel> WallPage(Services& s, const Viewer& v, int64_t wall_id,
                               std::string_view lang, const WallTablesRenderer& render,
                               int* retry_after_seconds);

// The "On the wall" block under a route's page (/routes/{id},
// /variations/{id}) for a route of a gym.
struct RouteGymBlockModel {
  // The route's history, oldest first, for members of its gym (empty for
  // others, or when it could not be read).
  std::vector<HistoryEntry> history;
  // Whether `v` may change the route (Routes::CanChange: the owner; the
  // gym's setters unless a draft): the block's form and buttons.
  bool can_change = false;
};

// The gym block of route `r` (already read and admitted by the route's page,
// which charges its history: ReadCosts::RouteBlocksCost) for `v`; nullopt
// when there is none to show: a route of no gym, or a draft to a viewer who
// is not a member of its gym. Never fails: an unreadable role or history
// shows as a non-member's block.
std::optional<RouteGymBlockModel> RouteGymBlock(Services& s, const Viewer& v, const RouteView& r);

// The gym page (/gyms/{id}).
struct GymPageModel {
  Gym gym;  // with the viewer's role
  std::vector<Wall> walls;
  std::vector<Circuit> circuits;
  std::vector<Member> members;
  // The gym's history, for its setters and head setters only (issue 31).
  std::vector<GymHistoryEntry> history;
  std::string language;  // the gym's default language ("" = none or unreadable)
};

// The gym page of gym `gym` for `v`. Members only (kNotFound "no gym N").
// Its lists (walls, circuits, members: ReadCosts::GymListCost) and, for
// setters, its history (GymHistoryCost) are counted first and charged to
// `v` on the gym's share before they are read (issue 34). Errors: as above,
// kResourceExhausted (with *retry_after_seconds), the store's.
Result<GymPageModel> GymPage(Services& s, const Viewer& v, int64_t gym,
                             int* retry_after_seconds);

// What the setting dashboard's kept text is made from (rendered by the
// caller: the page's body or the API's JSON).
struct DashboardContent {
  const GymDashboard* dashboard = nullptr;  // not owned
  // Each route's ascent grade by id (one cached fit of the gym).
  const std::map<int64_t, AscentGrade>* ascents = nullptr;  // not owned
  // The routes the gym's climbers are most likely to project (issue 35);
  // null when not asked for.
  const ProjectList* projects = nullptr;  // not owned
};

// Renders the dashboard's kept text. Called at most once per call, while
// the work budget's slot is held.
using DashboardRenderer = std::function<std::string(const DashboardContent&)>;

// The setting dashboard page (/gyms/{id}/dashboard).
struct DashboardPageModel {
  Gym gym;  // read each time (its name is the title; a rename moves no version)
  // The page's body (kept or just rendered); never null.
  std::shared_ptr<const std::string> body;
};

// The dashboard page of gym `gym` for `v`, its body rendered by `render`:
// members only (kNotFound "no gym N", as Gyms::Get), then Dashboard::Get's
// rules. The body is kept per (gym, viewer, language `lang`, wall shown
// `only_wall` (0: all), gym name) at the gym's stamp (read before the
// dashboard): a kept body is returned without reading or charging
// anything; otherwise the dashboard is read, its rows (a row per wall, and
// per route on it, band and style: list_per_row) charged to `v` on the
// gym's share, then the ascent grades and (all walls shown) the projects
// read. Errors: as above, kResourceExhausted (with *retry_after_seconds),
// the store's.
Result<DashboardPageModel> DashboardPage(Services& s, const Viewer& v, int64_t gym,
                                         std::string_view lang, int64_t only_wall,
                                         const DashboardRenderer& render,
                                         int* retry_after_seconds);

// GET /api/gyms/{id}/dashboard: as DashboardPage without the gym read first
// (Dashboard::Get refuses), the projects always read, the text kept per
// (gym, viewer) at the gym's stamp. Never null on success.
Result<std::shared_ptr<const std::string>> DashboardJson(Services& s, const Viewer& v, int64_t gym,
                                                         const DashboardRenderer& render,
                                                         int* retry_after_seconds);

// Charges `cost` render units to `v` in s.renders for work on `gym` (the
// member share when `v` is a member) and returns the slot to hold while
// working. Errors: WorkBudget::Admit's, with *retry_after_seconds.
Result<WorkBudget::Slot> AdmitPageWork(Services& s, const Viewer& v, double cost,
                                       std::optional<int64_t> gym, int* retry_after_seconds);

}  // namespace sb::app

#endif  // SB_APP_PAGE_MODELS_H_
