// Gym pages (issue 21): /gyms, /gyms/{id}, /walls/{id}, and the gym block of
// a route page. Each asks app::Gyms / app::Routes and renders (gym_pages.h).
#include "app/clock.h"
#include "base/date.h"
#include "base/text.h"
#include "gym/rules.h"
#include "web/dashboard_handlers.h"
#include "web/gym_pages.h"
#include "web/handlers.h"
#include "web/logbook_handlers.h"

namespace sb::web {

namespace {

// Today's date (UTC), what the wall page's "set all planned routes of today" means.
std::string Today() { return UtcDateText(app::SystemClock().Now()); }

void Html(Exchange& x, const std::string& html) {
  x.res.SetHeader("Cache-Control", "no-store");
  x.res.SetBody(200, html, "text/html; charset=utf-8");
}

}  // namespace

void PageGyms(Exchange& x) {
  if (!x.caller.viewer.logged_in()) return PageError(x, Status::Unauthenticated("Log in first."));
  Result<std::vector<app::Gym>> gyms = x.services.gyms.Mine(x.caller.viewer);
  if (!gyms.ok()) return PageError(x, gyms.status());
  Html(x, GymsPage(x.caller.page(), *gyms));
}

void PageGym(Exchange& x) {
  Result<int64_t> id = PathId(x.req, "No such gym.");
  if (!id.ok()) return PageError(x, id.status());
  Result<app::Gym> gym = x.services.gyms.Get(x.caller.viewer, *id);
  if (!gym.ok()) return PageError(x, gym.status());
  Result<std::vector<app::Wall>> walls = x.services.gyms.Walls(x.caller.viewer, *id);
  if (!walls.ok()) return PageError(x, walls.status());
  Result<std::vector<app::Circuit>> circuits = x.services.gyms.Circuits(x.caller.viewer, *id);
  if (!circuits.ok()) return PageError(x, circuits.status());
  Result<std::vector<app::Member>> members = x.services.gyms.Members(x.caller.viewer, *id);
  if (!members.ok()) return PageError(x, members.status());
  std::vector<app::GymHistoryEntry> history;  // setters' (issue 31)
  std::optional<app::WorkBudget::Slot> slot;
  if (app::CanSet(gym->role)) {
    // Issue 34: the history rows, counted first.
    Result<double> cost = x.services.read_costs.GymHistoryCost(x.caller.viewer, *id);
    if (!cost.ok()) return PageError(x, cost.status());
    slot = AdmitWork(x, *cost, *id);
    if (!slot) return;
    Result<std::vector<app::GymHistoryEntry>> h = x.services.gyms.GymHistory(x.caller.viewer, *id);
    if (!h.ok()) return PageError(x, h.status());
    history = std::move(h).value();
  }
  Result<std::string> language = x.services.profiles.GymLanguage(*id);  // issue 32
  Html(x, GymPage(x.caller.page(), *gym, *walls, *circuits, *members, history,
                  language.ok() ? *language : std::string()));
}

void PageWall(Exchange& x) {
  Result<int64_t> id = PathId(x.req, "No such wall.");
  if (!id.ok()) return PageError(x, id.status());
  Result<app::Wall> wall = x.services.gyms.GetWall(x.caller.viewer, *id);
  if (!wall.ok()) return PageError(x, wall.status());
  Result<app::Gym> gym = x.services.gyms.Get(x.caller.viewer, wall->gym_id);
  if (!gym.ok()) return PageError(x, gym.status());
  // Issue 22: the route tables are kept per (wall, viewer) at the gym's data
  // version and day (app::RenderCache); the stamp is read before the routes.
  // The wall and gym above are read each time (a gym's rename moves no version).
  Result<std::optional<app::Stamp>> stamp = x.services.rendered.StampOf(wall->gym_id);
  if (!stamp.ok()) return PageError(x, stamp.status());
  const app::RenderKey key{"wall/" + x.caller.lang, wall->id, x.caller.viewer.user_id.value_or(0)};
  if (*stamp) {
    if (auto hit = x.services.rendered.Find(key, **stamp)) {
      return Html(x, WallPage(x.caller.page(), *gym, *wall, *hit));
    }
  }
  app::RouteQuery q;
  q.gym = wall->gym_id;
  q.wall = std::to_string(wall->id);
  q.limit = x.services.options.limits.wall_page_rows;
  q.sort = "set";
  Result<app::RoutePage> routes = x.services.routes.Search(x.caller.viewer, q);
  if (!routes.ok()) return PageError(x, routes.status());
  // Each route's grade from ascents (one cached fit of the gym, issue 23).
  // One fit for the page (issue 22: not one tick-version query per route).
  std::map<int64_t, std::string> ascent;
  Result<std::map<int64_t, app::AscentGrade>> ascents =
      x.services.logbook.Ascents(x.caller.viewer, routes->routes);
  if (ascents.ok()) {
    for (const auto& [id, a] : *ascents) ascent[id] = AscentCell(a);
  }
  const app::WallAge age = app::WallAgeOf(*wall, routes->routes, app::SystemClock().Now());
  std::string tables = WallRoutesHtml(*gym, *wall, routes->routes, &ascent,
                                      WallStatus(*wall, age, x.caller.lang), x.caller.lang, Today());
  // A page without its ascent grades (the fit failed) is not kept.
  if (*stamp && ascents.ok()) {
    return Html(x, WallPage(x.caller.page(), *gym, *wall,
                            *x.services.rendered.Keep(key, **stamp, std::move(tables))));
  }
  Html(x, WallPage(x.caller.page(), *gym, *wall, tables));
}

std::string GymBlock(Exchange& x, const app::RouteView& r) {
  if (!r.gym_id) return "";
  Result<std::string> role = x.services.gyms.RoleIn(x.caller.viewer, *r.gym_id);
  const bool member = role.ok() && !role->empty();
  if (!member && r.state == gym::RouteState::kDraft) return "";  // nothing to say to outsiders about a draft
  std::vector<app::HistoryEntry> history;
  if (member) {
    Result<std::vector<app::HistoryEntry>> h = x.services.routes.History(x.caller.viewer, r.id);
    if (h.ok()) history = std::move(h).value();
  }
  // The editing rule is app's (Routes::CanChange: the owner; the gym's
  // setters unless a draft), as the state change's.
  const bool can_set = x.services.routes.CanChange(x.caller.viewer, r);
  // Issue 31: the circuit the route is set in.
  const std::string circuit_row =
      r.circuit_id ? "<dt>" + Tr(x.caller.page(), "Circuit") + "</dt><dd id=\"route-circuit\">" +
                         XmlEscape(r.circuit_colour) + "</dd>"
                   : std::string();
  return RouteGymBlock(r, history, can_set, x.caller.lang, circuit_row);
}

}  // namespace sb::web
