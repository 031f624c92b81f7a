// The climbers' logbook (issue 23; docs/web.md, "Logbook"): ticks of a
// gym's routes from a phone at /r/{id} (device cookie) or a signed-in
// climber, their budgets and burst rule, the setters' review of held ticks,
// a climber's logbook, and a route's ascent grade (grades/ratings.h fitted
// on the gym's unheld ticks with the setter's grade as prior).
#ifndef SB_APP_LOGBOOK_H_
#define SB_APP_LOGBOOK_H_

#include <cstdint>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "app/burst.h"
#include "app/clock.h"
#include "app/options.h"
#include "app/participants.h"
#include "app/types.h"
#include "base/status.h"
#include "store/store.h"
#include "store/visibility.h"
#include "store/tick_store.h"

namespace sb::app {

namespace logbook_internal {
struct FitState;  // logbook.cc
}  // namespace logbook_internal

// The logbook's limits, each with its reason.
struct LogbookPolicy {
  // The window of the budgets below.
  int window_seconds = 3600;
  // Ticks (new or edited) per address per window: a gym's wifi puts every
  // climber behind one address, so this is generous; it bounds what one
  // machine stuffs by clearing its cookie.
  int ticks_per_address = 600;
  // Ticks per route per window: a busy route gets a few dozen climbers an
  // hour; hundreds is a script.
  int ticks_per_route = 200;
  // Ticks per climber (device or account) per window: a hard session logs
  // some 30 routes and edits a few.
  int ticks_per_climber = 60;
  // The burst rule (app/burst.h, shared with study responses): a tick from a
  // new identity (a device whose first tick is within burst_window_seconds)
  // on a route is held for the route's setters when `burst_new_identities`
  // new identities already ticked that route from the same address within
  // the window.
  int burst_window_seconds = BurstRule{}.window_seconds;
  int burst_new_identities = BurstRule{}.new_identities;
  // Fitted gyms kept in the ascent-grade cache (one entry per gym and
  // discipline; each entry is refitted when the gym's ticks change). A
  // chain of 20 gyms with bouldering and roped walls needs 40 (issue 22: at
  // 16, wall pages of the chain refitted a gym on most requests, 15-40 s
  // each); an entry holds one grade per ticked route (~10,500 at chain scale).
  int fit_cache_entries = 48;
  // The single-route update (docs/grades.md, "A new tick"): a tick logged
  // while its (gym, discipline) fit is cached updates that route's grade in
  // place (grades::RateRoute, the climbers held at the fit's abilities)
  // instead of refitting the gym (1.7 s at chain size, issue 23). Held
  // climbers drift from what a refit would give as ticks accumulate, so the
  // entry is refitted in full (lazily: by the next request that reads it)
  // once it has absorbed more than max(fit_incremental_min_ticks,
  // fit_incremental_percent % of the ticks it was fitted on) ticks. 2% of a
  // chain gym is ~5,000 ticks, one refit per ~5,000 ticks instead of one per
  // tick; the error against a refit at that point is in docs/grades.md.
  int fit_incremental_percent = 2;
  // The floor of that budget for small gyms (a refit of a small gym takes
  // milliseconds; its drift per tick is larger, so few ticks are absorbed).
  int fit_incremental_min_ticks = 20;

  // Every field > 0; errors name the field. Pure.
  Status Validate() const;
};

// What a climber logs about one route.
struct TickInput {
  std::string outcome;           // "flash", "send" or "attempt"
  std::optional<int> attempts;   // tries (send: including the send)
  std::optional<int> stars;      // 1..5
  std::string felt_grade;        // any scale grades reads; "" = none
  std::string comment;           // "" = none
};

// The outcome of logging a tick.
struct TickSaved {
  Participant participant;  // device climbers: is_new means set the cookie
  Tick tick;
  bool edited = false;  // the climber's tick of that route and day was replaced
  bool held = false;    // held for the route's setters (burst rule)
};

// A route's grade from ascents.
struct AscentGrade {
  int ticks = 0;         // unheld ticks of the route
  bool fitted = false;   // false: no ticks (nothing below is set)
  std::string discipline;
  double value = 0, lo = 0, hi = 0;  // on the axis, 80% interval
  std::string grade, lo_grade, hi_grade;  // in the route's scale
  // "soft" (the interval lies below the setter's band), "sandbagged" (above)
  // or "" (it overlaps the band, or the route has no setter's grade).
  std::string verdict;
  // The felt-grade consensus of the unheld ticks: median and count.
  int felt_votes = 0;
  std::string felt_median;
};

// One route of the logbook's "not tried yet" list.
struct UntriedRoute {
  int64_t id = 0;
  std::string name, grade, colour;
};

// A climber's logbook.
struct LogbookView {
  std::string climber;  // "u:ID" or "d:HASH" ("" = nobody yet: no cookie)
  std::vector<Tick> ticks;                     // newest day first
  std::map<int64_t, std::string> route_names;  // of the ticked routes
  // Sends (flash or send) by band of the route's setter grade: (band name,
  // count), hardest first; routes without a grade under "?".
  std::vector<std::pair<std::string, int>> pyramid;
  // The gym's routes on the wall (state "set") not ticked yet, by wall
  // (wall name, routes); routes without a wall under "".
  std::vector<std::pair<std::string, std::vector<UntriedRoute>>> untried;
};

// Thread-safe. Does not own `store` or `clock`.
class Logbook {
 public:
  Logbook(store::Store* store, Clock* clock, LogbookPolicy policy = {});

  // Logs (or edits: one per climber, route and day) a tick on a route
  // visible to `v` that belongs to a gym. The climber is the account when
  // signed in, else the device of `participant_token` (a new one when it
  // names none). Errors: kNotFound "no route N"; kInvalidInput naming the
  // field (outcome, attempts, stars, felt grade, comment, route not in a
  // gym); kResourceExhausted over a budget ("too many ticks from this
  // address ...", *retry_after_seconds set); kInternal when the
  // store has no TickStore.
  Result<TickSaved> Log(const Viewer& v, int64_t route_id, std::string_view participant_token,
                        const TickInput& input, int* retry_after_seconds = nullptr);

  // The ascent grade of a visible route (kNotFound as Log).
  Result<AscentGrade> Ascent(const Viewer& v, int64_t route_id);
  // The ascent grades of many routes of one gym at once (the dashboard's
  // rows, issue 22/23), from the same cached fits as Ascent: route id ->
  // grade, every id present (fitted = false without unheld ticks; routes of
  // other gyms too). The caller has checked the viewer sees `route_ids`.
  Result<std::map<int64_t, AscentGrade>> Ascents(int64_t gym_id,
                                                 const std::vector<int64_t>& route_ids);
  // The ascent grades of routes `v` already read through a listing (a wall
  // page's rows), by route id: one version check and one cached fit per
  // (gym, discipline) for the whole list, not per route (issue 22: a wall
  // page of 200 routes read the gym's tick version 200 times). Routes
  // outside a gym get the empty grade. Visibility is the listing's: routes
  // are not read again.
  Result<std::map<int64_t, AscentGrade>> Ascents(const Viewer& v,
                                                 const std::vector<RouteView>& routes);

  // Setters of the route's gym (head, setter) and the route's owner only:
  // every tick of the route (kPermission otherwise, kUnauthenticated when
  // not signed in).
  Result<std::vector<Tick>> ForSetters(const Viewer& v, int64_t route_id);
  // Setters: accepts (state "ok") or discards a tick of the route.
  // kNotFound for a tick of another route.
  Status Decide(const Viewer& v, int64_t route_id, int64_t tick_id, bool accept);

  // The logbook of the signed-in climber, or of the device cookie.
  Result<LogbookView> Mine(const Viewer& v, std::string_view participant_token);

  // How many full fits (FitGym refits of a gym and discipline) this logbook
  // has run: for tests and benchmarks of the single-route update.
  // Thread-safe.
  uint64_t FullFits();

  // After sign-in: moves the device's ticks into the climber's logbook.
  // Returns how many moved (0 without a usable cookie). kUnauthenticated
  // when not signed in.
  Result<int> MergeDevice(const Viewer& v, std::string_view participant_token);

 private:
  struct Fit {
    std::map<int64_t, AscentGrade> routes;
  };
  // A cached fit: shared, so a cache hit copies no map (a single-route update
  // replaces the pointer with an updated copy), the gym's tick version it is
  // current for, and when it was last used.
  struct CachedFit {
    store::TickVersion version;
    std::shared_ptr<const Fit> fit;
    // What the single-route update keeps of the full fit (logbook.cc); read
    // and changed only under mu_. Null: this entry is refitted when its
    // version is stale, not updated.
    std::shared_ptr<logbook_internal::FitState> state;
    uint64_t used = 0;
  };
  // The route when the viewer sees it (`reach` kOnTheWall: the climbers'
  // page /r/{id}, where a route on the wall is shown to anyone).
  Result<store::RouteRecord> Visible(const Viewer& v, int64_t route_id,
                                     store::Reach reach = store::Reach::kListed);
  Status RequireSetter(const Viewer& v, const store::RouteRecord& route);
  Result<std::shared_ptr<const Fit>> FitGym(int64_t gym_id, const std::string& discipline);
  // Replaces each grade of `grades` (route id -> grade) whose route the
  // gym's cached `discipline` fit has; the others stay as they are.
  Status FillAscents(int64_t gym_id, const std::string& discipline,
                     std::map<int64_t, AscentGrade>* grades);
  // Whether a fit of the gym (either discipline) is cached.
  bool HasCachedFit(int64_t gym_id);
  // After Log stored `saved` (replacing `old` when set) on `route`, with the
  // gym's tick version `before` and `after` the write: updates the cached
  // fits of the route's gym in place when nothing else changed meanwhile
  // (docs/grades.md, "A new tick"); otherwise leaves them to be refitted.
  void AbsorbTick(const store::RouteRecord& route, const store::TickRecord& saved,
                  const std::optional<store::TickRecord>& old,
                  const store::TickVersion& before, const store::TickVersion& after);

  store::Store* store_;
  store::TickStore* ticks_;
  Clock* clock_;
  const LogbookPolicy policy_;
  std::mutex mu_;
  std::map<std::pair<int64_t, std::string>, CachedFit> cache_;  // (gym, discipline)
  uint64_t uses_ = 0;
  uint64_t full_fits_ = 0;
};

// The climber key of a viewer or device: "u:ID", else "d:HASH" of a valid
// token, else nullopt. Pure.
std::optional<std::string> ClimberKey(const Viewer& v, std::string_view participant_token);

}  // namespace sb::app

#endif  // SB_APP_LOGBOOK_H_
