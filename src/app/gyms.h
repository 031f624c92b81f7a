// Gyms (issue 21): a gym, its team (head setters, setters, climbers), its
// walls and circuits, and the role rules every gym request passes. Routes
// (app/routes.h) use the same rules for a route's gym fields.
//
// The rules (docs/web.md "Gyms"):
// - whoever creates a gym is its head setter; the install's first gym's
//   first account (Welcome) is its head setter;
// - a head setter manages members, walls and circuits;
// - head setters and setters create and edit the gym's routes; climbers
//   cannot edit;
// - a gym's ids answer kNotFound to anyone who is not a member (never its
//   data); a member without the role gets kPermission.
#ifndef SB_APP_GYMS_H_
#define SB_APP_GYMS_H_

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "app/options.h"
#include "base/status.h"
#include "gym/records.h"
#include "gym/rules.h"
#include "store/gym_store.h"
#include "store/store.h"

namespace sb::app {

// ---- the app's view types (web and cli render from these) -----------------

// A gym as a member sees it: `role` is the viewer's ("head", "setter",
// "climber").
struct Gym {
  int64_t id = 0;
  std::string name;
  std::string role;
  int64_t revision = 0;  // issue 31: one more on every rename
};

// A member (its role: "head", "setter", "climber"), a wall (or sector; the
// floor-plan rectangle is all set or all unset) and a circuit (a tape colour
// with an optional grade range): the gym's nouns of gym/records.h, the same
// structs the store keeps. A wall or circuit edited with revision > 0 is
// refused (kConflict) unless that is the stored one (issue 31).
using Member = gym::Member;
using Wall = gym::Wall;
using Circuit = gym::Circuit;

// One change of a gym's set-up (issue 31): who, when, what.
struct GymHistoryEntry {
  std::string who;
  std::string at;
  std::string what;
};

// One change of a route: who, when ("YYYY-MM-DD HH:MM:SS" UTC), what.
struct HistoryEntry {
  std::string who;
  std::string at;
  std::string what;
};

// Limits of the gym records, with their reasons.
struct GymLimits {
  // Gym, wall and member names print on tags and page titles.
  static constexpr size_t kMaxNameBytes = 100;
  // A circuit colour is a word or two ("blue", "neon green").
  static constexpr size_t kMaxColourBytes = 40;
  // Angles: from a slab lying back 90 degrees to a roof (90 past vertical).
  static constexpr double kMinAngle = -90, kMaxAngle = 90;
  // A reset cycle longer than two years is no cycle.
  static constexpr int kMaxResetWeeks = 104;
  // Floor-plan grid cells per side (a gym's floor in half-metre cells).
  static constexpr int kMaxPlanCells = 1000;
  // Setters named on one route.
  static constexpr size_t kMaxSetters = 10;
  // Gyms one account may create (a chain's head setter: tens of gyms).
  static constexpr size_t kMaxGymsPerAccount = 50;
};

// The roles and route states, their names and the cycle's one rule (plan →
// set → strip) live in gym/rules.h (issue 31, one home for the gym's
// rules); the app and its callers name them through these.
using gym::CanSet;
using gym::CheckTransition;
using gym::NameOf;
using gym::Role;
using gym::RouteState;
using gym::RouteStateOf;
// Whether `role` names a role ("head", "setter", "climber").
inline bool IsRole(std::string_view role) { return gym::RoleOf(role).has_value(); }
// Whether `state` names a route state (draft, planned, set, stripped).
inline bool IsRouteState(std::string_view state) { return gym::RouteStateOf(state).has_value(); }

// Checks a wall's fields; kInvalidInput naming the field.
Status ValidateWall(const Wall& w);

// Thread-safe. Does not own `store`.
class Gyms {
 public:
  Gyms(store::Store* store, const Options& options);

  // Creates the install's first gym named `name` when there is none (run
  // when the services start). Errors: the store's.
  Status EnsureFirstGym(const std::string& name);
  // After a sign-up: when the install's first gym has no members, the new
  // account becomes its head setter. Errors: the store's.
  Status Welcome(int64_t user_id);

  // Creates a gym with the viewer as its head setter. Errors:
  // kUnauthenticated; kInvalidInput "name: ..."; kResourceExhausted beyond
  // kMaxGymsPerAccount.
  Result<int64_t> Create(const Viewer& v, const std::string& name);
  // Head setters only: renames the gym. Errors as AddMember, kInvalidInput
  // "name: ..."; kConflict when `revision` > 0 is not the stored one.
  // Recorded in the gym's history.
  Status Rename(const Viewer& v, int64_t gym, const std::string& name, int64_t revision = 0);
  // The viewer's gyms with their role (none when not logged in).
  Result<std::vector<Gym>> Mine(const Viewer& v);
  // A gym the viewer is a member of; kNotFound "no gym N" otherwise.
  Result<Gym> Get(const Viewer& v, int64_t gym);
  // The viewer's role in `gym` ("" when not a member or not logged in).
  Result<std::string> RoleIn(const Viewer& v, int64_t gym);
  // The gym a request without one means: the viewer's only gym, else the
  // install's first; nullopt when there is no gym. (Reads only: a write
  // names its gym through WriteGym.)
  Result<std::optional<int64_t>> DefaultGym(const Viewer& v);
  // The gym a route write (create, import, variation) goes to (issue 31:
  // every write names its gym; never the install's first gym by default).
  // `asked` given: that gym, when the viewer is its setter or head setter
  // (kNotFound "no gym N" for a non-member, kPermission for a climber).
  // `asked` absent: no gym (a personal route) for an account in no gym or
  // only a climber of one gym; the gym itself for its one setter or head
  // setter; kInvalidInput "gym: ..." for a member of two or more gyms.
  // `personal` (the request's "gym": null): no gym, whatever the memberships.
  // `what` ends the permission message ("add routes to it").
  Result<std::optional<int64_t>> WriteGym(const Viewer& v, std::optional<int64_t> asked,
                                          bool personal, const std::string& what);

  // Head setters only: adds `username` to the gym as `role` (or changes
  // their role). Errors: kNotFound (not a member, or no such user),
  // kPermission (not the head setter), kInvalidInput (role).
  Status AddMember(const Viewer& v, int64_t gym, const std::string& username,
                   const std::string& role);
  // Members only (kNotFound otherwise).
  Result<std::vector<Member>> Members(const Viewer& v, int64_t gym);
  // Head setters only (issue 31): changes a member's role (kNotFound when
  // `username` is no member) or removes them; a head setter neither demotes
  // nor removes themselves (kInvalidInput). Takes effect on the next request
  // (roles are read per request). Recorded in the gym's history.
  Status SetRole(const Viewer& v, int64_t gym, const std::string& username,
                 const std::string& role);
  Status RemoveMember(const Viewer& v, int64_t gym, const std::string& username);
  // Setters and head setters: the gym's history, oldest first.
  Result<std::vector<GymHistoryEntry>> GymHistory(const Viewer& v, int64_t gym);

  // Head setters only: a new wall (gym_id = `w.gym_id`) or an edit of one
  // (every field of `w` replaces the stored one). Errors: kNotFound for
  // another gym's ids, kPermission, kInvalidInput (ValidateWall), kConflict
  // for a name the gym has.
  // EditWall: kConflict when w.revision > 0 is not the stored revision.
  // DeleteWall: kConflict "N routes are on the wall" while routes not
  // stripped are on it (stripped ones keep its name). Each is recorded in
  // the gym's history.
  Result<int64_t> AddWall(const Viewer& v, const Wall& w);
  Status EditWall(const Viewer& v, const Wall& w);
  Status DeleteWall(const Viewer& v, int64_t gym, int64_t wall);
  // Members only.
  Result<std::vector<Wall>> Walls(const Viewer& v, int64_t gym);
  Result<Wall> GetWall(const Viewer& v, int64_t wall);
  // A wall of `gym` by id ("12") or by name (ignoring case), with no role
  // check (the caller has checked the role). kNotFound "no wall ..." when
  // the gym has none such.
  Result<Wall> ResolveWall(int64_t gym, const std::string& id_or_name);

  // Head setters only: a new circuit. Errors as AddWall; grade_from /
  // grade_to must be grades (any scale) when given.
  Result<int64_t> AddCircuit(const Viewer& v, const Circuit& c);
  // Head setters only (issue 31): replaces circuit c.id of c.gym_id
  // (kNotFound for another gym's; kConflict as EditWall) or removes it.
  Status EditCircuit(const Viewer& v, const Circuit& c);
  // Removing a circuit clears it from the routes set in it (they keep their
  // colour; each one's history and the gym's say so).
  Status DeleteCircuit(const Viewer& v, int64_t gym, int64_t circuit);
  // A circuit of `gym` by id ("12") or colour (ignoring case), with no role
  // check (the caller has checked the role). "circuit: ..." when
  // the gym has none such (kInvalidInput, issue 31).
  Result<Circuit> ResolveCircuit(int64_t gym, const std::string& id_or_colour);
  // Members only.
  Result<std::vector<Circuit>> Circuits(const Viewer& v, int64_t gym);

  // The history of a route, oldest first (the caller checks visibility).
  Result<std::vector<HistoryEntry>> History(int64_t route_id);

  // The viewer's memberships (Viewer::gyms); empty when not logged in.
  Result<std::vector<GymRole>> RolesOf(const Viewer& v);

 private:
  // The viewer's role, kNotFound "no gym N" when not a member.
  Result<std::string> MemberRole(const Viewer& v, int64_t gym);
  Status RequireHead(const Viewer& v, int64_t gym);
  // A member of `gym` by user name (kNotFound "username: ..." otherwise).
  Result<store::MemberRecord> FindMember(int64_t gym, const std::string& username);
  // A circuit of `gym` (kNotFound "no circuit N" otherwise).
  Result<Circuit> FindCircuit(int64_t gym, int64_t circuit);
  // Appends `what` by the viewer to the gym's history.
  Status Record(const Viewer& v, int64_t gym, const std::string& what);

  store::Store* store_;
  store::GymStore* gyms_;
  const Options options_;
};

}  // namespace sb::app

#endif  // SB_APP_GYMS_H_
