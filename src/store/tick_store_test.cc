// TickStore (schema 7) on both backends: one tick per route, climber and
// day; the gym's version; states; merging a device into an account; new
// identities from one origin.
#include "store/tick_store.h"

#include <gtest/gtest.h>

#include <map>
#include <memory>
#include <string>
#include <vector>

#include "store/gym_store.h"
#include "store/target_store.h"
#include "store/test_backends.h"
#include "store/tick_page.h"

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

// Issue 34: a fit's read of one discipline returns only the ticks in state
// "ok" on that discipline's routes ("bouldering" includes routes without a
// grade discipline), by id; the aged routes are counted per climber over
// every discipline.
TEST_P(TickStoreTest, AFitReadsOnlyItsDisciplinesTicks) {
  RouteRecord roped;
  roped.name = "Rope";
  roped.crdl = "name: Rope\n---\nR jug\n";
  roped.move_count = 1;
  roped.gym_id = gym_;
  roped.state = gym::RouteState::kSet;
  roped.grade_discipline = "roped";
  Result<int64_t> rope = store_->InsertRoute(roped);
  ASSERT_TRUE(rope.ok()) << rope.status().message();
  TickRecord felt = Tick(route_, "d:aa", "2026-11-20", "send", "2026-11-20 10:00:00");
  felt.attempts = 2;
  felt.felt_discipline = "bouldering";
  felt.felt_value = 3.5;
  ASSERT_TRUE(ticks_->PutTick(felt).ok());
  ASSERT_TRUE(ticks_->PutTick(Tick(other_, "d:aa", "2026-11-20", "send", "2026-11-20 11:00:00")).ok());
  ASSERT_TRUE(ticks_->PutTick(Tick(*rope, "d:aa", "2026-11-20", "flash", "2026-11-20 12:00:00")).ok());
  TickRecord held = Tick(*rope, "d:bb", "2026-11-21", "send", "2026-11-21 10:00:00");
  held.state = gym::TickState::kHeld;
  ASSERT_TRUE(ticks_->PutTick(held).ok());
  Result<std::vector<TickRecord>> boulder = ticks_->GymDisciplineTicks(gym_, "bouldering");
  ASSERT_TRUE(boulder.ok()) << boulder.status().message();
  ASSERT_EQ(boulder->size(), 2u);
  EXPECT_EQ((*boulder)[0].route_id, route_);
  EXPECT_EQ((*boulder)[0].attempts, 2);
  EXPECT_EQ((*boulder)[0].felt_value, 3.5);
  EXPECT_EQ((*boulder)[0].state, gym::TickState::kOk);
  EXPECT_EQ((*boulder)[1].route_id, other_);
  EXPECT_LT((*boulder)[0].id, (*boulder)[1].id);
  // Read in pages of one tick (issue 34: both backends page): the same rows.
  const int64_t was = SetGymTickPageForTesting(1);
  Result<std::vector<TickRecord>> paged = ticks_->GymDisciplineTicks(gym_, "bouldering");
  SetGymTickPageForTesting(was);
  ASSERT_TRUE(paged.ok()) << paged.status().message();
  ASSERT_EQ(paged->size(), 2u);
  EXPECT_EQ((*paged)[0].id, (*boulder)[0].id);
  EXPECT_EQ((*paged)[1].id, (*boulder)[1].id);
  // Issue 34 (memory): the same ticks handed over a page at a time, pages of
  // one tick here; an error from the callback stops the read.
  SetGymTickPageForTesting(1);
  std::vector<int64_t> ids;
  int pages = 0;
  Status each =
      ticks_->EachGymDisciplineTicksPage(gym_, "bouldering", [&](std::vector<TickRecord>& page) {
        ++pages;
        for (const TickRecord& t : page) {
          ids.push_back(t.id);
        }
        return Status::Ok();
      });
  Status stopped = ticks_->EachGymDisciplineTicksPage(
      gym_, "bouldering", [](std::vector<TickRecord>&) { return Status::InvalidInput("stop"); });
  SetGymTickPageForTesting(was);
  ASSERT_TRUE(each.ok()) << each.message();
  EXPECT_EQ(pages, 2);
  EXPECT_EQ(ids, (std::vector<int64_t>{(*boulder)[0].id, (*boulder)[1].id}));
  EXPECT_EQ(stopped.code(), Status::Code::kInvalidInput);
  Result<std::vector<TickRecord>> rope_ticks = ticks_->GymDisciplineTicks(gym_, "roped");
  ASSERT_TRUE(rope_ticks.ok());
  ASSERT_EQ(rope_ticks->size(), 1u);  // the held one is not counted
  EXPECT_EQ((*rope_ticks)[0].outcome, "flash");
  Result<std::map<std::string, int64_t>> aged =
      ticks_->AgedRouteCounts(gym_, "2026-11-20 11:30:00");
  ASSERT_TRUE(aged.ok()) << aged.status().message();
  EXPECT_EQ(*aged, (std::map<std::string, int64_t>{{"d:aa", 2}}));
  EXPECT_EQ(ticks_->AgedRouteCounts(gym_, "2026-12-01 00:00:00")->at("d:aa"), 3);
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

// Issue 34: the gym's ticks are read in pages by id (a keyset on (gym_id,
// id)); with pages of 1, 2 and 3 ticks the read is the same rows in the same
// order as in one page, held and other gyms' ticks left out.
TEST_P(TickStoreTest, GymTicksReadInSmallPagesAreTheSameRowsInTheSameOrder) {
  Result<int64_t> g2 = GymStoreOf(store_.get())->CreateGym("Other", std::nullopt);
  ASSERT_TRUE(g2.ok()) << g2.status().message();
  RouteRecord elsewhere;
  elsewhere.name = "E";
  elsewhere.crdl = "name: E\n---\nR jug\n";
  elsewhere.move_count = 1;
  elsewhere.gym_id = *g2;
  elsewhere.state = gym::RouteState::kSet;
  Result<int64_t> e = store_->InsertRoute(elsewhere);
  ASSERT_TRUE(e.ok()) << e.status().message();
  for (int i = 0; i < 7; ++i) {
    const std::string day = "2026-11-1" + std::to_string(i);
    TickRecord t = Tick(i % 2 ? route_ : other_, "d:c" + std::to_string(i % 3), day,
                        i % 3 ? "send" : "attempt", day + " 10:00:00");
    t.stars = 1 + i % 5;
    if (i == 4) t.state = gym::TickState::kHeld;
    ASSERT_TRUE(ticks_->PutTick(t).ok());
    TickRecord there = Tick(*e, "d:x" + std::to_string(i), day, "send", day + " 11:00:00");
    there.gym_id = *g2;
    ASSERT_TRUE(ticks_->PutTick(there).ok());
  }
  Result<std::vector<TickRecord>> whole = ticks_->GymTicks(gym_);
  ASSERT_TRUE(whole.ok()) << whole.status().message();
  ASSERT_EQ(whole->size(), 6u);
  for (size_t i = 1; i < whole->size(); ++i) EXPECT_LT((*whole)[i - 1].id, (*whole)[i].id);
  for (int64_t page : {1, 2, 3}) {
    const int64_t before = SetGymTickPageForTesting(page);
    Result<std::vector<TickRecord>> paged = ticks_->GymTicks(gym_);
    SetGymTickPageForTesting(before);
    ASSERT_TRUE(paged.ok()) << paged.status().message();
    ASSERT_EQ(paged->size(), whole->size()) << "page " << page;
    for (size_t i = 0; i < whole->size(); ++i) {
      const TickRecord &a = (*whole)[i], &b = (*paged)[i];
      EXPECT_EQ(a.id, b.id) << "page " << page;
      EXPECT_EQ(a.gym_id, gym_);
      EXPECT_EQ(a.climber, b.climber);
      EXPECT_EQ(a.route_id, b.route_id);
      EXPECT_EQ(a.stars, b.stars);
      EXPECT_EQ(a.outcome, b.outcome);
      EXPECT_EQ(a.revision, b.revision);
      EXPECT_EQ(b.state, gym::TickState::kOk);
    }
  }
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
