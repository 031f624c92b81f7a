// Abilities that drift (ratings_drift.h): the chain problem, a rising
// climber recovered better with drift than without, the static path left
// bit-identical, intervals that follow one-sided evidence, and the drifting
// synthetic gym's goals.
#include "grades/ratings_drift.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "base/hash.h"
#include "base/number.h"
#include "grades/ratings_io.h"
#include "grades/ratings_synth.h"

namespace sb::grades {
namespace {

const RatingParams kV = RatingParams::For(Discipline::kBouldering);

TEST(RatingsDrift, DaysModesAndSeason) {
  EXPECT_EQ(DayNumber("1970-01-01"), 0);
  EXPECT_EQ(DayNumber("2026-01-01"), 20454);
  EXPECT_EQ(DayNumber("2024-03-01") - DayNumber("2024-02-28"), 2);  // leap year
  EXPECT_EQ(*ParseDriftMode("auto"), DriftMode::kAuto);
  auto bad = ParseDriftMode("yes");
  ASSERT_FALSE(bad.ok());
  EXPECT_EQ(bad.status().message(), "--drift: expected on, off or auto, got 'yes'");
  EXPECT_FALSE(DriftApplies(DriftMode::kAuto, 100, 100 + kSeasonDays));
  EXPECT_TRUE(DriftApplies(DriftMode::kAuto, 100, 101 + kSeasonDays));
  EXPECT_TRUE(DriftApplies(DriftMode::kOn, 5, 5));
  EXPECT_FALSE(DriftApplies(DriftMode::kOff, 0, 1000));
}

TEST(RatingsDrift, ReaderKeepsDatesWithoutChangingTheProblem) {
  const std::string ticks =
      "climber,route,date,outcome,attempts,felt_grade\n"
      "ann,A,2026-01-05,flash,,\n"
      "ann,B,2026-01-06,send,3,V4\n"
      "bob,A,2026-06-01,attempt,2,\n"
      "ann,B,2026-09-01,send,2,\n";
  const std::string routes = "route,grade\nA,V3\nB,V5\n";
  auto plain = ReadRatingsInput(ticks, "T", routes, "R");
  RatingsReadOptions ro;
  ro.keep_dates = true;
  auto dated = ReadRatingsInput(ticks, "T", routes, "R", ro);
  ASSERT_TRUE(plain.ok() && dated.ok());
  EXPECT_TRUE(plain->dated.empty());
  ASSERT_EQ(dated->dated.size(), 4u);
  EXPECT_EQ(dated->first_day, DayNumber("2026-01-05"));
  EXPECT_EQ(dated->last_day, DayNumber("2026-09-01"));
  ASSERT_EQ(plain->problem.pairs.size(), dated->problem.pairs.size());
  for (size_t i = 0; i < plain->problem.pairs.size(); ++i) {
    EXPECT_EQ(plain->problem.pairs[i].wins, dated->problem.pairs[i].wins);
    EXPECT_EQ(plain->problem.pairs[i].losses, dated->problem.pairs[i].losses);
  }
  // Nodes: ann's two weeks in January are one node (5 and 6 January share a
  // week from the first day), then September; bob one node.
  auto dp = BuildDriftProblem(dated->problem, dated->dated);
  ASSERT_TRUE(dp.ok()) << dp.status().message();
  ASSERT_EQ(dp->num_nodes(), 3);
  EXPECT_EQ(dp->climber_start, (std::vector<int32_t>{0, 2, 3}));
  EXPECT_EQ(dp->node_day[1] - dp->node_day[0], (DayNumber("2026-09-01") - dp->first_day) / 7 * 7);
  ASSERT_EQ(dp->pairs.size(), 4u);  // (A, ann@jan), (A, bob), (B, ann@jan), (B, ann@sep)
  auto fit = FitDriftRatings(*dp, kV);
  ASSERT_TRUE(fit.ok()) << fit.status().message();
  EXPECT_TRUE(fit->drift_sd_estimated);
  EXPECT_GE(fit->grid.size(), 2u);  // the walk over the grid: at least two points
  EXPECT_EQ(fit->drift_sd > 0, true);
  EXPECT_EQ(fit->fit.ability[0], fit->node_value[1]);  // ann's latest
}

// The static fit's every value and sd, %.17g, hashed: computed from main's
// unchanged FitRatings (issue 35's drift-off bit-identity). A change of
// the static fit changes this digest.
TEST(RatingsDrift, StaticFitIsBitIdenticalWithDriftOff) {
  SynthGymParams sp;
  sp.climbers = 60;
  sp.routes = 50;
  sp.ticks_per_route = 8;
  sp.seed = 7;
  const SynthGym gym = *MakeSynthGym(sp);
  // Through the reader with and without dates: the same problem, the same fit.
  RatingsReadOptions ro;
  ro.keep_dates = true;
  auto a = ReadRatingsInput(SynthTicksCsv(gym), "T", SynthRoutesCsv(gym), "R");
  auto b = ReadRatingsInput(SynthTicksCsv(gym), "T", SynthRoutesCsv(gym), "R", ro);
  ASSERT_TRUE(a.ok() && b.ok());
  auto fa = FitRatings(a->problem, kV);
  auto fb = FitRatings(b->problem, kV);
  ASSERT_TRUE(fa.ok() && fb.ok());
  std::string text;
  for (const auto* v : {&fa->difficulty, &fa->difficulty_sd, &fa->ability, &fa->ability_sd}) {
    for (double x : *v) text += FormatDouble(x, 17) + ",";
  }
  std::string text_b;
  for (const auto* v : {&fb->difficulty, &fb->difficulty_sd, &fb->ability, &fb->ability_sd}) {
    for (double x : *v) text_b += FormatDouble(x, 17) + ",";
  }
  EXPECT_EQ(text, text_b);
  EXPECT_EQ(Fnv1a64(text), 0xb3a4b07740ed4a1dull) << std::hex << Fnv1a64(text);
}

// A climber who rises from about V2 to V7 over a year among static
// climbers: drift on puts their latest ability near V7; a static fit
// averages the year.
TEST(RatingsDrift, RisingClimberIsRecoveredBetterWithDrift) {
  RatingProblemBuilder b;
  std::vector<DatedTick> dated;
  const int day0 = DayNumber("2026-01-01");
  // Routes V0..V9, each set (setter's grade exact), tried by ten static
  // climbers of known level and by the riser.
  const int routes = 10;
  for (int r = 0; r < routes; ++r) b.SetSetterGrade(r, r);
  auto add = [&](int c, int r, int day, TickOutcome o, std::optional<int> n) {
    const Games g = *TickGames(o, n);
    b.AddTick(c, r, g);
    dated.push_back({c, r, day0 + day, g});
  };
  // Static climbers 1..10 at level c - 1: flash below, fail above.
  for (int c = 1; c <= 10; ++c) {
    for (int r = 0; r < routes; ++r) {
      const int day = (c * 31 + r * 17) % 360;
      if (r < c - 1) add(c, r, day, TickOutcome::kFlash, std::nullopt);
      else if (r == c - 1) add(c, r, day, TickOutcome::kSend, 3);
      else add(c, r, day, TickOutcome::kAttempt, 3);
    }
  }
  // The riser (climber 0): level 2 + 5 t / 360 on day t, a tick every 12 days.
  for (int day = 0; day < 360; day += 12) {
    const double level = 2 + 5.0 * day / 360;
    for (int r = 0; r < routes; ++r) {
      if (std::abs(r - level) > 1.6) continue;
      if (r < level - 0.5) add(0, r, day, TickOutcome::kFlash, std::nullopt);
      else if (r < level + 0.5) add(0, r, day, TickOutcome::kSend, 2);
      else add(0, r, day, TickOutcome::kAttempt, 3);
    }
  }
  const RatingProblem p = b.Build();
  auto still = FitRatings(p, kV);
  ASSERT_TRUE(still.ok());
  auto dp = BuildDriftProblem(p, dated);
  ASSERT_TRUE(dp.ok());
  auto moving = FitDriftRatings(*dp, kV);
  ASSERT_TRUE(moving.ok()) << moving.status().message();
  const double truth = 2 + 5.0 * 348 / 360;  // the last tick's level
  const double err_still = std::abs(still->ability[0] - truth);
  const double err_moving = std::abs(moving->fit.ability[0] - truth);
  EXPECT_LT(err_moving, 0.6) << moving->fit.ability[0];
  EXPECT_GT(err_still, 1.5) << still->ability[0];
  EXPECT_LT(err_moving, err_still / 3);
  // The evidence prefers a drift to none: the chosen w is not the grid's least.
  EXPECT_GT(moving->drift_sd, kDriftSdGrid[0]);
  // Its interval holds the truth; the static one does not.
  EXPECT_LE(std::abs(moving->fit.ability[0] - truth), kZ80 * moving->fit.ability_sd[0]);
  EXPECT_GT(std::abs(still->ability[0] - truth), kZ80 * still->ability_sd[0]);
}

// A route nobody sent: the likelihood is flat above (any harder fits the
// failures), so its interval reaches further up than down; a route every
// climber flashed, the other way.
TEST(RatingsDrift, SkewedIntervalsFollowOneSidedEvidence) {
  RatingProblemBuilder b;
  // Routes 0..5 at V1..V6 pin eight climbers around V3-V4.
  for (int r = 0; r < 6; ++r) b.SetSetterGrade(r, r + 1);
  for (int c = 0; c < 8; ++c) {
    for (int r = 0; r < 6; ++r) {
      b.AddTick(c, r, r + 1 <= 3 + c % 2 ? Games{1, 0} : Games{0, 2});
    }
    b.AddTick(c, 6, Games{0, 4});  // route 6 (no setter's grade): nobody sent
    b.AddTick(c, 7, Games{1, 0});  // route 7 (no setter's grade): everybody flashed
  }
  const RatingProblem p = b.Build();
  auto fit = FitRatings(p, kV);
  ASSERT_TRUE(fit.ok());
  std::vector<double> ab;
  for (const RatingPair& q : p.pairs) ab.push_back(fit->ability[size_t(q.climber)]);
  const std::vector<Interval> iv = SkewedRouteIntervals(p, p.pairs, ab, kV, *fit);
  ASSERT_EQ(iv.size(), 8u);
  const double v6 = fit->difficulty[6], v7 = fit->difficulty[7];
  EXPECT_GT(iv[6].hi - v6, 1.2 * (v6 - iv[6].lo)) << iv[6].lo << " " << v6 << " " << iv[6].hi;
  EXPECT_GT(v7 - iv[7].lo, 1.2 * (iv[7].hi - v7)) << iv[7].lo << " " << v7 << " " << iv[7].hi;
  // Two-sided evidence: nearly the symmetric interval.
  for (int r = 0; r < 6; ++r) {
    const double sd = fit->difficulty_sd[size_t(r)];
    EXPECT_GT(iv[size_t(r)].hi - iv[size_t(r)].lo, 0.8 * 2 * kZ80 * sd) << r;
    EXPECT_LT(iv[size_t(r)].hi - iv[size_t(r)].lo, 1.5 * 2 * kZ80 * sd) << r;
  }
}

// The issue's goal on the drifting gym at 20 ticks a route: with drift,
// coverage of the 80% intervals 70-90% and Spearman >= 0.98; without, the
// intervals are overconfident.
TEST(RatingsDrift, DriftingGymGoalFigures) {
  SynthGymParams sp;  // 400 routes, 300 climbers, 20 ticks a route, seed 1
  auto gym = MakeDriftingGym(sp);
  ASSERT_TRUE(gym.ok()) << gym.status().message();
  auto on = EvaluateDriftingGym(*gym, kV, true);
  auto off = EvaluateDriftingGym(*gym, kV, false);
  ASSERT_TRUE(on.ok() && off.ok());
  EXPECT_GE(on->routes.spearman, 0.98);
  EXPECT_GE(on->routes.coverage, 0.70);
  EXPECT_LE(on->routes.coverage, 0.90);
  EXPECT_GE(on->skewed_coverage, 0.70);
  EXPECT_LE(on->skewed_coverage, 0.90);
  EXPECT_LT(on->climber_mae, off->climber_mae);
  EXPECT_GT(on->routes.coverage, off->routes.coverage);
}

}  // namespace
}  // namespace sb::grades
