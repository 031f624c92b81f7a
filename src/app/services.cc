#include "app/services.h"

#include "base/log.h"

namespace sb::app {

Services::Services(Database* store, const Options& opts, Clock* clock)
    : options(opts),
      plans(opts.plan_cache_entries),
      accounts(store, opts, clock),
      routes(store, opts, &plans),
      variations(store, opts, &plans),
      maps(store, opts),
      climber_feedback(store, opts, clock),
      studies(store, opts, clock),
      renders(opts.renders),
      gyms(store, opts),
      logbook(store, clock),
      read_costs(store, &logbook, opts.render_costs, opts.renders),
      chances(store, &logbook, clock),
      dashboard(store, opts, clock),
      reports(store, &gyms, &logbook, ReportLimits::kMaxRoutes, opts.render_costs),
      setting_days(store, opts, &routes, &gyms, &variations, &renders, &dashboard, &logbook,
                   clock),
      rendered(store, clock),
      profiles(store, opts),
      scales(store, &gyms),
      imports(store, opts, &routes, &gyms, &scales) {
  // An install starts with one gym (issue 21), named at its first start.
  if (Status g = gyms.EnsureFirstGym(opts.first_gym_name); !g.ok()) {
    LogError("first gym: " + g.message());
  }
  // Rows written by an older version get their metadata columns (grades,
  // colour, wall, ...) derived again; a failure leaves them as they were.
  Result<int> refreshed = routes.RefreshMetadata();
  if (!refreshed.ok()) LogError("route metadata: " + refreshed.status().message());
}

}  // namespace sb::app
