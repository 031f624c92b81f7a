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
#include "grades/ratings_synth.h"

namespace sb::grades {
namespace {

using nlohmann::json;

constexpr double kTolerance = 1e-6;

std::string ScipyUnavailable() {
  if (::access("/usr/bin/python3", X_OK) != 0) return "/usr/bin/python3 is missing";
  if (std::system("/usr/bin/python3 -c 'import scipy.special, scipy.optimize' >/dev/null 2>&1") !=
      0) {
    return "/usr/bin/python3 has no scipy (install Debian's python3-scipy: scripts/setup.sh)";
  }
  return "";
}

struct Case {
  std::string label;
  RatingParams params;
  RatingProblem problem;
  json spec;
};

Case MakeCase(const std::string& label, int climbers, int routes, int ticks, uint64_t seed,
              Discipline d, std::vector<int> ungraded) {
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
    b.AddTick(t.climber, t.route, *TickGames(t.outcome, t.attempts), felt);
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
            {"ticks", tks}};
  return c;
}

TEST(RatingsScipy, FitAndIntervalsAgreeWithScipy) {
  if (std::string why = ScipyUnavailable(); !why.empty()) GTEST_SKIP() << why;
  std::vector<Case> cases;
  cases.push_back(MakeCase("bouldering 12x15x6", 12, 15, 6, 21, Discipline::kBouldering, {2}));
  cases.push_back(MakeCase("bouldering 30x40x10", 30, 40, 10, 22, Discipline::kBouldering, {}));
  cases.push_back(MakeCase("bouldering 8x10x2", 8, 10, 2, 23, Discipline::kBouldering, {0, 5}));
  cases.push_back(MakeCase("roped 20x25x5", 20, 25, 5, 24, Discipline::kRoped, {7}));
  json input = {{"cases", json::array()}};
  for (const Case& c : cases) input["cases"].push_back(c.spec);

  const auto dir = std::filesystem::path(::testing::TempDir()) /
                   ("sb_ratings_scipy_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const auto in = dir / "in.json", out = dir / "out.json", err = dir / "err.txt";
  std::ofstream(in) << input.dump();
  const std::string cmd = "/usr/bin/python3 '" + std::string(SB_SOURCE_DIR) +
                          "/src/grades/ratings_scipy.py' '" + in.string() + "' '" + out.string() +
                          "' 2>'" + err.string() + "'";
  const int rc = std::system(cmd.c_str());
  if (rc != 0) {
    std::ifstream e(err);
    std::stringstream ss;
    ss << e.rdbuf();
    FAIL() << "ratings_scipy.py failed (" << rc << "): " << ss.str();
  }
  json ref = json::parse(std::ifstream(out));
  std::filesystem::remove_all(dir);
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

}  // namespace
}  // namespace sb::grades
