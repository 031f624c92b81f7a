#include "gym/rules.h"

#include <set>
#include <string>
#include <utility>

#include <gtest/gtest.h>

namespace sb::gym {
namespace {

TEST(GymRules, RoleNamesRoundTrip) {
  std::set<std::string> names;
  for (Role r : kRoles) {
    ASSERT_NE(NameOf(r), nullptr);
    EXPECT_EQ(RoleOf(NameOf(r)), r) << NameOf(r);
    Result<Role> parsed = ParseRole(NameOf(r));
    ASSERT_TRUE(parsed.ok());
    EXPECT_EQ(*parsed, r);
    names.insert(NameOf(r));
  }
  EXPECT_EQ(names, (std::set<std::string>{"head", "setter", "climber"}));
}

TEST(GymRules, UnknownRolesAreRefusedNamingTheField) {
  for (const char* bad : {"", "Head", " head", "setter ", "admin", "owner", "draft"}) {
    EXPECT_FALSE(RoleOf(bad)) << bad;
    Result<Role> r = ParseRole(bad, "members[1].role");
    ASSERT_FALSE(r.ok()) << bad;
    EXPECT_EQ(r.status().code(), Status::Code::kInvalidInput);
    EXPECT_EQ(r.status().message(), "members[1].role: expected head, setter or climber");
  }
  EXPECT_EQ(ParseRole("x").status().message(), "role: expected head, setter or climber");
}

TEST(GymRules, WhoSets) {
  EXPECT_TRUE(CanSet(Role::kHead));
  EXPECT_TRUE(CanSet(Role::kSetter));
  EXPECT_FALSE(CanSet(Role::kClimber));
  EXPECT_TRUE(CanSet("head"));
  EXPECT_TRUE(CanSet("setter"));
  EXPECT_FALSE(CanSet("climber"));
  EXPECT_FALSE(CanSet(""));
  EXPECT_FALSE(CanSet("Setter"));
  EXPECT_TRUE(IsHead("head"));
  EXPECT_FALSE(IsHead("setter"));
  EXPECT_FALSE(IsHead(""));
}

TEST(GymRules, StateNamesRoundTrip) {
  std::set<std::string> names;
  for (RouteState s : kRouteStates) {
    EXPECT_EQ(RouteStateOf(NameOf(s)), s) << NameOf(s);
    Result<RouteState> parsed = ParseRouteState(NameOf(s));
    ASSERT_TRUE(parsed.ok());
    EXPECT_EQ(*parsed, s);
    EXPECT_TRUE(Is(NameOf(s), s));
    names.insert(NameOf(s));
  }
  EXPECT_EQ(names, (std::set<std::string>{"draft", "planned", "set", "stripped"}));
  EXPECT_FALSE(Is("set", RouteState::kStripped));
  EXPECT_TRUE(Is("climber", Role::kClimber));
}

TEST(GymRules, UnknownStatesAreRefusedNamingTheField) {
  for (const char* bad : {"", "Set", "set ", "archived", "on the wall", "head"}) {
    EXPECT_FALSE(RouteStateOf(bad)) << bad;
    Result<RouteState> s = ParseRouteState(bad, "to");
    ASSERT_FALSE(s.ok()) << bad;
    EXPECT_EQ(s.status().code(), Status::Code::kInvalidInput);
    EXPECT_EQ(s.status().message(), "to: expected draft, planned, set or stripped");
  }
}

// Every pair of states: exactly the cycle's changes are allowed.
TEST(GymRules, TheCycleAndNothingElse) {
  using S = RouteState;
  const std::set<std::pair<S, S>> allowed = {{S::kDraft, S::kPlanned},
                                             {S::kDraft, S::kSet},
                                             {S::kPlanned, S::kSet},
                                             {S::kPlanned, S::kDraft},
                                             {S::kSet, S::kStripped}};
  int refused = 0;
  for (S from : kRouteStates) {
    for (S to : kRouteStates) {
      const bool want = allowed.count({from, to}) > 0;
      EXPECT_EQ(MayChange(from, to), want) << NameOf(from) << " -> " << NameOf(to);
      Status s = CheckTransition(from, to);
      EXPECT_EQ(s.ok(), want) << NameOf(from) << " -> " << NameOf(to);
      if (want) continue;
      ++refused;
      EXPECT_EQ(s.code(), Status::Code::kConflict);
      EXPECT_EQ(s.message().rfind("state: ", 0), 0u) << s.message();
    }
  }
  EXPECT_EQ(refused, 16 - 5);
  EXPECT_EQ(CheckTransition(S::kSet, S::kSet).message(), "state: the route is set already");
  EXPECT_EQ(CheckTransition(S::kStripped, S::kSet).message(),
            "state: a stripped route cannot become set (plan → set → strip)");
}

TEST(GymRules, MembersSeeTheirRolesStates) {
  for (RouteState s : kRouteStates) {
    EXPECT_TRUE(MemberSees(Role::kHead, s)) << NameOf(s);
    EXPECT_TRUE(MemberSees(Role::kSetter, s)) << NameOf(s);
    EXPECT_EQ(MemberSees(Role::kClimber, s), s == RouteState::kSet || s == RouteState::kStripped)
        << NameOf(s);
  }
  EXPECT_EQ(kOnTheWall, RouteState::kSet);
}

TEST(GymRules, DueForAReset) {
  EXPECT_FALSE(DueForReset(std::nullopt, 1000));  // no cycle: never due
  EXPECT_FALSE(DueForReset(6, std::nullopt));      // nothing on the wall
  EXPECT_FALSE(DueForReset(6, 41));
  EXPECT_TRUE(DueForReset(6, 42));  // the day the cycle is reached
  EXPECT_TRUE(DueForReset(6, 43));
  EXPECT_TRUE(DueForReset(1, 7));
  EXPECT_FALSE(DueForReset(1, 6));
}

}  // namespace
}  // namespace sb::gym
