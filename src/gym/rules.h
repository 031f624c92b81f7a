// The gym's rules (issue 31): one home for the names and rules of a gym's
// nouns that the store (SQL) and the application layer (every check) both
// read. Roles and route states are enum classes with one name table each
// (the names are what the database, the JSON API, CRDL headers and forms
// spell); the cycle's state changes, the members' visibility table and the
// "due for a reset" rule are written here once.
//
// Everything here is a pure function or a constant: thread-safe, no
// allocation except the error texts of the Parse* functions.
#ifndef SB_GYM_RULES_H_
#define SB_GYM_RULES_H_

#include <cstdint>
#include <optional>
#include <string_view>

#include "base/status.h"

namespace sb::gym {

// ---- roles ------------------------------------------------------------------

// A member's role in a gym: head setter (manages the team, walls, circuits,
// targets), setter (creates and edits the gym's routes), climber (ticks).
enum class Role { kHead, kSetter, kClimber };
inline constexpr Role kRoles[] = {Role::kHead, Role::kSetter, Role::kClimber};

// The role's name: "head", "setter", "climber" (the stored and API spelling).
// Never null; a static string.
const char* NameOf(Role r);
// The role named exactly `name` (no trimming, no case folding); nullopt for
// any other text, "" included.
std::optional<Role> RoleOf(std::string_view name);
// As RoleOf for input: kInvalidInput "<field>: expected head, setter or
// climber" when `name` names no role.
Result<Role> ParseRole(std::string_view name, std::string_view field = "role");
// Whether the role creates and edits the gym's routes (head or setter).
bool CanSet(Role r);
// The same for a role name; false for "" (no member) and unknown names.
bool CanSet(std::string_view role_name);
// Whether `role_name` names the head-setter role.
bool IsHead(std::string_view role_name);

// ---- route states and the cycle ---------------------------------------------

// A gym route's state: a draft (its owner's), planned (for a setting day),
// set (on the wall), stripped (the archive).
enum class RouteState { kDraft, kPlanned, kSet, kStripped };
inline constexpr RouteState kRouteStates[] = {RouteState::kDraft, RouteState::kPlanned,
                                              RouteState::kSet, RouteState::kStripped};

// The state's name: "draft", "planned", "set", "stripped". Never null.
const char* NameOf(RouteState s);
// The state named exactly `name`; nullopt for any other text.
std::optional<RouteState> RouteStateOf(std::string_view name);
// As RouteStateOf for input: kInvalidInput "<field>: expected draft,
// planned, set or stripped" when `name` names no state.
Result<RouteState> ParseRouteState(std::string_view name, std::string_view field = "state");

// Whether the text `name` is the name of `s` (for text at a boundary; a
// record's state is the enum: compare with ==).
inline bool Is(std::string_view name, RouteState s) { return name == NameOf(s); }
// Whether the text `name` is the name of `r`.
inline bool Is(std::string_view name, Role r) { return name == NameOf(r); }

// Whether a route may change from `from` to `to` by a state change (the
// cycle plan → set → strip): draft → planned or set; planned → set or back
// to draft; set → stripped. Nothing leaves the archive (stripped), and no
// state changes to itself.
bool MayChange(RouteState from, RouteState to);
// MayChange as a Status: kConflict "state: the route is X already" or
// "state: a X route cannot become Y (plan → set → strip)".
Status CheckTransition(RouteState from, RouteState to);

// ---- tick states ---------------------------------------------------------------

// A tick's state (issue 23): counted (ok), held back as part of a burst for
// the gym's setters to accept or discard, or discarded (kept, never counted).
enum class TickState { kOk, kHeld, kDiscarded };
inline constexpr TickState kTickStates[] = {TickState::kOk, TickState::kHeld,
                                            TickState::kDiscarded};

// The tick state's name: "ok", "held", "discarded" (the stored and API
// spelling). Never null.
const char* NameOf(TickState s);
// The tick state named exactly `name`; nullopt for any other text.
std::optional<TickState> TickStateOf(std::string_view name);
// As TickStateOf for input: kInvalidInput "<field>: expected ok, held or
// discarded" when `name` names no tick state.
Result<TickState> ParseTickState(std::string_view name, std::string_view field = "state");

// ---- visibility ---------------------------------------------------------------

// The members' part of the visibility rule (docs/web.md "Who sees a route";
// the whole rule: store/visibility.h): whether a member of a route's gym
// with role `r` sees a route of that gym in state `s`. Head setters and
// setters see every state, climbers only set and stripped routes. The one
// table both the C++ predicate and the SQL condition are made from.
bool MemberSees(Role r, RouteState s);
// The state of a route on the wall: its climbers' page `/r/{id}` (the QR code
// of its tag) is shown to anyone who has the link.
inline constexpr RouteState kOnTheWall = RouteState::kSet;

// ---- resets -------------------------------------------------------------------

// Whether a wall with a reset cycle of `reset_weeks` (nullopt: none) is due
// for a reset when its oldest route on the wall was set `age_days` ago
// (nullopt: no route or no set date): the age has reached the cycle. A wall
// without a cycle is never due.
bool DueForReset(std::optional<int> reset_weeks, std::optional<int64_t> age_days);

}  // namespace sb::gym

#endif  // SB_GYM_RULES_H_
