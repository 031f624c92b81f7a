// Abilities that drift (issue 35; docs/grades.md, "Abilities that drift"):
// the ascent rating of ratings.h with each climber's ability a Wiener chain
// over the weeks of their ticks (Whole-History Rating, Coulom 2008; Scarff's
// climbing-ratings "pages"), solved by Newton's method whose step is a
// conjugate-gradient solve preconditioned by each climber's tridiagonal
// block; the chain's variance w^2 per year chosen by the Laplace marginal
// likelihood on a grid. Also: a drifting synthetic gym, and intervals that
// follow one-sided evidence (skewed).
//
//   auto dp = BuildDriftProblem(in.problem, in.dated);        // in: ReadRatingsInput
//   auto fit = FitDriftRatings(*dp, RatingParams::For(in.discipline));
//   fit->fit.ability[c]    // climber c's latest ability (its last week)
//
// Static fits (ratings.h) are untouched: nothing here runs unless asked for.
#ifndef SB_GRADES_RATINGS_DRIFT_H_
#define SB_GRADES_RATINGS_DRIFT_H_

#include <cstdint>
#include <optional>
#include <span>
#include <string_view>
#include <vector>

#include "base/status.h"
#include "grades/ratings.h"
#include "grades/ratings_synth.h"

namespace sb::grades {

// Whether abilities drift: off (static, ratings.h), on, or auto (on when the
// ticks span more than a season, kSeasonDays).
enum class DriftMode { kOff = 0, kOn = 1, kAuto = 2 };
// "off", "on", "auto". Never fails.
const char* DriftModeName(DriftMode m);
// Parses DriftModeName() output. Errors: kInvalidInput "FIELD: expected on,
// off or auto, got 'TEXT'".
Result<DriftMode> ParseDriftMode(std::string_view text, std::string_view field = "--drift");

// A season: a gym's routes stay up for weeks and a climber's level moves
// little over a few months; ticks spanning more than this many days (first
// to last date) turn drift on under kAuto.
inline constexpr int kSeasonDays = 120;
// Days of one node of a climber's chain (one ability per climber per week,
// as Scarff's "pages"; a week's ticks share it).
inline constexpr int kDriftNodeDays = 7;
// The grid of w (grades per square root of a year) whose Laplace marginal
// likelihood chooses the chain's variance; and the value used when the
// likelihood cannot be computed (above kMaxExactRoutes routes): WHR's Go
// value (14 Elo^2 a day, Coulom 2008) is 0.41 logit per sqrt(year), 0.37 V
// grades at k = ln 3; the drifting synthetic gyms' estimates sit near 1.
inline constexpr double kDriftSdGrid[] = {0.1, 0.2, 0.35, 0.5, 0.7, 1.0, 1.4, 2.0, 2.8, 4.0};
inline constexpr double kDefaultDriftSd = 0.7;

// Days since 1970-01-01 of an ISO date "YYYY-MM-DD" (IsIsoDate holds). Pure.
int DayNumber(std::string_view iso_date);

// One tick with its day (DayNumber) and games.
struct DatedTick {
  int32_t climber = 0;
  int32_t route = 0;
  int32_t day = 0;
  Games games;
};

// The data of a drifting fit: the static problem's routes (setters' grades,
// felt grades), climbers and model, with the games per (node, route).
struct DriftProblem {
  RatingProblem base;  // its pairs are not used
  // Per node: its climber and its day (the first day of its week). A
  // climber's nodes are contiguous and in day order:
  // [climber_start[c], climber_start[c + 1]).
  std::vector<int32_t> node_climber, node_day;
  std::vector<int32_t> climber_start;
  // Games per (node, route), sorted by (route, node); `climber` is the node.
  std::vector<RatingPair> pairs;
  int first_day = 0, last_day = 0;  // of the ticks (0, 0 without any)
  int node_days = kDriftNodeDays;
  int num_nodes() const { return static_cast<int>(node_climber.size()); }
};

// The drifting problem of `base` (as Build() made it) and the same ticks
// with their days. Errors: kInvalidInput for node_days < 1, an index out of
// range. Pure.
Result<DriftProblem> BuildDriftProblem(const RatingProblem& base,
                                       std::span<const DatedTick> ticks,
                                       int node_days = kDriftNodeDays);

// Whether `mode` drifts for ticks from first_day to last_day.
bool DriftApplies(DriftMode mode, int first_day, int last_day);

struct DriftOptions {
  // w, the chain's sd in grades per sqrt(year) (ability variance w^2 dt
  // between nodes dt years apart); nullopt: chosen on kDriftSdGrid by the
  // Laplace marginal likelihood (exact intervals only; else kDefaultDriftSd).
  std::optional<double> sd;
};

// A drifting fit: `fit` as a static fit reads (difficulties with their sds;
// abilities and sds of each climber's latest node), plus every node.
struct DriftFit {
  RatingFit fit;
  std::vector<double> node_value;   // per node
  std::vector<double> latest_day;   // per climber: the day of its latest node
  double drift_sd = 0;              // w used
  bool drift_sd_estimated = false;  // chosen on the grid
  double log_evidence = 0;          // Laplace log marginal likelihood at w (exact only)
  // The grid: w and its log evidence (empty unless estimated).
  std::vector<std::pair<double, double>> grid;
};

// Fits the drifting model: the negative log posterior of ratings.h with the
// climber's prior replaced by a chain: first node ~ N(m, climber_sd^2),
// node j+1 - node j ~ N(0, w^2 (day_{j+1} - day_j) / 365.25). Intervals as
// options.intervals (exact: the Schur complement onto the routes with each
// climber's chain inverted; approximate: each route with its nodes'
// in-chain variances). Errors: as FitRatings; kInvalidInput for w <= 0.
// Pure; thread-safe.
Result<DriftFit> FitDriftRatings(const DriftProblem& problem, const RatingParams& params,
                                 const DriftOptions& drift = {},
                                 const RatingFitOptions& options = {});

// An interval [lo, hi] around a value.
struct Interval {
  double lo = 0, hi = 0;
};

// Intervals that follow the evidence (docs/grades.md, "Skewed intervals"):
// for each route, the conditional negative log posterior f(d) of its
// difficulty with the climbers held at `ability_of_pair` (one value per
// pair: the pair's climber's or node's fitted ability), rescaled so its
// curvature at the optimum is the Laplace marginal precision 1/sd^2; the
// interval is where f rises by kZ80^2 / 2. A quadratic f gives value -/+
// kZ80 sd; a route nobody sent (f flat above) gets a longer upper side.
// `pairs` sorted by route (RatingProblem's or DriftProblem's). Pure.
std::vector<Interval> SkewedRouteIntervals(const RatingProblem& base,
                                           std::span<const RatingPair> pairs,
                                           std::span<const double> ability_of_pair,
                                           const RatingParams& params, const RatingFit& fit);

// PredictSend for a climber whose ability is uncertain, a ~ N(ability,
// ability_sd^2) (a drifting fit's latest ability): the logits scaled by
// 1 / sqrt(1 + pi k^2 ability_sd^2 / 8), the probit approximation of the
// logistic-normal integral (MacKay 1992). ability_sd 0 is PredictSend. Pure.
SendChances PredictSendUncertain(const RatingParams& params, RatingModel model,
                                 double session_offset, double session_tries, double ability,
                                 double ability_sd, double difficulty);

// The knobs of a drifting synthetic gym (on top of SynthGymParams).
struct DriftGymParams {
  // Each climber's trend (grades a year) ~ N(trend_mean, trend_sd^2), plus a
  // Wiener process of wiener_sd grades per sqrt(year), over 365 days: a gym
  // of mostly improving climbers (a grade and a half a year on average),
  // the drift under which the static fit's intervals hold 63-66% (the
  // issue's 63%).
  double trend_mean = 1.5, trend_sd = 1.0, wiener_sd = 1.5;
  // A route is up for this many days (set on a uniform day of the year so
  // that it comes down by its end); its ticks fall while it is up.
  int route_days = 56;
};

// A gym as MakeSynthGym makes it, with abilities that drift: the ability of
// a climber on day t is start + trend t / 365 + W(t); a route's climber is
// chosen near its difficulty by their ability at the route's mid-life; the
// truth's ability (SynthGym::true_ability) is each climber's on day 364.
// `ability_at_tick` is each tick's true ability. Deterministic in the params.
struct DriftingGym {
  SynthGym gym;
  std::vector<double> ability_at_tick;
};
Result<DriftingGym> MakeDriftingGym(const SynthGymParams& params, const DriftGymParams& drift = {});

// The gym's ticks with their days (2026-01-01 + SynthTick::day).
std::vector<DatedTick> SynthDatedTicks(const SynthGym& gym, RatingModel model);

// A fit of a (drifting or static) synthetic gym against its truth, drifting
// or static, with symmetric or skewed intervals: the route figures of
// RatingEvaluation, and each climber's latest ability against their truth on
// the day of their last tick.
struct DriftEvaluation {
  RatingEvaluation routes;
  double skewed_coverage = 0;      // routes' skewed 80% intervals holding the truth
  double skewed_width = 0;         // their mean width
  double climber_mae = 0;          // |latest ability - truth at the last tick|
  double climber_coverage = 0;     // climbers' 80% intervals holding it
  bool drift = false;
  double drift_sd = 0;
};
Result<DriftEvaluation> EvaluateDriftingGym(const DriftingGym& gym, const RatingParams& params,
                                            bool drift, const DriftOptions& drift_options = {},
                                            const RatingFitOptions& options = {},
                                            RatingModel model = RatingModel::kTries);

}  // namespace sb::grades

#endif  // SB_GRADES_RATINGS_DRIFT_H_
