// The application layer in one object: what the web app and the CLI call.
//
//   auto db = app::OpenDatabase("var/strangebeta.db");   // app/database.h
//   app::Services services(db->get(), app::Options{});
//   services.routes.List(viewer, {});
#ifndef SB_APP_SERVICES_H_
#define SB_APP_SERVICES_H_

#include "app/accounts.h"
#include "app/budget.h"
#include "app/chances.h"
#include "app/climber_feedback.h"
#include "app/clock.h"
#include "app/dashboard.h"
#include "app/gym_import.h"
#include "app/gyms.h"
#include "app/logbook.h"
#include "app/maps.h"
#include "app/options.h"
#include "app/profiles.h"
#include "app/read_costs.h"
#include "app/render_cache.h"
#include "app/report.h"
#include "app/routes.h"
#include "app/scales.h"
#include "app/setting_day.h"
#include "app/studies_service.h"
#include "app/types.h"
#include "app/variations.h"

namespace sb::app {

// Owns the caches the services share; does not own `db` or `clock`.
// Thread-safe.
struct Services {
  Services(Database* db, const Options& options, Clock* clock = &SystemClock());

  const Options options;
  PlanCache plans;
  Accounts accounts;
  Routes routes;
  Variations variations;
  Maps maps;
  ClimberFeedback climber_feedback;
  StudyService studies;
  // The budget of pages and files (options.renders; costs in
  // options.render_costs), taken by the web layer before rendering.
  WorkBudget renders;
  Gyms gyms;
  // The climbers' logbook and ascent grades (issue 23).
  Logbook logbook;
  // What reading a logbook, a route's ticks, an ascent grade or a study
  // costs, from counts before the reading (issue 34; options.render_costs,
  // charged through `renders` by the web layer).
  ReadCosts read_costs;
  // A climber's chances on a route and the gym's likely projects, from
  // the logbook's cached fits (issue 35).
  Chances chances;
  // The setting dashboard and wall targets (issue 22).
  Dashboard dashboard;
  // The wall and setting-day reports over the logbook (issue 23).
  Reports reports;
  // Setting days (issue 22): proposals and accepting a candidate.
  SettingDays setting_days;
  // Rendered answers kept per gym data version and day (issue 22: the API
  // dashboard's JSON, a wall page's tables).
  RenderCache rendered;
  // Display names, languages and the account page (issue 32).
  Profiles profiles;
  // A gym's own grade scales and a wall's scale (issue 32).
  Scales scales;
  // A gym's own route list, previewed and confirmed; CRDL files once only
  // (issue 32).
  GymImport imports;
};

}  // namespace sb::app

#endif  // SB_APP_SERVICES_H_
