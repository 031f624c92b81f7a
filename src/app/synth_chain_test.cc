// The synthetic chain (issue 22): counts, the routes' contents, the ticks'
// days and determinism (byte-identical tables from the same params), on the
// backend $SB_TEST_BACKEND names (ctest runs the app tests on both).
#include "app/synth_chain.h"

#include <gtest/gtest.h>

#include <map>
#include <memory>
#include <set>
#include <string>

#include "app/seed.h"
#include "crdl/route.h"
#include "store/copy.h"
#include "store/gym_store.h"
#include "store/open.h"
#include "store/store_test_util.h"
#include "store/tick_store.h"

namespace sb::app {
namespace {

ChainParams Tiny() {
  ChainParams p;
  p.gyms = 2;
  p.walls = 6;
  p.on_wall = 30;
  p.archived = 60;
  p.ticks = 700;
  p.setters_per_gym = 2;
  p.climbers_per_gym = 40;
  p.seed = 7;
  p.today = "2026-11-26";
  p.fast_hash = true;
  return p;
}

class SynthChainTest : public ::testing::Test {
 protected:
  void SetUp() override {
    db_ = std::make_unique<store::testing::TestDatabase>(
        store::testing::BackendFromEnvironment(), "synth");
    SB_REQUIRE_DATABASE(*db_);
    Result<std::unique_ptr<store::Store>> s = store::OpenStore(db_->locator());
    ASSERT_TRUE(s.ok()) << s.status().message();
    store_ = std::move(s).value();
  }
  std::unique_ptr<store::testing::TestDatabase> db_;
  std::unique_ptr<store::Store> store_;
};

TEST_F(SynthChainTest, WritesTheCountsAskedFor) {
  Result<ChainSummary> s = SynthChain(store_.get(), Tiny(), DefaultExamplesDir());
  ASSERT_TRUE(s.ok()) << s.status().message();
  EXPECT_EQ(s->gyms, 2);
  EXPECT_EQ(s->walls, 6);
  EXPECT_EQ(s->accounts, 6);
  EXPECT_EQ(s->ticks, 700);
  store::GymStore* gs = store::GymStoreOf(store_.get());
  store::TickStore* ts = store::TickStoreOf(store_.get());
  Result<std::vector<store::GymRecord>> gyms = gs->ListGyms();
  ASSERT_TRUE(gyms.ok());
  ASSERT_EQ(gyms->size(), 2u);
  int64_t set = 0, stripped = 0, ticks = 0;
  for (const store::GymRecord& g : *gyms) {
    // Each Result is kept alive for its loop (value() of a temporary would dangle).
    Result<std::vector<store::RouteRecord>> all = store_->AllRoutes(std::nullopt);
    ASSERT_TRUE(all.ok());
    for (const store::RouteRecord& r : *all) {
      if (r.gym_id != g.id) continue;
      set += r.state == gym::RouteState::kSet;
      stripped += r.state == gym::RouteState::kStripped;
    }
    ticks += static_cast<int64_t>(ts->GymTicks(g.id).value().size());
    Result<std::vector<store::WallRecord>> walls = gs->ListWalls(g.id);
    ASSERT_TRUE(walls.ok());
    EXPECT_EQ(walls->size(), 3u);
    for (const store::WallRecord& w : *walls) {
      EXPECT_TRUE(w.plan_x && w.plan_w && w.reset_weeks) << w.name;
    }
    EXPECT_EQ(gs->ListCircuits(g.id).value().size(), 6u);
    EXPECT_EQ(gs->ListMembers(g.id).value().size(), 3u);
  }
  EXPECT_EQ(set, 30);
  EXPECT_EQ(stripped, 60);
  EXPECT_EQ(ticks, 700);
}

TEST_F(SynthChainTest, RoutesReadAsRoutesWithDatesInTheirWindow) {
  ASSERT_TRUE(SynthChain(store_.get(), Tiny(), DefaultExamplesDir()).ok());
  // The vocabulary: every move text of the bundled examples.
  std::set<std::string> vocabulary;
  for (const char* f : {"crimp-ladder.crdl", "dyno-problem.crdl"}) {
    Result<Route> r = ReadCrdlFile(DefaultExamplesDir() + "/" + f);
    ASSERT_TRUE(r.ok());
    for (const Move& m : r->moves) vocabulary.insert(m.text);
  }
  Result<std::vector<store::RouteRecord>> all = store_->AllRoutes(std::nullopt);
  ASSERT_TRUE(all.ok());
  ASSERT_EQ(all->size(), 90u);
  int known_moves = 0;
  for (const store::RouteRecord& r : *all) {
    Result<Route> parsed = ParseCrdl(r.crdl, "route");
    ASSERT_TRUE(parsed.ok()) << parsed.status().message();
    EXPECT_GE(parsed->moves.size(), 4u);
    EXPECT_TRUE(r.grade_value.has_value()) << r.grade;
    EXPECT_TRUE(r.wall_id.has_value());
    EXPECT_FALSE(r.set_on.empty());
    if (r.state == gym::RouteState::kSet) {
      EXPECT_TRUE(r.strip_on.empty());
      EXPECT_GE(r.set_on, "2026-09-17");  // 70 days before today
      EXPECT_LE(r.set_on, "2026-11-26");
    } else {
      EXPECT_EQ(r.state, gym::RouteState::kStripped);
      EXPECT_LT(r.set_on, r.strip_on);
      EXPECT_LT(r.strip_on, "2026-11-26");
    }
    for (const Move& m : parsed->moves) known_moves += vocabulary.count(m.text) ? 1 : 0;
    // Ticks fall on days the route was up.
    Result<std::vector<store::TickRecord>> route_ticks =
        store::TickStoreOf(store_.get())->RouteTicks(r.id);
    ASSERT_TRUE(route_ticks.ok());
    for (const store::TickRecord& t : *route_ticks) {
      EXPECT_GE(t.day, r.set_on);
      EXPECT_LE(t.day, r.state == gym::RouteState::kSet ? std::string("2026-11-26") : r.strip_on);
    }
  }
  EXPECT_GT(known_moves, 0);  // moves come from the examples (two of twelve files checked)
}

TEST_F(SynthChainTest, SameParamsWriteTheSameTables) {
  ASSERT_TRUE(SynthChain(store_.get(), Tiny(), DefaultExamplesDir()).ok());
  store::testing::TestDatabase other(store::testing::BackendFromEnvironment(), "synth2");
  SB_REQUIRE_DATABASE(other);
  {
    Result<std::unique_ptr<store::Store>> s = store::OpenStore(other.locator());
    ASSERT_TRUE(s.ok());
    ASSERT_TRUE(SynthChain(s->get(), Tiny(), DefaultExamplesDir()).ok());
  }
  store::testing::TestDatabase seeded(store::testing::BackendFromEnvironment(), "synth3");
  SB_REQUIRE_DATABASE(seeded);
  {
    Result<std::unique_ptr<store::Store>> s = store::OpenStore(seeded.locator());
    ASSERT_TRUE(s.ok());
    ChainParams p = Tiny();
    p.seed = 8;
    ASSERT_TRUE(SynthChain(s->get(), p, DefaultExamplesDir()).ok());
  }
  store_.reset();
  Result<store::DatabaseSummary> a = store::Summarize(db_->locator());
  Result<store::DatabaseSummary> b = store::Summarize(other.locator());
  Result<store::DatabaseSummary> c = store::Summarize(seeded.locator());
  ASSERT_TRUE(a.ok() && b.ok() && c.ok());
  std::map<std::string, uint64_t> sa, sb, sc;
  for (const auto& t : a->tables) sa[t.name] = t.checksum;
  for (const auto& t : b->tables) sb[t.name] = t.checksum;
  for (const auto& t : c->tables) sc[t.name] = t.checksum;
  for (const char* table : {"walls", "circuits", "routes", "route_setters", "gym_members",
                            "ticks"}) {
    EXPECT_EQ(sa[table], sb[table]) << table;
  }
  EXPECT_NE(sa["routes"], sc["routes"]);  // another seed, another chain
  EXPECT_NE(sa["ticks"], sc["ticks"]);
}

TEST_F(SynthChainTest, RefusesADatabaseWithAccountsAndBadParams) {
  ASSERT_TRUE(store_->CreateUser("someone", "x").ok());
  Result<ChainSummary> s = SynthChain(store_.get(), Tiny(), DefaultExamplesDir());
  ASSERT_FALSE(s.ok());
  EXPECT_EQ(s.status().code(), Status::Code::kConflict);
  ChainParams p = Tiny();
  p.walls = 1;  // fewer walls than gyms
  EXPECT_NE(p.Validate().message().find("walls"), std::string::npos);
  p = Tiny();
  p.today = "2026-02-30";
  EXPECT_NE(p.Validate().message().find("today"), std::string::npos);
  p = ChainParams().Scaled(0.001);
  EXPECT_TRUE(p.Validate().ok()) << p.Validate().message();
  EXPECT_EQ(p.on_wall, 10);
  EXPECT_EQ(p.archived, 200);
  EXPECT_EQ(p.ticks, 5000);
}

}  // namespace
}  // namespace sb::app
