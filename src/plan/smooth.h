// Smoothing of a plan's subsequence boundaries with a variable-order Markov
// model over move symbols (paper section 10.3).
#ifndef SB_PLAN_SMOOTH_H_
#define SB_PLAN_SMOOTH_H_

#include <string>

#include "base/status.h"
#include "plan/plan.h"

namespace sb::plan {

// At each boundary of the variation (where the next move's provenance does not
// continue the same route with the next move), finds the insertion of up to
// two moves that minimises -log2 P of the symbol sequence under the model at
// `model_path` ("default" = the bundled model), and records it in
// plan->smoothing when it lowers the total. Sets plan->smoothing_model.
// Errors: the model cannot be read (kNotFound/kInvalidInput).
Status Smooth(const std::string& model_path, RoutePlan* plan);

}  // namespace sb::plan

#endif  // SB_PLAN_SMOOTH_H_
