// Tests of the rendered-answer cache (issue 22): the LRU helper's bounds and
// stamps, and that a gym's stamp moves with a write (both backends).
#include "app/render_cache.h"

#include <gtest/gtest.h>

#include "app/app_test_util.h"
#include "store/gym_store.h"

namespace sb::app {
namespace {

TEST(StampedLruTest, AHitNeedsTheSameStampAndTheLeastRecentlyUsedGoesFirst) {
  StampedLru<int, std::string> lru(/*max_entries=*/2, /*max_bytes=*/100);
  const Stamp s1{1, 10}, s2{2, 10}, next_day{1, 11};
  lru.Keep(1, s1, std::make_shared<const std::string>("one"), 3);
  ASSERT_NE(lru.Find(1, s1), nullptr);
  EXPECT_EQ(*lru.Find(1, s1), "one");
  EXPECT_EQ(lru.Find(1, s2), nullptr);        // a write moved the version
  EXPECT_EQ(lru.Find(1, next_day), nullptr);  // a new day: ages change
  EXPECT_EQ(lru.Find(2, s1), nullptr);
  lru.Keep(2, s1, std::make_shared<const std::string>("two"), 3);
  ASSERT_NE(lru.Find(1, s1), nullptr);  // 1 is now the most recently used
  lru.Keep(3, s1, std::make_shared<const std::string>("three"), 5);
  EXPECT_EQ(lru.size(), 2u);
  EXPECT_EQ(lru.Find(2, s1), nullptr);  // dropped: least recently used
  EXPECT_NE(lru.Find(1, s1), nullptr);
  EXPECT_NE(lru.Find(3, s1), nullptr);
  // Replacing an entry keeps one entry for the key, at the new stamp.
  lru.Keep(3, s2, std::make_shared<const std::string>("THREE"), 5);
  EXPECT_EQ(lru.size(), 2u);
  EXPECT_EQ(lru.Find(3, s1), nullptr);
  EXPECT_EQ(*lru.Find(3, s2), "THREE");
}

TEST(StampedLruTest, TheByteBoundDropsOldEntriesAndRefusesOversizedOnes) {
  StampedLru<int, std::string> lru(/*max_entries=*/10, /*max_bytes=*/100);
  const Stamp s{1, 1};
  lru.Keep(1, s, std::make_shared<const std::string>("a"), 60);
  lru.Keep(2, s, std::make_shared<const std::string>("b"), 60);  // 120 > 100: 1 goes
  EXPECT_EQ(lru.Find(1, s), nullptr);
  EXPECT_NE(lru.Find(2, s), nullptr);
  lru.Keep(3, s, std::make_shared<const std::string>("c"), 101);  // too big alone
  EXPECT_EQ(lru.Find(3, s), nullptr);
  EXPECT_NE(lru.Find(2, s), nullptr);
  // A value handed out stays valid after its entry is dropped.
  std::shared_ptr<const std::string> held = lru.Find(2, s);
  lru.Keep(4, s, std::make_shared<const std::string>("d"), 90);
  EXPECT_EQ(lru.Find(2, s), nullptr);
  EXPECT_EQ(*held, "b");
}

class RenderCacheTest : public testing::AppTest {};

TEST_F(RenderCacheTest, AGymsStampMovesWithEveryWriteAndTheDay) {
  Viewer head = User("head");
  Result<int64_t> created = store::GymStoreOf(store_.get())->CreateGym("Gym", head.user_id);
  ASSERT_TRUE(created.ok()) << created.status().message();
  const int64_t gym = *created;
  RenderCache& cache = services_->rendered;
  Result<std::optional<Stamp>> before = cache.StampOf(gym);
  ASSERT_TRUE(before.ok()) << before.status().message();
  ASSERT_TRUE(before->has_value());
  const RenderKey key{"wall", 7, *head.user_id};
  cache.Keep(key, **before, "old page");
  ASSERT_NE(cache.Find(key, **before), nullptr);
  EXPECT_EQ(*cache.Find(key, **cache.StampOf(gym)), "old page");  // nothing written: a hit

  Wall w;
  w.gym_id = gym;
  w.name = "Cave";
  ASSERT_TRUE(services_->gyms.AddWall(head, w).ok());
  Result<std::optional<Stamp>> after = cache.StampOf(gym);
  ASSERT_TRUE(after.ok() && after->has_value());
  EXPECT_GT((*after)->version, (*before)->version);
  EXPECT_EQ(cache.Find(key, **after), nullptr);  // the write shows on the next request
  clock_.Advance(86400);
  EXPECT_EQ((**cache.StampOf(gym)).day, (*after)->day + 1);
  // A gym that does not exist has no stamp: nothing is kept for it.
  Result<std::optional<Stamp>> none = cache.StampOf(987654);
  ASSERT_TRUE(none.ok());
  EXPECT_FALSE(none->has_value());
}

}  // namespace
}  // namespace sb::app
