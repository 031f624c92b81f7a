// app::Logbook: one tick per climber, route and day; the burst rule holds a
// phone that clears its cookie out of every consensus until a setter
// accepts; sign-in merges the device's ticks; budgets; the ascent grade.
#include "app/logbook.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "app/convert.h"
#include "app/logbook_fixture.h"
#include "store/gym_store.h"
#include "store/tick_store.h"

namespace sb::app {
namespace {

using testing::LogbookFixture;

class LogbookTest : public LogbookFixture {
 protected:
  void SetUp() override {
    LogbookFixture::SetUp();
    if (IsSkipped() || HasFatalFailure()) return;
    route_ = Route("Crimp Ladder", "V4");
  }
  int64_t Route(const std::string& name, const std::string& grade) {
    return Insert(GymRoute(name, grade));
  }
  static Viewer Anonymous(const std::string& address = "10.0.0.9") {
    Viewer v;
    v.address = address;
    return v;
  }
  static TickInput Input(const std::string& outcome, std::optional<int> attempts = std::nullopt,
                         const std::string& felt = "") {
    TickInput in;
    in.outcome = outcome;
    in.attempts = attempts;
    in.felt_grade = felt;
    return in;
  }

  int64_t route_ = 0;
};

TEST_F(LogbookTest, OneTickPerClimberRouteAndDayASecondEditsIt) {
  Logbook book(store_.get(), &clock_);
  Result<TickSaved> first = book.Log(Anonymous(), route_, "", Input("attempt", 3));
  ASSERT_TRUE(first.ok()) << first.status().message();
  EXPECT_TRUE(first->participant.is_new);
  EXPECT_FALSE(first->edited);
  EXPECT_EQ(first->tick.day, "2023-11-14");  // the fake clock's day
  TickInput send = Input("send", 4, "V5");
  send.stars = 4;
  send.comment = " nice ";
  Result<TickSaved> again = book.Log(Anonymous(), route_, first->participant.token, send);
  ASSERT_TRUE(again.ok()) << again.status().message();
  EXPECT_TRUE(again->edited);
  EXPECT_FALSE(again->participant.is_new);
  EXPECT_EQ(again->tick.id, first->tick.id);
  EXPECT_EQ(again->tick.outcome, "send");
  EXPECT_EQ(again->tick.stars, 4);
  EXPECT_EQ(again->tick.comment, "nice");
  EXPECT_EQ(again->tick.felt_value, 5.0);
  clock_.Advance(24 * 3600);
  Result<TickSaved> next_day = book.Log(Anonymous(), route_, first->participant.token,
                                        Input("flash"));
  ASSERT_TRUE(next_day.ok());
  EXPECT_NE(next_day->tick.id, first->tick.id);
  EXPECT_EQ(next_day->tick.attempts, 1);
  Result<LogbookView> mine = book.Mine(Anonymous(), first->participant.token);
  ASSERT_TRUE(mine.ok());
  ASSERT_EQ(mine->ticks.size(), 2u);
  EXPECT_EQ(mine->ticks[0].day, "2023-11-15");
  ASSERT_EQ(mine->pyramid.size(), 1u);
  EXPECT_EQ(mine->pyramid[0], std::make_pair(std::string("V4"), 1));
}

TEST_F(LogbookTest, RefusesBadFieldsNamingThem) {
  Logbook book(store_.get(), &clock_);
  auto message = [&](const TickInput& in) {
    Result<TickSaved> r = book.Log(Anonymous(), route_, "", in);
    return r.ok() ? std::string("ok") : r.status().message();
  };
  EXPECT_NE(message(Input("onsight")).find("outcome"), std::string::npos);
  EXPECT_NE(message(Input("send", 0)).find("attempts"), std::string::npos);
  EXPECT_NE(message(Input("flash", 3)).find("attempts"), std::string::npos);
  EXPECT_NE(message(Input("send", 2, "5.11a")).find("felt grade"), std::string::npos);
  EXPECT_NE(message(Input("send", 2, "V99x")).find("felt grade"), std::string::npos);
  TickInput stars = Input("send");
  stars.stars = 6;
  EXPECT_NE(message(stars).find("stars"), std::string::npos);
  EXPECT_EQ(book.Log(Anonymous(), 99999, "", Input("send")).status().code(),
            Status::Code::kNotFound);
}

TEST_F(LogbookTest, BurstOfNewIdentitiesIsHeldOutUntilASetterAccepts) {
  Logbook book(store_.get(), &clock_);
  // Five climbers on the gym's wifi: all count.
  for (int i = 0; i < 5; ++i) {
    Result<TickSaved> t = book.Log(Anonymous(), route_, "", Input("send", 2 + i % 3, "V4"));
    ASSERT_TRUE(t.ok()) << t.status().message();
    EXPECT_FALSE(t->held) << i;
  }
  Result<AscentGrade> before = book.Ascent(Anonymous(), route_);
  ASSERT_TRUE(before.ok()) << before.status().message();
  EXPECT_EQ(before->ticks, 5);
  EXPECT_EQ(before->felt_median, "V4");
  // One phone clears its cookie six times and votes V9: every vote is held.
  std::vector<int64_t> held;
  for (int i = 0; i < 6; ++i) {
    Result<TickSaved> t = book.Log(Anonymous(), route_, "", Input("attempt", 10, "V9"));
    ASSERT_TRUE(t.ok()) << t.status().message();
    EXPECT_TRUE(t->held) << i;
    held.push_back(t->tick.id);
  }
  // A climber from another address is not held.
  Result<TickSaved> other = book.Log(Anonymous("10.9.9.9"), route_, "", Input("flash"));
  ASSERT_TRUE(other.ok());
  EXPECT_FALSE(other->held);
  Result<AscentGrade> after = book.Ascent(Anonymous(), route_);
  ASSERT_TRUE(after.ok());
  EXPECT_EQ(after->ticks, 6);
  EXPECT_EQ(after->felt_median, "V4");
  EXPECT_EQ(after->felt_votes, 5);

  // The setter sees them; a climber may not.
  Result<std::vector<Tick>> seen = book.ForSetters(setter_, route_);
  ASSERT_TRUE(seen.ok()) << seen.status().message();
  EXPECT_EQ(seen->size(), 12u);
  Viewer climber = User("climber");
  EXPECT_EQ(book.ForSetters(climber, route_).status().code(), Status::Code::kPermission);
  EXPECT_EQ(book.Decide(climber, route_, held[0], true).code(), Status::Code::kPermission);
  EXPECT_EQ(book.ForSetters(Anonymous(), route_).status().code(),
            Status::Code::kUnauthenticated);
  // Accepting one brings it into the consensus; discarding drops it.
  ASSERT_TRUE(book.Decide(setter_, route_, held[0], true).ok());
  ASSERT_TRUE(book.Decide(setter_, route_, held[1], false).ok());
  EXPECT_EQ(book.Decide(setter_, route_, 99999, true).code(), Status::Code::kNotFound);
  Result<AscentGrade> accepted = book.Ascent(Anonymous(), route_);
  ASSERT_TRUE(accepted.ok());
  EXPECT_EQ(accepted->ticks, 7);
  EXPECT_EQ(accepted->felt_votes, 6);

  // After the window, new identities from that address count again.
  clock_.Advance(LogbookPolicy{}.burst_window_seconds + 1);
  Result<TickSaved> later = book.Log(Anonymous(), route_, "", Input("send"));
  ASSERT_TRUE(later.ok());
  EXPECT_FALSE(later->held);
}

TEST_F(LogbookTest, SignInMergesTheDevicesTicksIntoTheLogbook) {
  Logbook book(store_.get(), &clock_);
  const int64_t other = Route("Slab", "V2");
  Result<TickSaved> a = book.Log(Anonymous(), route_, "", Input("send", 3));
  ASSERT_TRUE(a.ok());
  const std::string token = a->participant.token;
  ASSERT_TRUE(book.Log(Anonymous(), other, token, Input("flash")).ok());
  Viewer ann = User("ann");
  ASSERT_TRUE(book.Log(ann, route_, "", Input("attempt", 2)).ok());
  clock_.Advance(60);
  // The device edits its tick of the route later: the newer of the two.
  ASSERT_TRUE(book.Log(Anonymous(), route_, token, Input("flash")).ok());
  EXPECT_EQ(book.MergeDevice(Anonymous(), token).status().code(),
            Status::Code::kUnauthenticated);
  Result<int> moved = book.MergeDevice(ann, token);
  ASSERT_TRUE(moved.ok()) << moved.status().message();
  EXPECT_EQ(*moved, 2);
  Result<LogbookView> mine = book.Mine(ann, "");
  ASSERT_TRUE(mine.ok());
  ASSERT_EQ(mine->ticks.size(), 2u);
  for (const Tick& t : mine->ticks) {
    EXPECT_EQ(t.climber, "u:" + std::to_string(*ann.user_id));
    EXPECT_EQ(t.outcome, "flash");  // both flashes; the newer edit won
  }
  EXPECT_TRUE(book.Mine(Anonymous(), token)->ticks.empty());
  EXPECT_EQ(*book.MergeDevice(ann, "not a token"), 0);
}

TEST_F(LogbookTest, BudgetsPerAddressRouteAndClimberAreNamed) {
  LogbookPolicy p;
  p.ticks_per_climber = 2;
  p.ticks_per_address = 3;
  p.burst_new_identities = 100;
  Logbook book(store_.get(), &clock_, p);
  Result<TickSaved> a = book.Log(Anonymous(), route_, "", Input("send"));
  ASSERT_TRUE(a.ok());
  ASSERT_TRUE(book.Log(Anonymous(), route_, a->participant.token, Input("flash")).ok());
  int retry = 0;
  Result<TickSaved> third =
      book.Log(Anonymous(), route_, a->participant.token, Input("attempt"), &retry);
  EXPECT_EQ(third.status().code(), Status::Code::kResourceExhausted);
  EXPECT_NE(third.status().message().find("ticks"), std::string::npos);
  EXPECT_GT(retry, 0);
  ASSERT_TRUE(book.Log(Anonymous(), route_, "", Input("send")).ok());
  EXPECT_EQ(book.Log(Anonymous(), route_, "", Input("send")).status().code(),
            Status::Code::kResourceExhausted);  // the address's fourth
  EXPECT_TRUE(book.Log(Anonymous("10.1.1.1"), route_, "", Input("send")).ok());
  LogbookPolicy bad;
  bad.burst_new_identities = 0;
  Logbook broken(store_.get(), &clock_, bad);
  Result<TickSaved> refused = broken.Log(Anonymous(), route_, "", Input("send"));
  EXPECT_NE(refused.status().message().find("burst_new_identities"), std::string::npos);
}

TEST_F(LogbookTest, AscentGradeHasAnIntervalAndFlagsOnlyOutsideTheBand) {
  Logbook book(store_.get(), &clock_);
  const int64_t easy = Route("Jugs", "V0");
  Result<AscentGrade> none = book.Ascent(Anonymous(), route_);
  ASSERT_TRUE(none.ok());
  EXPECT_FALSE(none->fitted);
  // Forty climbers of all sorts flash the "V4"; each also tries the V0.
  for (int i = 0; i < 40; ++i) {
    Viewer v = Anonymous("10.0.1." + std::to_string(i));
    Result<TickSaved> t = book.Log(v, route_, "", Input("flash"));
    ASSERT_TRUE(t.ok()) << t.status().message();
    ASSERT_TRUE(book.Log(v, easy, t->participant.token, Input("flash")).ok());
  }
  Result<AscentGrade> g = book.Ascent(Anonymous(), route_);
  ASSERT_TRUE(g.ok()) << g.status().message();
  EXPECT_TRUE(g->fitted);
  EXPECT_EQ(g->ticks, 40);
  EXPECT_LT(g->lo, g->value);
  EXPECT_GT(g->hi, g->value);
  EXPECT_LT(g->value, 4.0);
  EXPECT_FALSE(g->grade.empty());
  // Cached: the same answer without new ticks.
  Result<AscentGrade> again = book.Ascent(Anonymous(), route_);
  EXPECT_EQ(again->value, g->value);
  if (g->hi < 3.5) {
    EXPECT_EQ(g->verdict, "soft");
  } else {
    EXPECT_EQ(g->verdict, "");
  }
  // The same evidence on both: the setter's grades keep them apart.
  Result<AscentGrade> e = book.Ascent(Anonymous(), easy);
  ASSERT_TRUE(e.ok());
  EXPECT_EQ(e->ticks, 40);
  EXPECT_LT(e->value, g->value);
  // A new tick is seen at once (the cache follows the gym's ticks).
  ASSERT_TRUE(book.Log(Anonymous("10.0.2.1"), route_, "", Input("attempt", 20)).ok());
  Result<AscentGrade> moved = book.Ascent(Anonymous(), route_);
  ASSERT_TRUE(moved.ok());
  EXPECT_EQ(moved->ticks, 41);
  EXPECT_GT(moved->value, g->value);
  // A page's routes at once (issue 22): the same grades as one by one; an
  // untried route and a route outside a gym are not fitted.
  const int64_t untried = Route("Untried", "V2");
  std::vector<RouteView> page;
  for (int64_t id : {route_, easy, untried}) page.push_back(ToView(*store_->GetRoute(id)));
  RouteView loose;
  loose.id = 999999;
  page.push_back(loose);
  Result<std::map<int64_t, AscentGrade>> all = book.Ascents(Anonymous(), page);
  ASSERT_TRUE(all.ok()) << all.status().message();
  ASSERT_EQ(all->size(), 4u);
  EXPECT_EQ(all->at(route_).value, book.Ascent(Anonymous(), route_)->value);
  EXPECT_EQ(all->at(route_).ticks, 41);
  EXPECT_EQ(all->at(easy).value, book.Ascent(Anonymous(), easy)->value);
  EXPECT_EQ(all->at(easy).grade, book.Ascent(Anonymous(), easy)->grade);
  EXPECT_FALSE(all->at(untried).fitted);
  EXPECT_FALSE(all->at(999999).fitted);
}

}  // namespace
}  // namespace sb::app
