#include "app/seed.h"

#include <gtest/gtest.h>

#include "app/app_test_util.h"
#include "base/files.h"

namespace sb::app {
namespace {

using testing::AppTest;

TEST_F(AppTest, DemoAccountAndExamples) {
  std::filesystem::create_directories(dir_ / "ex");
  ASSERT_TRUE(WriteFileAtomic((dir_ / "ex" / "b.crdl").string(), "name: B\n---\nR jug\n").ok());
  ASSERT_TRUE(WriteFileAtomic((dir_ / "ex" / "a.crdl").string(), "---\nL crimp\n").ok());
  ASSERT_TRUE(WriteFileAtomic((dir_ / "ex" / "bad.crdl").string(), "no separator\n").ok());
  Result<int64_t> demo = EnsureDemoAccount(store_.get(), true);
  ASSERT_TRUE(demo.ok());
  EXPECT_EQ(*EnsureDemoAccount(store_.get(), true), *demo);
  std::vector<std::string> skipped;
  Result<int> n = SeedExamples(store_.get(), (dir_ / "ex").string(), *demo, &skipped);
  ASSERT_TRUE(n.ok());
  EXPECT_EQ(*n, 2);
  EXPECT_EQ(skipped.size(), 1u);
  auto all = store_->AllRoutes(std::nullopt);
  ASSERT_EQ(all->size(), 2u);
  EXPECT_EQ((*all)[0].name, "a");  // the file stem names an unnamed route
  EXPECT_EQ((*all)[1].name, "B");
  EXPECT_EQ(*SeedExamples(store_.get(), (dir_ / "nope").string(), *demo, nullptr), 0);
  EXPECT_TRUE(services_->accounts.LogIn(kDemoUser, kDemoPassword, "1.2.3.4").ok());
  EXPECT_FALSE(DefaultExamplesDir().empty());
}

// Issue 34: a non-demo install's first account has no published password:
// a fresh random one, shown once, that logs in; the demo password does not.
TEST_F(AppTest, FirstAccountHasAOneTimeRandomPassword) {
  std::string password;
  Result<int64_t> first = CreateFirstAccount(store_.get(), &password, true);
  ASSERT_TRUE(first.ok()) << first.status().message();
  EXPECT_EQ(password.size(), 24u);
  EXPECT_NE(password, kDemoPassword);
  EXPECT_TRUE(services_->accounts.LogIn(kFirstUser, password, "1.2.3.4").ok());
  EXPECT_FALSE(services_->accounts.LogIn(kFirstUser, kDemoPassword, "1.2.3.5").ok());
  EXPECT_FALSE(store_->FindUserByName(kDemoUser).ok());
  std::string again;
  EXPECT_EQ(CreateFirstAccount(store_.get(), &again, true).status().code(),
            Status::Code::kConflict);
  EXPECT_TRUE(again.empty());
}

// make run's demo: a gym whose head setter is the demo account, two circuits,
// a wall row per distinct `wall:` text, every example on the wall.
TEST_F(AppTest, DemoGymHoldsTheExamplesOnItsWalls) {
  std::filesystem::create_directories(dir_ / "ex");
  const char* files[][2] = {{"a.crdl", "name: A\nwall: big roof\n---\nR jug\n"},
                            {"b.crdl", "name: B\nwall: slab\n---\nL crimp\n"},
                            {"c.crdl", "name: C\nwall: big roof\n---\nR sloper\n"},
                            {"d.crdl", "name: D\n---\nR pinch\n"}};
  for (const auto& [name, text] : files) {
    ASSERT_TRUE(WriteFileAtomic((dir_ / "ex" / name).string(), text).ok());
  }
  Result<int64_t> demo = EnsureDemoAccount(store_.get(), true);
  ASSERT_TRUE(demo.ok());
  Result<int64_t> gym = EnsureDemoGym(store_.get(), "Demo Gym", *demo);
  ASSERT_TRUE(gym.ok()) << gym.status().message();
  Result<int> n = SeedExamples(store_.get(), (dir_ / "ex").string(), *demo, nullptr, *gym);
  ASSERT_TRUE(n.ok()) << n.status().message();
  EXPECT_EQ(*n, 4);
  Viewer head;
  head.user_id = *demo;
  head.username = kDemoUser;
  Result<std::vector<Wall>> walls = services_->gyms.Walls(head, *gym);
  ASSERT_TRUE(walls.ok()) << walls.status().message();
  ASSERT_EQ(walls->size(), 2u);
  EXPECT_EQ((*walls)[0].name, "big roof");
  EXPECT_EQ((*walls)[0].angle, 45);
  EXPECT_EQ((*walls)[1].name, "slab");
  EXPECT_EQ((*walls)[1].angle, -10);
  EXPECT_EQ(services_->gyms.Circuits(head, *gym)->size(), 2u);
  EXPECT_EQ(*services_->gyms.RoleIn(head, *gym), "head");
  auto all = store_->AllRoutes(std::nullopt);
  ASSERT_EQ(all->size(), 4u);
  for (const store::RouteRecord& r : *all) {
    EXPECT_EQ(r.gym_id, *gym) << r.name;
    EXPECT_EQ(r.state, gym::RouteState::kSet) << r.name;
    EXPECT_EQ(r.wall_id.has_value(), r.name != "D") << r.name;
  }
  EXPECT_EQ((*all)[0].wall_id, (*all)[2].wall_id);  // A and C share the roof
}

}  // namespace
}  // namespace sb::app
