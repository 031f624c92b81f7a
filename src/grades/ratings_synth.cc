#include "grades/ratings_synth.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>

#include "base/csv.h"
#include "base/number.h"
#include "grades/ratings_synth_draw.h"
#include "grades/scale.h"

namespace sb::grades {

namespace synth {

namespace {

int Whole(double v, int lo, int hi) { return std::clamp(int(std::lround(v)), lo, hi); }

}  // namespace

int NearestClimber::operator()(double t) const {
  auto it = std::lower_bound(sorted_.begin(), sorted_.end(), t);
  size_t i = size_t(it - sorted_.begin());
  if (i == sorted_.size() || (i > 0 && t - sorted_[i - 1] < sorted_[i] - t)) --i;
  return order_[i];
}

void DrawRoute(Draw& draw, const SynthGymParams& sp, double* difficulty, int* setter_grade) {
  const double d = std::clamp(sp.difficulty_mean + sp.difficulty_sd * draw.Normal(), -1.0, 14.0);
  *difficulty = d;
  *setter_grade = Whole(d + sp.setter_sd * draw.Normal(), -1, kVTopNumber);
}

int PickClimber(Draw& draw, const SynthGymParams& sp, double d, const NearestClimber& nearest,
                std::vector<int>* seen) {
  int c = 0;
  for (int tries = 0; tries < 8; ++tries) {
    c = nearest(d + 0.5 + sp.choice_sd * draw.Normal());
    if (std::find(seen->begin(), seen->end(), c) == seen->end()) break;
  }
  seen->push_back(c);
  return c;
}

Session DrawSession(Draw& draw, const SynthGymParams& sp, double p) {
  Session s;
  s.tries = 1 + draw.Below(sp.max_tries);
  for (int t = 1; t <= s.tries && !s.sent_at; ++t) {
    if (draw.Uniform() < p) s.sent_at = t;
  }
  return s;
}

void FinishTick(Draw& draw, const SynthGymParams& sp, const Session& s, double a, double d,
                SynthTick* tick) {
  if (s.sent_at == 1) {
    tick->outcome = TickOutcome::kFlash;
  } else if (s.sent_at > 1) {
    tick->outcome = TickOutcome::kSend;
    tick->attempts = s.sent_at;
  } else {
    tick->outcome = TickOutcome::kAttempt;
    // A single try is often logged without a count (the model reads it as 1).
    if (s.tries > 1 || draw.Uniform() < 0.5) tick->attempts = s.tries;
  }
  if (s.sent_at && draw.Uniform() < sp.felt_share) {
    tick->felt = Whole(d - sp.felt_bias * (a - d) + sp.felt_sd * draw.Normal(), -1, kVTopNumber);
  }
}

}  // namespace synth

namespace {

using synth::Draw;

std::string VName(int v) { return v < 0 ? "VB" : "V" + std::to_string(v); }

std::string DateOf(int day) {
  static const int kDays[12] = {31, 28, 31, 30, 31, 30, 31, 31, 30, 31, 30, 31};
  int m = 0;
  while (m < 11 && day >= kDays[m]) day -= kDays[m++];
  char b[32];
  std::snprintf(b, sizeof b, "2026-%02d-%02d", m + 1, day + 1);
  return b;
}

double Median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

std::vector<double> Ranks(std::span<const double> v) {
  std::vector<size_t> order(v.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) { return v[a] < v[b]; });
  std::vector<double> rank(v.size());
  for (size_t i = 0; i < order.size();) {
    size_t j = i;
    while (j + 1 < order.size() && v[order[j + 1]] == v[order[i]]) ++j;
    const double avg = 0.5 * double(i + j) + 1;
    for (size_t k = i; k <= j; ++k) rank[order[k]] = avg;
    i = j + 1;
  }
  return rank;
}

}  // namespace

Status SynthGymParams::Validate() const {
  auto bad = [](const char* field, const std::string& want) {
    return Status::InvalidInput(std::string(field) + ": expected " + want);
  };
  if (climbers < 1 || climbers > kMaxSynthClimbers) {
    return bad("--climbers", "1 to " + std::to_string(kMaxSynthClimbers));
  }
  if (routes < 1 || routes > kMaxSynthRoutes) {
    return bad("--routes", "1 to " + std::to_string(kMaxSynthRoutes));
  }
  if (ticks_per_route < 0 || int64_t(ticks_per_route) * routes > kMaxSynthTicks) {
    return bad("--ticks-per-route",
               "0 or more, at most " + std::to_string(kMaxSynthTicks) + " ticks in all");
  }
  if (max_tries < 1 || max_tries > kMaxTickAttempts) return bad("max_tries", "1 to 500");
  const std::pair<const char*, double> positive[] = {
      {"difficulty_sd", difficulty_sd},   {"ability_sd", ability_sd}, {"choice_sd", choice_sd},
      {"logit_per_unit", logit_per_unit}, {"setter_sd", setter_sd},   {"felt_sd", felt_sd}};
  for (const auto& [f, v] : positive) {
    if (!std::isfinite(v) || v <= 0) return bad(f, "a number > 0");
  }
  if (!(felt_share >= 0 && felt_share <= 1)) return bad("felt_share", "0 to 1");
  if (!std::isfinite(felt_bias) || !std::isfinite(difficulty_mean) ||
      !std::isfinite(ability_mean)) {
    return bad("felt_bias / means", "finite numbers");
  }
  return Status::Ok();
}

Result<SynthGym> MakeSynthGym(const SynthGymParams& sp) {
  SB_RETURN_IF_ERROR(sp.Validate());
  Draw draw(sp.seed);
  SynthGym gym;
  gym.true_ability.resize(size_t(sp.climbers));
  for (double& a : gym.true_ability) {
    a = std::clamp(sp.ability_mean + sp.ability_sd * draw.Normal(), -1.0, 15.0);
  }
  gym.true_difficulty.resize(size_t(sp.routes));
  gym.setter_grade.resize(size_t(sp.routes));
  for (size_t r = 0; r < size_t(sp.routes); ++r) {
    synth::DrawRoute(draw, sp, &gym.true_difficulty[r], &gym.setter_grade[r]);
  }
  // Climbers by ability, to find the one nearest a target.
  const synth::NearestClimber nearest(gym.true_ability.size(),
                                      [&](size_t c) { return gym.true_ability[c]; });
  gym.ticks.reserve(size_t(sp.routes) * size_t(sp.ticks_per_route));
  std::vector<int> seen;
  for (int r = 0; r < sp.routes; ++r) {
    const double d = gym.true_difficulty[size_t(r)];
    seen.clear();
    for (int k = 0; k < sp.ticks_per_route; ++k) {
      SynthTick tick;
      tick.climber = synth::PickClimber(draw, sp, d, nearest, &seen);
      tick.route = r;
      const double a = gym.true_ability[size_t(tick.climber)];
      const synth::Session session = synth::DrawSession(draw, sp, synth::TryChance(sp, a, d));
      tick.day = draw.Below(365);
      synth::FinishTick(draw, sp, session, a, d, &tick);
      gym.ticks.push_back(tick);
    }
  }
  return gym;
}

std::string SynthTicksCsv(const SynthGym& gym) {
  std::string out = "climber,route,date,outcome,attempts,felt_grade\n";
  for (const SynthTick& t : gym.ticks) {
    out += "c" + std::to_string(t.climber + 1) + ",r" + std::to_string(t.route + 1) + "," +
           DateOf(t.day) + "," + TickOutcomeName(t.outcome) + "," +
           (t.attempts ? std::to_string(*t.attempts) : "") + "," + (t.felt ? VName(*t.felt) : "") +
           "\n";
  }
  return out;
}

std::string SynthRoutesCsv(const SynthGym& gym) {
  std::string out = "route,grade\n";
  for (size_t r = 0; r < gym.setter_grade.size(); ++r) {
    out += "r" + std::to_string(r + 1) + "," + VName(gym.setter_grade[r]) + "\n";
  }
  return out;
}

std::string SynthTruthCsv(const SynthGym& gym) {
  std::string out = "kind,name,value\n";
  for (size_t r = 0; r < gym.true_difficulty.size(); ++r) {
    out += "route,r" + std::to_string(r + 1) + "," + FormatDouble(gym.true_difficulty[r]) + "\n";
  }
  for (size_t c = 0; c < gym.true_ability.size(); ++c) {
    out += "climber,c" + std::to_string(c + 1) + "," + FormatDouble(gym.true_ability[c]) + "\n";
  }
  return out;
}

RatingProblem SynthProblem(const SynthGym& gym, RatingModel model) {
  RatingProblemBuilder b;
  b.SetModel(model);
  b.EnsureClimbers(int(gym.true_ability.size()));
  b.EnsureRoutes(int(gym.true_difficulty.size()));
  for (size_t r = 0; r < gym.setter_grade.size(); ++r) {
    b.SetSetterGrade(int(r), gym.setter_grade[r]);
  }
  for (const SynthTick& t : gym.ticks) {
    auto games = TickGamesFor(model, t.outcome, t.attempts);  // within range: always ok
    b.AddTick(t.climber, t.route, games.ok() ? *games : Games{},
              t.felt ? std::optional<double>(*t.felt) : std::nullopt);
    if (t.attempts) {
      b.AddSessionTries(*t.attempts);
    } else if (t.outcome == TickOutcome::kFlash) {
      b.AddSessionTries(1);
    }
  }
  return b.Build();
}

Result<RatingEvaluation> EvaluateSynthGym(const SynthGym& gym, const RatingParams& params,
                                          const RatingFitOptions& options, RatingModel model) {
  const RatingProblem problem = SynthProblem(gym, model);
  SB_ASSIGN_OR_RETURN(RatingFit fit, FitRatings(problem, params, options));
  RatingEvaluation ev = CompareWithTruth(gym, fit.difficulty, fit.difficulty_sd);
  ev.exact_intervals = fit.exact_intervals;
  return ev;
}

RatingEvaluation CompareWithTruth(const SynthGym& gym, std::span<const double> difficulty,
                                  std::span<const double> difficulty_sd) {
  RatingEvaluation ev;
  const size_t n = gym.true_difficulty.size();
  const bool intervals = !difficulty_sd.empty();
  ev.routes = int(n);
  ev.ticks = int(gym.ticks.size());
  ev.spearman = Spearman(difficulty, gym.true_difficulty);
  std::vector<std::vector<double>> felt(n);
  for (const SynthTick& t : gym.ticks) {
    if (t.felt) felt[size_t(t.route)].push_back(*t.felt);
  }
  int covered = 0;
  double felt_err = 0, fit_err_felt = 0;
  for (size_t r = 0; r < n; ++r) {
    const double truth = gym.true_difficulty[r];
    const double v = difficulty[r];
    if (intervals) {
      const double sd = difficulty_sd[r];
      if (truth >= v - kZ80 * sd && truth <= v + kZ80 * sd) ++covered;
      ev.mean_interval_width += 2 * kZ80 * sd;
    }
    ev.mae += std::abs(v - truth);
    ev.setter_mae += std::abs(gym.setter_grade[r] - truth);
    if (!felt[r].empty()) {
      ++ev.felt_routes;
      felt_err += std::abs(Median(felt[r]) - truth);
      fit_err_felt += std::abs(v - truth);
    }
  }
  if (intervals) {
    ev.coverage = double(covered) / double(n);
    ev.mean_interval_width /= double(n);
  } else {
    ev.coverage = ev.mean_interval_width = std::nan("");
  }
  ev.mae /= double(n);
  ev.setter_mae /= double(n);
  if (ev.felt_routes > 0) {
    ev.felt_mae = felt_err / ev.felt_routes;
    ev.mae_felt_routes = fit_err_felt / ev.felt_routes;
  }
  return ev;
}

double Spearman(std::span<const double> a, std::span<const double> b) {
  if (a.size() != b.size() || a.size() < 2) return std::nan("");
  const std::vector<double> ra = Ranks(a), rb = Ranks(b);
  const double n = double(a.size());
  const double mean = (n + 1) / 2;
  double sab = 0, saa = 0, sbb = 0;
  for (size_t i = 0; i < a.size(); ++i) {
    sab += (ra[i] - mean) * (rb[i] - mean);
    saa += (ra[i] - mean) * (ra[i] - mean);
    sbb += (rb[i] - mean) * (rb[i] - mean);
  }
  if (saa == 0 || sbb == 0) return std::nan("");
  return sab / std::sqrt(saa * sbb);
}

}  // namespace sb::grades
