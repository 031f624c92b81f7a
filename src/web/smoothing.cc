#include "web/smoothing.h"

#if __has_include("plan/smooth.h")
#include "plan/smooth.h"
#define SB_WEB_HAVE_SMOOTH 1
#else
#define SB_WEB_HAVE_SMOOTH 0
#endif

namespace sb::web {

Status SmoothPlan(plan::RoutePlan* plan) {
#if SB_WEB_HAVE_SMOOTH
  return plan::Smooth("default", plan);
#else
  (void)plan;
  return Status::NotFound("smoothing is not available in this build yet");
#endif
}

}  // namespace sb::web
