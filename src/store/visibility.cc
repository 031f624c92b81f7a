#include "store/visibility.h"

#include "gym/rules.h"

namespace sb::store {

bool MemberSees(std::string_view role, std::string_view state) {
  const std::optional<gym::Role> r = gym::RoleOf(role);
  const std::optional<gym::RouteState> s = gym::RouteStateOf(state);
  return r && s && gym::MemberSees(*r, *s);
}

bool Sees(const RouteSight& r, std::optional<int64_t> viewer, std::string_view role_in_gym,
          Reach reach) {
  if (r.in_library) return true;
  if (viewer && r.owner_id && *viewer == *r.owner_id) return true;
  if (!r.gym_id) return false;
  const std::optional<gym::Role> role = gym::RoleOf(role_in_gym);
  if (role && gym::MemberSees(*role, r.state)) return true;
  return reach == Reach::kOnTheWall && r.state == gym::kOnTheWall;
}

std::string SeesSql(std::string_view t_view, int* params) {
  const std::string t(t_view);
  // One term per role: the states gym::MemberSees gives it (its table is
  // the only place that says which).
  std::string roles;
  for (gym::Role role : gym::kRoles) {
    std::string states;
    for (gym::RouteState state : gym::kRouteStates) {
      if (!gym::MemberSees(role, state)) continue;
      states += (states.empty() ? "'" : ", '") + std::string(gym::NameOf(state)) + "'";
    }
    if (states.empty()) continue;
    roles += (roles.empty() ? "" : " OR ") + std::string("(m.role = '") + gym::NameOf(role) +
             "' AND " + t + ".state IN (" + states + "))";
  }
  if (roles.empty()) roles = "1 = 0";
  *params = 2;
  // Never NULL (a NULL owner would make NOT of it NULL, and a variation
  // of an orphaned private route pass the sources' test).
  return "(" + t + ".is_public = 1 OR (" + t + ".owner_id IS NOT NULL AND " + t +
         ".owner_id = ?) OR (" + t +
         ".gym_id IS NOT NULL AND EXISTS (SELECT 1 FROM gym_members m WHERE m.gym_id = " + t +
         ".gym_id AND m.user_id = ? AND (" + roles + "))))";
}

}  // namespace sb::store
