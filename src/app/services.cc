#include "app/services.h"

namespace sb::app {

Services::Services(store::Store* store, const Options& opts, Clock* clock)
    : options(opts),
      plans(opts.plan_cache_entries),
      accounts(store, opts, clock),
      routes(store, opts, &plans),
      variations(store, opts, &plans),
      maps(store, opts),
      climber_feedback(store, opts, clock),
      studies(store, opts, clock) {}

}  // namespace sb::app
