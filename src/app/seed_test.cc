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

}  // namespace
}  // namespace sb::app
