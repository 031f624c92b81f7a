// Issue 32: a gym scale's mapping suggested by a season's ascents. From the
// ascent grades (the rating fit's difficulties, on the axis) of the routes
// labelled in a gym scale, each label's range on the common axis: the cut
// between two neighbouring labels is where the fewest of their routes fall
// on the wrong side (a one-dimensional classifier), the outer ends are the
// 10% and 90% quantiles, cuts are made ascending, and each range is written
// as the grades of the built-in scale the labels were given in whose values
// lie inside it (so the labels ascend without overlapping). docs/grades.md
// ("A gym's own scale", "Suggested by the ascents"), measured on synthetic
// gyms by EvaluateScaleSuggestion (docs/BENCHMARKS.md).
//
//   std::vector<std::vector<double>> fitted(scale.labels.size());  // per label
//   auto s = sb::grades::SuggestLabels(scale, fitted);
//   s->labels[1].spec  -> {"2", "V1", "V2"}
#ifndef SB_GRADES_SCALE_SUGGEST_H_
#define SB_GRADES_SCALE_SUGGEST_H_

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "base/status.h"
#include "grades/gym_scale.h"

namespace sb::grades {

// One label's suggestion.
struct SuggestedLabel {
  LabelSpec spec;        // the suggested from/to (or the given ones when kept)
  LabelSpec given;       // as the scale has it now
  int routes = 0;        // routes with an ascent grade carrying this label
  double median = 0;     // their median ascent grade (on the axis); 0 without
  double lo = 0, hi = 0; // the suggested range before it is written in grades
  bool kept = false;     // fewer than min_routes routes: the given range kept
};

struct ScaleSuggestion {
  std::vector<SuggestedLabel> labels;  // the scale's labels, in order
  int routes = 0;                      // routes used, all labels
  // The suggested labels as MakeGymScale reads them (always valid).
  std::vector<LabelSpec> Specs() const;
};

// Labels with fewer routes than this keep their range (a label's quantiles
// from two routes would be noise).
inline constexpr int kMinRoutesPerSuggestedLabel = 5;

// Suggests `scale`'s ranges from `values`: per label (same order, same
// size as scale.labels), the ascent grades of its routes on the scale's
// axis. Errors: kInvalidInput when the sizes differ or a value is not
// finite. Pure; deterministic.
Result<ScaleSuggestion> SuggestLabels(const GymScale& scale,
                                      const std::vector<std::vector<double>>& values,
                                      int min_routes = kMinRoutesPerSuggestedLabel);

// A route's ascent grade with its label's pull taken out: the fit's value
// `fitted` (sd `fitted_sd`, the Laplace approximation) is the precision-
// weighted mean of what the ticks say and the prior (the label's value
// `prior`, sd `prior_sd` = RatingParams::setter_sd), so what the ticks say
// alone is fitted + (fitted - prior) w_prior / w_data, w_data = 1/fitted_sd^2
// - 1/prior_sd^2. A suggestion read from the fitted values keeps part of the
// old mapping (a route with 10 ticks keeps about a third of its label's
// pull); nullopt when the ticks weigh less than kMinDataWeight times the
// prior (too few to say). Pure.
inline constexpr double kMinDataWeight = 0.5;
std::optional<double> WithoutPrior(double fitted, double fitted_sd, double prior,
                                   double prior_sd);

// The measurement on a synthetic gym (grades/ratings_synth.h): routes with
// true difficulties, labelled by setters who read them in `truth` (the
// label whose range holds round(difficulty + N(0, setter_sd))), ticks from
// the logistic model, the fit's prior each route's label read in `guess`
// (the mapping the gym started with), then SuggestLabels on the fitted
// difficulties; compared bound by bound with `truth`.
struct ScaleSuggestEvaluation {
  int routes = 0, ticks = 0;
  double guess_bound_mae = 0;      // mean |guess bound - truth bound|, in grades of the axis
  double suggested_bound_mae = 0;  // the same for the suggestion
  double exact_bounds = 0;         // share of the suggestion's bounds equal to the truth's
  double within_one = 0;           // share within one grade of the truth
  ScaleSuggestion suggestion;
};

struct ScaleSuggestParams {
  int routes = 200;
  int climbers = 300;
  int ticks_per_route = 10;
  uint64_t seed = 1;
  bool remove_prior = true;  // WithoutPrior on each fitted value (as the app does)
};

// Errors: the labels' scales differ in size or discipline, the generator's
// and the fit's. Deterministic.
Result<ScaleSuggestEvaluation> EvaluateScaleSuggestion(const GymScale& truth,
                                                       const GymScale& guess,
                                                       const ScaleSuggestParams& params);

}  // namespace sb::grades

#endif  // SB_GRADES_SCALE_SUGGEST_H_
