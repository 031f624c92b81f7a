// app::Logbook: one tick per climber, route and day; the burst rule holds a
// phone that clears its cookie out of every consensus until a setter
// accepts; sign-in merges the device's ticks; budgets; the ascent grade.
#include "app/logbook.h"

#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <map>
#include <memory>
#include <set>
#include <string>
#include <thread>
#include <vector>

#include "app/discipline.h"
#include "app/logbook_fixture.h"
#include "base/date.h"
#include "grades/ratings.h"
#include "grades/ratings_synth.h"
#include "grades/scale.h"
#include "store/gym_store.h"
#include "store/tick_page.h"
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
  // The policy without the issue-34 standing rules (every identity
  // established: no pooling, no rush), for the tests of the rules before it.
  static LogbookPolicy Unearned() {
    LogbookPolicy p;
    p.history_routes = 0;
    return p;
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

// A small synthetic gym (docs/grades.md, "A new tick"): eight bouldering
// routes V0..V7 and one roped 5.10a, twelve climbers of abilities 0 to 6.6
// (each from its own address) tick every route once, each outcome drawn from
// the model (a flash with P = 1 / (1 + 3^(d - a)), else two tries without a
// send) with a fixed seed, some with a felt grade.
class SyntheticGymTest : public LogbookTest {
 protected:
  void SetUp() override {
    LogbookTest::SetUp();
    if (IsSkipped() || HasFatalFailure()) return;
    for (int i = 0; i < 8; ++i) {
      boulders_.push_back(Route("B" + std::to_string(i), "V" + std::to_string(i)));
    }
    store::RouteRecord r = GymRoute("Rope", "5.10a");
    r.grade_discipline = "roped";
    Result<grades::Grade> g = grades::ParseGrade("5.10a", {grades::Discipline::kRoped, {}});
    ASSERT_TRUE(g.ok()) << g.status().message();
    r.grade_value = g->value;
    rope_ = Insert(r);
  }
  // Logs the gym's ticks through `book`. Issue 34: climbers earn their
  // standing first (three routes each on day 0, four new identities per
  // route, under the rush rule), the rest two days later; the clock then
  // moves two more days so every climber is established on every route.
  void Populate(Logbook& book) {
    uint64_t seed = 42;
    auto uniform = [&seed] {
      seed = seed * 6364136223846793005ULL + 1442695040888963407ULL;
      return double(seed >> 11) / double(1ULL << 53);
    };
    // The outcomes drawn in the order climber, route (as before the warm-up).
    bool flashes[12][8];
    for (int c = 0; c < 12; ++c) {
      for (int i = 0; i < 8; ++i) flashes[c][i] = uniform() < 1 / (1 + std::pow(3.0, i - 0.6 * c));
    }
    std::vector<std::string> tokens(12);
    auto tick = [&](int c, int i) {
      Viewer v = Anonymous("10.3.0." + std::to_string(c));
      const std::string felt = c % 3 == 0 ? "V" + std::to_string(std::max(0, i - c / 6)) : "";
      Result<TickSaved> t =
          i == 8 ? book.Log(v, rope_, tokens[size_t(c)], Input(c > 5 ? "flash" : "attempt"))
                 : book.Log(v, boulders_[size_t(i)], tokens[size_t(c)],
                            flashes[c][i] ? Input("flash", std::nullopt, felt)
                                          : Input("attempt", 2, felt));
      ASSERT_TRUE(t.ok()) << t.status().message();
      ASSERT_FALSE(t->held) << c << " " << i;
      if (tokens[size_t(c)].empty()) tokens[size_t(c)] = t->participant.token;
    };
    auto warm_up = [](int c, int i) { return (i - 3 * c % 9 + 9) % 9 < 3; };
    for (int c = 0; c < 12; ++c) {
      for (int i = 0; i < 9; ++i) {
        if (warm_up(c, i)) ASSERT_NO_FATAL_FAILURE(tick(c, i));
      }
    }
    clock_.Advance(2 * 86400);
    for (int c = 0; c < 12; ++c) {
      for (int i = 0; i < 9; ++i) {
        if (!warm_up(c, i)) ASSERT_NO_FATAL_FAILURE(tick(c, i));
      }
    }
    clock_.Advance(2 * 86400);
  }
  // The grade of `route` from a full fit of the gym (a fresh logbook).
  AscentGrade Refit(int64_t route) {
    Logbook fresh(store_.get(), &clock_);
    Result<AscentGrade> a = fresh.Ascent(Anonymous(), route);
    EXPECT_TRUE(a.ok()) << a.status().message();
    EXPECT_EQ(fresh.FullFits(), 1u);
    return a.ok() ? *a : AscentGrade{};
  }
  // The incremental grade agrees with a refit within kValueTolerance (grade
  // units) for the value and kIntervalTolerance for the interval's ends
  // (docs/grades.md, "A new tick": measured here 0.074 and 0.102 at most with
  // 8 of 104 ticks absorbed, the untouched routes included).
  void ExpectAgreesWithRefit(Logbook& book, int64_t route, const char* what) {
    static constexpr double kValueTolerance = 0.1;
    static constexpr double kIntervalTolerance = 0.15;
    Result<AscentGrade> a = book.Ascent(Anonymous(), route);
    ASSERT_TRUE(a.ok()) << a.status().message();
    const AscentGrade full = Refit(route);
    EXPECT_EQ(a->ticks, full.ticks) << what;
    EXPECT_NEAR(a->value, full.value, kValueTolerance) << what;
    EXPECT_NEAR(a->lo, full.lo, kIntervalTolerance) << what;
    EXPECT_NEAR(a->hi, full.hi, kIntervalTolerance) << what;
    EXPECT_EQ(a->felt_votes, full.felt_votes) << what;
    EXPECT_EQ(a->felt_median, full.felt_median) << what;
  }

  std::vector<int64_t> boulders_;
  int64_t rope_ = 0;
};

TEST_F(SyntheticGymTest, ANewTickUpdatesTheCachedFitWithoutARefit) {
  LogbookPolicy policy;
  policy.fit_incremental_min_ticks = 1000;  // no refit for drift here
  Logbook book(store_.get(), &clock_, policy);
  ASSERT_NO_FATAL_FAILURE(Populate(book));
  const int64_t route = boulders_[2];
  Result<AscentGrade> before = book.Ascent(Anonymous(), route);
  ASSERT_TRUE(before.ok()) << before.status().message();
  ASSERT_TRUE(book.Ascent(Anonymous(), rope_).ok());
  ASSERT_EQ(book.FullFits(), 2u);  // one per discipline
  EXPECT_EQ(before->ticks, 12);

  // A new climber tries the V2 six times: the route's grade moves up at
  // once, in the POST's own answer path (Ascent), without a refit.
  Viewer newcomer = Anonymous("10.4.0.1");
  Result<TickSaved> t = book.Log(newcomer, route, "", Input("attempt", 6, "V4"));
  ASSERT_TRUE(t.ok()) << t.status().message();
  Result<AscentGrade> after = book.Ascent(Anonymous(), route);
  ASSERT_TRUE(after.ok());
  EXPECT_EQ(book.FullFits(), 2u);
  EXPECT_EQ(after->ticks, 13);
  // Issue 34: a new identity counts as one game in the route's pool (six
  // tries weigh as one failure), so the grade barely moves; the update still
  // agrees with a refit.
  EXPECT_NEAR(after->value, before->value, 0.1);
  ExpectAgreesWithRefit(book, route, "new tick");
  // The roped entry stayed valid (its ticks did not change).
  ASSERT_TRUE(book.Ascent(Anonymous(), rope_).ok());
  EXPECT_EQ(book.FullFits(), 2u);

  // An edit (same climber, route and day) replaces the tick's games.
  Result<TickSaved> edit =
      book.Log(newcomer, route, t->participant.token, Input("flash", std::nullopt, "V1"));
  ASSERT_TRUE(edit.ok()) << edit.status().message();
  ASSERT_TRUE(edit->edited);
  Result<AscentGrade> edited = book.Ascent(Anonymous(), route);
  ASSERT_TRUE(edited.ok());
  EXPECT_EQ(book.FullFits(), 2u);
  EXPECT_EQ(edited->ticks, 13);
  EXPECT_LT(edited->value, after->value);
  ExpectAgreesWithRefit(book, route, "edit");

  // A new route's first tick is rated from its prior and that tick.
  const int64_t fresh_route = Route("New", "V3");
  ASSERT_TRUE(book.Log(newcomer, fresh_route, t->participant.token, Input("send", 3)).ok());
  Result<AscentGrade> first = book.Ascent(Anonymous(), fresh_route);
  ASSERT_TRUE(first.ok());
  EXPECT_TRUE(first->fitted);
  EXPECT_EQ(book.FullFits(), 2u);
  ExpectAgreesWithRefit(book, fresh_route, "new route");

  // A burst from one address: five new identities count, the sixth is held
  // and changes nothing.
  const int64_t busy = boulders_[5];
  for (int i = 0; i < 5; ++i) {
    Result<TickSaved> b = book.Log(Anonymous("10.5.0.1"), busy, "", Input("flash"));
    ASSERT_TRUE(b.ok()) << b.status().message();
    ASSERT_FALSE(b->held);
  }
  Result<AscentGrade> unheld = book.Ascent(Anonymous(), busy);
  ASSERT_TRUE(unheld.ok());
  EXPECT_EQ(unheld->ticks, 17);
  Result<TickSaved> held = book.Log(Anonymous("10.5.0.1"), busy, "", Input("flash"));
  ASSERT_TRUE(held.ok()) << held.status().message();
  ASSERT_TRUE(held->held);
  Result<AscentGrade> same = book.Ascent(Anonymous(), busy);
  ASSERT_TRUE(same.ok());
  EXPECT_EQ(same->ticks, unheld->ticks);
  EXPECT_EQ(same->value, unheld->value);
  EXPECT_EQ(same->hi, unheld->hi);
  EXPECT_EQ(book.FullFits(), 2u);
  ExpectAgreesWithRefit(book, busy, "burst");
  for (int64_t r : boulders_) ExpectAgreesWithRefit(book, r, "every route");
  EXPECT_EQ(book.FullFits(), 2u);
}

TEST_F(SyntheticGymTest, AfterItsDriftBudgetTheEntryIsRefittedInTheBackground) {
  LogbookPolicy policy;
  policy.fit_incremental_percent = 0;
  EXPECT_NE(policy.Validate().message().find("fit_incremental_percent"), std::string::npos);
  policy.fit_incremental_percent = 2;
  policy.fit_incremental_min_ticks = 2;  // 2% of 96 ticks is 1: the floor
  Logbook book(store_.get(), &clock_, policy);
  ASSERT_NO_FATAL_FAILURE(Populate(book));
  ASSERT_TRUE(book.Ascent(Anonymous(), boulders_[0]).ok());
  ASSERT_EQ(book.FullFits(), 1u);
  for (int i = 0; i < 3; ++i) {
    ASSERT_TRUE(book.Log(Anonymous("10.6.0." + std::to_string(i)), boulders_[1], "",
                         Input("flash"))
                    .ok());
    book.WaitForRefits();  // issue 34: the refit runs in the background
    ASSERT_TRUE(book.Ascent(Anonymous(), boulders_[1]).ok());
    // Two ticks are absorbed; the third is over the budget: refitted.
    EXPECT_EQ(book.FullFits(), i < 2 ? 1u : 2u) << i;
  }
  ExpectAgreesWithRefit(book, boulders_[1], "after the refit");
  Result<AscentGrade> now = book.Ascent(Anonymous(), boulders_[1]);
  EXPECT_EQ(now->value, Refit(boulders_[1]).value);  // exactly: it is a refit
}

// Issue 34: anonymous readers of throw-away gyms cannot flush a real gym's
// fit: a gym with members and 50+ ticks is kept over theirs, a gym of fewer
// than five tick writes is fitted without being cached, and one without
// members is not fitted for them at all.
TEST_F(SyntheticGymTest, ThrowAwayGymsCannotFlushARealGymsFit) {
  LogbookPolicy policy;
  policy.fit_cache_entries = 2;
  Logbook book(store_.get(), &clock_, policy);
  ASSERT_NO_FATAL_FAILURE(Populate(book));
  ASSERT_TRUE(book.Ascent(Anonymous(), boulders_[0]).ok());
  ASSERT_EQ(book.FullFits(), 1u);
  store::GymStore* gyms = store::GymStoreOf(store_.get());
  for (int i = 0; i < 6; ++i) {
    Result<int64_t> g = gyms->CreateGym("Throw-away " + std::to_string(i), setter_.user_id);
    ASSERT_TRUE(g.ok());
    store::RouteRecord r = GymRoute("T" + std::to_string(i), "V3");
    r.gym_id = *g;
    const int64_t id = Insert(r);
    const int ticks = i < 3 ? 5 : 2;  // cached (not kept), or fitted uncached
    for (int k = 0; k < ticks; ++k) {
      ASSERT_TRUE(book.Log(Anonymous("10.11." + std::to_string(i) + "." + std::to_string(k)), id,
                           "", Input("flash"))
                      .ok());
    }
    Result<AscentGrade> a = book.Ascent(Anonymous(), id);
    ASSERT_TRUE(a.ok());
    EXPECT_TRUE(a->fitted) << i;
  }
  EXPECT_LE(book.CachedFits(), 2u);
  const uint64_t fits = book.FullFits();
  ASSERT_TRUE(book.Ascent(Anonymous(), boulders_[0]).ok());
  EXPECT_EQ(book.FullFits(), fits);  // still cached: no refit
  // A gym without members: nothing for anonymous readers, a fit for members.
  Result<int64_t> bare = gyms->CreateGym("No members", std::nullopt);
  if (bare.ok()) {
    store::RouteRecord r = GymRoute("Bare", "V3");
    r.gym_id = *bare;
    const int64_t id = Insert(r);
    for (int k = 0; k < 6; ++k) {
      ASSERT_TRUE(book.Log(Anonymous("10.12.0." + std::to_string(k)), id, "", Input("flash")).ok());
    }
    EXPECT_FALSE(book.Ascent(Anonymous(), id)->fitted);
    EXPECT_TRUE(book.Ascent(setter_, id)->fitted);
  }
}

// Issue 34: ticks arriving together each update the cached fit (ticks of a
// gym are serialised), so no reader refits afterwards.
TEST_F(SyntheticGymTest, ConcurrentTicksAreAllAbsorbedWithoutARefit) {
  LogbookPolicy policy;
  policy.fit_incremental_min_ticks = 1000;  // no refit for drift here
  Logbook book(store_.get(), &clock_, policy);
  ASSERT_NO_FATAL_FAILURE(Populate(book));
  ASSERT_TRUE(book.Ascent(Anonymous(), boulders_[0]).ok());
  ASSERT_EQ(book.FullFits(), 1u);
  std::vector<std::thread> phones;
  std::atomic<int> failed{0};
  for (int p = 0; p < 8; ++p) {
    phones.emplace_back([&, p] {
      std::string token;
      for (int i = 0; i < 4; ++i) {
        Result<TickSaved> t = book.Log(Anonymous("10.7.0." + std::to_string(p)),
                                       boulders_[size_t((p + i) % 8)], token, Input("send", 2));
        if (!t.ok() || t->held) {
          ++failed;
          continue;
        }
        if (token.empty()) token = t->participant.token;
      }
    });
  }
  for (std::thread& t : phones) t.join();
  ASSERT_EQ(failed.load(), 0);
  for (int64_t r : boulders_) {
    Result<AscentGrade> a = book.Ascent(Anonymous(), r);
    ASSERT_TRUE(a.ok());
    EXPECT_EQ(a->ticks, 12 + 4) << r;  // 12 of Populate, 4 of the phones each
    EXPECT_EQ(a->age_seconds, 0);
  }
  EXPECT_EQ(book.FullFits(), 1u);
  for (int64_t r : boulders_) ExpectAgreesWithRefit(book, r, "concurrent ticks");
}

// Issue 34: the first fit of a gym is made once however many read it at once
// (single flight); every reader gets the same grades.
TEST_F(SyntheticGymTest, ConcurrentReadersShareOneFit) {
  {
    Logbook writer(store_.get(), &clock_);
    ASSERT_NO_FATAL_FAILURE(Populate(writer));
  }
  Logbook book(store_.get(), &clock_);
  std::vector<std::thread> readers;
  std::vector<double> values(8, -99);
  for (int i = 0; i < 8; ++i) {
    readers.emplace_back([&, i] {
      Result<AscentGrade> a = book.Ascent(Anonymous(), boulders_[3]);
      if (a.ok()) values[size_t(i)] = a->value;
    });
  }
  for (std::thread& t : readers) t.join();
  EXPECT_EQ(book.FullFits(), 1u);
  for (double v : values) EXPECT_EQ(v, values[0]);
  EXPECT_EQ(book.CachedFits(), 1u);
}

// Issue 34: a tick's answer never waits for a fit: with none kept, the
// answer's grade (KeptAscent) is unfitted and the gym's first fit is made in
// the background, once however many ask at once; the next answer has it.
TEST_F(SyntheticGymTest, ATicksAnswerNeverMakesTheFirstFit) {
  {
    Logbook writer(store_.get(), &clock_);
    ASSERT_NO_FATAL_FAILURE(Populate(writer));
  }
  Logbook book(store_.get(), &clock_);
  Result<TickSaved> t = book.Log(Anonymous("10.12.0.1"), boulders_[2], "", Input("send", 2));
  ASSERT_TRUE(t.ok()) << t.status().message();
  Result<AscentGrade> first = book.KeptAscent(Anonymous(), boulders_[2]);
  ASSERT_TRUE(first.ok());
  EXPECT_FALSE(first->fitted);  // none was kept: the answer did not wait for one
  std::vector<std::thread> phones;
  std::atomic<int> fitted{0}, failed{0};
  for (int i = 0; i < 8; ++i) {
    phones.emplace_back([&] {
      Result<AscentGrade> a = book.KeptAscent(Anonymous(), boulders_[2]);
      if (!a.ok()) ++failed;
      if (a.ok() && a->fitted) ++fitted;
    });
  }
  for (std::thread& p : phones) p.join();
  EXPECT_EQ(failed.load(), 0);
  EXPECT_LE(fitted.load(), 8);  // those after the background fit landed see it
  book.WaitForRefits();
  EXPECT_EQ(book.FullFits(), 1u);  // one background fit for the nine answers
  EXPECT_EQ(book.CachedFits(), 1u);
  Result<AscentGrade> a = book.KeptAscent(Anonymous(), boulders_[2]);
  ASSERT_TRUE(a.ok());
  EXPECT_TRUE(a->fitted);
  EXPECT_EQ(a->ticks, 12 + 1);
  EXPECT_EQ(a->age_seconds, 0);
  EXPECT_EQ(book.FullFits(), 1u);
}

// Issue 34: a discipline's fit reads only that discipline's ticks (the one
// roped route's 12, not the gym's 108), and counts them as a fit over all
// the gym's ticks did (the new identities' pooling from every discipline's
// history).
TEST_F(SyntheticGymTest, ADisciplinesFitReadsOnlyItsTicks) {
  {
    Logbook writer(store_.get(), &clock_);
    ASSERT_NO_FATAL_FAILURE(Populate(writer));
  }
  Logbook book(store_.get(), &clock_);
  Result<AscentGrade> rope = book.Ascent(Anonymous(), rope_);
  ASSERT_TRUE(rope.ok()) << rope.status().message();
  EXPECT_EQ(book.FullFits(), 1u);
  EXPECT_EQ(book.TicksRead(), 12u);
  EXPECT_EQ(rope->ticks, 12);
  Result<AscentGrade> boulder = book.Ascent(Anonymous(), boulders_[0]);
  ASSERT_TRUE(boulder.ok()) << boulder.status().message();
  EXPECT_EQ(book.FullFits(), 2u);
  EXPECT_EQ(book.TicksRead(), 12u + 96u);
  EXPECT_EQ(boulder->ticks, 12);
}

// Issue 34: a big gym's stale fit (ticks written by another process) is
// shown with its age while one background refit runs; readers never wait
// for it, and the refit brings the grades current.
TEST_F(SyntheticGymTest, AStaleBigGymIsRefittedOnceInTheBackground) {
  LogbookPolicy policy;
  policy.fit_background_min_ticks = 1;  // the synthetic gym counts as big
  Logbook book(store_.get(), &clock_, policy);
  ASSERT_NO_FATAL_FAILURE(Populate(book));
  Result<AscentGrade> before = book.Ascent(Anonymous(), boulders_[4]);
  ASSERT_TRUE(before.ok());
  ASSERT_EQ(book.FullFits(), 1u);
  {
    Logbook other(store_.get(), &clock_, policy);  // another server process
    ASSERT_TRUE(other.Log(Anonymous("10.8.0.1"), boulders_[4], "", Input("attempt", 5)).ok());
  }
  std::vector<std::thread> readers;
  std::atomic<int> stale{0};
  for (int i = 0; i < 8; ++i) {
    readers.emplace_back([&] {
      Result<AscentGrade> a = book.Ascent(Anonymous(), boulders_[4]);
      if (a.ok() && a->ticks == before->ticks && a->age_seconds > 0) ++stale;
    });
  }
  for (std::thread& t : readers) t.join();
  book.WaitForRefits();
  EXPECT_EQ(book.FullFits(), 2u);  // one refit for the eight readers
  EXPECT_GE(stale.load(), 1);      // the first reader at least saw the old fit, aged
  Result<AscentGrade> after = book.Ascent(Anonymous(), boulders_[4]);
  ASSERT_TRUE(after.ok());
  EXPECT_EQ(after->ticks, before->ticks + 1);
  EXPECT_EQ(after->age_seconds, 0);
  EXPECT_EQ(book.FullFits(), 2u);
}

// Issue 34: ticks keep arriving while background refits run (every tick is
// over the drift budget): each refit replays the ticks written during it, so
// it is current when published and no reader refits again.
TEST_F(SyntheticGymTest, TicksDuringARefitAreReplayedIntoIt) {
  LogbookPolicy policy;
  policy.fit_incremental_min_ticks = 1;
  policy.fit_incremental_percent = 1;
  Logbook book(store_.get(), &clock_, policy);
  ASSERT_NO_FATAL_FAILURE(Populate(book));
  ASSERT_TRUE(book.Ascent(Anonymous(), boulders_[0]).ok());
  std::vector<std::thread> phones;
  for (int p = 0; p < 4; ++p) {
    phones.emplace_back([&, p] {
      std::string token;
      for (int i = 0; i < 8; ++i) {
        Result<TickSaved> t = book.Log(Anonymous("10.10.0." + std::to_string(p)),
                                       boulders_[size_t(i)], token, Input("attempt", 1 + p));
        if (t.ok() && token.empty()) token = t->participant.token;
      }
    });
  }
  for (std::thread& t : phones) t.join();
  book.WaitForRefits();
  const uint64_t fits = book.FullFits();
  EXPECT_GE(fits, 2u);
  for (int64_t r : boulders_) {
    Result<AscentGrade> a = book.Ascent(Anonymous(), r);
    ASSERT_TRUE(a.ok());
    EXPECT_EQ(a->ticks, 16) << r;
  }
  book.WaitForRefits();
  EXPECT_EQ(book.FullFits(), fits);  // current: nothing refitted by the reads
}


// Issue 34 (memory): the store reads the gym's ticks in pages by id; a fit
// made from pages of 3 ticks (35 pages here) is the fit made from one page,
// value for value, on either backend.
TEST_F(SyntheticGymTest, TheFitIsTheSameReadInPagesOfThreeTicks) {
  Logbook book(store_.get(), &clock_);
  ASSERT_NO_FATAL_FAILURE(Populate(book));
  std::vector<AscentGrade> whole;
  for (int64_t r : boulders_) whole.push_back(Refit(r));
  whole.push_back(Refit(rope_));
  const int64_t before = store::SetGymTickPageForTesting(3);
  std::vector<AscentGrade> paged;
  for (int64_t r : boulders_) paged.push_back(Refit(r));
  paged.push_back(Refit(rope_));
  store::SetGymTickPageForTesting(before);
  ASSERT_EQ(whole.size(), paged.size());
  for (size_t i = 0; i < whole.size(); ++i) {
    EXPECT_TRUE(whole[i].fitted) << i;
    EXPECT_EQ(whole[i].ticks, paged[i].ticks) << i;
    EXPECT_EQ(whole[i].value, paged[i].value) << i;
    EXPECT_EQ(whole[i].lo, paged[i].lo) << i;
    EXPECT_EQ(whole[i].hi, paged[i].hi) << i;
    EXPECT_EQ(whole[i].grade, paged[i].grade) << i;
    EXPECT_EQ(whole[i].felt_votes, paged[i].felt_votes) << i;
    EXPECT_EQ(whole[i].felt_median, paged[i].felt_median) << i;
  }
}

// Issue 34 (memory): the old fit, made from the discipline's ticks held as
// one vector of records (main at 70c1919's Logbook::DoFlight, kept here as
// the reference): each route's difficulty and its standard deviation.
std::map<int64_t, std::pair<double, double>> RecordsFit(store::Store* store, int64_t gym,
                                                        const std::string& discipline,
                                                        const std::string& aged,
                                                        int history_routes) {
  std::map<int64_t, std::pair<double, double>> out;
  store::TickStore* ticks = store::TickStoreOf(store);
  Result<grades::Discipline> d = grades::ParseDiscipline(discipline);
  Result<std::vector<store::TickRecord>> all = ticks->GymDisciplineTicks(gym, discipline);
  Result<std::map<std::string, int64_t>> aged_counts = ticks->AgedRouteCounts(gym, aged);
  EXPECT_TRUE(d.ok() && all.ok() && aged_counts.ok());
  if (!d.ok() || !all.ok() || !aged_counts.ok()) return out;
  std::map<int64_t, store::RouteRecord> routes;
  std::vector<const store::TickRecord*> used;
  for (const store::TickRecord& t : *all) {
    auto it = routes.find(t.route_id);
    if (it == routes.end()) it = routes.emplace(t.route_id, *store->GetRoute(t.route_id)).first;
    if (FitDiscipline(it->second.grade_discipline) == discipline) used.push_back(&t);
  }
  std::map<int64_t, int> route_index;
  for (const auto& [id, r] : routes) {
    if (FitDiscipline(r.grade_discipline) == discipline) {
      route_index.emplace(id, static_cast<int>(route_index.size()));
    }
  }
  std::map<std::string, std::set<int64_t>> aged_here;
  for (const store::TickRecord& t : *all) {
    if (t.state == gym::TickState::kOk && t.created_at <= aged) aged_here[t.climber].insert(t.route_id);
  }
  grades::RatingProblemBuilder b;
  b.EnsureRoutes(static_cast<int>(route_index.size()));
  std::map<std::string, int> climber_index;
  for (const store::TickRecord* t : used) {
    auto n = aged_counts->find(t->climber);
    int64_t others = n == aged_counts->end() ? 0 : n->second;
    if (aged_here[t->climber].count(t->route_id)) --others;
    const bool young = others < history_routes;
    Result<grades::TickOutcome> o = grades::ParseTickOutcome(t->outcome);
    if (!o.ok()) continue;
    Result<grades::Games> g = grades::TickGames(*o, t->attempts);
    if (!g.ok()) continue;
    std::optional<double> felt;
    if (young) {
      const bool sent = g->wins > 0;
      *g = grades::Games{sent ? 1 : 0, sent ? 0 : 1};
    } else if (t->felt_value && t->felt_discipline == discipline) {
      felt = t->felt_value;
    }
    const std::string key = young ? "new:" + std::to_string(t->route_id) : t->climber;
    auto c = climber_index.emplace(key, static_cast<int>(climber_index.size())).first;
    b.AddTick(c->second, route_index.at(t->route_id), *g, felt);
    if (t->attempts) {
      b.AddSessionTries(*t->attempts);
    } else if (t->outcome == "flash") {
      b.AddSessionTries(1);
    }
  }
  b.EnsureClimbers(static_cast<int>(climber_index.size()));
  for (const auto& [id, idx] : route_index) {
    const store::RouteRecord& r = routes.at(id);
    if (r.grade_value && r.grade_discipline == discipline) b.SetSetterGrade(idx, *r.grade_value);
  }
  Result<grades::RatingFit> fit = grades::FitRatings(b.Build(), grades::RatingParams::For(*d));
  EXPECT_TRUE(fit.ok());
  if (!fit.ok()) return out;
  for (const auto& [id, idx] : route_index) {
    out[id] = {fit->difficulty[size_t(idx)], fit->difficulty_sd[size_t(idx)]};
  }
  return out;
}

// Issue 34 (memory): the fit consumes the store's pages of ticks into a
// compact form (app/logbook.cc FitTicks) instead of holding the gym's ticks
// as one vector of records. Its grades are the records' fit's, value for
// value, read in pages of 10,000 or of 2, with some identities pooled as new
// (only the warm-up ticks are old enough here).
TEST_F(SyntheticGymTest, ThePagedCompactFitIsTheFitOfTheRecords) {
  {
    Logbook writer(store_.get(), &clock_);
    ASSERT_NO_FATAL_FAILURE(Populate(writer));
  }
  LogbookPolicy policy;
  policy.history_age_seconds = 3 * 86400;
  const std::string aged = UtcTimeText(clock_.Now() - policy.history_age_seconds);
  std::map<int64_t, std::pair<double, double>> want =
      RecordsFit(store_.get(), gym_, "bouldering", aged, policy.history_routes);
  for (const auto& [id, v] : RecordsFit(store_.get(), gym_, "roped", aged, policy.history_routes)) {
    want[id] = v;
  }
  ASSERT_EQ(want.size(), boulders_.size() + 1);
  // Some identities are pooled as new: the fit differs from one where none is.
  EXPECT_NE(want.at(boulders_[0]),
            RecordsFit(store_.get(), gym_, "bouldering", aged, 0).at(boulders_[0]));
  for (int64_t page : {int64_t{10000}, int64_t{2}}) {
    const int64_t before = store::SetGymTickPageForTesting(page);
    Logbook fresh(store_.get(), &clock_, policy);
    for (const auto& [id, v] : want) {
      Result<AscentGrade> a = fresh.Ascent(Anonymous(), id);
      ASSERT_TRUE(a.ok()) << a.status().message();
      EXPECT_EQ(a->value, v.first) << id << " page " << page;
      EXPECT_EQ(a->lo, v.first - grades::kZ80 * v.second) << id << " page " << page;
      EXPECT_EQ(a->hi, v.first + grades::kZ80 * v.second) << id << " page " << page;
    }
    store::SetGymTickPageForTesting(before);
    EXPECT_EQ(fresh.FullFits(), 2u);
  }
}

// Issue 34 (memory): big fits run one at a time in the process: four
// logbooks (as after a restart, or readers of two disciplines) fitting the
// gym at once, every gym counting as big, never ran two together.
TEST_F(SyntheticGymTest, BigFitsRunOneAtATime) {
  {
    Logbook writer(store_.get(), &clock_);
    ASSERT_NO_FATAL_FAILURE(Populate(writer));
  }
  LogbookPolicy policy;
  policy.fit_background_min_ticks = 1;
  std::vector<std::unique_ptr<Logbook>> books;
  for (int i = 0; i < 4; ++i)
    books.push_back(std::make_unique<Logbook>(store_.get(), &clock_, policy));
  std::vector<std::thread> readers;
  std::atomic<int> fitted{0};
  for (int i = 0; i < 4; ++i) {
    readers.emplace_back([&, i] {
      Result<AscentGrade> a = books[size_t(i)]->Ascent(Anonymous(), i % 2 ? rope_ : boulders_[0]);
      if (a.ok() && a->fitted) ++fitted;
    });
  }
  for (std::thread& t : readers) t.join();
  EXPECT_EQ(fitted.load(), 4);
  EXPECT_EQ(Logbook::MostBigFitsAtOnce(), 1);
}

// Issue 34 (memory): the fit cache is bounded in bytes too: entries are
// charged by their size, and past fit_cache_bytes the least recently used
// goes (never the one just made).
TEST_F(SyntheticGymTest, TheFitCacheIsBoundedInBytes) {
  {
    Logbook writer(store_.get(), &clock_);
    ASSERT_NO_FATAL_FAILURE(Populate(writer));
  }
  int64_t both = 0;
  {
    Logbook book(store_.get(), &clock_);
    ASSERT_TRUE(book.Ascent(Anonymous(), boulders_[0]).ok());
    const int64_t boulder = book.CachedFitBytes();
    EXPECT_GT(boulder, 8 * 1000);  // 8 routes' grades and the state at least
    ASSERT_TRUE(book.Ascent(Anonymous(), rope_).ok());
    both = book.CachedFitBytes();
    EXPECT_GT(both, boulder);
    EXPECT_EQ(book.CachedFits(), 2u);
  }
  LogbookPolicy policy;
  policy.fit_cache_bytes = both - 1;
  Logbook book(store_.get(), &clock_, policy);
  ASSERT_TRUE(book.Ascent(Anonymous(), rope_).ok());
  ASSERT_TRUE(book.Ascent(Anonymous(), boulders_[0]).ok());
  // The roped fit went (12 ticks: below fit_keep_min_ticks, so it goes
  // before a kept entry; it would anyway, as the least recently used).
  EXPECT_EQ(book.CachedFits(), 1u);
  EXPECT_LT(book.CachedFitBytes(), both);
  ASSERT_TRUE(book.Ascent(Anonymous(), boulders_[0]).ok());
  EXPECT_EQ(book.FullFits(), 2u);  // the bouldering one kept
  ASSERT_TRUE(book.Ascent(Anonymous(), rope_).ok());
  EXPECT_EQ(book.FullFits(), 3u);  // the roped one refitted
}

// Issue 34, grades no one can push: a V3 route with ten honest ticks from
// established climbers (each with day-old ticks on three other routes), and
// an eleventh established climber who has not ticked it yet.
class IntegrityTest : public LogbookTest {
 protected:
  void SetUp() override {
    LogbookTest::SetUp();
    if (IsSkipped() || HasFatalFailure()) return;
    for (int i = 0; i < 10; ++i) {
      others_.push_back(Route("O" + std::to_string(i), "V" + std::to_string(i % 6)));
    }
    target_ = Route("Target", "V3");
    Logbook book(store_.get(), &clock_);
    tokens_.resize(11);
    for (int c = 0; c < 11; ++c) {
      const double ability = 2.5 + 0.2 * c;
      for (int k = 0; k < 3; ++k) {  // three or four new identities per route
        const int i = (3 * c + k) % 10;
        ASSERT_NO_FATAL_FAILURE(Honest(book, c, others_[size_t(i)],
                                       i % 6 < ability ? Input("flash") : Input("attempt", 2)));
      }
    }
    clock_.Advance(2 * 86400);
    for (int c = 0; c < 10; ++c) {
      ASSERT_NO_FATAL_FAILURE(Honest(book, c, target_, c % 2 ? Input("send", 2) : Input("flash")));
    }
    clock_.Advance(3600);
    base_ = Refitted();
  }
  void Honest(Logbook& book, int c, int64_t route, const TickInput& in) {
    Result<TickSaved> t = book.Log(Anonymous("10.20.0." + std::to_string(c)), route,
                                   tokens_[size_t(c)], in);
    ASSERT_TRUE(t.ok()) << t.status().message();
    ASSERT_FALSE(t->held);
    if (tokens_[size_t(c)].empty()) tokens_[size_t(c)] = t->participant.token;
  }
  // The target's grade from a full fit (a fresh logbook, as after a restart).
  double Refitted() {
    Logbook fresh(store_.get(), &clock_);
    Result<AscentGrade> a = fresh.Ascent(setter_, target_);
    EXPECT_TRUE(a.ok() && a->fitted);
    return a.ok() ? a->value : 0;
  }
  // After an attack through `book`: the grade moved less than half a grade
  // (kept fit and full refit), and honest climbers still tick: the eleventh
  // established climber (counted, not held) and a new phone elsewhere.
  void ExpectHeldOrBounded(Logbook& book, int attackers, const char* what) {
    Result<AscentGrade> shown = book.Ascent(setter_, target_);
    ASSERT_TRUE(shown.ok());
    const double refit = Refitted();
    std::map<int64_t, std::string> reasons;
    Result<std::vector<Tick>> ticks = book.ForSetters(setter_, target_, &reasons);
    ASSERT_TRUE(ticks.ok());
    int held = 0;
    for (const Tick& t : *ticks) held += t.state == gym::TickState::kHeld;
    std::printf("%s: %d attackers, %d held; grade %.3f -> %.3f (kept fit %.3f)\n", what,
                attackers, held, base_, refit, shown->value);
    EXPECT_LT(std::abs(refit - base_), 0.5) << what;
    EXPECT_LT(std::abs(shown->value - base_), 0.5) << what;
    EXPECT_EQ(static_cast<int>(reasons.size()), held);
    for (const auto& [id, why] : reasons) EXPECT_FALSE(why.empty()) << id;
    Result<TickSaved> honest = book.Log(Anonymous("10.20.0.10"), target_, tokens_[10], Input("flash"));
    ASSERT_TRUE(honest.ok()) << honest.status().message();
    EXPECT_FALSE(honest->held) << what;
    EXPECT_TRUE(book.Log(Anonymous("10.99.0.1"), others_[2], "", Input("send", 2)).ok()) << what;
  }

  std::vector<int64_t> others_;
  int64_t target_ = 0;
  std::vector<std::string> tokens_;
  double base_ = 0;
};

TEST_F(IntegrityTest, EightNewAccountsFromEightAddressesMoveItLessThanHalfAGrade) {
  Logbook book(store_.get(), &clock_);
  ASSERT_TRUE(book.Ascent(setter_, target_).ok());  // a kept fit, updated tick by tick
  for (int i = 0; i < 8; ++i) {
    Viewer sybil = User("sybil" + std::to_string(i), "10.40.0." + std::to_string(i));
    ASSERT_TRUE(book.Log(sybil, target_, "", Input("attempt", 30)).ok()) << i;
  }
  ExpectHeldOrBounded(book, 8, "8 accounts, 8 addresses");
}

TEST_F(IntegrityTest, FiftyFourDevicesAgedOnOtherRoutesFromOneAddressAreHeldOrBounded) {
  Logbook book(store_.get(), &clock_);
  ASSERT_TRUE(book.Ascent(setter_, target_).ok());
  std::vector<std::string> devices(54);
  for (int d = 0; d < 54; ++d) {  // ageing: three other routes each
    for (int k = 0; k < 3; ++k) {
      Result<TickSaved> t =
          book.Log(Anonymous("10.30.0.1"), others_[size_t((d + k) % 6)], devices[size_t(d)],
                   Input("flash"));
      ASSERT_TRUE(t.ok()) << t.status().message();
      if (devices[size_t(d)].empty()) devices[size_t(d)] = t->participant.token;
    }
  }
  clock_.Advance(600);  // ten minutes
  for (int d = 0; d < 54; ++d) {
    ASSERT_TRUE(book.Log(Anonymous("10.30.0.1"), target_, devices[size_t(d)], Input("attempt", 30)).ok())
        << d;
  }
  ExpectHeldOrBounded(book, 54, "54 aged devices, one address");
}

TEST_F(IntegrityTest, TwentyDevicesFromTwentyAddressesAreHeldOrBounded) {
  Logbook book(store_.get(), &clock_);
  ASSERT_TRUE(book.Ascent(setter_, target_).ok());
  for (int d = 0; d < 20; ++d) {
    ASSERT_TRUE(
        book.Log(Anonymous("10.50.0." + std::to_string(d)), target_, "", Input("attempt", 30)).ok())
        << d;
  }
  ExpectHeldOrBounded(book, 20, "20 devices, 20 addresses");
}

// The rule is the rush rule, not the burst rule: a new identity past the
// rush from many addresses is held with the rush named; an established
// climber's tick is never held by it.
TEST_F(IntegrityTest, TheRushRuleNamesItselfToTheSetter) {
  Logbook book(store_.get(), &clock_);
  std::vector<bool> held;
  for (int d = 0; d < 7; ++d) {
    Result<TickSaved> t =
        book.Log(Anonymous("10.60.0." + std::to_string(d)), target_, "", Input("flash"));
    ASSERT_TRUE(t.ok());
    held.push_back(t->held);
  }
  EXPECT_EQ(held, (std::vector<bool>{false, false, false, false, false, true, true}));
  std::map<int64_t, std::string> reasons;
  ASSERT_TRUE(book.ForSetters(setter_, target_, &reasons).ok());
  ASSERT_EQ(reasons.size(), 2u);
  for (const auto& [id, why] : reasons) EXPECT_EQ(why.rfind("rush:", 0), 0u) << why;
  // A day later the rush window has passed: a new identity counts again.
  clock_.Advance(86400 + 1);
  Result<TickSaved> later = book.Log(Anonymous("10.60.1.1"), target_, "", Input("flash"));
  ASSERT_TRUE(later.ok());
  EXPECT_FALSE(later->held);
}

// Issue 34: what the new-identity rule costs on the synthetic gyms
// (docs/grades.md, "Ticks no one can push"): each gym fitted on its first
// `day` days of ticks, once as recorded and once with the ticks of
// identities that have fewer than three other routes ticked a day before
// pooled per route as one game each (felt grades dropped), as Logbook's fit
// does. The loss must stay under 0.01 in Spearman and 2 points of coverage.
TEST(NewIdentityWeightsTest, CostLittleOnTheSyntheticGyms) {
  for (int per_route : {20, 5}) {
    for (int day : {45, 364}) {
      grades::SynthGymParams sp;
      sp.ticks_per_route = per_route;
      Result<grades::SynthGym> gym = grades::MakeSynthGym(sp);
      ASSERT_TRUE(gym.ok());
      std::vector<grades::SynthTick> upto;
      for (const grades::SynthTick& t : gym->ticks) {
        if (t.day <= day) upto.push_back(t);
      }
      std::map<int, std::set<int>> aged;  // climber -> routes ticked before `day`
      for (const grades::SynthTick& t : upto) {
        if (t.day < day) aged[t.climber].insert(t.route);
      }
      auto fit = [&](bool pooled, int* pooled_ticks) {
        grades::RatingProblemBuilder b;
        const int climbers = static_cast<int>(gym->true_ability.size());
        b.EnsureClimbers(climbers);
        b.EnsureRoutes(static_cast<int>(gym->true_difficulty.size()));
        for (size_t r = 0; r < gym->setter_grade.size(); ++r) b.SetSetterGrade(int(r), gym->setter_grade[r]);
        int extra = 0;
        for (const grades::SynthTick& t : upto) {
          Result<grades::Games> g = grades::TickGames(t.outcome, t.attempts);
          if (!g.ok()) continue;
          const std::set<int>& mine = aged[t.climber];
          const bool young = pooled && int(mine.size() - mine.count(t.route)) < 3;
          if (young) {
            ++*pooled_ticks;
            const bool sent = g->wins > 0;
            b.AddTick(climbers + t.route, t.route, grades::Games{sent ? 1 : 0, sent ? 0 : 1});
            extra = std::max(extra, t.route + 1);
          } else {
            b.AddTick(t.climber, t.route, *g,
                      t.felt ? std::optional<double>(*t.felt) : std::nullopt);
          }
        }
        b.EnsureClimbers(climbers + extra);
        Result<grades::RatingFit> f =
            grades::FitRatings(b.Build(), grades::RatingParams::For(grades::Discipline::kBouldering));
        EXPECT_TRUE(f.ok());
        std::pair<double, double> out{0, 0};
        if (!f.ok()) return out;
        out.first = grades::Spearman(f->difficulty, gym->true_difficulty);
        int covered = 0;
        for (size_t r = 0; r < gym->true_difficulty.size(); ++r) {
          const double truth = gym->true_difficulty[r];
          covered += std::abs(truth - f->difficulty[r]) <= grades::kZ80 * f->difficulty_sd[r];
        }
        out.second = double(covered) / double(gym->true_difficulty.size());
        return out;
      };
      int none = 0, pooled_ticks = 0;
      const auto [rho0, cov0] = fit(false, &none);
      const auto [rho1, cov1] = fit(true, &pooled_ticks);
      std::printf("synthetic gym, %d ticks per route, first %d days (%zu ticks, %d pooled): "
                  "Spearman %.4f -> %.4f, coverage %.3f -> %.3f\n",
                  per_route, day + 1, upto.size(), pooled_ticks, rho0, rho1, cov0, cov1);
      EXPECT_GT(rho1, rho0 - 0.01) << per_route << " " << day;
      EXPECT_GT(cov1, cov0 - 0.02) << per_route << " " << day;
      if (per_route == 20 && day == 364) {
        // The goal figures of docs/grades.md ("Goal figures") hold with the
        // weights on: Spearman >= 0.95 at 20 ticks a route, coverage 70-90%.
        EXPECT_GE(rho1, 0.95);
        EXPECT_GE(cov1, 0.70);
        EXPECT_LE(cov1, 0.90);
      }
      // Coverage stays honest at every tick count (70-90%).
      EXPECT_GE(cov1, 0.70) << per_route << " " << day;
      EXPECT_LE(cov1, 0.90) << per_route << " " << day;
    }
  }
}

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
  Logbook book(store_.get(), &clock_, Unearned());
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

// Issue 34: a route's budget is per address: one address that spends it
// blocks only itself; climbers on other addresses keep ticking the route.
TEST_F(LogbookTest, ARoutesTickBudgetIsPerAddressNotShared) {
  LogbookPolicy p;
  p.ticks_per_route = 3;
  p.burst_new_identities = 100;
  Logbook book(store_.get(), &clock_, p);
  for (int i = 0; i < 3; ++i) {
    ASSERT_TRUE(book.Log(Anonymous("10.9.0.1"), route_, "", Input("send")).ok()) << i;
  }
  int retry = 0;
  EXPECT_EQ(book.Log(Anonymous("10.9.0.1"), route_, "", Input("send"), &retry).status().code(),
            Status::Code::kResourceExhausted);
  EXPECT_GT(retry, 0);
  for (int i = 0; i < 3; ++i) {
    EXPECT_TRUE(book.Log(Anonymous("10.9.1." + std::to_string(i)), route_, "", Input("send")).ok())
        << i;
  }
}

TEST_F(LogbookTest, AscentGradeHasAnIntervalAndFlagsOnlyOutsideTheBand) {
  Logbook book(store_.get(), &clock_, Unearned());
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
  for (int64_t id : {route_, easy, untried}) page.push_back(*store_->GetRoute(id));
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
