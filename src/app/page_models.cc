#include "app/page_models.h"

#include <algorithm>
#include <map>
#include <string>
#include <utility>

#include "app/clock.h"
#include "app/discipline.h"
#include "base/date.h"
#include "gym/rules.h"

namespace sb::app {

Result<WorkBudget::Slot> AdmitPageWork(Services& s, const Viewer& v, double cost,
                                       std::optional<int64_t> gym, int* retry_after_seconds) {
  int retry = 0;
  bool busy = false;
  Result<WorkBudget::Slot> slot = s.renders.Admit(v, cost, &retry, &busy, gym);
  if (retry_after_seconds) *retry_after_seconds = slot.ok() ? 0 : retry;
  return slot;
}

namespace {

// The ascent grades of a listing `v` read (Logbook::Ascents: one cached fit
// per gym and discipline): per (gym, discipline) of `routes`, the fit this
// reader would make (fit_per_tick per tick, as ReadCosts::AscentCost), the
// whole bounded by what `before` leaves of the reader's per-request cap (a
// gym's first fit must still be made once).
Result<double> ListedAscentsCost(Services& s, const Viewer& v, const std::vector<RouteView>& routes,
                                 double before) {
  SB_RETURN_IF_ERROR(s.options.render_costs.Validate());
  // One route per (gym, discipline) of the fits (FitDiscipline).
  std::map<std::pair<int64_t, std::string>, const RouteView*> groups;
  for (const RouteView& r : routes) {
    if (!r.gym_id) continue;
    groups.emplace(std::make_pair(*r.gym_id, FitDiscipline(r.grade_discipline)), &r);
  }
  double fits = 0;
  for (const auto& [key, route] : groups) {
    SB_ASSIGN_OR_RETURN(int64_t n, s.logbook.ReaderFitTicks(*route));
    fits += static_cast<double>(n) * s.options.render_costs.fit_per_tick;
  }
  const double cap = v.logged_in() ? s.options.renders.user_max_cost : s.options.renders.anonymous_max_cost;
  return std::min(fits, std::max(0.0, cap - before));
}

// Issue 31: the routes on `wall` that `v` sees, current first: planned, then
// set (each newest set first), then the drafts `v` sees, then the stripped,
// at most `rows` in all; `total` counts every route of the wall `v` sees. So
// however many routes were stripped from the wall, the page (and its buttons
// for several routes at once) holds the routes on it.
Result<RoutePage> CurrentFirst(Services& s, const Viewer& v, const Wall& wall, int rows) {
  RoutePage out;
  for (gym::RouteState state : {gym::RouteState::kPlanned, gym::RouteState::kSet,
                                gym::RouteState::kDraft, gym::RouteState::kStripped}) {
    RouteQuery q;
    q.gym = wall.gym_id;
    q.wall = std::to_string(wall.id);
    q.state = gym::NameOf(state);
    q.sort = "set";
    const int left = rows - static_cast<int>(out.routes.size());
    q.limit = std::max(left, 1);  // a full page still counts the state's routes
    SB_ASSIGN_OR_RETURN(RoutePage page, s.routes.Search(v, q));
    out.total += page.total;
    for (RouteView& r : page.routes) {
      if (static_cast<int>(out.routes.size()) >= rows) break;
      out.routes.push_back(std::move(r));
    }
  }
  out.limit = rows;
  return out;
}

}  // namespace

Result<WallPageModel> WallPage(Services& s, const Viewer& v, int64_t wall_id,
                               std::string_view lang, const WallTablesRenderer& render,
                               int* retry_after_seconds) {
  if (retry_after_seconds) *retry_after_seconds = 0;
  WallPageModel m;
  SB_ASSIGN_OR_RETURN(m.wall, s.gyms.GetWall(v, wall_id));
  SB_ASSIGN_OR_RETURN(m.gym, s.gyms.Get(v, m.wall.gym_id));
  // Issue 22: the route tables are kept per (wall, viewer) at the gym's data
  // version and day (app::RenderCache); the stamp is read before the routes.
  // The wall and gym above are read each time (a gym's rename moves no version).
  SB_ASSIGN_OR_RETURN(std::optional<Stamp> stamp, s.rendered.StampOf(m.wall.gym_id));
  const RenderKey key{"wall/" + std::string(lang), m.wall.id, v.user_id.value_or(0)};
  if (stamp) {
    if (auto hit = s.rendered.Find(key, *stamp)) {
      m.tables = std::move(hit);
      return m;
    }
  }
  SB_ASSIGN_OR_RETURN(RoutePage routes,
                      CurrentFirst(s, v, m.wall, s.options.limits.wall_page_rows));
  // Issue 34: the rows listed and the fit this reader would make, counted
  // before the fit is read.
  const double rows =
      static_cast<double>(routes.routes.size()) * s.options.render_costs.list_per_row;
  SB_ASSIGN_OR_RETURN(double fit, ListedAscentsCost(s, v, routes.routes, rows));
  const double cost = rows + fit;
  SB_ASSIGN_OR_RETURN(WorkBudget::Slot slot,
                      AdmitPageWork(s, v, cost, m.wall.gym_id, retry_after_seconds));
  WallRoutes w;
  w.gym = &m.gym;
  w.wall = &m.wall;
  // Each route's grade from ascents (one cached fit of the gym, issue 23).
  // One fit for the page (issue 22: not one tick-version query per route).
  Result<std::map<int64_t, AscentGrade>> ascents = s.logbook.Ascents(v, routes.routes);
  w.ascents_ok = ascents.ok();
  if (ascents.ok()) w.ascents = std::move(ascents).value();
  const int64_t now = SystemClock().Now();
  w.age = WallAgeOf(m.wall, routes.routes, now);
  w.today = UtcDateText(now);  // what "set all planned routes of today" means
  w.total = routes.total;
  w.routes = std::move(routes.routes);
  std::string tables = render(w);
  // A page without its ascent grades (the fit failed) is not kept.
  if (stamp && w.ascents_ok) {
    m.tables = s.rendered.Keep(key, *stamp, std::move(tables));
  } else {
    m.tables = std::make_shared<const std::string>(std::move(tables));
  }
  return m;
}

std::optional<RouteGymBlockModel> RouteGymBlock(Services& s, const Viewer& v, const RouteView& r) {
  if (!r.gym_id) return std::nullopt;
  Result<std::string> role = s.gyms.RoleIn(v, *r.gym_id);
  const bool member = role.ok() && !role->empty();
  // Nothing to say to outsiders about a draft.
  if (!member && r.state == gym::RouteState::kDraft) return std::nullopt;
  RouteGymBlockModel m;
  if (member) {
    Result<std::vector<HistoryEntry>> h = s.routes.History(v, r.id);
    if (h.ok()) m.history = std::move(h).value();
  }
  // The editing rule is Routes::CanChange (the owner; the gym's setters
  // unless a draft), as the state change's.
  m.can_change = s.routes.CanChange(v, r);
  return m;
}

Result<GymPageModel> GymPage(Services& s, const Viewer& v, int64_t gym,
                             int* retry_after_seconds) {
  if (retry_after_seconds) *retry_after_seconds = 0;
  GymPageModel m;
  SB_ASSIGN_OR_RETURN(m.gym, s.gyms.Get(v, gym));
  // Issue 34: the lists and (setters', issue 31) the history, counted first.
  double cost = 0;
  for (ReadCosts::GymList list : {ReadCosts::GymList::kWalls, ReadCosts::GymList::kCircuits,
                                  ReadCosts::GymList::kMembers}) {
    SB_ASSIGN_OR_RETURN(double c, s.read_costs.GymListCost(v, gym, list));
    cost += c;
  }
  const bool setter = CanSet(m.gym.role);
  if (setter) {
    SB_ASSIGN_OR_RETURN(double c, s.read_costs.GymHistoryCost(v, gym));
    cost += c;
  }
  SB_ASSIGN_OR_RETURN(WorkBudget::Slot slot, AdmitPageWork(s, v, cost, gym, retry_after_seconds));
  SB_ASSIGN_OR_RETURN(m.walls, s.gyms.Walls(v, gym));
  SB_ASSIGN_OR_RETURN(m.circuits, s.gyms.Circuits(v, gym));
  SB_ASSIGN_OR_RETURN(m.members, s.gyms.Members(v, gym));
  if (setter) {
    SB_ASSIGN_OR_RETURN(m.history, s.gyms.GymHistory(v, gym));
  }
  Result<std::string> language = s.profiles.GymLanguage(gym);  // issue 32
  if (language.ok()) m.language = std::move(language).value();
  return m;
}

namespace {

// The render units of a dashboard: a row per route on the walls.
double DashboardCost(Services& s, const GymDashboard& d) {
  double rows = 0;
  for (const WallDashboard& w : d.walls) rows += 1 + w.on_wall + w.bands.size() + w.styles.size();
  return rows * s.options.render_costs.list_per_row;
}

// The dashboard of `gym` kept as `key`, read, admitted and rendered on a
// miss (DashboardPage, DashboardJson).
Result<std::shared_ptr<const std::string>> KeptDashboard(Services& s, const Viewer& v,
                                                         int64_t gym, const RenderKey& key,
                                                         bool with_projects,
                                                         const DashboardRenderer& render,
                                                         int* retry_after_seconds) {
  // Issue 22: kept per key at the gym's data version and day
  // (app::RenderCache); the stamp is read before the dashboard.
  SB_ASSIGN_OR_RETURN(std::optional<Stamp> stamp, s.rendered.StampOf(gym));
  if (stamp) {
    if (auto hit = s.rendered.Find(key, *stamp)) return hit;
  }
  SB_ASSIGN_OR_RETURN(GymDashboard d, s.dashboard.Get(v, gym));
  SB_ASSIGN_OR_RETURN(WorkBudget::Slot slot,
                      AdmitPageWork(s, v, DashboardCost(s, d), gym, retry_after_seconds));
  // The ascent grades of the dashboard's routes: one cached fit of the gym
  // (the wall page's numbers).
  std::vector<int64_t> ids;
  for (const WallDashboard& w : d.walls) {
    for (const DashboardRoute& r : w.routes) ids.push_back(r.id);
  }
  SB_ASSIGN_OR_RETURN(auto ascents, s.logbook.Ascents(d.gym.id, ids));
  DashboardContent c;
  c.dashboard = &d;
  c.ascents = &ascents;
  ProjectList projects;
  if (with_projects) {
    // Issue 35: the routes its climbers are most likely to project.
    std::vector<ProjectCandidate> routes;
    for (const WallDashboard& w : d.walls) {
      for (const DashboardRoute& r : w.routes) {
        routes.push_back({r.id, r.name, r.grade, w.wall.name, w.wall.discipline});
      }
    }
    SB_ASSIGN_OR_RETURN(projects, s.chances.Projects(d.gym.id, routes));
    c.projects = &projects;
  }
  std::string text = render(c);
  if (stamp) return s.rendered.Keep(key, *stamp, std::move(text));
  return std::make_shared<const std::string>(std::move(text));
}

}  // namespace

Result<DashboardPageModel> DashboardPage(Services& s, const Viewer& v, int64_t gym,
                                         std::string_view lang, int64_t only_wall,
                                         const DashboardRenderer& render,
                                         int* retry_after_seconds) {
  if (retry_after_seconds) *retry_after_seconds = 0;
  DashboardPageModel m;
  // The gym is read each time (a rename moves no version), and names the
  // kept body.
  SB_ASSIGN_OR_RETURN(m.gym, s.gyms.Get(v, gym));
  const RenderKey key{"dashboard " + std::string(lang) + " " + std::to_string(only_wall) + " " +
                          m.gym.name,
                      gym, v.user_id.value_or(0)};
  SB_ASSIGN_OR_RETURN(m.body, KeptDashboard(s, v, gym, key, /*with_projects=*/only_wall == 0,
                                            render, retry_after_seconds));
  return m;
}

Result<std::shared_ptr<const std::string>> DashboardJson(Services& s, const Viewer& v, int64_t gym,
                                                         const DashboardRenderer& render,
                                                         int* retry_after_seconds) {
  if (retry_after_seconds) *retry_after_seconds = 0;
  const RenderKey key{"api_dashboard", gym, v.user_id.value_or(0)};
  return KeptDashboard(s, v, gym, key, /*with_projects=*/true, render, retry_after_seconds);
}

}  // namespace sb::app
