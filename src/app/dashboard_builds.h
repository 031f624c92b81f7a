// Issue 34: how often the setting dashboard read its routes again (a test's
// view of app::Dashboard's cache; app/dashboard.cc). Kept apart from
// app/dashboard.h, which every web file includes.
#ifndef SB_APP_DASHBOARD_BUILDS_H_
#define SB_APP_DASHBOARD_BUILDS_H_

#include <cstdint>

namespace sb::app {

// How many times any Dashboard in this process built the route-derived part
// of a dashboard (walls, bands, styles, gaps, the archive's mix, circuits:
// every route of the gym read). Dashboard::Get keeps that part while the
// gym's data other than ticks stays, so a tick does not move this; a
// route's change does. Thread-safe.
int64_t DashboardRouteBuilds();

}  // namespace sb::app

#endif  // SB_APP_DASHBOARD_BUILDS_H_
