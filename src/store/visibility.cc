#include "store/visibility.h"

namespace sb::store {

namespace {

// The members' part of the rule: which states of its gym's routes each role
// sees. Sees and SeesSql both read this table (and nothing else names it).
struct RoleSight {
  std::string_view role;
  std::string_view states[4];
};
constexpr RoleSight kRoleSight[] = {
    {"head", {"draft", "planned", "set", "stripped"}},
    {"setter", {"draft", "planned", "set", "stripped"}},
    {"climber", {"set", "stripped"}},
};

// The state a route on the wall has (Reach::kOnTheWall).
constexpr std::string_view kOnTheWallState = "set";

}  // namespace

bool MemberSees(std::string_view role, std::string_view state) {
  if (role.empty() || state.empty()) return false;
  for (const RoleSight& r : kRoleSight) {
    if (r.role != role) continue;
    for (std::string_view s : r.states) {
      if (!s.empty() && s == state) return true;
    }
  }
  return false;
}

bool Sees(const RouteSight& r, std::optional<int64_t> viewer, std::string_view role_in_gym,
          Reach reach) {
  if (r.in_library) return true;
  if (viewer && r.owner_id && *viewer == *r.owner_id) return true;
  if (!r.gym_id) return false;
  if (MemberSees(role_in_gym, r.state)) return true;
  return reach == Reach::kOnTheWall && r.state == kOnTheWallState;
}

std::string SeesSql(std::string_view t_view, int* params) {
  const std::string t(t_view);
  std::string roles;
  for (const RoleSight& r : kRoleSight) {
    std::string states;
    for (std::string_view s : r.states) {
      if (!s.empty()) states += (states.empty() ? "'" : ", '") + std::string(s) + "'";
    }
    roles += (roles.empty() ? "" : " OR ") + std::string("(m.role = '") + std::string(r.role) +
             "' AND " + t + ".state IN (" + states + "))";
  }
  *params = 2;
  // Never NULL (a NULL owner would make NOT of it NULL, and a variation
  // of an orphaned private route pass the sources' test).
  return "(" + t + ".is_public = 1 OR (" + t + ".owner_id IS NOT NULL AND " + t +
         ".owner_id = ?) OR (" + t +
         ".gym_id IS NOT NULL AND EXISTS (SELECT 1 FROM gym_members m WHERE m.gym_id = " + t +
         ".gym_id AND m.user_id = ? AND (" + roles + "))))";
}

}  // namespace sb::store
