#include "gym/rules.h"

#include <string>

namespace sb::gym {

namespace {

// The one name table of each enum, in enum order.
constexpr const char* kRoleNames[] = {"head", "setter", "climber"};
constexpr const char* kStateNames[] = {"draft", "planned", "set", "stripped"};
constexpr const char* kTickStateNames[] = {"ok", "held", "discarded"};

// The cycle's changes (from, to); MayChange reads only this.
struct Change {
  RouteState from, to;
};
constexpr Change kChanges[] = {
    {RouteState::kDraft, RouteState::kPlanned},   {RouteState::kDraft, RouteState::kSet},
    {RouteState::kPlanned, RouteState::kSet},     {RouteState::kPlanned, RouteState::kDraft},
    {RouteState::kSet, RouteState::kStripped},
};

// Which states of its gym's routes each role sees, by [role][state] in enum
// order; MemberSees reads only this.
constexpr bool kSees[3][4] = {
    /* head    */ {true, true, true, true},
    /* setter  */ {true, true, true, true},
    /* climber */ {false, false, true, true},
};

// "a, b or c" of a name table.
template <size_t N>
std::string Alternatives(const char* const (&names)[N]) {
  std::string out;
  for (size_t i = 0; i < N; ++i) {
    if (i > 0) out += i + 1 == N ? " or " : ", ";
    out += names[i];
  }
  return out;
}

// The value of `all` named `name` (NameOf), nullopt for none.
template <class E, size_t N>
std::optional<E> ByName(const E (&all)[N], std::string_view name) {
  for (E e : all) {
    if (name == NameOf(e)) return e;
  }
  return std::nullopt;
}

// ByName for input: kInvalidInput "<field>: expected <names>" for none.
template <class E, size_t N, size_t M>
Result<E> Parse(const E (&all)[N], const char* const (&names)[M], std::string_view name,
                std::string_view field) {
  if (std::optional<E> e = ByName(all, name)) return *e;
  return Status::InvalidInput(std::string(field) + ": expected " + Alternatives(names));
}

}  // namespace

const char* NameOf(Role r) { return kRoleNames[static_cast<int>(r)]; }

std::optional<Role> RoleOf(std::string_view name) { return ByName(kRoles, name); }

Result<Role> ParseRole(std::string_view name, std::string_view field) {
  return Parse(kRoles, kRoleNames, name, field);
}

bool CanSet(Role r) { return r == Role::kHead || r == Role::kSetter; }

bool CanSet(std::string_view role_name) {
  std::optional<Role> r = RoleOf(role_name);
  return r && CanSet(*r);
}

bool IsHead(std::string_view role_name) { return RoleOf(role_name) == Role::kHead; }

const char* NameOf(RouteState s) { return kStateNames[static_cast<int>(s)]; }

std::optional<RouteState> RouteStateOf(std::string_view name) {
  return ByName(kRouteStates, name);
}

Result<RouteState> ParseRouteState(std::string_view name, std::string_view field) {
  return Parse(kRouteStates, kStateNames, name, field);
}

bool MayChange(RouteState from, RouteState to) {
  for (const Change& c : kChanges) {
    if (c.from == from && c.to == to) return true;
  }
  return false;
}

Status CheckTransition(RouteState from, RouteState to) {
  if (MayChange(from, to)) return Status::Ok();
  if (from == to) {
    return Status::Conflict(std::string("state: the route is ") + NameOf(to) + " already");
  }
  return Status::Conflict(std::string("state: a ") + NameOf(from) + " route cannot become " +
                          NameOf(to) + " (plan → set → strip)");
}

const char* NameOf(TickState s) { return kTickStateNames[static_cast<int>(s)]; }

std::optional<TickState> TickStateOf(std::string_view name) { return ByName(kTickStates, name); }

Result<TickState> ParseTickState(std::string_view name, std::string_view field) {
  return Parse(kTickStates, kTickStateNames, name, field);
}

bool MemberSees(Role r, RouteState s) {
  return kSees[static_cast<int>(r)][static_cast<int>(s)];
}

bool DueForReset(std::optional<int> reset_weeks, std::optional<int64_t> age_days) {
  return reset_weeks && age_days && *age_days >= int64_t{*reset_weeks} * 7;
}

}  // namespace sb::gym
