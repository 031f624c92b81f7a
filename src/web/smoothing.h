// The smoothing hook of the web app ("smooth": true): the one place where the
// web app calls the plan module's smoothing (Markov model over move symbols).
#ifndef SB_WEB_SMOOTHING_H_
#define SB_WEB_SMOOTHING_H_

#include "base/status.h"
#include "plan/plan.h"

namespace sb::web {

// Fills plan->smoothing and plan->smoothing_model with the bundled default
// model (plan::Smooth("default", ...)). Errors: whatever smoothing reports
// when it is not available or the model cannot be read; the plan's moves are
// never changed. Thread-safe.
Status SmoothPlan(plan::RoutePlan* plan);

}  // namespace sb::web

#endif  // SB_WEB_SMOOTHING_H_
