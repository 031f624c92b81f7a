#include "app/services.h"

#include "base/log.h"

namespace sb::app {

Services::Services(store::Store* store, const Options& opts, Clock* clock)
    : options(opts),
      plans(opts.plan_cache_entries),
      accounts(store, opts, clock),
      routes(store, opts, &plans),
      variations(store, opts, &plans),
      maps(store, opts),
      climber_feedback(store, opts, clock),
      studies(store, opts, clock),
      renders(opts.renders) {
  // Rows written by an older version get their metadata columns (grades,
  // colour, wall, ...) derived again; a failure leaves them as they were.
  Result<int> refreshed = routes.RefreshMetadata();
  if (!refreshed.ok()) LogError("route metadata: " + refreshed.status().message());
}

}  // namespace sb::app
