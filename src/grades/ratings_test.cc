// The ascent rating (ratings.h): ticks as games, the builder, the fit's
// optimum and intervals against a dense Hessian written out here, the
// single-route update, warm starts, determinism; the synthetic gym and the
// issue's goal figures at 20 ticks per route (ratings_synth.h).
#include "grades/ratings.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "grades/ratings_synth.h"

namespace sb::grades {
namespace {

const RatingParams kV = RatingParams::For(Discipline::kBouldering);

Games G(TickOutcome o, std::optional<int> n) {
  auto g = TickGames(o, n);
  EXPECT_TRUE(g.ok()) << g.status().message();
  return g.ok() ? *g : Games{};
}

TEST(Ratings, TicksAsGames) {
  EXPECT_EQ(G(TickOutcome::kFlash, std::nullopt).wins, 1);
  EXPECT_EQ(G(TickOutcome::kFlash, 1).losses, 0);
  EXPECT_EQ(G(TickOutcome::kSend, 3).wins, 1);
  EXPECT_EQ(G(TickOutcome::kSend, 3).losses, 2);
  EXPECT_EQ(G(TickOutcome::kSend, std::nullopt).losses, kSendDefaultAttempts - 1);
  EXPECT_EQ(G(TickOutcome::kSend, 1).losses, 0);
  EXPECT_EQ(G(TickOutcome::kAttempt, std::nullopt).losses, 1);
  EXPECT_EQ(G(TickOutcome::kAttempt, 4).losses, 4);
  EXPECT_EQ(G(TickOutcome::kAttempt, 4).wins, 0);
  auto flash2 = TickGames(TickOutcome::kFlash, 2);
  ASSERT_FALSE(flash2.ok());
  EXPECT_NE(flash2.status().message().find("a flash is one try"), std::string::npos);
  EXPECT_FALSE(TickGames(TickOutcome::kAttempt, 0).ok());
  EXPECT_FALSE(TickGames(TickOutcome::kSend, kMaxTickAttempts + 1).ok());
  EXPECT_TRUE(TickGames(TickOutcome::kSend, kMaxTickAttempts).ok());
  EXPECT_EQ(*ParseTickOutcome("attempt"), TickOutcome::kAttempt);
  auto bad = ParseTickOutcome("Flash");
  ASSERT_FALSE(bad.ok());
  EXPECT_EQ(bad.status().message(), "outcome: expected flash, send or attempt, got 'Flash'");
}

TEST(Ratings, BuilderAggregatesPairsInRouteOrder) {
  RatingProblemBuilder b;
  b.AddTick(2, 1, {0, 3});
  b.AddTick(0, 1, {1, 0}, 5.0);
  b.AddTick(2, 1, {1, 1}, 3.0);
  b.AddTick(1, 0, {1, 0});
  b.SetSetterGrade(3, 4.0);
  RatingProblem p = b.Build();
  ASSERT_TRUE(p.Validate().ok());
  ASSERT_EQ(p.pairs.size(), 3u);
  EXPECT_EQ(p.pairs[0].route, 0);
  EXPECT_EQ(p.pairs[1].climber, 0);
  EXPECT_EQ(p.pairs[2].climber, 2);
  EXPECT_EQ(p.pairs[2].wins, 1);
  EXPECT_EQ(p.pairs[2].losses, 4);
  EXPECT_EQ(p.num_routes(), 4);
  EXPECT_EQ(p.num_climbers, 3);
  EXPECT_EQ(p.route_ticks[1], 3);
  EXPECT_EQ(p.climber_ticks[2], 2);
  EXPECT_EQ(p.felt_count[1], 2);
  EXPECT_DOUBLE_EQ(p.felt_sum[1], 8.0);
  EXPECT_FALSE(p.setter[0].has_value());
  EXPECT_DOUBLE_EQ(*p.setter[3], 4.0);
  p.pairs[0].wins = 0;
  p.pairs[0].losses = 0;
  EXPECT_FALSE(p.Validate().ok());
}

TEST(Ratings, ParamsValidateNamesTheField) {
  RatingParams k = kV;
  k.felt_sd = 0;
  Status s = k.Validate();
  ASSERT_FALSE(s.ok());
  EXPECT_NE(s.message().find("felt_sd"), std::string::npos);
  EXPECT_TRUE(RatingParams::For(Discipline::kRoped).Validate().ok());
  EXPECT_NEAR(RatingParams::For(Discipline::kRoped).logit_per_unit, 4 * std::log(2.1), 1e-15);
}

// A small gym: a dense Hessian of the negative log posterior written out
// from the formula of docs/grades.md, inverted by Gauss-Jordan.
std::vector<double> DenseInverseDiagonal(const RatingProblem& p, const RatingParams& k,
                                         const RatingFit& f) {
  const size_t c_n = size_t(p.num_climbers), n = c_n + size_t(p.num_routes());
  std::vector<std::vector<double>> h(n, std::vector<double>(2 * n, 0));
  for (size_t c = 0; c < c_n; ++c) h[c][c] = 1 / (k.climber_sd * k.climber_sd);
  for (size_t r = 0; r < size_t(p.num_routes()); ++r) {
    const double sd = p.setter[r] ? k.setter_sd : k.open_route_sd;
    h[c_n + r][c_n + r] = 1 / (sd * sd) + p.felt_count[r] / (k.felt_sd * k.felt_sd);
  }
  for (const RatingPair& q : p.pairs) {
    const size_t a = size_t(q.climber), d = c_n + size_t(q.route);
    const double pr =
        1 / (1 + std::exp(-k.logit_per_unit * (f.ability[a] - f.difficulty[d - c_n])));
    const double w = k.logit_per_unit * k.logit_per_unit * (q.wins + q.losses) * pr * (1 - pr);
    h[a][a] += w;
    h[d][d] += w;
    h[a][d] -= w;
    h[d][a] -= w;
  }
  for (size_t i = 0; i < n; ++i) h[i][n + i] = 1;
  for (size_t col = 0; col < n; ++col) {
    size_t piv = col;
    for (size_t i = col + 1; i < n; ++i) {
      if (std::abs(h[i][col]) > std::abs(h[piv][col])) piv = i;
    }
    std::swap(h[col], h[piv]);
    const double v = h[col][col];
    for (double& x : h[col]) x /= v;
    for (size_t i = 0; i < n; ++i) {
      if (i == col || h[i][col] == 0) continue;
      const double m = h[i][col];
      for (size_t j = 0; j < 2 * n; ++j) h[i][j] -= m * h[col][j];
    }
  }
  std::vector<double> diag(n);
  for (size_t i = 0; i < n; ++i) diag[i] = h[i][n + i];
  return diag;
}

SynthGym SmallGym(int climbers, int routes, int ticks, uint64_t seed) {
  SynthGymParams sp;
  sp.climbers = climbers;
  sp.routes = routes;
  sp.ticks_per_route = ticks;
  sp.seed = seed;
  auto gym = MakeSynthGym(sp);
  EXPECT_TRUE(gym.ok());
  return gym.ok() ? *gym : SynthGym{};
}

TEST(Ratings, ExactIntervalsAreTheInverseHessianDiagonal) {
  const SynthGym gym = SmallGym(25, 30, 8, 7);
  RatingProblem p = SynthProblem(gym);
  // Two routes without a setter's grade, one without ticks.
  p.setter[3].reset();
  p.setter[11].reset();
  auto fit = FitRatings(p, kV, {.intervals = IntervalMethod::kExact});
  ASSERT_TRUE(fit.ok()) << fit.status().message();
  EXPECT_TRUE(fit->exact_intervals);
  EXPECT_LE(fit->gradient_max, 1e-9);
  const std::vector<double> diag = DenseInverseDiagonal(p, kV, *fit);
  const size_t c_n = size_t(p.num_climbers);
  for (size_t c = 0; c < c_n; ++c) EXPECT_NEAR(fit->ability_sd[c], std::sqrt(diag[c]), 1e-10);
  for (size_t r = 0; r < size_t(p.num_routes()); ++r) {
    EXPECT_NEAR(fit->difficulty_sd[r], std::sqrt(diag[c_n + r]), 1e-10) << r;
  }
  // The approximation conditions on the other routes: never wider than exact, and close.
  auto approx = FitRatings(p, kV, {.intervals = IntervalMethod::kApproximate});
  ASSERT_TRUE(approx.ok());
  for (size_t r = 0; r < size_t(p.num_routes()); ++r) {
    EXPECT_EQ(approx->difficulty[r], fit->difficulty[r]);
    EXPECT_LE(approx->difficulty_sd[r], fit->difficulty_sd[r] + 1e-12);
    EXPECT_GT(approx->difficulty_sd[r], 0.8 * fit->difficulty_sd[r]);
  }
}

TEST(Ratings, PriorsAloneWithoutTicks) {
  RatingProblemBuilder b;
  b.SetSetterGrade(0, 2.0);
  b.SetSetterGrade(1, 6.0);
  b.EnsureRoutes(3);
  b.EnsureClimbers(1);
  auto fit = FitRatings(b.Build(), kV);
  ASSERT_TRUE(fit.ok());
  EXPECT_DOUBLE_EQ(fit->prior_mean, 4.0);
  EXPECT_DOUBLE_EQ(fit->difficulty[0], 2.0);
  EXPECT_DOUBLE_EQ(fit->difficulty_sd[0], kV.setter_sd);
  EXPECT_DOUBLE_EQ(fit->difficulty[2], 4.0);  // no setter's grade: the prior mean
  EXPECT_DOUBLE_EQ(fit->difficulty_sd[2], kV.open_route_sd);
  EXPECT_DOUBLE_EQ(fit->ability[0], 4.0);
  EXPECT_DOUBLE_EQ(fit->ability_sd[0], kV.climber_sd);
}

TEST(Ratings, OutcomesMoveTheRouteTheRightWay) {
  // Route 0 is flashed by everyone, route 1 never sent, route 2 split;
  // all graded V4 by the setter.
  RatingProblemBuilder b;
  for (int c = 0; c < 10; ++c) {
    b.AddTick(c, 0, {1, 0});
    b.AddTick(c, 1, {0, 3});
    b.AddTick(c, 2, c % 2 ? Games{1, 0} : Games{0, 1});
  }
  for (int r = 0; r < 3; ++r) b.SetSetterGrade(r, 4.0);
  auto fit = FitRatings(b.Build(), kV);
  ASSERT_TRUE(fit.ok());
  EXPECT_LT(fit->difficulty[0], 4.0);
  EXPECT_GT(fit->difficulty[1], 4.0);
  EXPECT_LT(fit->difficulty[0], fit->difficulty[2]);
  EXPECT_LT(fit->difficulty[2], fit->difficulty[1]);
  // Felt grades pull: the same ticks with felt V7 on route 2 rate it harder.
  RatingProblemBuilder b2;
  for (int c = 0; c < 10; ++c) {
    b2.AddTick(c, 0, {1, 0});
    b2.AddTick(c, 1, {0, 3});
    b2.AddTick(c, 2, c % 2 ? Games{1, 0} : Games{0, 1}, 7.0);
  }
  for (int r = 0; r < 3; ++r) b2.SetSetterGrade(r, 4.0);
  auto felt = FitRatings(b2.Build(), kV);
  ASSERT_TRUE(felt.ok());
  EXPECT_GT(felt->difficulty[2], fit->difficulty[2] + 0.5);
  EXPECT_LT(felt->difficulty_sd[2], fit->difficulty_sd[2]);
}

TEST(Ratings, DeterministicAndWarmStartAgree) {
  const SynthGym gym = SmallGym(200, 300, 10, 3);
  const RatingProblem p = SynthProblem(gym);
  auto a = FitRatings(p, kV);
  auto b = FitRatings(p, kV);
  ASSERT_TRUE(a.ok() && b.ok());
  EXPECT_EQ(a->difficulty, b->difficulty);  // bit-identical
  EXPECT_EQ(a->difficulty_sd, b->difficulty_sd);
  EXPECT_EQ(a->ability_sd, b->ability_sd);
  RatingFitOptions warm;
  warm.warm_start = &*a;
  auto w = FitRatings(p, kV, warm);
  ASSERT_TRUE(w.ok());
  EXPECT_LT(w->newton_iterations, a->newton_iterations);
  for (size_t r = 0; r < p.setter.size(); ++r)
    EXPECT_NEAR(w->difficulty[r], a->difficulty[r], 1e-9);
  // A new climber and a new route since the last fit: the warm start keeps
  // the known values and reaches the cold fit's optimum.
  SynthGym more = gym;
  more.true_ability.push_back(4);
  more.true_difficulty.push_back(4);
  more.setter_grade.push_back(6);
  more.ticks.push_back({200, 300, 0, TickOutcome::kSend, 3, 5});
  more.ticks.push_back({200, 4, 0, TickOutcome::kFlash, std::nullopt, std::nullopt});
  const RatingProblem q = SynthProblem(more);
  auto cold = FitRatings(q, kV);
  auto grown = FitRatings(q, kV, warm);
  ASSERT_TRUE(cold.ok() && grown.ok());
  ASSERT_EQ(grown->difficulty.size(), 301u);
  for (size_t r = 0; r < q.setter.size(); ++r) {
    EXPECT_NEAR(grown->difficulty[r], cold->difficulty[r], 1e-9);
  }
  EXPECT_NEAR(grown->ability[200], cold->ability[200], 1e-9);
}

TEST(Ratings, SingleRouteUpdate) {
  const SynthGym gym = SmallGym(100, 150, 10, 5);
  const RatingProblem p = SynthProblem(gym);
  auto fit = FitRatings(p, kV);
  ASSERT_TRUE(fit.ok());
  // At the joint optimum the one-route solve with the climbers held fixed
  // returns the fit's own value.
  for (int r : {0, 17, 149}) {
    auto e = EvidenceOf(p, kV, *fit, r);
    ASSERT_TRUE(e.ok());
    EXPECT_EQ(e->ticks, 10);
    auto rr = RateRoute(*e, *fit, kV);
    ASSERT_TRUE(rr.ok());
    EXPECT_NEAR(rr->value, fit->difficulty[size_t(r)], 1e-8);
    // The sd folds in the climbers' uncertainty: between the approximate and
    // twice the exact one.
    EXPECT_GT(rr->sd, 0.5 * fit->difficulty_sd[size_t(r)]);
    EXPECT_LT(rr->sd, 2 * fit->difficulty_sd[size_t(r)]);
  }
  // A new flash by the gym's weakest climber makes route 17 easier; a
  // failed try by the strongest makes it harder; a brand-new climber gets the prior.
  size_t weak = 0, strong = 0;
  for (size_t c = 0; c < fit->ability.size(); ++c) {
    if (fit->ability[c] < fit->ability[weak]) weak = c;
    if (fit->ability[c] > fit->ability[strong]) strong = c;
  }
  auto e = *EvidenceOf(p, kV, *fit, 17);
  RouteEvidence easier = e, harder = e;
  AddTickTo(&easier, int(weak), {1, 0}, std::nullopt);
  AddTickTo(&harder, int(strong), {0, 5}, std::nullopt);
  const double before = fit->difficulty[17];
  EXPECT_LT(RateRoute(easier, *fit, kV)->value, before);
  EXPECT_GT(RateRoute(harder, *fit, kV)->value, before);
  RouteEvidence fresh = e;
  AddTickTo(&fresh, 100000, {0, 1}, 9.0);
  EXPECT_EQ(fresh.ticks, 11);
  EXPECT_GT(RateRoute(fresh, *fit, kV)->value, before);
  EXPECT_FALSE(EvidenceOf(p, kV, *fit, 150).ok());
}

TEST(Ratings, ExactIntervalsAreLimited) {
  RatingProblemBuilder b;
  b.EnsureRoutes(kMaxExactRoutes + 1);
  b.EnsureClimbers(1);
  auto fit = FitRatings(b.Build(), kV, {.intervals = IntervalMethod::kExact});
  ASSERT_FALSE(fit.ok());
  EXPECT_NE(fit.status().message().find("limited to"), std::string::npos);
}

TEST(RatingsSynth, GeneratorIsDeterministicAndShaped) {
  const SynthGym a = SmallGym(50, 40, 6, 11), b = SmallGym(50, 40, 6, 11);
  EXPECT_EQ(SynthTicksCsv(a), SynthTicksCsv(b));
  EXPECT_EQ(SynthRoutesCsv(a), SynthRoutesCsv(b));
  EXPECT_NE(SynthTicksCsv(a), SynthTicksCsv(SmallGym(50, 40, 6, 12)));
  EXPECT_EQ(a.ticks.size(), 240u);
  int felt = 0, sends = 0;
  for (const SynthTick& t : a.ticks) {
    if (t.felt) ++felt;
    if (t.outcome != TickOutcome::kAttempt) ++sends;
    EXPECT_TRUE(TickGames(t.outcome, t.attempts).ok());
  }
  EXPECT_GT(felt, 0);
  EXPECT_LT(felt, sends);  // few: only some senders leave one
  EXPECT_EQ(SynthTicksCsv(a).substr(0, 46), "climber,route,date,outcome,attempts,felt_grade");
  SynthGymParams bad;
  bad.routes = 0;
  auto g = MakeSynthGym(bad);
  ASSERT_FALSE(g.ok());
  EXPECT_NE(g.status().message().find("--routes"), std::string::npos);
}

TEST(RatingsSynth, SpearmanMatchesHandValues) {
  const std::vector<double> a = {1, 2, 3, 4, 5}, b = {5, 6, 7, 8, 7};
  // ranks b: 1, 2, 3.5, 5, 3.5 -> rho = 0.82078268166812329 (scipy.stats.spearmanr)
  EXPECT_NEAR(Spearman(a, b), 0.82078268166812329, 1e-12);
  EXPECT_NEAR(Spearman(a, std::vector<double>{5, 4, 3, 2, 1}), -1, 1e-15);
  EXPECT_TRUE(std::isnan(Spearman(a, std::vector<double>{1, 1, 1, 1, 1})));
}

// The goal at 20 ticks per route on the documented generator:
// rank correlation >= 0.95, 80% intervals covering 70-90% of routes, and an
// error at least 30% below the felt grades' median.
TEST(RatingsSynth, GoalFiguresAtTwentyTicksPerRoute) {
  SynthGymParams sp;  // the defaults of `strangebeta ratings eval`
  sp.ticks_per_route = 20;
  auto gym = MakeSynthGym(sp);
  ASSERT_TRUE(gym.ok());
  auto ev = EvaluateSynthGym(*gym, kV);
  ASSERT_TRUE(ev.ok()) << ev.status().message();
  EXPECT_TRUE(ev->exact_intervals);
  EXPECT_GE(ev->spearman, 0.95);
  EXPECT_GE(ev->coverage, 0.70);
  EXPECT_LE(ev->coverage, 0.90);
  EXPECT_GT(ev->felt_routes, 100);
  EXPECT_LE(ev->mae_felt_routes, 0.7 * ev->felt_mae);
  EXPECT_LT(ev->mae, ev->setter_mae);
}

// The per-pair passes on threads change no bit: the same fit (values, sds,
// the session offset, the iteration counts) on 1, 2 and 3 threads, for
// both models, on a problem above the one-thread size.
TEST(Ratings, ThreadsChangeNoBit) {
  const SynthGym gym = SmallGym(300, 1100, 20, 5);  // 22,000 ticks
  for (RatingModel model : {RatingModel::kTries, RatingModel::kSession}) {
    SCOPED_TRACE(RatingModelName(model));
    const RatingProblem p = SynthProblem(gym, model);
    RatingFitOptions one;
    one.threads = 1;
    one.intervals = IntervalMethod::kApproximate;
    auto base = FitRatings(p, kV, one);
    ASSERT_TRUE(base.ok()) << base.status().message();
    for (int t : {2, 3}) {
      RatingFitOptions o = one;
      o.threads = t;
      auto f = FitRatings(p, kV, o);
      ASSERT_TRUE(f.ok()) << f.status().message();
      EXPECT_EQ(f->difficulty, base->difficulty) << t;
      EXPECT_EQ(f->ability, base->ability) << t;
      EXPECT_EQ(f->difficulty_sd, base->difficulty_sd) << t;
      EXPECT_EQ(f->ability_sd, base->ability_sd) << t;
      EXPECT_EQ(f->session_offset, base->session_offset) << t;
      EXPECT_EQ(f->newton_iterations, base->newton_iterations) << t;
      EXPECT_EQ(f->cg_iterations, base->cg_iterations) << t;
    }
  }
}

}  // namespace
}  // namespace sb::grades
