#include "app/routes.h"

#include <gtest/gtest.h>

#include "app/app_test_util.h"

namespace sb::app {
namespace {

using testing::AppTest;
using testing::kCrimpLadder;
using testing::kSlabDance;
using Code = Status::Code;

TEST_F(AppTest, RoutesVisibilityAndOwnership) {
  Viewer alice = User("alice"), bob = User("bob"), anon;
  Routes& r = services_->routes;
  int64_t pub = AddRoute(alice, kCrimpLadder);
  int64_t priv = AddRoute(alice, kSlabDance, false);
  EXPECT_EQ(r.Get(anon, pub)->name, "Crimp Ladder");
  EXPECT_EQ(r.Get(anon, pub)->setter, "Carol");
  EXPECT_EQ(r.Get(anon, pub)->move_count, 6);
  EXPECT_TRUE(r.Get(alice, priv).ok());
  // A private route of someone else reads exactly like an absent one.
  Status hidden = r.Get(bob, priv).status(), absent = r.Get(bob, 987654).status();
  EXPECT_EQ(hidden.code(), Code::kNotFound);
  EXPECT_EQ(hidden.message(), "no route " + std::to_string(priv));
  EXPECT_EQ(absent.message(), "no route 987654");
  EXPECT_EQ(r.Get(anon, priv).status().code(), Code::kNotFound);

  EXPECT_EQ(r.List(anon, {})->size(), 1u);
  EXPECT_EQ(r.List(alice, {})->size(), 2u);
  RouteQuery q;
  q.grade = "v4";
  EXPECT_EQ(r.List(anon, q)->size(), 1u);
  q = {};
  q.limit = 0;
  EXPECT_EQ(r.List(anon, q).status().code(), Code::kInvalidInput);
  q.limit = 1'000'000;  // cut to the limit, not refused
  EXPECT_TRUE(r.List(anon, q).ok());

  // Changes: log in first, only the owner, invisible = absent.
  RouteEdit edit;
  edit.crdl = kSlabDance;
  EXPECT_EQ(r.Update(anon, pub, edit).code(), Code::kUnauthenticated);
  EXPECT_EQ(r.Update(bob, pub, edit).code(), Code::kPermission);
  EXPECT_EQ(r.Update(bob, priv, edit).code(), Code::kNotFound);
  EXPECT_EQ(r.Delete(bob, pub).code(), Code::kPermission);
  EXPECT_EQ(r.Delete(anon, pub).code(), Code::kUnauthenticated);
  ASSERT_TRUE(r.Update(alice, pub, edit).ok());
  EXPECT_EQ(r.Get(anon, pub)->name, "Slab Dance");
  RouteEdit hide;
  hide.is_public = false;
  ASSERT_TRUE(r.Update(alice, pub, hide).ok());
  EXPECT_EQ(r.Get(anon, pub).status().code(), Code::kNotFound);
  ASSERT_TRUE(r.Delete(alice, pub).ok());
  EXPECT_EQ(r.Get(alice, pub).status().code(), Code::kNotFound);
  EXPECT_EQ(r.Delete(alice, pub).code(), Code::kNotFound);
  EXPECT_EQ(r.Create(anon, kCrimpLadder, true).status().code(), Code::kUnauthenticated);
}

TEST_F(AppTest, BadCrdlIsRefusedWithItsLocationAsData) {
  Viewer alice = User("alice");
  Result<int64_t> id = services_->routes.Create(alice, "name: x\n---\nR jug\nX what\n", true);
  ASSERT_FALSE(id.ok());
  EXPECT_EQ(id.status().code(), Code::kInvalidInput);
  ASSERT_TRUE(id.status().location().has_value());
  EXPECT_EQ(id.status().location()->line, 4);
  EXPECT_EQ(id.status().location()->column, 1);
  EXPECT_EQ(id.status().reason(), "expected hand L or R, got \"X\"");
  int64_t ok = AddRoute(alice, kCrimpLadder);
  RouteEdit bad;
  bad.crdl = "name: y\n";  // no "---" (an empty move section is a route: issue 32)
  EXPECT_EQ(services_->routes.Update(alice, ok, bad).code(), Code::kInvalidInput);
  EXPECT_EQ(services_->routes.Get(alice, ok)->name, "Crimp Ladder");  // unchanged
}

}  // namespace
}  // namespace sb::app
