// Internal to web/: the setting dashboard (issue 22; docs/web.md
// "Dashboard", docs/setting.md "The dashboard"): its JSON API, the head
// setter's targets, and the page /gyms/{id}/dashboard with the floor plan
// and the per-wall charts as server-rendered SVG. Bound to paths in
// server.cc; every answer comes from app::Dashboard.
#ifndef SB_WEB_DASHBOARD_HANDLERS_H_
#define SB_WEB_DASHBOARD_HANDLERS_H_

#include <cstdint>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "app/dashboard.h"
#include "app/logbook.h"
#include "web/handlers.h"

namespace sb::web {

void GetDashboard(Exchange& x);    // GET /api/gyms/{id}/dashboard (members)
void PutWallTargets(Exchange& x);  // PUT /api/gyms/{id}/walls/{wall}/targets (head setters)
// PUT /api/gyms/{id}/targets {"discipline", "grades", "styles"} (head setters; issue 22)
void PutDisciplineTargets(Exchange& x);
void PageDashboard(Exchange& x);   // GET /gyms/{id}/dashboard[?wall=W] (members)

// Route id -> its grade from ascents (issue 23; app::Logbook::Ascents).
using DashboardAscents = std::map<int64_t, app::AscentGrade>;

// The page's HTML (escaped user text; SVG plan and charts with data
// tables). `only_wall` shows one wall's section (0 = every wall); each
// route row shows its grade from `ascents` (an empty cell when absent). Pure.
std::string DashboardPage(const PageViewer& v, const app::GymDashboard& d, int64_t only_wall,
                          const DashboardAscents& ascents = {});
// The page's body, inside the layout (what DashboardPage wraps; issue 22:
// kept by app::RenderCache). `projects_html` (issue 35, ProjectsHtml) goes
// after the discipline sections when every wall is shown. Pure.
std::string DashboardBody(const app::GymDashboard& d, int64_t only_wall,
                          const DashboardAscents& ascents = {},
                          const std::string& projects_html = "", std::string_view lang = "en");
// The floor plan as SVG: walls on their plan rectangles, filled by the age
// of what is on them, each a link to /walls/{id}; "" when no wall has a
// rectangle. Pure.
std::string PlanSvg(const app::GymDashboard& d, std::string_view lang = "en");
// The wall page's line from the age of what is on it (app::WallAgeOf: how
// many routes are on the wall, the oldest one's age in days, whether the
// wall is due for a reset by the one rule, gym::DueForReset), with a link to
// the gym's dashboard; "" when nothing is on the wall. Pure.
std::string WallStatus(const app::Wall& wall, const app::WallAge& age,
                       std::string_view lang = "en");

}  // namespace sb::web

#endif  // SB_WEB_DASHBOARD_HANDLERS_H_
