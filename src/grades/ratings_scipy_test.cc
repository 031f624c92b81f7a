// The fit against an independent implementation: ratings_scipy.py (numpy +
// scipy.optimize.minimize under Debian's /usr/bin/python3) fits the same
// posterior from the raw ticks of small synthetic gyms (with routes without
// a setter's grade, without ticks, and a roped gym); values and standard
// deviations must agree to 1e-6.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "base/number.h"
#include "grades/ratings.h"
#include "grades/ratings_scipy_test_util.h"
#include "grades/ratings_synth.h"

namespace sb::grades {
namespace {

using nlohmann::json;

constexpr double kTolerance = 1e-6;

struct Case {
  std::string label;
  RatingParams params;
  RatingProblem problem;
  json spec;
};

Case MakeCase(const std::string& label, int climbers, int routes, int ticks, uint64_t seed,
              Discipline d, std::vector<int> ungraded, RatingModel model = RatingModel::kTries) {
  SynthGymParams sp;
  sp.climbers = climbers;
  sp.routes = routes;
  sp.ticks_per_route = ticks;
  sp.seed = seed;
  SynthGym gym = *MakeSynthGym(sp);
  Case c;
  c.label = label;
  c.params = RatingParams::For(d);
  // A roped gym: the same games on the YDS axis (values scaled into YDS units).
  const double scale = d == Discipline::kRoped ? 0.37 : 1.0;
  const double offset = d == Discipline::kRoped ? 10.0 : 0.0;
  RatingProblemBuilder b;
  b.SetModel(model);
  b.EnsureClimbers(climbers);
  b.EnsureRoutes(routes + 1);  // the last route has no ticks
  json setter = json::array(), tks = json::array();
  for (int r = 0; r <= routes; ++r) {
    const bool graded =
        r < routes && std::find(ungraded.begin(), ungraded.end(), r) == ungraded.end();
    if (graded) {
      const double v = offset + scale * gym.setter_grade[size_t(r)];
      b.SetSetterGrade(r, v);
      setter.push_back(v);
    } else {
      setter.push_back(nullptr);
    }
  }
  for (const SynthTick& t : gym.ticks) {
    std::optional<double> felt;
    if (t.felt) felt = offset + scale * *t.felt;
    b.AddTick(t.climber, t.route, *TickGamesFor(model, t.outcome, t.attempts), felt);
    if (t.attempts) {
      b.AddSessionTries(*t.attempts);
    } else if (t.outcome == TickOutcome::kFlash) {
      b.AddSessionTries(1);
    }
    tks.push_back({t.climber, t.route, TickOutcomeName(t.outcome),
                   t.attempts ? json(*t.attempts) : json(nullptr),
                   felt ? json(*felt) : json(nullptr)});
  }
  c.problem = b.Build();
  c.spec = {{"params",
             {{"logit_per_unit", c.params.logit_per_unit},
              {"climber_sd", c.params.climber_sd},
              {"setter_sd", c.params.setter_sd},
              {"open_route_sd", c.params.open_route_sd},
              {"felt_sd", c.params.felt_sd}}},
            {"climbers", climbers},
            {"routes", routes + 1},
            {"setter", setter},
            {"ticks", tks},
            {"model", RatingModelName(model)}};
  // Every pair of the first climbers and routes, and one unseen climber and
  // route (indices past the fit's: at the prior).
  json pairs = json::array();
  for (int cl = 0; cl < std::min(climbers, 6); ++cl) {
    for (int r = 0; r < std::min(routes + 1, 8); ++r) pairs.push_back({cl, r});
  }
  pairs.push_back({climbers, 0});
  pairs.push_back({0, routes + 1});
  pairs.push_back({climbers, routes + 1});
  pairs.push_back({1, routes});  // the route without ticks
  c.spec["pairs"] = pairs;
  return c;
}

// Runs ratings_scipy.py on the cases; null (with a failure recorded) when it fails.
json RunScipy(const std::vector<Case>& cases) {
  json specs = json::array();
  for (const Case& c : cases) specs.push_back(c.spec);
  return RunScipyOracle("ratings_scipy.py", specs);
}

TEST(RatingsScipy, FitAndIntervalsAgreeWithScipy) {
  if (std::string why = ScipyUnavailable(); !why.empty()) GTEST_SKIP() << why;
  std::vector<Case> cases;
  cases.push_back(MakeCase("bouldering 12x15x6", 12, 15, 6, 21, Discipline::kBouldering, {2}));
  cases.push_back(MakeCase("bouldering 30x40x10", 30, 40, 10, 22, Discipline::kBouldering, {}));
  cases.push_back(MakeCase("bouldering 8x10x2", 8, 10, 2, 23, Discipline::kBouldering, {0, 5}));
  cases.push_back(MakeCase("roped 20x25x5", 20, 25, 5, 24, Discipline::kRoped, {7}));
  json ref = RunScipy(cases);
  if (ref.is_null()) return;  // failed (reported)

  ASSERT_EQ(ref["cases"].size(), cases.size());
  for (size_t i = 0; i < cases.size(); ++i) {
    SCOPED_TRACE(cases[i].label);
    const json& r = ref["cases"][i];
    ASSERT_TRUE(r["success"].get<bool>());
    auto fit = FitRatings(cases[i].problem, cases[i].params);
    ASSERT_TRUE(fit.ok()) << fit.status().message();
    ASSERT_TRUE(fit->exact_intervals);
    EXPECT_NEAR(fit->prior_mean, r["prior_mean"].get<double>(), kTolerance);
    ASSERT_EQ(r["difficulty"].size(), fit->difficulty.size());
    ASSERT_EQ(r["ability"].size(), fit->ability.size());
    for (size_t k = 0; k < fit->difficulty.size(); ++k) {
      EXPECT_NEAR(fit->difficulty[k], r["difficulty"][k].get<double>(), kTolerance) << k;
      EXPECT_NEAR(fit->difficulty_sd[k], r["difficulty_sd"][k].get<double>(), kTolerance) << k;
    }
    for (size_t k = 0; k < fit->ability.size(); ++k) {
      EXPECT_NEAR(fit->ability[k], r["ability"][k].get<double>(), kTolerance) << k;
      EXPECT_NEAR(fit->ability_sd[k], r["ability_sd"][k].get<double>(), kTolerance) << k;
    }
  }
}

// The predictions (p_flash, p_send) of both models, the session model's
// offset b estimated jointly, and its fit's values and sds, against the
// SciPy implementation; pairs with an unseen climber or route at the prior.
TEST(RatingsScipy, PredictionsAgreeWithScipy) {
  if (std::string why = ScipyUnavailable(); !why.empty()) GTEST_SKIP() << why;
  std::vector<Case> cases;
  cases.push_back(MakeCase("session 12x15x6", 12, 15, 6, 31, Discipline::kBouldering, {2},
                           RatingModel::kSession));
  cases.push_back(MakeCase("session 30x40x10", 30, 40, 10, 32, Discipline::kBouldering, {},
                           RatingModel::kSession));
  cases.push_back(MakeCase("session roped 20x25x5", 20, 25, 5, 33, Discipline::kRoped, {7},
                           RatingModel::kSession));
  cases.push_back(MakeCase("tries 12x15x6", 12, 15, 6, 34, Discipline::kBouldering, {3}));
  json ref = RunScipy(cases);
  if (ref.is_null()) return;
  ASSERT_EQ(ref["cases"].size(), cases.size());
  for (size_t i = 0; i < cases.size(); ++i) {
    SCOPED_TRACE(cases[i].label);
    const json& r = ref["cases"][i];
    ASSERT_TRUE(r["success"].get<bool>());
    auto fit = FitRatings(cases[i].problem, cases[i].params);
    ASSERT_TRUE(fit.ok()) << fit.status().message();
    EXPECT_NEAR(fit->session_offset, r["session_offset"].get<double>(), kTolerance);
    for (size_t k = 0; k < fit->difficulty.size(); ++k) {
      EXPECT_NEAR(fit->difficulty[k], r["difficulty"][k].get<double>(), kTolerance) << k;
      EXPECT_NEAR(fit->difficulty_sd[k], r["difficulty_sd"][k].get<double>(), kTolerance) << k;
    }
    for (size_t k = 0; k < fit->ability.size(); ++k) {
      EXPECT_NEAR(fit->ability[k], r["ability"][k].get<double>(), kTolerance) << k;
      EXPECT_NEAR(fit->ability_sd[k], r["ability_sd"][k].get<double>(), kTolerance) << k;
    }
    const json& pairs = cases[i].spec["pairs"];
    ASSERT_EQ(r["p_flash"].size(), pairs.size());
    for (size_t k = 0; k < pairs.size(); ++k) {
      const size_t c = pairs[k][0].get<size_t>(), rt = pairs[k][1].get<size_t>();
      const double a = c < fit->ability.size() ? fit->ability[c] : fit->prior_mean;
      const double d = rt < fit->difficulty.size() ? fit->difficulty[rt] : fit->prior_mean;
      const SendChances p =
          PredictSend(cases[i].params, fit->model, fit->session_offset, fit->session_tries, a, d);
      EXPECT_NEAR(p.p_flash, r["p_flash"][k].get<double>(), kTolerance) << c << "," << rt;
      EXPECT_NEAR(p.p_send, r["p_send"][k].get<double>(), kTolerance) << c << "," << rt;
    }
  }
}

}  // namespace
}  // namespace sb::grades
