// The session model with zones and session offsets (ratings_session.h):
// against the independent SciPy implementation (ratings_scipy.py,
// "session_zones") to 1e-6, its parts switching off, and bad input.
#include "grades/ratings_session.h"
#include "grades/ratings_scipy_test_util.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <random>
#include <sstream>
#include <string>
#include <vector>

namespace sb::grades {
namespace {

using nlohmann::json;

constexpr double kTolerance = 1e-6;

// A small competition: every climber tries every route once; tries and zones
// drawn from the model (a zone ~1.5 grades easier than the top), with rows of
// unknown tries, unknown zone tries, no zone and 0 tries mixed in.
std::vector<SessionObs> MakeRows(int climbers, int routes, uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> n01(0, 1);
  std::uniform_real_distribution<double> u01(0, 1);
  std::vector<double> a(static_cast<size_t>(climbers)), d(static_cast<size_t>(routes));
  for (double& v : a) v = 1.5 * n01(rng);
  for (double& v : d) v = 1.5 * n01(rng);
  std::vector<SessionObs> rows;
  for (int r = 0; r < routes; ++r) {
    for (int c = 0; c < climbers; ++c) {
      SessionObs o;
      o.climber = c;
      o.route = r;
      const double p = 1 / (1 + std::exp(-1.0986 * (a[size_t(c)] - d[size_t(r)])));
      const double pz = 1 / (1 + std::exp(-1.0986 * (a[size_t(c)] - d[size_t(r)] + 1.5)));
      const int budget = 1 + int(u01(rng) * 6);
      int top_at = 0, zone_at = 0;
      for (int t = 1; t <= budget; ++t) {
        if (!zone_at && u01(rng) < pz) zone_at = t;
        if (zone_at && !top_at && u01(rng) < p) top_at = t;
      }
      o.top = top_at > 0;
      o.tries = top_at ? top_at : budget;
      o.zone = zone_at > 0;
      o.zone_tries = zone_at ? zone_at : budget;
      const double kind = u01(rng);
      if (kind < 0.06) {
        o.tries.reset();  // unknown count
      } else if (kind < 0.10) {
        o.zone_tries.reset();
      } else if (kind < 0.13) {
        o.zone.reset();
        o.zone_tries.reset();
      } else if (kind < 0.15 && !o.top) {
        o.tries = 0;  // no try
        o.zone = false;
        o.zone_tries = 0;
      }
      rows.push_back(o);
    }
  }
  return rows;
}

json Spec(const std::vector<SessionObs>& rows, int climbers, int routes,
          const SessionModelParams& k) {
  json j = {{"model", "session_zones"},
            {"climbers", climbers},
            {"routes", routes},
            {"params",
             {{"logit_per_unit", k.logit_per_unit},
              {"climber_sd", k.climber_sd},
              {"route_sd", k.route_sd},
              {"zone_sd", k.zone_sd},
              {"route_offset_sd", k.route_offset_sd},
              {"climber_offset_sd", k.climber_offset_sd},
              {"offset_mean", k.offset_mean},
              {"offset_sd", k.offset_sd},
              {"delta_sd", k.delta_sd},
              {"prior_mean", k.prior_mean},
              {"later_tries_weight", k.later_tries_weight}}}};
  json rs = json::array();
  for (const SessionObs& o : rows) {
    rs.push_back({o.climber, o.route, o.top ? 1 : 0, o.tries ? json(*o.tries) : json(nullptr),
                  o.zone ? json(*o.zone ? 1 : 0) : json(nullptr),
                  o.zone_tries ? json(*o.zone_tries) : json(nullptr)});
  }
  j["rows"] = rs;
  json pairs = json::array();
  for (int c = 0; c < climbers; ++c) {
    for (int r = 0; r < routes; ++r) pairs.push_back({c, r});
  }
  pairs.push_back({climbers, 0});  // unseen climber
  pairs.push_back({0, routes});    // unseen route
  j["pairs"] = pairs;
  return j;
}

TEST(RatingsSession, AgreesWithScipy) {
  if (std::string why = ScipyUnavailable(); !why.empty()) GTEST_SKIP() << why;
  struct Case {
    int climbers, routes;
    uint64_t seed;
    SessionModelParams k;
  };
  std::vector<Case> cases;
  cases.push_back({10, 6, 41, SessionModelParams::Defaults()});
  SessionModelParams off = SessionModelParams::Defaults();
  off.route_offset_sd = 0;  // zones only
  off.climber_offset_sd = 0;
  off.prior_mean = 4;
  cases.push_back({8, 5, 43, off});
  SessionModelParams nozone = SessionModelParams::Defaults();
  nozone.zone_sd = 0;  // offsets only
  nozone.climber_sd = 2;
  nozone.later_tries_weight = 0.3;
  cases.push_back({9, 4, 44, nozone});
  json specs = json::array();
  std::vector<std::vector<SessionObs>> rows;
  for (const Case& c : cases) {
    rows.push_back(MakeRows(c.climbers, c.routes, c.seed));
    specs.push_back(Spec(rows.back(), c.climbers, c.routes, c.k));
  }
  json ref = RunScipyOracle("ratings_scipy.py", specs);
  if (ref.is_null()) return;
  ASSERT_EQ(ref["cases"].size(), cases.size());
  for (size_t i = 0; i < cases.size(); ++i) {
    SCOPED_TRACE("case " + std::to_string(i));
    const json& r = ref["cases"][i];
    ASSERT_TRUE(r["success"].get<bool>());
    auto fit = FitSessionModel(rows[i], cases[i].climbers, cases[i].routes, cases[i].k);
    ASSERT_TRUE(fit.ok()) << fit.status().message();
    EXPECT_NEAR(fit->offset, r["offset"].get<double>(), kTolerance);
    EXPECT_NEAR(fit->delta, r["delta"].get<double>(), kTolerance);
    auto near = [&](const std::vector<double>& v, const char* key) {
      ASSERT_EQ(v.size(), r[key].size()) << key;
      for (size_t j = 0; j < v.size(); ++j) {
        EXPECT_NEAR(v[j], r[key][j].get<double>(), kTolerance) << key << "[" << j << "]";
      }
    };
    near(fit->ability, "ability");
    near(fit->difficulty, "difficulty");
    near(fit->zone_difficulty, "zone_difficulty");
    near(fit->route_offset, "route_offset");
    near(fit->climber_offset, "climber_offset");
    const json& pairs = specs[i]["pairs"];
    for (size_t j = 0; j < pairs.size(); ++j) {
      const int c = pairs[j][0].get<int>(), rt = pairs[j][1].get<int>();
      const SendChances p = PredictSessionModel(cases[i].k, *fit, c, rt);
      EXPECT_NEAR(p.p_flash, r["p_flash"][j].get<double>(), kTolerance) << c << "," << rt;
      EXPECT_NEAR(p.p_send, r["p_send"][j].get<double>(), kTolerance) << c << "," << rt;
    }
  }
}

// With zones and both offsets off, the model is the session model of
// ratings.h (b estimated jointly) on the same ticks.
TEST(RatingsSession, WithoutZonesAndOffsetsIsTheSessionModel) {
  const std::vector<SessionObs> rows = MakeRows(12, 9, 45);
  SessionModelParams k = SessionModelParams::Defaults();
  k.zone_sd = k.route_offset_sd = k.climber_offset_sd = k.later_tries_weight = 0;
  k.climber_sd = k.route_sd = 3;  // RatingParams' bouldering defaults
  auto fit = FitSessionModel(rows, 12, 9, k);
  ASSERT_TRUE(fit.ok()) << fit.status().message();
  RatingProblemBuilder b;
  b.SetModel(RatingModel::kSession);
  b.EnsureClimbers(12);
  b.EnsureRoutes(9);
  for (const SessionObs& o : rows) {
    if (o.tries && *o.tries == 0) continue;
    const TickOutcome out = !o.top                       ? TickOutcome::kAttempt
                            : (o.tries && *o.tries == 1) ? TickOutcome::kFlash
                                                         : TickOutcome::kSend;
    b.AddTick(o.climber, o.route, *TickGamesFor(RatingModel::kSession, out, o.tries));
  }
  RatingParams p = RatingParams::For(Discipline::kBouldering);
  auto ref = FitRatings(b.Build(), p);
  ASSERT_TRUE(ref.ok()) << ref.status().message();
  EXPECT_NEAR(fit->offset, ref->session_offset, 1e-7);
  for (size_t i = 0; i < fit->ability.size(); ++i) {
    EXPECT_NEAR(fit->ability[i], ref->ability[i], 1e-7);
  }
  for (size_t i = 0; i < fit->difficulty.size(); ++i) {
    EXPECT_NEAR(fit->difficulty[i], ref->difficulty[i], 1e-7);
  }
}

// A gym's problem (setters' grades, felt grades) as observations and route
// priors: with the offsets off, the same fit as FitRatings' session model.
TEST(RatingsSession, GymProblemMatchesTheSessionFit) {
  SynthGymParams sp;
  sp.climbers = 30;
  sp.routes = 40;
  sp.ticks_per_route = 6;
  sp.seed = 46;
  const SynthGym gym = *MakeSynthGym(sp);
  const RatingProblem problem = SynthProblem(gym, RatingModel::kSession);
  const RatingParams params = RatingParams::For(Discipline::kBouldering);
  auto ref = FitRatings(problem, params);
  ASSERT_TRUE(ref.ok()) << ref.status().message();
  auto obs = SessionObsOfProblem(problem);
  ASSERT_TRUE(obs.ok()) << obs.status().message();
  SessionModelParams k = SessionModelParams::Defaults();
  k.zone_sd = k.route_offset_sd = k.climber_offset_sd = k.later_tries_weight = 0;
  k.prior_mean = ref->prior_mean;
  k.climber_sd = params.climber_sd;
  auto fit = FitSessionModel(*obs, problem.num_climbers, problem.num_routes(), k,
                             RoutePriorsOfProblem(problem, params, ref->prior_mean));
  ASSERT_TRUE(fit.ok()) << fit.status().message();
  EXPECT_NEAR(fit->offset, ref->session_offset, 1e-7);
  for (size_t i = 0; i < fit->difficulty.size(); ++i) {
    EXPECT_NEAR(fit->difficulty[i], ref->difficulty[i], 1e-7) << i;
  }
  for (size_t i = 0; i < fit->ability.size(); ++i) {
    EXPECT_NEAR(fit->ability[i], ref->ability[i], 1e-7) << i;
  }
  EXPECT_FALSE(SessionObsOfProblem(SynthProblem(gym, RatingModel::kTries)).ok());
}

TEST(RatingsSession, RefusesBadInput) {
  SessionModelParams k = SessionModelParams::Defaults();
  std::vector<SessionObs> rows(1);
  rows[0].climber = 3;
  auto fit = FitSessionModel(rows, 2, 1, k);
  ASSERT_FALSE(fit.ok());
  EXPECT_EQ(fit.status().message(), "session model: observation 0: index out of range");
  rows[0].climber = 0;
  rows[0].top = true;
  rows[0].tries = 0;
  EXPECT_FALSE(FitSessionModel(rows, 1, 1, k).ok());
  k.route_offset_sd = -1;
  rows[0].tries = 1;
  auto bad = FitSessionModel(rows, 1, 1, k);
  ASSERT_FALSE(bad.ok());
  EXPECT_EQ(bad.status().message(),
            "session model: route_offset_sd: expected a number >= 0, got -1");
}

}  // namespace
}  // namespace sb::grades
