// Grades from ascents (issue 23; docs/grades.md, "Grades from ascents"): a
// Bradley-Terry (logistic) model of climber-versus-route games, fitted
// jointly for routes and climbers by maximum a posteriori with the setter's
// grade as a Gaussian prior on each route's difficulty and felt grades as
// Gaussian observations of it; 80% intervals from the Laplace approximation.
//
//   RatingProblemBuilder b;
//   auto games = TickGames(TickOutcome::kSend, 3);     // 2 losses, 1 win
//   b.AddTick(climber, route, *games, felt_value);      // felt: optional
//   b.SetSetterGrade(route, 4.0);                       // V4
//   auto fit = FitRatings(b.Build(), RatingParams::For(Discipline::kBouldering));
//   fit->difficulty[route], fit->difficulty_sd[route]   // on the V axis
//
// Everything is on the numeric axis of the discipline (scale.h): V units for
// bouldering, YDS units for roped. Deterministic: the same problem and
// parameters give bit-identical fits, whatever the number of threads (each
// sum over pairs is made by one thread in a fixed order).
#ifndef SB_GRADES_RATINGS_H_
#define SB_GRADES_RATINGS_H_

#include <cstdint>
#include <optional>
#include <string_view>
#include <vector>

#include "base/status.h"
#include "grades/scale.h"

namespace sb::grades {

// How a tick ended: a flash (first try), a send after some tries, or tries
// without a send.
enum class TickOutcome { kFlash = 0, kSend = 1, kAttempt = 2 };

// "flash", "send", "attempt". Never fails.
const char* TickOutcomeName(TickOutcome o);
// Parses TickOutcomeName() output (exact, lower case). Errors: kInvalidInput
// "FIELD: expected flash, send or attempt, got 'TEXT'".
Result<TickOutcome> ParseTickOutcome(std::string_view text, std::string_view field = "outcome");

// Most tries one tick may report: a project session of a whole season is a
// few hundred tries at most; more is a typo and would let one row outweigh a
// route's other ticks.
inline constexpr int kMaxTickAttempts = 500;
// Tries assumed for a send whose count is empty: a send that is not a flash
// took at least two tries, and two is the least informative such claim.
inline constexpr int kSendDefaultAttempts = 2;

// The games one tick stands for, climber against route: per-try games at
// P = s(k (a - d)) and, in the session model, session games at
// P = s(k (a - d) + b) (b: RatingFit::session_offset).
struct Games {
  int wins = 0;
  int losses = 0;
  int session_wins = 0;
  int session_losses = 0;
};

// How ticks become games (docs/grades.md, "A model of the session").
enum class RatingModel {
  // Every try is a game (TickGames): the gyms' model, the default.
  kTries = 0,
  // Two games per tick: its first try (won by a flash) at s(k (a - d)), and
  // the session (won by a send, whatever the tries) at s(k (a - d) + b).
  kSession = 1,
};
// "tries", "session". Never fails.
const char* RatingModelName(RatingModel m);
// Parses RatingModelName() output. Errors: kInvalidInput "FIELD: expected
// tries or session, got 'TEXT'".
Result<RatingModel> ParseRatingModel(std::string_view text, std::string_view field = "model");

// A tick as games: flash = 1 win (attempts empty or 1); send after n tries =
// n - 1 losses then 1 win (n empty: kSendDefaultAttempts; n = 1 is a flash);
// attempt = n losses (n empty: 1). Errors: kInvalidInput naming "attempts"
// for n < 1, n > kMaxTickAttempts, or a flash with n != 1. Pure.
Result<Games> TickGames(TickOutcome outcome, std::optional<int> attempts);
// A tick as games under `model`: kTries is TickGames; kSession is a flash =
// first try won + session won, a send = first try lost + session won, an
// attempt = first try lost + session lost (attempts checked as TickGames
// does). Pure.
Result<Games> TickGamesFor(RatingModel model, TickOutcome outcome, std::optional<int> attempts);

// The model's parameters, all on the discipline's axis (grade units).
struct RatingParams {
  // Logit of one unit of the axis: P(a try succeeds) = 1 / (1 + exp(-k (a - d)))
  // for ability a and difficulty d. Bouldering ln 3 (one V grade ~ 3x harder:
  // board studies, Drummond & Popinga 2021 find 3.2x); roped 4 ln 2.1 (2.1x per
  // sport grade step, one YDS letter, four letters per YDS unit).
  double logit_per_unit = 0;
  // Prior standard deviation of climbers' abilities around the prior mean
  // (the mean of the setters' grades): the spread of a gym's climbers.
  double climber_sd = 0;
  // Standard deviation of the setter's grade around the route's difficulty
  // (how far setters are off: about one grade).
  double setter_sd = 0;
  // Prior standard deviation of a route without a setter's grade (around the
  // prior mean): as wide as the climbers' spread.
  double open_route_sd = 0;
  // Standard deviation of one felt grade around the route's difficulty
  // (noisier than the setter: climbers grade from one go, by feel).
  double felt_sd = 0;

  // The documented defaults of a discipline (docs/grades.md).
  static RatingParams For(Discipline d);
  // Every field finite and > 0; errors name the field. Pure.
  Status Validate() const;
};

// One climber-route pair's games, summed over its ticks.
struct RatingPair {
  int32_t climber = 0;
  int32_t route = 0;
  int32_t wins = 0;
  int32_t losses = 0;
  int32_t session_wins = 0;  // the session model's session games (else 0)
  int32_t session_losses = 0;
};

// The data of a fit, indexed 0..num_climbers-1 and 0..num_routes()-1.
// Build one with RatingProblemBuilder.
struct RatingProblem {
  int num_climbers = 0;
  // The games' model (kTries: no session games).
  RatingModel model = RatingModel::kTries;
  // Mean tries of a session in the ticks with a known count (a flash 1, a
  // send after n tries n, an attempt of n tries n; 0 without any): a
  // session's length for the tries model's p_send.
  double session_tries = 0;
  // One entry per pair with at least one game, sorted by (route, climber).
  std::vector<RatingPair> pairs;
  // Per route: the setter's grade (nullopt: none), the sum and count of its
  // felt grades, its number of ticks.
  std::vector<std::optional<double>> setter;
  std::vector<double> felt_sum;
  std::vector<int> felt_count;
  std::vector<int> route_ticks;
  // Per climber: number of ticks.
  std::vector<int> climber_ticks;

  int num_routes() const { return static_cast<int>(setter.size()); }
  // Sizes agree, indices in range, pairs sorted and unique, values finite.
  Status Validate() const;
};

// Collects ticks and setter grades, aggregating games per pair. Indices
// are the caller's (dense, from 0). Not thread-safe.
class RatingProblemBuilder {
 public:
  // Room for n ticks (no reallocation up to them).
  void Reserve(size_t n) { entries_.reserve(n); }
  // Makes sure climbers 0..n-1 / routes 0..n-1 exist (with no ticks).
  void EnsureClimbers(int n);
  void EnsureRoutes(int n);
  // One tick of `climber` on `route` (indices >= 0) with its games and
  // optional felt grade (a value on the axis).
  void AddTick(int climber, int route, Games games, std::optional<double> felt = std::nullopt);
  // The setter's grade of `route` (a value on the axis); the last call wins.
  void SetSetterGrade(int route, double value);
  void SetModel(RatingModel m) { p_.model = m; }
  // Counts one session of `tries` tries (known counts only) in session_tries.
  void AddSessionTries(int tries) {
    tries_sum_ += tries;
    ++tries_n_;
  }
  // The problem (pairs sorted by route then climber); the builder is left empty.
  RatingProblem Build();

 private:
  struct Entry {
    uint64_t key;  // route << 32 | climber
    int32_t wins, losses, session_wins, session_losses;
  };
  std::vector<Entry> entries_;
  RatingProblem p_;
  double tries_sum_ = 0;
  int64_t tries_n_ = 0;
};

// Routes up to this many get exact marginal variances (the dense Schur
// complement of the climbers' block, Cholesky, O(routes^3): about a second at
// this size); larger problems use the approximation below.
inline constexpr int kMaxExactRoutes = 1200;
// The two-sided 80% normal quantile: an interval is value -/+ kZ80 * sd.
inline constexpr double kZ80 = 1.2815515655446004;

// How the intervals' standard deviations are computed from the Hessian H of
// the negative log posterior at the optimum (the Laplace approximation).
enum class IntervalMethod {
  kAuto = 0,     // kExact up to kMaxExactRoutes routes, else kApproximate
  kExact,        // sqrt of the diagonal of H^-1 (refused above kMaxExactRoutes)
  kApproximate,  // each route with its climbers marginalised, other routes
                 // held fixed: 1 / (H_rr - sum_c H_rc^2 / H_cc); same for climbers
};

struct RatingFit;

struct RatingFitOptions {
  // Stop when the largest gradient component of the negative log posterior
  // is below this (grade units; far below any printed digit).
  double gradient_tolerance = 1e-9;
  // Newton iterations before giving up (the problem is convex; typical fits
  // take 5 to 15).
  int max_newton_iterations = 100;
  IntervalMethod intervals = IntervalMethod::kAuto;
  // Start from this fit's values (a refit after new ticks). Indices are
  // kept: climbers and routes added since (indices past the fit's) start
  // from their priors; a fit with more climbers or routes than the problem
  // is ignored. Not owned; may be null.
  const RatingFit* warm_start = nullptr;
  // The session model's offset b (logit) held at this value; without, b is
  // estimated with the abilities and difficulties (joint MAP, prior
  // N(kSessionOffsetPriorMean, kSessionOffsetPriorSd^2)). Ignored by kTries.
  std::optional<double> session_offset = std::nullopt;
  // Threads of the per-pair passes (0: the machine's cores). The fit is
  // bit-identical for every value (each sum is made by one thread in a fixed
  // order); problems under 20,000 pairs run on one. One by default: on the
  // shared 2-core machine threads cost more CPU than they saved
  // (docs/BENCHMARKS.md).
  int threads = 1;
};

// The session offset's prior: a session of a few tries is likelier sent than
// one try (5 tries at p = 1/2: 97%, logit 3.4, one try logit 0), weakly.
inline constexpr double kSessionOffsetPriorMean = 2.0;
inline constexpr double kSessionOffsetPriorSd = 2.0;

// A fit: per route and per climber the posterior mode and the Laplace
// standard deviation, on the axis.
struct RatingFit {
  std::vector<double> difficulty, difficulty_sd;
  std::vector<double> ability, ability_sd;
  double prior_mean = 0;  // the climbers' and open routes' prior mean
  RatingModel model = RatingModel::kTries;
  double session_offset = 0;  // b of the session model (0 for kTries)
  double session_tries = 0;   // RatingProblem::session_tries
  bool exact_intervals = false;
  int newton_iterations = 0;
  int cg_iterations = 0;
  double gradient_max = 0;  // largest |gradient| component at the end
};

// Fits the model (docs/grades.md: negative log posterior
//   sum_pairs -[W log s(k(a-d)) + L log s(-k(a-d))]
//   + sum_c (a_c - m)^2 / 2 climber_sd^2
//   + sum_r (d_r - g_r)^2 / 2 setter_sd^2   (routes with a setter's grade g_r)
//   + sum_r (d_r - m)^2 / 2 open_route_sd^2 (routes without)
//   + sum_felt (f - d_r)^2 / 2 felt_sd^2,
// m = mean of the setters' grades, else of the felt grades, else 0) by
// Newton's method with a Jacobi-preconditioned conjugate-gradient solve of
// each step and a backtracking line search. Errors: kInvalidInput from
// params.Validate() / problem.Validate(), or kExact above kMaxExactRoutes;
// kInternal when Newton does not converge. Pure; thread-safe.
Result<RatingFit> FitRatings(const RatingProblem& problem, const RatingParams& params,
                             const RatingFitOptions& options = {});

// A climber's chances on a route, from ability a and difficulty d: p_flash =
// s(k (a - d)); p_send, a send in one session: the session model's s(k (a -
// d) + b), the tries model's 1 - (1 - p_flash)^session_tries (one session as
// long as the fit's mean; at least one try). Pure.
struct SendChances {
  double p_flash = 0, p_send = 0;
};
SendChances PredictSend(const RatingParams& params, RatingModel model, double session_offset,
                        double session_tries, double ability, double difficulty);

// Everything the single-route update needs about one route.
struct RouteEvidence {
  double prior_mean = 0, prior_sd = 1;  // setter's grade and setter_sd, or m and open_route_sd
  double felt_sum = 0;
  int felt_count = 0;
  int ticks = 0;
  std::vector<RatingPair> pairs;  // this route's pairs (route field ignored)
};

// The evidence of `route` in `problem` under `params` with `fit`'s prior
// mean. Errors: kInvalidInput for an index out of range.
Result<RouteEvidence> EvidenceOf(const RatingProblem& problem, const RatingParams& params,
                                 const RatingFit& fit, int route);
// Adds one tick to the evidence (merging into the climber's pair).
void AddTickTo(RouteEvidence* e, int climber, Games games, std::optional<double> felt);

// A route's rating from the single-route update.
struct RouteRating {
  double value = 0, sd = 0;
  int newton_iterations = 0;
};

// The incremental update after a new tick: the route's difficulty by a
// one-dimensional Newton solve with the climbers' abilities held at `fit`'s
// values; its sd counts each climber's uncertainty (ability_sd) as extra
// noise on that climber's games: precision = prior + felt + sum over pairs
// of 1 / (1/h + ability_sd^2), h the pair's Fisher information. O(the
// route's pairs). A new climber (index past fit.ability) gets the prior
// (mean fit.prior_mean, sd params.climber_sd). The next full fit moves the
// climbers too. Errors: kInvalidInput from params.Validate(). Pure.
Result<RouteRating> RateRoute(const RouteEvidence& evidence, const RatingFit& fit,
                              const RatingParams& params);

}  // namespace sb::grades

#endif  // SB_GRADES_RATINGS_H_
