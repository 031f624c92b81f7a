#include "plan/smooth.h"

namespace sb::plan {

Status Smooth(const std::string& model_path, RoutePlan* plan) {
  (void)plan;
  return Status::InvalidInput("--smooth " + model_path +
                              ": smoothing needs the markov and language modules, which this "
                              "build does not include yet");
}

}  // namespace sb::plan
