// TargetStore (schema 8) on both backends: a wall's targets are replaced as
// a whole, listed in byte order, kept per wall, gone with the wall's gym;
// bad kinds, duplicate names and unknown walls are refused without a change.
#include "store/target_store.h"

#include <gtest/gtest.h>

#include <memory>
#include <string>
#include <tuple>
#include <vector>

#include "store/test_backends.h"
#include "store/tick_store.h"

namespace sb::store {
namespace {

class TargetStoreTest : public testing::BackendTest {
 protected:
  TargetStoreTest() : BackendTest("target", testing::Make::kStoreAndGym) {}
  void SetUpStore() override {
    targets_ = TargetStoreOf(store_.get());
    ASSERT_NE(targets_, nullptr);
    gyms_ = GymStoreOf(store_.get());
    WallRecord w;
    w.gym_id = gym_;
    w.name = "Cave";
    cave_ = *gyms_->InsertWall(w);
    w.name = "Slab";
    slab_ = *gyms_->InsertWall(w);
  }

  TargetStore* targets_ = nullptr;
  GymStore* gyms_ = nullptr;
  int64_t cave_ = 0, slab_ = 0;
};

INSTANTIATE_TEST_SUITE_P(Backends, TargetStoreTest, testing::Backends(), testing::BackendName);

TEST_P(TargetStoreTest, SetReplacesTheWallsTargetsAndListsThemInByteOrder) {
  ASSERT_TRUE(targets_
                  ->SetWallTargets(cave_, {{0, "grade", "V3", 2},
                                           {0, "style", "heel hook", 0.1 + 0.2},
                                           {0, "grade", "V10", 1},
                                           {0, "grade", "V1", 3}})
                  .ok());
  ASSERT_TRUE(targets_->SetWallTargets(slab_, {{0, "style", "crimp", 0.25}}).ok());
  Result<std::vector<TargetRecord>> t = targets_->WallTargets(cave_);
  ASSERT_TRUE(t.ok()) << t.status().message();
  ASSERT_EQ(t->size(), 4u);
  EXPECT_EQ((*t)[0], (TargetRecord{cave_, "grade", "V1", 3}));
  EXPECT_EQ((*t)[1], (TargetRecord{cave_, "grade", "V10", 1}));
  EXPECT_EQ((*t)[2], (TargetRecord{cave_, "grade", "V3", 2}));
  EXPECT_EQ((*t)[3].value, 0.1 + 0.2);  // doubles round-trip exactly
  // A second set replaces, not merges.
  ASSERT_TRUE(targets_->SetWallTargets(cave_, {{0, "grade", "V5", 4}}).ok());
  t = targets_->WallTargets(cave_);
  ASSERT_TRUE(t.ok());
  ASSERT_EQ(t->size(), 1u);
  EXPECT_EQ((*t)[0].name, "V5");
  Result<std::vector<TargetRecord>> all = targets_->GymTargets(gym_);
  ASSERT_TRUE(all.ok());
  ASSERT_EQ(all->size(), 2u);
  EXPECT_EQ((*all)[0].wall_id, cave_);
  EXPECT_EQ((*all)[1].wall_id, slab_);
  // An empty list clears.
  ASSERT_TRUE(targets_->SetWallTargets(cave_, {}).ok());
  EXPECT_TRUE(targets_->WallTargets(cave_)->empty());
}

TEST_P(TargetStoreTest, RefusesBadKindsDuplicatesAndUnknownWallsWithoutAChange) {
  ASSERT_TRUE(targets_->SetWallTargets(cave_, {{0, "grade", "V3", 2}}).ok());
  Status s = targets_->SetWallTargets(cave_, {{0, "grade", "V4", 1}, {0, "colour", "x", 1}});
  EXPECT_EQ(s.code(), Status::Code::kInvalidInput) << s.message();
  s = targets_->SetWallTargets(cave_, {{0, "grade", "V4", 1}, {0, "grade", "V4", 2}});
  EXPECT_EQ(s.code(), Status::Code::kInvalidInput) << s.message();
  EXPECT_NE(s.message().find("twice"), std::string::npos) << s.message();
  s = targets_->SetWallTargets(999999, {{0, "grade", "V4", 1}});
  EXPECT_EQ(s.code(), Status::Code::kNotFound) << s.message();
  Result<std::vector<TargetRecord>> t = targets_->WallTargets(cave_);
  ASSERT_TRUE(t.ok());
  ASSERT_EQ(t->size(), 1u);
  EXPECT_EQ((*t)[0].name, "V3");
  EXPECT_TRUE(targets_->WallTargets(999999)->empty());
}

// Schema 12: the gym's targets per discipline, replaced per discipline.
TEST_P(TargetStoreTest, DisciplineTargetsRoundTripPerDiscipline) {
  ASSERT_TRUE(targets_
                  ->SetDisciplineTargets(gym_, "bouldering",
                                         {{0, "", "grade", "V4", 3},
                                          {0, "", "style", "heel hook", 0.1 + 0.2},
                                          {0, "", "grade", "V10", 1}})
                  .ok());
  ASSERT_TRUE(
      targets_->SetDisciplineTargets(gym_, "roped", {{0, "", "grade", "5.10", 6}}).ok());
  Result<std::vector<DisciplineTargetRecord>> t = targets_->DisciplineTargets(gym_);
  ASSERT_TRUE(t.ok()) << t.status().message();
  ASSERT_EQ(t->size(), 4u);
  EXPECT_EQ((*t)[0], (DisciplineTargetRecord{gym_, "bouldering", "grade", "V10", 1}));
  EXPECT_EQ((*t)[1], (DisciplineTargetRecord{gym_, "bouldering", "grade", "V4", 3}));
  EXPECT_EQ((*t)[2].value, 0.1 + 0.2);  // doubles round-trip exactly
  EXPECT_EQ((*t)[3], (DisciplineTargetRecord{gym_, "roped", "grade", "5.10", 6}));
  // Replacing one discipline leaves the other; bad input changes nothing.
  ASSERT_TRUE(targets_->SetDisciplineTargets(gym_, "bouldering", {}).ok());
  EXPECT_EQ(targets_->SetDisciplineTargets(gym_, "ice", {}).code(), Status::Code::kInvalidInput);
  EXPECT_EQ(targets_
                ->SetDisciplineTargets(gym_, "roped",
                                       {{0, "", "grade", "5.9", 1}, {0, "", "grade", "5.9", 2}})
                .code(),
            Status::Code::kInvalidInput);
  EXPECT_EQ(targets_->SetDisciplineTargets(999999, "roped", {}).code(), Status::Code::kNotFound);
  t = targets_->DisciplineTargets(gym_);
  ASSERT_TRUE(t.ok());
  ASSERT_EQ(t->size(), 1u);
  EXPECT_EQ((*t)[0].discipline, "roped");
  EXPECT_TRUE(targets_->DisciplineTargets(999999)->empty());
}

TEST_P(TargetStoreTest, TickSumsCountUnheldTicksAndStarsPerRoute) {
  RouteRecord r;
  r.name = "A";
  r.crdl = "name: A\n---\nR jug\n";
  r.move_count = 1;
  r.gym_id = gym_;
  r.state = gym::RouteState::kSet;
  const int64_t a = *store_->InsertRoute(r);
  TickStore* ticks = TickStoreOf(store_.get());
  ASSERT_NE(ticks, nullptr);
  int n = 0;
  for (auto [climber, stars, state] : {std::tuple<const char*, int, const char*>{"u:1", 4, "ok"},
                                       {"u:2", 0, "ok"},
                                       {"u:3", 5, "ok"},
                                       {"d:x", 1, "held"}}) {
    TickRecord t;
    t.route_id = a;
    t.gym_id = gym_;
    t.climber = climber;
    t.day = "2026-11-2" + std::to_string(n++);
    t.outcome = "send";
    if (stars) t.stars = stars;
    t.state = *gym::TickStateOf(state);
    t.created_at = t.updated_at = "2026-11-20 10:00:00";
    ASSERT_TRUE(ticks->PutTick(t).ok());
  }
  Result<std::vector<RouteTickSum>> sums = targets_->GymTickSums(gym_);
  ASSERT_TRUE(sums.ok()) << sums.status().message();
  ASSERT_EQ(sums->size(), 1u);
  EXPECT_EQ((*sums)[0].route_id, a);
  EXPECT_EQ((*sums)[0].ticks, 3);
  EXPECT_EQ((*sums)[0].star_votes, 2);
  EXPECT_EQ((*sums)[0].star_sum, 9);
  // By route state: a stripped route's ticks count in its state only.
  RouteRecord old = r;
  old.name = "B";
  old.state = gym::RouteState::kStripped;
  const int64_t b = *store_->InsertRoute(old);
  TickRecord t;
  t.route_id = b;
  t.gym_id = gym_;
  t.climber = "u:1";
  t.day = "2026-10-01";
  t.outcome = "flash";
  t.stars = 2;
  t.created_at = t.updated_at = "2026-10-01 10:00:00";
  ASSERT_TRUE(ticks->PutTick(t).ok());
  Result<std::vector<RouteTickSum>> set = targets_->StateTickSums(gym_, "set");
  ASSERT_TRUE(set.ok()) << set.status().message();
  ASSERT_EQ(set->size(), 1u);
  EXPECT_EQ((*set)[0].route_id, a);
  EXPECT_EQ((*set)[0].ticks, 3);
  EXPECT_EQ((*set)[0].star_sum, 9);
  Result<std::vector<RouteTickSum>> gone = targets_->StateTickSums(gym_, "stripped");
  ASSERT_TRUE(gone.ok()) << gone.status().message();
  ASSERT_EQ(gone->size(), 1u);
  EXPECT_EQ((*gone)[0].route_id, b);
  EXPECT_EQ((*gone)[0].ticks, 1);
  EXPECT_EQ((*gone)[0].star_votes, 1);
  EXPECT_EQ((*gone)[0].star_sum, 2);
  EXPECT_EQ(targets_->GymTickSums(gym_)->size(), 2u);
  EXPECT_TRUE(targets_->StateTickSums(gym_ + 1000, "set")->empty());
  // By route ids (a setting day's pool): only those asked, each once, by id;
  // unknown ids absent; more ids than one query takes.
  Result<std::vector<RouteTickSum>> only_b = targets_->RouteTickSums({b, b, b + 1000});
  ASSERT_TRUE(only_b.ok()) << only_b.status().message();
  ASSERT_EQ(only_b->size(), 1u);
  EXPECT_EQ((*only_b)[0].route_id, b);
  EXPECT_EQ((*only_b)[0].star_sum, 2);
  // Ids unknown (negative, so they sort first) fill the first query but one
  // place: `a` ends it, `b` is the second query's.
  ASSERT_LT(a, b);
  std::vector<int64_t> many = {b, a};
  for (size_t i = 1; i < kTickSumIdsPerQuery; ++i) many.push_back(-static_cast<int64_t>(i));
  Result<std::vector<RouteTickSum>> both = targets_->RouteTickSums(many);
  ASSERT_TRUE(both.ok()) << both.status().message();
  ASSERT_EQ(both->size(), 2u);
  EXPECT_EQ((*both)[0].route_id, a);
  EXPECT_EQ((*both)[0].ticks, 3);
  EXPECT_EQ((*both)[0].star_votes, 2);
  EXPECT_EQ((*both)[1].route_id, b);
  EXPECT_TRUE(targets_->RouteTickSums({})->empty());
}

}  // namespace
}  // namespace sb::store
