// The visibility rule of routes (issue 31, docs/web.md "Who sees a route"):
// written once, here, and applied both in C++ (Sees, over a route read from
// the store) and in SQL (SeesSql, the WHERE term of every route list and
// search on both backends), from the same table of roles and states.
#ifndef SB_STORE_VISIBILITY_H_
#define SB_STORE_VISIBILITY_H_

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include "gym/rules.h"

namespace sb::store {

// Where a route is asked for.
enum class Reach {
  // Lists, search, the route's pages and JSON, history, exports, tag sheets.
  kListed,
  // The climbers' page of one route, `/r/{id}` (the QR code on its tag):
  // a gym route on the wall (state "set") is shown to anyone who has it.
  kOnTheWall,
};

// What the rule reads of a route (RouteRecord and SourceRoute have these).
struct RouteSight {
  bool in_library = false;          // routes.is_public: "public" / "library"
  std::optional<int64_t> owner_id;  // nullopt: seeded or orphaned
  std::optional<int64_t> gym_id;    // nullopt: a personal route
  gym::RouteState state = gym::RouteState::kDraft;
};

// Whether a member of a route's gym with `role` ("head", "setter",
// "climber"; "" for no member) sees a route of that gym in `state`: head
// setters and setters see every state, climbers only routes set or stripped.
// Pure.
bool MemberSees(std::string_view role, std::string_view state);

// The rule for one route (not its sources): the viewer (`viewer`, nullopt
// when logged out) sees it when
//   - the route is in the shared library (a personal route made public, a
//     gym route its gym published: off by default for gym routes), or
//   - the viewer owns it, or
//   - the viewer's role in the route's gym (`role_in_gym`, "" for none)
//     sees its state (MemberSees), or
//   - reach is kOnTheWall and it is a gym route in state "set".
// A variation is seen only when every route it was made from is seen too,
// each by this rule with Reach::kListed (the caller loops over the sources:
// app::IsVisible). Pure.
bool Sees(const RouteSight& r, std::optional<int64_t> viewer, std::string_view role_in_gym,
          Reach reach = Reach::kListed);

// The same rule (Reach::kListed) as an SQL condition over the routes
// aliased `t` (columns is_public, owner_id, gym_id, state), reading the
// viewer's roles from gym_members. Every '?' in it is the viewer's id (-1
// when logged out); `*params` is set to their count. The same text on both
// backends.
std::string SeesSql(std::string_view t, int* params);

}  // namespace sb::store

#endif  // SB_STORE_VISIBILITY_H_
