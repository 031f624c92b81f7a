// The drifting fit against an independent implementation:
// ratings_drift_scipy.py (numpy + scipy.optimize.minimize under Debian's
// /usr/bin/python3) fits the same posterior (weekly nodes, Wiener links)
// from the raw dated ticks of small drifting gyms; difficulties, their sds,
// each climber's latest ability and sd, and the Laplace log evidence that
// chooses w must agree to 1e-6.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "grades/ratings_drift.h"
#include "grades/ratings_scipy_test_util.h"
#include "grades/ratings_synth.h"

namespace sb::grades {
namespace {

using nlohmann::json;

constexpr double kTolerance = 1e-6;

struct DriftCase {
  std::string label;
  DriftProblem problem;
  double w = 1;
  json spec;
};

DriftCase MakeDriftCase(const std::string& label, int climbers, int routes, int ticks,
                        uint64_t seed, double w, int ungraded) {
  SynthGymParams sp;
  sp.climbers = climbers;
  sp.routes = routes;
  sp.ticks_per_route = ticks;
  sp.seed = seed;
  const DriftingGym dg = *MakeDriftingGym(sp);
  SynthGym gym = dg.gym;
  const RatingParams k = RatingParams::For(Discipline::kBouldering);
  RatingProblem base = SynthProblem(gym);
  base.setter[size_t(ungraded)] = std::nullopt;
  DriftCase c;
  c.label = label;
  c.w = w;
  c.problem = *BuildDriftProblem(base, SynthDatedTicks(gym, RatingModel::kTries));
  json setter = json::array(), tks = json::array();
  for (size_t r = 0; r < base.setter.size(); ++r) {
    setter.push_back(base.setter[r] ? json(*base.setter[r]) : json(nullptr));
  }
  const int day0 = DayNumber("2026-01-01");
  for (const SynthTick& t : gym.ticks) {
    tks.push_back({t.climber, t.route, TickOutcomeName(t.outcome),
                   t.attempts ? json(*t.attempts) : json(nullptr),
                   t.felt ? json(double(*t.felt)) : json(nullptr), day0 + t.day});
  }
  c.spec = {{"params",
             {{"logit_per_unit", k.logit_per_unit},
              {"climber_sd", k.climber_sd},
              {"setter_sd", k.setter_sd},
              {"open_route_sd", k.open_route_sd},
              {"felt_sd", k.felt_sd}}},
            {"climbers", climbers},
            {"routes", routes},
            {"setter", setter},
            {"ticks", tks},
            {"w", w},
            {"node_days", kDriftNodeDays}};
  return c;
}

TEST(RatingsDriftScipy, DriftingFitAndEvidenceAgreeWithScipy) {
  if (std::string why = ScipyUnavailable(); !why.empty()) GTEST_SKIP() << why;
  std::vector<DriftCase> cases;
  cases.push_back(MakeDriftCase("12x15x6 w=1", 12, 15, 6, 41, 1.0, 2));
  cases.push_back(MakeDriftCase("20x25x6 w=2", 20, 25, 6, 42, 2.0, 7));
  json specs = json::array();
  for (const DriftCase& c : cases) specs.push_back(c.spec);
  const json ref = RunScipyOracle("ratings_drift_scipy.py", specs);
  if (ref.is_null()) return;  // failed (reported)
  ASSERT_EQ(ref["cases"].size(), cases.size());
  const RatingParams k = RatingParams::For(Discipline::kBouldering);
  for (size_t i = 0; i < cases.size(); ++i) {
    SCOPED_TRACE(cases[i].label);
    const json& r = ref["cases"][i];
    ASSERT_TRUE(r["success"].get<bool>());
    DriftOptions d;
    d.sd = cases[i].w;
    auto fit = FitDriftRatings(cases[i].problem, k, d);
    ASSERT_TRUE(fit.ok()) << fit.status().message();
    ASSERT_TRUE(fit->fit.exact_intervals);
    EXPECT_EQ(r["nodes"].get<int>(), cases[i].problem.num_nodes());
    ASSERT_EQ(r["difficulty"].size(), fit->fit.difficulty.size());
    for (size_t j = 0; j < fit->fit.difficulty.size(); ++j) {
      EXPECT_NEAR(fit->fit.difficulty[j], r["difficulty"][j].get<double>(), kTolerance) << j;
      EXPECT_NEAR(fit->fit.difficulty_sd[j], r["difficulty_sd"][j].get<double>(), kTolerance) << j;
    }
    ASSERT_EQ(r["ability"].size(), fit->fit.ability.size());
    for (size_t j = 0; j < fit->fit.ability.size(); ++j) {
      EXPECT_NEAR(fit->fit.ability[j], r["ability"][j].get<double>(), kTolerance) << j;
      EXPECT_NEAR(fit->fit.ability_sd[j], r["ability_sd"][j].get<double>(), kTolerance) << j;
    }
    EXPECT_NEAR(fit->log_evidence, r["log_evidence"].get<double>(), kTolerance);
  }
}

}  // namespace
}  // namespace sb::grades
