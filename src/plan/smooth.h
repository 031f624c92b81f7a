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
// Each boundary is judged on its own against the unsmoothed sequence; a
// suggestion's inserted moves alternate hands starting with the hand other
// than the move before the boundary. Not thread-safe for one plan.
// Suggestions saving `min_bits` or less are dropped (0 = any saving).
Status Smooth(const std::string& model_path, RoutePlan* plan, double min_bits = 0.0);

// The bundled model (data/models/default.sbm, see FindDataFile), or "".
std::string DefaultModelPath();

}  // namespace sb::plan

#endif  // SB_PLAN_SMOOTH_H_
