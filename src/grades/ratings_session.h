// The session model with zones and session offsets (issue 35; docs/grades.md,
// "A model of the session", "Real outcomes"): the session model of
// ratings.h (a first-try game and a session game per tick) extended with
// what competition results record and gyms' sessions show:
//
//   - zones: a boulder's zone is a second, easier target on the same
//     boulder; each row's zone outcome is evidence about the same climber
//     (a first-try zone game and a session zone game at the zone's own
//     difficulty z_r, whose prior is centred on d_r - delta, delta one
//     unknown for the fit);
//   - a session offset per route e_r (a read-and-send boulder against a
//     project: tries that fail at first but end in a top) and per climber
//     u_c (persistence, learning within a session), Gaussian around 0, on
//     the top's session game only.
//
//   p_flash = s(k (a - d))       p_send = s(k (a - d) + b + e_r + u_c)
//
// Fitted by MAP (Newton with a Jacobi-preconditioned conjugate-gradient
// step on the sparse design, backtracking line search) to a gradient of
// 1e-9. Deterministic (one thread, fixed order). The SciPy oracle
// (ratings_scipy.py, "session_zones") re-implements it to 1e-6.
#ifndef SB_GRADES_RATINGS_SESSION_H_
#define SB_GRADES_RATINGS_SESSION_H_

#include <cstdint>
#include <optional>
#include <vector>

#include "base/status.h"
#include "grades/ratings.h"
#include "grades/ratings_synth.h"

namespace sb::grades {

// One session of a climber on a route: did it top, in how many tries, did
// it reach the zone, in how many tries.
struct SessionObs {
  int32_t climber = 0;  // 0..climbers-1
  int32_t route = 0;    // 0..routes-1
  bool top = false;
  // With a top: the try that topped (1 = flash); without: the tries made;
  // nullopt: unknown (a top then counts as a send, not a flash); 0: no
  // try (no top games).
  std::optional<int> tries;
  // The zone outcome (nullopt: the route has no zone or it is unknown).
  std::optional<bool> zone;
  // With a zone: the try that reached it; without: the tries made; nullopt:
  // unknown (no first-try zone game); 0: no try (no zone games).
  std::optional<int> zone_tries;
};

// The model's priors (all on the V axis for bouldering, k logit per unit).
// A standard deviation of 0 turns its part off (no zone games, no route or
// climber offsets); so does a later tries' weight of 0.
struct SessionModelParams {
  double logit_per_unit = 1.0986122886681098;  // ln 3: one V grade
  double climber_sd = 2;    // abilities ~ N(prior_mean, climber_sd^2)
  double route_sd = 4;      // top difficulties ~ N(prior_mean, route_sd^2)
  double zone_sd = 1;       // zone difficulty ~ N(d_r - delta, zone_sd^2)
  double route_offset_sd = 1;      // e_r ~ N(0, route_offset_sd^2)
  double climber_offset_sd = 0.3;  // u_c ~ N(0, climber_offset_sd^2)
  // The tries after the first as per-try games s(k (a - d)) at this weight
  // (a top in n: one won and n - 2 lost; none in n: n - 1 lost; 0: none).
  double later_tries_weight = 0.2;
  double offset_mean = kSessionOffsetPriorMean;  // b ~ N(offset_mean, offset_sd^2)
  double offset_sd = kSessionOffsetPriorSd;
  double delta_sd = 10;   // delta ~ N(0, delta_sd^2): weak
  double prior_mean = 0;  // the climbers' and routes' prior mean

  // The defaults chosen by cross-validation on the World Cup rows with
  // heldout = 0 (docs/grades.md, "Real outcomes"): the values above.
  static SessionModelParams Defaults() { return {}; }
  // Sds and the weight finite and >= 0 (climber_sd, route_sd, offset_sd, delta_sd and k
  // > 0); errors name the field. Pure.
  Status Validate() const;
};

struct SessionModelFit {
  std::vector<double> ability, climber_offset;                    // per climber
  std::vector<double> difficulty, zone_difficulty, route_offset;  // per route
  double offset = 0;  // b
  double delta = 0;   // the zones' mean distance below the tops
  double prior_mean = 0;
  int newton_iterations = 0;
  int cg_iterations = 0;
  double gradient_max = 0;
};

// A route's own prior on its top difficulty (a gym's setter's grade with
// its sd, felt grades folded in): replaces N(prior_mean, route_sd^2).
struct RoutePrior {
  double mean = 0, sd = 1;
};

// Fits the model to `obs` (climbers and routes indices below the counts);
// `route_prior`: empty, or one per route. Errors: kInvalidInput from
// params.Validate(), an index out of range, tries above kMaxTickAttempts
// (naming the observation) or a route prior of the wrong size or a sd not
// > 0; kInternal when Newton does not converge. Pure; thread-safe.
Result<SessionModelFit> FitSessionModel(const std::vector<SessionObs>& obs, int climbers,
                                        int routes, const SessionModelParams& params,
                                        const std::vector<RoutePrior>& route_prior = {});

// The session games of a gym's problem (built with RatingModel::kSession:
// per pair, first-try wins and losses and session wins and losses) as
// observations with the same first-try and session games: a flash per
// first-try win, a send in 2 per session win past those, an attempt of one
// try per session loss (no zones; the counts of tries are not kept, so fit
// these with later_tries_weight 0). Errors: kInvalidInput when the problem is not a session model's
// or a pair's counts disagree (first-try games != session games). Pure.
Result<std::vector<SessionObs>> SessionObsOfProblem(const RatingProblem& problem);

// The route priors of a gym's problem under `params`: the setter's grade
// (sd setter_sd) or the fit's prior mean (sd open_route_sd), each route's
// felt grades folded in as Gaussian observations (sd felt_sd). Pure.
std::vector<RoutePrior> RoutePriorsOfProblem(const RatingProblem& problem,
                                             const RatingParams& params, double prior_mean);

// A gym's problem (built with RatingModel::kSession) fitted by this model:
// SessionObsOfProblem's rows, RoutePriorsOfProblem's priors, abilities
// N(prior_mean, params.climber_sd^2), k = params.logit_per_unit, the
// offsets' and b's priors of `k` and no later-tries games (the problem
// keeps no try counts). Returns the parameters used with the fit. Errors: those of
// SessionObsOfProblem and FitSessionModel. Pure.
struct GymSessionFit {
  SessionModelParams params;
  SessionModelFit fit;
};
Result<GymSessionFit> FitGymSessionModel(
    const RatingProblem& problem, const RatingParams& params, double prior_mean,
    const SessionModelParams& k = SessionModelParams::Defaults());

// A synthetic gym (ratings_synth.h) fitted by this model (no zones: the
// session games with the route and climber offsets of `k`; the setters'
// grades and felt grades as route priors under `params`, abilities
// N(mean setter's grade, params.climber_sd^2); no later-tries games: the
// session problem keeps no try counts): spearman, mae and
// setter_mae as EvaluateSynthGym; no intervals (coverage and width NaN),
// mae_felt_routes and felt_mae as there. Pure.
Result<RatingEvaluation> EvaluateSynthGymSession(const SynthGym& gym, const RatingParams& params,
                                                 const SessionModelParams& k);

// p_flash and p_send of `climber` on `route` (an index < 0 or past the fit:
// unseen, at the prior mean, or at `unseen_difficulty` when given, with
// offset 0). Pure.
SendChances PredictSessionModel(const SessionModelParams& params, const SessionModelFit& fit,
                                int climber, int route,
                                std::optional<double> unseen_difficulty = std::nullopt);

}  // namespace sb::grades

#endif  // SB_GRADES_RATINGS_SESSION_H_
