#include "app/tags.h"

#include <algorithm>

#include "base/text.h"
#include "gym/rules.h"

namespace sb::app {

plan::TagInfo TagInfoOf(const RouteView& r, const std::string& url) {
  plan::TagInfo t;
  t.name = r.name;
  t.grade = r.grade;
  t.colour = r.colour;
  // The gym's wall row and assigned setters (issue 21) before the CRDL's
  // free text.
  t.wall = r.wall_name.empty() ? r.wall : r.wall_name;
  for (const RouteSetter& s : r.setters) {
    if (!Trim(s.name).empty()) t.setters.emplace_back(Trim(s.name));
  }
  if (t.setters.empty()) {
    for (std::string_view s : Split(r.setter, ',')) {
      if (!Trim(s).empty()) t.setters.emplace_back(Trim(s));
    }
  }
  if (t.setters.empty() && !r.owner_name.empty()) t.setters.push_back(r.owner_name);
  t.planned = r.state == gym::RouteState::kPlanned;
  if (t.planned) {  // the planned date, never the day it was added
    t.set_on = r.set_on.empty() ? r.planned_on : r.set_on;
  } else {
    t.set_on = r.set_on.empty() ? r.created_at.substr(0, 10) : r.set_on;
  }
  t.url = url;
  return t;
}

Result<std::vector<RouteView>> TagSheetRoutes(Routes& routes, const Viewer& v,
                                                       const std::vector<int64_t>& ids,
                                                       const Limits& limits) {
  if (ids.empty()) return Status::InvalidInput("ids: name at least one route (ids=1,2,3)");
  if (ids.size() > limits.max_tag_sheet_routes) {
    return Status::InvalidInput("ids: at most " + std::to_string(limits.max_tag_sheet_routes) +
                                " routes per sheet of tags (" + std::to_string(ids.size()) +
                                " given)");
  }
  std::vector<RouteView> out;
  out.reserve(ids.size());
  for (int64_t id : ids) {
    SB_ASSIGN_OR_RETURN(RouteView r, routes.Get(v, id));
    out.push_back(std::move(r));
  }
  return out;
}

Result<std::vector<RouteView>> GymTagSheetRoutes(Routes& routes, const Viewer& v,
                                                          int64_t gym, const std::string& wall,
                                                          const std::string& state,
                                                          const Limits& limits) {
  std::vector<std::string> states;
  if (Trim(state).empty()) {
    states = {gym::NameOf(gym::RouteState::kPlanned), gym::NameOf(gym::RouteState::kSet)};
  } else {
    states = {std::string(Trim(state))};
  }
  std::vector<RouteView> listed;
  for (const std::string& s : states) {
    RouteQuery q;
    q.gym = gym;
    q.wall = wall;
    q.state = s;
    q.sort = "name";
    q.limit = static_cast<int>(limits.max_tag_sheet_routes) + 1;
    SB_ASSIGN_OR_RETURN(RoutePage page, routes.Search(v, q));
    if (listed.size() + static_cast<size_t>(page.total) > limits.max_tag_sheet_routes) {
      return Status::InvalidInput(
          "wall: " + std::to_string(listed.size() + static_cast<size_t>(page.total)) +
          " routes match, at most " + std::to_string(limits.max_tag_sheet_routes) +
          " print on one sheet of tags; choose a wall or a state");
    }
    for (RouteView& r : page.routes) listed.push_back(std::move(r));
  }
  std::vector<RouteView> out;
  out.reserve(listed.size());
  for (const RouteView& r : listed) {
    // GetRoute fills the setters, which lists leave out.
    SB_ASSIGN_OR_RETURN(RouteView full, routes.Get(v, r.id));
    out.push_back(std::move(full));
  }
  std::stable_sort(out.begin(), out.end(), [](const RouteView& a,
                                              const RouteView& b) {
    const std::string& wa = a.wall_name.empty() ? a.wall : a.wall_name;
    const std::string& wb = b.wall_name.empty() ? b.wall : b.wall_name;
    if (wa != wb) return wa < wb;
    return ToLower(a.name) < ToLower(b.name);
  });
  return out;
}

}  // namespace sb::app
