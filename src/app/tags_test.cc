#include "app/tags.h"

#include <gtest/gtest.h>

#include "app/app_test_util.h"

namespace sb::app {
namespace {

using testing::AppTest;
using Code = Status::Code;

TEST(TagInfoTest, ARouteRecordFillsTheTag) {
  RouteView r;
  r.id = 7;
  r.name = "Crimp Ladder";
  r.grade = "V4";
  r.colour = "blue";
  r.wall = "the cave";
  r.setter = "Carol, Dan ,";
  r.owner_name = "alice";
  r.set_on = "2026-11-20";
  r.created_at = "2026-11-01T10:00:00Z";
  plan::TagInfo t = TagInfoOf(r, "http://gym/r/7");
  EXPECT_EQ(t.name, "Crimp Ladder");
  EXPECT_EQ(t.grade, "V4");
  EXPECT_EQ(t.colour, "blue");
  EXPECT_EQ(t.wall, "the cave");
  EXPECT_EQ(t.setters, (std::vector<std::string>{"Carol", "Dan"}));
  EXPECT_EQ(t.set_on, "2026-11-20");
  EXPECT_EQ(t.url, "http://gym/r/7");
  // No setter or set date: the owner, the day it was added.
  r.setter.clear();
  r.set_on.clear();
  t = TagInfoOf(r, "");
  EXPECT_EQ(t.setters, std::vector<std::string>{"alice"});
  EXPECT_EQ(t.set_on, "2026-11-01");
}

TEST_F(AppTest, ASheetPrintsVisibleRoutesInOrderUpToTheLimit) {
  Viewer alice = User("alice"), bob = User("bob");
  const int64_t a = AddRoute(alice, testing::kCrimpLadder);
  const int64_t b = AddRoute(alice, testing::kSlabDance, false);
  Limits limits;
  limits.max_tag_sheet_routes = 3;
  Result<std::vector<RouteView>> got =
      TagSheetRoutes(services_->routes, alice, {b, a, b}, limits);
  ASSERT_TRUE(got.ok()) << got.status().message();
  ASSERT_EQ(got->size(), 3u);
  EXPECT_EQ((*got)[0].id, b);
  EXPECT_EQ((*got)[1].id, a);
  // Another user's private route: "no route N", as for a missing one.
  Status hidden = TagSheetRoutes(services_->routes, bob, {a, b}, limits).status();
  EXPECT_EQ(hidden.code(), Code::kNotFound);
  EXPECT_EQ(hidden.message(), "no route " + std::to_string(b));
  Status over = TagSheetRoutes(services_->routes, alice, {a, a, a, a}, limits).status();
  EXPECT_EQ(over.code(), Code::kInvalidInput);
  EXPECT_NE(over.message().find("at most 3"), std::string::npos) << over.message();
  EXPECT_EQ(TagSheetRoutes(services_->routes, alice, {}, limits).status().code(),
            Code::kInvalidInput);
}

}  // namespace
}  // namespace sb::app
