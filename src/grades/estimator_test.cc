// The estimator end to end on synthetic routes whose grade really depends
// on their moves (it must beat the baselines there, and match them when
// moves carry no information), folds that keep groups together, the file
// format (round trip, determinism, damage) and the per-move difficulty hook.
#include "grades/estimator.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <random>
#include <set>
#include <string>
#include <vector>

#include "base/hash.h"
#include "grades/evaluate.h"

namespace sb::grades {
namespace {

// A route of band `band` (0..4, bouldering): harder bands have more bad
// holds, crosses and crimps, fewer jugs; `signal` = 0 makes moves
// independent of the band.
TrainingRoute MakeRoute(int id, int band, double signal, std::mt19937_64* rng) {
  std::uniform_real_distribution<double> u(0, 1);
  TrainingRoute r;
  r.id = id;
  r.group = id;
  r.discipline = Discipline::kBouldering;
  r.value = band;
  const int n = 5 + static_cast<int>(u(*rng) * 6);
  const double hard = signal * band / 4.0 + (1 - signal) * 0.5;
  for (int i = 0; i < n; ++i) {
    MoveFacts m;
    m.parsed = true;
    m.bad_hold = u(*rng) < 0.1 + 0.6 * hard;
    m.cross = u(*rng) < 0.05 + 0.3 * hard;
    m.good_hold = u(*rng) < 0.6 - 0.5 * hard;
    const bool crimp = u(*rng) < 0.2 + 0.6 * hard;
    m.hold_families = crimp ? kHoldCrimp : kHoldJug;
    m.symbol = std::string(crimp ? "crimp" : "jug") + (m.bad_hold ? ":BAD" : "");
    r.reading.moves.push_back(m);
  }
  return r;
}

std::vector<TrainingRoute> MakeSet(int n, double signal, uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::vector<TrainingRoute> out;
  for (int i = 0; i < n; ++i) {
    // Bands skewed toward the middle, as gym grades are.
    const int band = std::vector<int>{0, 1, 1, 2, 2, 2, 2, 3, 3, 4}[static_cast<size_t>(i % 10)];
    out.push_back(MakeRoute(1000 + i, band, signal, &rng));
  }
  return out;
}

TEST(Estimator, BeatsTheBaselinesWhenMovesCarryTheGrade) {
  auto ev = CrossValidate(MakeSet(200, 1.0, 1), 5);
  ASSERT_TRUE(ev.ok()) << ev.status().message();
  ASSERT_EQ(ev->disciplines.size(), 1u);
  const DisciplineEvaluation& d = ev->disciplines[0];
  EXPECT_EQ(d.n, 200);
  const double best = std::min(d.majority.mae, d.median.mae);
  EXPECT_LT(d.model.mae, 0.8 * best) << d.model.mae << " vs " << best;
  EXPECT_GT(d.model.within_one, std::max(d.majority.within_one, d.median.within_one));
  for (double l2 : d.l2) EXPECT_FALSE(std::isinf(l2));  // features were kept
}

TEST(Estimator, FallsBackToThresholdsWhenMovesCarryNothing) {
  auto ev = CrossValidate(MakeSet(200, 0.0, 2), 5);
  ASSERT_TRUE(ev.ok()) << ev.status().message();
  const DisciplineEvaluation& d = ev->disciplines[0];
  // Without signal the model may not do much worse than the median baseline.
  EXPECT_LT(d.model.mae, d.median.mae + 0.15);
  // Baselines on this set: the majority and the median band are 2 in every fold.
  EXPECT_NEAR(d.majority.mae, 1.0 * (2 + 1 + 1 + 1 + 1 + 2) / 10, 1e-12);
  EXPECT_EQ(d.majority.exact, d.median.exact);
}

TEST(Estimator, FoldsKeepGroupsTogetherAndAreDeterministic) {
  std::vector<TrainingRoute> routes = MakeSet(60, 1.0, 3);
  for (size_t i = 0; i < routes.size(); ++i) routes[i].group = 1000 + static_cast<int>(i / 3);
  std::vector<const TrainingRoute*> ptrs;
  for (const TrainingRoute& r : routes) ptrs.push_back(&r);
  const std::vector<int> fold = AssignFolds(ptrs, 4);
  for (size_t i = 0; i < routes.size(); ++i) {
    EXPECT_EQ(fold[i], fold[i - i % 3]) << "route " << i << " left its group";
  }
  std::vector<int> per(4, 0);
  for (int f : fold) ++per[static_cast<size_t>(f)];
  for (int c : per) EXPECT_GE(c, 12);  // 20 groups dealt round-robin: 5 groups each
  EXPECT_EQ(AssignFolds(ptrs, 4), fold);
  std::vector<const TrainingRoute*> reversed(ptrs.rbegin(), ptrs.rend());
  std::vector<int> again = AssignFolds(reversed, 4);
  for (size_t i = 0; i < routes.size(); ++i) EXPECT_EQ(again[routes.size() - 1 - i], fold[i]);
}

TEST(Estimator, FileRoundTripIsExactAndDeterministic) {
  std::vector<TrainingRoute> routes = MakeSet(80, 1.0, 4);
  // A few roped routes too, so both sections are written.
  std::mt19937_64 rng(9);
  for (int i = 0; i < 30; ++i) {
    TrainingRoute r = MakeRoute(5000 + i, i % 3, 1.0, &rng);
    r.discipline = Discipline::kRoped;
    r.value = 9 + i % 3;
    r.reading.moves[0].symbol = "odd symbol %\n";  // escaped in the file
    routes.push_back(r);
  }
  auto est = GradeEstimator::Train(routes);
  ASSERT_TRUE(est.ok()) << est.status().message();
  const std::string bytes = est->Serialize();
  auto twin = GradeEstimator::Train(routes);
  ASSERT_TRUE(twin.ok());
  EXPECT_EQ(twin->Serialize(), bytes);
  auto back = GradeEstimator::Parse(bytes, "est.sbg");
  ASSERT_TRUE(back.ok()) << back.status().message();
  EXPECT_EQ(back->Serialize(), bytes);
  for (const TrainingRoute& r : routes) {
    auto a = est->EstimateRoute(r.reading, r.discipline);
    auto b = back->EstimateRoute(r.reading, r.discipline);
    ASSERT_TRUE(a.ok() && b.ok());
    EXPECT_EQ(a->probabilities, b->probabilities);
    EXPECT_EQ(a->band, b->band);
    EXPECT_LE(a->low, a->band);
    EXPECT_GE(a->high, a->band);
  }
}

TEST(Estimator, DamagedFilesAreRefusedWithTheirName) {
  auto est = GradeEstimator::Train(MakeSet(60, 1.0, 5));
  ASSERT_TRUE(est.ok());
  const std::string good = est->Serialize();
  auto refused = [](const std::string& bytes, const std::string& fragment) {
    auto r = GradeEstimator::Parse(bytes, "m.sbg");
    ASSERT_FALSE(r.ok()) << fragment;
    EXPECT_EQ(r.status().code(), Status::Code::kInvalidInput);
    EXPECT_EQ(r.status().message().rfind("m.sbg", 0), 0u) << r.status().message();
    EXPECT_NE(r.status().message().find(fragment), std::string::npos) << r.status().message();
  };
  std::string flipped = good;
  flipped[good.size() / 2] ^= 1;
  refused(flipped, "checksum mismatch");
  refused(good.substr(0, good.size() - 5), "newline");
  refused("", "newline");
  refused("hello\n", "wrong magic");
  std::string v2 = good;
  v2.replace(v2.find(" 1\n"), 3, " 2\n");
  refused(v2, "unsupported version");
  // Content errors behind a valid checksum name the line.
  auto resum = [](std::string body) {
    char sum[40];
    std::snprintf(sum, sizeof sum, "checksum %016llx\n",
                  static_cast<unsigned long long>(Fnv1a64(body)));
    return body + sum;
  };
  const std::string body = good.substr(0, good.rfind("checksum "));
  std::string b = body;
  const size_t at = b.find("thresholds ");
  b.replace(at, 11, "thresholdz ");
  const std::string line = std::to_string(std::count(b.begin(), b.begin() + at, '\n') + 1);
  refused(resum(b), ":" + line + ": not a valid grade estimator file: expected 'thresholds'");
  b = body;
  b.replace(b.find("l2 "), 3, "l2 -");
  refused(resum(b), "l2: expected a positive number or inf");
  b = body;
  b.erase(b.find("end\n"));
  refused(resum(b), "");
  // Every truncation of the body (re-checksummed) is refused or parses, never crashes.
  for (size_t cut = 0; cut < body.size(); cut += 97) {
    auto r = GradeEstimator::Parse(resum(body.substr(0, cut)), "m.sbg");
    if (r.ok()) {
      EXPECT_NE(r->model(Discipline::kBouldering), nullptr);
    }
  }
}

TEST(Estimator, PerMoveDifficultyBecomesFeatures) {
  std::vector<TrainingRoute> routes = MakeSet(60, 0.0, 6);
  for (TrainingRoute& r : routes) {
    for (size_t i = 0; i < r.reading.moves.size(); ++i) {
      r.reading.move_difficulty.push_back(r.value + 0.1 * static_cast<double>(i % 2));
    }
  }
  auto est = GradeEstimator::Train(routes);
  ASSERT_TRUE(est.ok()) << est.status().message();
  const DisciplineModel* m = est->model(Discipline::kBouldering);
  ASSERT_NE(m, nullptr);
  EXPECT_TRUE(m->UsesMoveDifficulty());
  EXPECT_EQ(m->feature_names, [] {
    auto v = FeatureNames(true);
    v.push_back(kMarkovFeature);
    return v;
  }());
  // The difficulty carries the band: the estimate follows it.
  auto e = est->EstimateRoute(routes[0].reading, Discipline::kBouldering);
  ASSERT_TRUE(e.ok());
  EXPECT_EQ(e->band, routes[0].band());
  // A reading without it is refused by this model, with a hint.
  RouteReading plain = routes[0].reading;
  plain.move_difficulty.clear();
  auto refused = est->EstimateRoute(plain, Discipline::kBouldering);
  ASSERT_FALSE(refused.ok());
  EXPECT_NE(refused.status().message().find("give the per-move difficulty"), std::string::npos);
  plain.move_difficulty = {1.0};
  EXPECT_FALSE(est->EstimateRoute(plain, Discipline::kBouldering).ok());
  // Mixed training input is refused.
  routes[3].reading.move_difficulty.clear();
  EXPECT_FALSE(GradeEstimator::Train(routes).ok());
  // No model for the other discipline.
  auto none = est->EstimateRoute(routes[0].reading, Discipline::kRoped);
  ASSERT_FALSE(none.ok());
  EXPECT_EQ(none.status().code(), Status::Code::kNotFound);
}

// The per-move difficulty's profile, computed by hand: max, mean, hardest
// three-move window, mean of the three hardest moves, share above 0.5.
TEST(Estimator, DifficultyProfileFeaturesAreComputed) {
  RouteReading r;
  r.moves.resize(6);
  r.move_difficulty = {0.1, 0.9, 0.2, 0.6, 0.7, 0.05};
  const std::vector<std::string>& names = FeatureNames(true);
  const std::vector<double> f = RouteFeatures(r);
  ASSERT_EQ(f.size(), names.size());
  const size_t k = FeatureNames(false).size();
  ASSERT_EQ(names.size(), k + 5);
  EXPECT_EQ(std::vector<std::string>(names.begin() + static_cast<long>(k), names.end()),
            (std::vector<std::string>{"difficulty_max", "difficulty_mean", "difficulty_sustained",
                                      "difficulty_top3", "difficulty_high_share"}));
  EXPECT_NEAR(f[k], 0.9, 1e-12);
  EXPECT_NEAR(f[k + 1], 2.55 / 6, 1e-12);
  EXPECT_NEAR(f[k + 2], (0.9 + 0.2 + 0.6) / 3, 1e-12);  // the window 0.9, 0.2, 0.6
  EXPECT_NEAR(f[k + 3], (0.9 + 0.7 + 0.6) / 3, 1e-12);  // not consecutive
  EXPECT_NEAR(f[k + 4], 3.0 / 6, 1e-12);                // 0.9, 0.6, 0.7
  // Fewer moves than three: the top mean is over all of them; 0.5 is not above 0.5.
  r.moves.resize(2);
  r.move_difficulty = {0.5, 0.3};
  const std::vector<double> g = RouteFeatures(r);
  EXPECT_NEAR(g[k + 3], 0.4, 1e-12);
  EXPECT_NEAR(g[k + 4], 0.0, 1e-12);
  // Without the per-move difficulty the features stop before them.
  r.move_difficulty.clear();
  EXPECT_EQ(RouteFeatures(r).size(), k);
}

TEST(Estimator, FormatsBandsInAnyScale) {
  EXPECT_EQ(FormatBand(Discipline::kRoped, 11, Scale::kYds), "5.11");
  EXPECT_EQ(FormatBand(Discipline::kRoped, 11, Scale::kFrench), "6c+");
  EXPECT_EQ(FormatBand(Discipline::kBouldering, 4, Scale::kV), "V4");
  EXPECT_EQ(FormatBand(Discipline::kBouldering, 4, Scale::kFont), "6B/6B+");
  EXPECT_EQ(FormatBand(Discipline::kBouldering, 4, Scale::kYds), "5.12a");
}

TEST(Estimator, TrainingNeedsTwoBandsAndTwoGroups) {
  std::vector<TrainingRoute> routes = MakeSet(10, 1.0, 7);
  for (TrainingRoute& r : routes) r.value = 3;
  auto e = GradeEstimator::Train(routes);
  ASSERT_FALSE(e.ok());
  EXPECT_NE(e.status().message().find("two bands"), std::string::npos);
  EXPECT_FALSE(CrossValidate(MakeSet(10, 1.0, 7), 1).ok());
  EXPECT_FALSE(CrossValidate(MakeSet(10, 1.0, 7), 20).ok());  // more folds than groups
}

}  // namespace
}  // namespace sb::grades
