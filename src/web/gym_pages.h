// Server-rendered pages of gyms (issue 21): the viewer's gyms, a gym (walls,
// circuits, members, and the head setter's forms), a wall (its routes by
// state), and the gym block of a route page (state, wall, setters,
// history). Every piece of user text is escaped. Pure; thread-safe.
#ifndef SB_WEB_GYM_PAGES_H_
#define SB_WEB_GYM_PAGES_H_

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "app/gyms.h"
#include "app/routes.h"
#include "web/pages.h"

namespace sb::web {

// "/gyms": the viewer's gyms and a form to create one.
std::string GymsPage(const PageViewer& v, const std::vector<app::Gym>& gyms);
// "/gyms/{id}": walls (linking their pages), circuits, members; the head
// setter's forms to add each, and (issue 31) to rename the gym, edit and
// remove walls and circuits, change members' roles and remove them; the
// gym's `history` (shown when not empty). Head setters also get a form for
// the gym's default `language` (issue 32; "" = none).
std::string GymPage(const PageViewer& v, const app::Gym& gym, const std::vector<app::Wall>& walls,
                    const std::vector<app::Circuit>& circuits,
                    const std::vector<app::Member>& members,
                    const std::vector<app::GymHistoryEntry>& history = {},
                    const std::string& language = "");
// "/walls/{id}": the wall's routes grouped by state (on the wall, planned,
// drafts, stripped), a form to plan a route on it for setters. With
// `ascent_cells` (route id -> a <td>, logbook_handlers.h AscentCell) each
// row shows the route's ascent grade (issue 23); the page links the wall's
// climbers' report. `status` (HTML, not escaped) goes under the title: the
// dashboard's age and due line (dashboard_handlers.h, WallStatus).
std::string WallPage(const PageViewer& v, const app::Gym& gym, const app::Wall& wall,
                     const std::vector<app::RouteView>& routes,
                     const std::map<int64_t, std::string>* ascent_cells = nullptr,
                     const std::string& status = "");
// The part of "/walls/{id}" made from the wall's routes (issue 22: kept by
// app::RenderCache per gym data version, day and viewer): `status`, the
// report link and the route tables, as WallPage above shows them; for
// setters with `today` given (issue 31) the buttons "set all planned routes
// of today" and "strip this wall", each carrying the revisions of the routes
// shown for it (disabled when there are none). Pure.
std::string WallRoutesHtml(const app::Gym& gym, const app::Wall& wall,
                           const std::vector<app::RouteView>& routes,
                           const std::map<int64_t, std::string>* ascent_cells,
                           const std::string& status, std::string_view lang = "en",
                           const std::string& today = "");
// "/walls/{id}" around `routes_html` (WallRoutesHtml): the gym link, the
// title and the wall's line above, the setters' line below. Pure.
std::string WallPage(const PageViewer& v, const app::Gym& gym, const app::Wall& wall,
                     const std::string& routes_html);
// The block a route page shows for a route of a gym: state, wall, setters,
// set / strip dates and history; with `can_set`, a form to change them
// (carrying the route's revision, issue 31) and the plan / set / strip
// buttons its state allows (an empty date keeps the route's, or is today).
// `circuit_row` (issue 31): the rendered <dt>/<dd> of the route's circuit, after its wall.
std::string RouteGymBlock(const app::RouteView& r, const std::vector<app::HistoryEntry>& history,
                          bool can_set, std::string_view lang = "en",
                          const std::string& circuit_row = "");

}  // namespace sb::web

#endif  // SB_WEB_GYM_PAGES_H_
