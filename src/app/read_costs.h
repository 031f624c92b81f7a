// What the pages and answers that read a climber's, a route's or a study's
// rows cost, in render units (app::RenderCosts), computed from counts before
// the reading (issue 34: "every page and API answer that reads more than a
// bounded number of rows has a cost checked before the work, and its cost
// grows with what it reads"; docs/web.md, "Work budgets"). The web layer
// charges these to the caller through app::Services::renders (WorkBudget)
// before it calls the service that reads; the report's cost is
// Reports::Plan's (app/report.h), the export's the visible routes'.
//
// Each cost counts the rows the service will read (one indexed COUNT query
// or a row the service reads anyway), never the rows themselves.
#ifndef SB_APP_READ_COSTS_H_
#define SB_APP_READ_COSTS_H_

#include <cstdint>
#include <optional>
#include <string_view>

#include "app/logbook.h"
#include "app/options.h"
#include "app/types.h"
#include "base/status.h"
#include "store/count_store.h"
#include "store/store.h"

namespace sb::app {

// Thread-safe. Does not own its arguments.
class ReadCosts {
 public:
  // `costs`: options.render_costs; `budget`: options.renders (the
  // per-request caps a reader's share of a first fit is bounded by).
  ReadCosts(store::Store* store, Logbook* logbook, RenderCosts costs, BudgetPolicy budget);

  // A climber's logbook (GET /logbook, GET /api/logbook, GET
  // /api/account/ticks.csv): their ticks (row_per_read each), one route
  // read per ticked route (route_read), and a "not tried yet" list of at
  // most kUntriedRoutesPerGym rows (list_per_row) per gym listed (the gyms
  // ticked and, signed in, the viewer's gyms). 0 without a climber. Errors:
  // the store's; Validate()'s.
  Result<double> LogbookCost(const Viewer& v, std::string_view participant_token);
  // Every tick of a route for its setters (GET /api/routes/{id}/ticks and
  // the held ticks on /r/{id}): each tick (row_per_read) and each held
  // tick's reason worked out again (held_reason, at most kMaxHeldReasons).
  // 0 when `v` is not a setter or head setter of the route's gym nor its
  // owner, or does not see it (the service refuses before reading).
  // `*gym`, when given, is set to the route's gym when it is seen.
  Result<double> RouteTicksCost(const Viewer& v, int64_t route_id,
                                std::optional<int64_t>* gym = nullptr);
  // A route's ascent grade (GET /api/routes/{id}/ascent, the ascent section
  // of /r/{id} and of the route and plan pages): the fit of the route's gym
  // and discipline when this reader would be the one to make it
  // (fit_per_tick per tick of the gym; 0 when the kept fit is current,
  // refitted in the background or by another reader's flight), bounded by
  // what is left of the reader's per-request cap (a big gym's first fit
  // after a start must still be made once: docs/web.md); signed in, their
  // own ticks read for the chances (row_per_read each); with `with_held`,
  // RouteTicksCost. Routes the viewer does not see, or outside a gym, cost
  // 0 (the service answers 404 or nothing). `*gym`, when given, is set to
  // the route's gym (the member share of the work). Errors: the store's.
  Result<double> AscentCost(const Viewer& v, int64_t route_id, bool with_held,
                            std::optional<int64_t>* gym = nullptr);
  // Issue 34, the reads costed since (docs/web.md, "Work budgets"); each is
  // one indexed COUNT (store/count_store.h) before the reading, and 0 when
  // the service would refuse before reading.
  //
  // A gym's history (GET /api/gyms/{gym}/history, the history list of
  // /gyms/{gym} for its setters): each row read with its author's name and
  // listed (row_per_read + list_per_row). 0 unless `v` sets in `gym`.
  Result<double> GymHistoryCost(const Viewer& v, int64_t gym);
  // A route's history (GET /api/routes/{id}/history; the "on the wall"
  // block of /routes/{id} and /variations/{id} for the gym's members,
  // `members_only`): as a gym's history row. 0 when `v` does not see the
  // route (or, with `members_only`, is not a member of its gym). `*gym`,
  // when given, is set to the route's gym when it is seen (here and below).
  Result<double> RouteHistoryCost(const Viewer& v, int64_t route_id, bool members_only,
                                  std::optional<int64_t>* gym = nullptr);
  // A route's feedback consensus (the consensus block of /routes/{id},
  // /variations/{id} and /r/{id}): each feedback row read and summarised
  // (row_per_read). 0 when `v` does not see the route.
  Result<double> ConsensusCost(const Viewer& v, int64_t route_id,
                               std::optional<int64_t>* gym = nullptr);
  // The blocks under a route's and a variation's page (/routes/{id},
  // /variations/{id}): RouteHistoryCost(members_only) + ConsensusCost, with
  // the route read once.
  Result<double> RouteBlocksCost(const Viewer& v, int64_t route_id);
  // The climbers' answers for the route's owner (GET /r/{id}/responses):
  // each feedback row read, tabulated, analysed and summarised
  // (answer_per_row, measured). 0 unless `v` owns the route.
  Result<double> FeedbackAnswersCost(const Viewer& v, int64_t route_id,
                                     std::optional<int64_t>* gym = nullptr);
  // A setter's drift (GET /drift): every route they own read whole in one
  // list (route_listed) and each feedback row on them summarised
  // (row_per_read).
  // 0 signed out.
  Result<double> DriftCost(const Viewer& v);
  // The gym's lists (issue 34): GET /api/gyms/{gym}/members, /walls,
  // /circuits and /scales, and the walls, circuits and members of
  // /gyms/{gym}: each row read and listed (list_per_row). 0 unless `v` is a
  // member of `gym` (the services answer others 404 before reading).
  // Errors: the store's.
  enum class GymList { kMembers, kWalls, kCircuits, kScales };
  Result<double> GymListCost(const Viewer& v, int64_t gym, GymList list);
  // A study's answers read for its results, CSVs, analysis, box plot and
  // held list: responses x routes answer rows (study_per_answer each).
  // Pure.
  double StudyCost(const Study& s) const;

  const RenderCosts& costs() const { return costs_; }

 private:
  // The route when `v` sees it (on the wall) and, with `in_gym`, it is in a
  // gym; nullopt otherwise.
  Result<std::optional<store::RouteRecord>> Seen(const Viewer& v, int64_t route_id,
                                                 bool in_gym = true);
  store::Store* store_;
  store::TickStore* ticks_;
  store::CountStore* counts_;
  app::Logbook* logbook_;
  const RenderCosts costs_;
  const BudgetPolicy budget_;
};

}  // namespace sb::app

#endif  // SB_APP_READ_COSTS_H_
