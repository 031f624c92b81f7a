// TickStore (schema 7) on both backends: one tick per route, climber and
// day; the gym's version; states; merging a device into an account; new
// identities from one origin.
#include "store/tick_store.h"

#include <gtest/gtest.h>

#include <memory>
#include <string>
#include <vector>

#include "store/gym_store.h"
#include "store/target_store.h"
#include "store/test_backends.h"

namespace sb::store {
namespace {

class TickStoreTest : public testing::BackendTest {
 protected:
  TickStoreTest() : BackendTest("tick", testing::Make::kStoreAndGym) {}
  void SetUpStore() override {
    ticks_ = TickStoreOf(store_.get());
    ASSERT_NE(ticks_, nullptr);
    route_ = Route("A");
    other_ = Route("B");
  }
  int64_t Route(const std::string& name) {
    RouteRecord r;
    r.name = name;
    r.crdl = "name: " + name + "\n---\nR jug\n";
    r.move_count = 1;
    r.gym_id = gym_;
    r.state = gym::RouteState::kSet;
    Result<int64_t> id = store_->InsertRoute(r);
    EXPECT_TRUE(id.ok()) << id.status().message();
    return id.ok() ? *id : 0;
  }
  TickRecord Tick(int64_t route, const std::string& climber, const std::string& day,
                  const std::string& outcome, const std::string& at) {
    TickRecord t;
    t.route_id = route;
    t.gym_id = gym_;
    t.climber = climber;
    t.origin = "o1";
    t.day = day;
    t.outcome = outcome;
    t.created_at = at;
    t.updated_at = at;
    return t;
  }

  TickStore* ticks_ = nullptr;
  int64_t route_ = 0, other_ = 0;
};

INSTANTIATE_TEST_SUITE_P(Backends, TickStoreTest, testing::Backends(), testing::BackendName);

TEST_P(TickStoreTest, OneTickPerRouteClimberAndDayASecondEditsIt) {
  TickRecord t = Tick(route_, "d:aa", "2026-11-20", "attempt", "2026-11-20 10:00:00");
  t.attempts = 3;
  t.stars = 4;
  t.felt_grade = "V5";
  t.felt_discipline = "bouldering";
  t.felt_value = 5.0;
  t.comment = "crimpy";
  Result<TickRecord> first = ticks_->PutTick(t);
  ASSERT_TRUE(first.ok()) << first.status().message();
  EXPECT_EQ(first->revision, 1);
  EXPECT_EQ(first->attempts, 3);
  EXPECT_EQ(first->felt_value, 5.0);
  EXPECT_EQ(first->comment, "crimpy");

  TickRecord again = Tick(route_, "d:aa", "2026-11-20", "send", "2026-11-20 11:00:00");
  again.attempts = 4;
  Result<TickRecord> second = ticks_->PutTick(again);
  ASSERT_TRUE(second.ok()) << second.status().message();
  EXPECT_EQ(second->id, first->id);
  EXPECT_EQ(second->outcome, "send");
  EXPECT_EQ(second->attempts, 4);
  EXPECT_EQ(second->stars, std::nullopt);
  EXPECT_EQ(second->created_at, "2026-11-20 10:00:00");
  EXPECT_EQ(second->updated_at, "2026-11-20 11:00:00");
  EXPECT_EQ(second->revision, 2);

  // Another day is another tick.
  ASSERT_TRUE(ticks_->PutTick(Tick(route_, "d:aa", "2026-11-21", "flash", "2026-11-21 10:00:00"))
                  .ok());
  EXPECT_EQ(ticks_->RouteTicks(route_)->size(), 2u);
  EXPECT_EQ((*ticks_->ClimberTicks("d:aa"))[0].day, "2026-11-21");  // newest first
  EXPECT_GT(ticks_->GymTickVersion(gym_)->ticks, 1);
  // Issue 34: the counts a page's cost is made from, before the reading.
  TickRecord held = Tick(route_, "d:bb", "2026-11-21", "send", "2026-11-21 10:00:00");
  held.state = gym::TickState::kHeld;
  ASSERT_TRUE(ticks_->PutTick(held).ok());
  Result<TickCounts> by_route = ticks_->CountRouteTicks(route_);
  ASSERT_TRUE(by_route.ok()) << by_route.status().message();
  EXPECT_EQ(by_route->ticks, 3);
  EXPECT_EQ(by_route->held, 1);
  EXPECT_EQ(by_route->routes, 1);
  Result<TickCounts> by_climber = ticks_->CountClimberTicks("d:aa");
  ASSERT_TRUE(by_climber.ok()) << by_climber.status().message();
  EXPECT_EQ(by_climber->ticks, static_cast<int64_t>(ticks_->ClimberTicks("d:aa")->size()));
  EXPECT_EQ(by_climber->routes, 1);
  EXPECT_EQ(by_climber->gyms, 1);
  EXPECT_EQ(by_climber->held, 0);
  EXPECT_EQ(ticks_->CountClimberTicks("d:nobody")->ticks, 0);
  EXPECT_EQ(ticks_->CountRouteTicks(99999)->ticks, 0);

  // Unknown route: kNotFound.
  Result<TickRecord> bad = ticks_->PutTick(Tick(99999, "d:aa", "2026-11-21", "flash", "x"));
  EXPECT_EQ(bad.status().code(), Status::Code::kNotFound);
  // A refused outcome never reaches the table.
  EXPECT_FALSE(ticks_->PutTick(Tick(route_, "d:bb", "2026-11-21", "onsight", "x")).ok());
}

// Schema 13: every write that changes a gym's dashboard or wall pages moves
// its data version (triggers, same transaction); only tick writes move the
// tick version; another gym's versions stay.
TEST_P(TickStoreTest, EveryKindOfWriteMovesTheGymsDataVersion) {
  TickVersion v = *ticks_->GymTickVersion(gym_);
  ASSERT_GT(v.data, 0);
  auto moved = [&](const char* what, bool ticks) {
    TickVersion now = *ticks_->GymTickVersion(gym_);
    EXPECT_GT(now.data, v.data) << what;
    if (ticks) EXPECT_GT(now.ticks, v.ticks) << what;
    else EXPECT_EQ(now.ticks, v.ticks) << what;
    v = now;
  };
  int64_t r = Route("C");
  moved("route insert", false);
  RouteRecord route = *store_->GetRoute(r);
  route.name = "C2";
  ASSERT_TRUE(store_->UpdateRouteMetadata(route).ok());
  moved("route edit", false);
  GymStore* gyms = GymStoreOf(store_.get());
  ASSERT_NE(gyms, nullptr);
  WallRecord w;
  w.gym_id = gym_;
  w.name = "North";
  Result<int64_t> wall = gyms->InsertWall(w);
  ASSERT_TRUE(wall.ok()) << wall.status().message();
  moved("wall insert", false);
  TargetStore* targets = TargetStoreOf(store_.get());
  ASSERT_NE(targets, nullptr);
  ASSERT_TRUE(targets->SetWallTargets(*wall, {{*wall, "grade", "V3", 2}}).ok());
  moved("targets", false);
  FeedbackRecord f;
  f.route_id = route_;
  f.participant = "p1";
  f.created_at = f.updated_at = "2026-11-20 10:00:00";
  ASSERT_TRUE(store_->PutFeedback(f).ok());
  moved("feedback", false);
  Result<TickRecord> t = ticks_->PutTick(Tick(route_, "d:aa", "2026-11-20", "send", "t1"));
  ASSERT_TRUE(t.ok());
  moved("tick", true);
  ASSERT_TRUE(ticks_->SetTickState(t->id, "held", "t2").ok());
  moved("tick state", true);
  // No such gym: zeros, not an error.
  EXPECT_EQ(*ticks_->GymTickVersion(gym_ + 1000), TickVersion{});
}

TEST_P(TickStoreTest, HeldTicksLeaveTheGymsTicksUntilAccepted) {
  Result<TickRecord> a = ticks_->PutTick(Tick(route_, "d:aa", "2026-11-20", "send", "t1"));
  TickRecord held = Tick(route_, "d:bb", "2026-11-20", "send", "t1");
  held.state = gym::TickState::kHeld;
  Result<TickRecord> b = ticks_->PutTick(held);
  ASSERT_TRUE(a.ok() && b.ok());
  EXPECT_EQ(ticks_->GymTicks(gym_)->size(), 1u);
  TickVersion before = *ticks_->GymTickVersion(gym_);
  ASSERT_TRUE(ticks_->SetTickState(b->id, "ok", "t2").ok());
  EXPECT_EQ(ticks_->GymTicks(gym_)->size(), 2u);
  EXPECT_NE(*ticks_->GymTickVersion(gym_), before);
  ASSERT_TRUE(ticks_->SetTickState(b->id, "discarded", "t3").ok());
  EXPECT_EQ(ticks_->GymTicks(gym_)->size(), 1u);
  EXPECT_TRUE(ticks_->ClimberTicks("d:bb")->empty());
  EXPECT_EQ(ticks_->SetTickState(99999, "ok", "t").code(), Status::Code::kNotFound);
  EXPECT_FALSE(ticks_->SetTickState(a->id, "weird", "t").ok());
}

TEST_P(TickStoreTest, MergeMovesADevicesTicksAndKeepsTheNewerOfTwo) {
  Result<int64_t> user = store_->CreateUser("ann", "h");
  ASSERT_TRUE(user.ok());
  const std::string me = "u:" + std::to_string(*user);
  TickRecord mine = Tick(route_, me, "2026-11-20", "attempt", "2026-11-20 09:00:00");
  mine.user_id = *user;
  ASSERT_TRUE(ticks_->PutTick(mine).ok());
  ASSERT_TRUE(
      ticks_->PutTick(Tick(route_, "d:aa", "2026-11-20", "send", "2026-11-20 12:00:00")).ok());
  ASSERT_TRUE(
      ticks_->PutTick(Tick(other_, "d:aa", "2026-11-20", "flash", "2026-11-20 12:00:00")).ok());
  ASSERT_TRUE(
      ticks_->PutTick(Tick(other_, "d:zz", "2026-11-20", "flash", "2026-11-20 12:00:00")).ok());
  Result<int> moved = ticks_->MergeTicks("d:aa", me, *user);
  ASSERT_TRUE(moved.ok()) << moved.status().message();
  EXPECT_EQ(*moved, 2);
  std::vector<TickRecord> all = *ticks_->ClimberTicks(me);
  ASSERT_EQ(all.size(), 2u);
  for (const TickRecord& t : all) {
    EXPECT_EQ(t.user_id, *user);
    if (t.route_id == route_) EXPECT_EQ(t.outcome, "send");  // the newer one
  }
  EXPECT_TRUE(ticks_->ClimberTicks("d:aa")->empty());
  EXPECT_EQ(ticks_->ClimberTicks("d:zz")->size(), 1u);
  EXPECT_EQ(*ticks_->MergeTicks("d:aa", me, *user), 0);
}

TEST_P(TickStoreTest, NewIdentitiesCountsOnlyClimbersFirstSeenSince) {
  // An old climber (first tick long ago) does not count; new ones do, once each.
  ASSERT_TRUE(ticks_->PutTick(Tick(other_, "d:old", "2026-11-01", "send", "2026-11-01 10:00:00"))
                  .ok());
  ASSERT_TRUE(ticks_->PutTick(Tick(route_, "d:old", "2026-11-20", "send", "2026-11-20 10:00:00"))
                  .ok());
  for (std::string c : {"d:n1", "d:n2", "d:n3"}) {
    ASSERT_TRUE(
        ticks_->PutTick(Tick(route_, c, "2026-11-20", "send", "2026-11-20 10:01:00")).ok());
  }
  TickRecord elsewhere = Tick(route_, "d:n4", "2026-11-20", "send", "2026-11-20 10:01:00");
  elsewhere.origin = "o2";
  ASSERT_TRUE(ticks_->PutTick(elsewhere).ok());
  EXPECT_EQ(*ticks_->NewIdentitiesSince(route_, "o1", "2026-11-20 10:00:00"), 3);
  EXPECT_EQ(*ticks_->NewIdentitiesSince(route_, "o2", "2026-11-20 10:00:00"), 1);
  EXPECT_EQ(*ticks_->NewIdentitiesSince(route_, "o1", "2026-11-20 10:05:00"), 0);
  EXPECT_EQ(*ticks_->NewIdentitiesSince(other_, "o1", "2026-11-20 10:00:00"), 0);
}

}  // namespace
}  // namespace sb::store
