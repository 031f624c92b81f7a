// Synthetic gyms for the ascent rating (docs/grades.md, "Grades from
// ascents", "The synthetic gym"): climbers with abilities, routes with true
// difficulties, tries drawn from the logistic model, few and biased felt
// grades, noisy setters' grades; and the evaluation of a fit against the
// truth (rank correlation, interval coverage, errors against the felt
// grades' median).
//
//   SynthGymParams sp;  sp.routes = 400;  sp.ticks_per_route = 20;
//   auto gym = MakeSynthGym(sp);                       // bouldering, V axis
//   auto ev = EvaluateSynthGym(*gym, RatingParams::For(Discipline::kBouldering));
#ifndef SB_GRADES_RATINGS_SYNTH_H_
#define SB_GRADES_RATINGS_SYNTH_H_

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "base/status.h"
#include "grades/ratings.h"

namespace sb::grades {

// Size limits of the generator (memory: about 40 bytes per tick).
inline constexpr int kMaxSynthClimbers = 10'000'000;
inline constexpr int kMaxSynthRoutes = 10'000'000;
inline constexpr int64_t kMaxSynthTicks = 50'000'000;

// The generator's knobs; values on the V axis (a bouldering gym).
struct SynthGymParams {
  int climbers = 300;
  int routes = 400;
  int ticks_per_route = 20;  // every route gets exactly this many ticks
  uint64_t seed = 1;
  double difficulty_mean = 4, difficulty_sd = 2.5;  // true route difficulty, clamped to VB..V14
  double ability_mean = 4.5, ability_sd = 2.5;      // climbers, clamped to VB..V15
  // A climber tries routes near their level: the tick's climber is the one
  // whose ability is nearest a target drawn from N(route + 0.5, choice_sd).
  double choice_sd = 1.5;
  int max_tries = 6;                           // a session's tries, uniform in 1..max_tries
  double logit_per_unit = 1.0986122886681098;  // ln 3: the model's own
  double setter_sd = 1.0;                      // setter's grade: round(d + N(0, setter_sd))
  double felt_share = 0.25;                    // share of sends that leave a felt grade
  double felt_bias = 0.3;  // felt = round(d - felt_bias (a - d) + N(0, felt_sd)):
  double felt_sd = 1.0;    // strong climbers feel routes easier
  // Ranges, names the field. Pure.
  Status Validate() const;
};

// One synthetic tick (a CSV row of TICKS.csv).
struct SynthTick {
  int climber = 0;
  int route = 0;
  int day = 0;  // 0..364 of 2026
  TickOutcome outcome = TickOutcome::kFlash;
  std::optional<int> attempts;
  std::optional<int> felt;  // a whole V grade (-1 = VB)
};

struct SynthGym {
  std::vector<double> true_difficulty, true_ability;
  std::vector<int> setter_grade;  // whole V grades (-1 = VB)
  std::vector<SynthTick> ticks;
};

// Generates a gym (deterministic in the params, std::mt19937_64 with
// explicit transforms, so the same seed gives the same gym everywhere).
// Errors: kInvalidInput from Validate().
Result<SynthGym> MakeSynthGym(const SynthGymParams& params);

// The gym as files: TICKS.csv (climber,route,date,outcome,attempts,
// felt_grade; climbers "c1".., routes "r1"..), ROUTES.csv (route,grade in V)
// and TRUTH.csv (kind,name,value: kind route or climber, value on the V axis).
std::string SynthTicksCsv(const SynthGym& gym);
std::string SynthRoutesCsv(const SynthGym& gym);
std::string SynthTruthCsv(const SynthGym& gym);

// The gym as a rating problem (the same games and felt grades TICKS.csv holds).
RatingProblem SynthProblem(const SynthGym& gym, RatingModel model = RatingModel::kTries);

// A fit against the truth.
struct RatingEvaluation {
  int routes = 0;
  int ticks = 0;
  double spearman = 0;             // fitted vs true difficulty, all routes
  double coverage = 0;             // share of routes whose 80% interval holds the truth
  double mae = 0;                  // mean |fitted - true|, all routes
  double setter_mae = 0;           // mean |setter's grade - true|, all routes
  int felt_routes = 0;             // routes with at least one felt grade
  double mae_felt_routes = 0;      // mean |fitted - true| on those routes
  double felt_mae = 0;             // mean |median felt grade - true| on those routes
  double mean_interval_width = 0;  // hi - lo, mean over routes
  bool exact_intervals = false;
};

// Fits `gym` with `params` and compares with its truth. Errors: from FitRatings.
Result<RatingEvaluation> EvaluateSynthGym(const SynthGym& gym, const RatingParams& params,
                                          const RatingFitOptions& options = {},
                                          RatingModel model = RatingModel::kTries);

// Fitted difficulties (one per route of `gym`) against its truth: routes,
// ticks, spearman, the errors and the felt grades' figures; with
// difficulty_sd (one per route), the 80% intervals' coverage and mean width,
// else both NaN (a fit without intervals). Pure.
RatingEvaluation CompareWithTruth(const SynthGym& gym, std::span<const double> difficulty,
                                  std::span<const double> difficulty_sd = {});

// Spearman's rank correlation (average ranks for ties; NaN when either side
// is constant or the sizes differ / are below 2). Pure.
double Spearman(std::span<const double> a, std::span<const double> b);

}  // namespace sb::grades

#endif  // SB_GRADES_RATINGS_SYNTH_H_
