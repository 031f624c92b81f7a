// The climbers' logbook (issue 23; docs/web.md, "Logbook"): ticks of a
// gym's routes from a phone at /r/{id} (device cookie) or a signed-in
// climber, their budgets and burst rule, the setters' review of held ticks,
// a climber's logbook, and a route's ascent grade (grades/ratings.h fitted
// on the gym's unheld ticks with the setter's grade as prior).
#ifndef SB_APP_LOGBOOK_H_
#define SB_APP_LOGBOOK_H_

#include <condition_variable>
#include <cstdint>
#include <deque>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <string_view>
#include <thread>
#include <utility>
#include <vector>

#include "app/burst.h"
#include "app/clock.h"
#include "app/options.h"
#include "app/participants.h"
#include "app/types.h"
#include "base/status.h"
#include "grades/ratings.h"
#include "store/store.h"
#include "store/visibility.h"
#include "store/tick_store.h"

namespace sb::app {

namespace logbook_internal {
struct FitState;  // logbook.cc
}  // namespace logbook_internal

// Routes a logbook's "not tried yet" list reads per gym (Logbook::Mine):
// a gym holds a few hundred routes on its walls; the list is cut here.
inline constexpr int kUntriedRoutesPerGym = 2000;
// Held ticks whose reason is worked out again per request
// (Logbook::ForSetters); the others are listed "reason not worked out".
inline constexpr int kMaxHeldReasons = 100;

// The logbook's limits, each with its reason.
struct LogbookPolicy {
  // The window of the budgets below.
  int window_seconds = 3600;
  // Ticks (new or edited) per address per window: a gym's wifi puts every
  // climber behind one address, so this is generous; it bounds what one
  // machine stuffs by clearing its cookie.
  int ticks_per_address = 600;
  // Ticks per route per address per window (issue 34: per address, not
  // shared, so one address exhausts only its own): a busy route gets a few
  // dozen climbers an hour, all behind the gym's wifi at worst; hundreds from
  // one address is a script.
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
  // Issue 34 (memory): the cache's entries are also charged by their size
  // (the grades and the single-route update's state, Logbook's estimate),
  // and the least recently used go (throw-away gyms' first) while they hold
  // more than this.
  int64_t fit_cache_bytes = int64_t{256} << 20;
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
  // Refits (issue 34): a stale entry of a gym fitted on at least this many
  // ticks is refitted in the background (one refit per gym and discipline at
  // a time), readers meanwhile get the last good fit with its age; a smaller
  // gym's refit (milliseconds) is done by the reader, still one at a time.
  int fit_background_min_ticks = 5000;
  // An anonymous request fits no gym without members, and a gym with fewer
  // than this many tick writes only without caching it (a throw-away gym
  // cannot make anonymous readers fill the cache); signed-in readers always
  // get a cached fit.
  int fit_anonymous_min_ticks = 5;
  // Cache entries of gyms with members fitted on at least this many ticks are
  // kept over others when the cache is full (least recently used first within
  // each class), so readers of throw-away gyms cannot flush a real gym's fit.
  int fit_keep_min_ticks = 50;
  // Earned influence (issue 34; docs/grades.md, "Ticks no one can push"): an
  // identity (account or device) is established at a gym for a route when it
  // has counted ("ok") ticks on at least `history_routes` other routes of the
  // gym, each at least `history_age_seconds` old. The ticks of identities
  // that are not ("new") count in the fit as one pooled climber per route,
  // each tick as one game (a send a win, an attempt a loss), with no felt
  // grade: many new identities weigh about as much as one climber's tick.
  int history_routes = 3;
  int history_age_seconds = 86400;
  // The rush rule: a new identity's tick on a route is held for its setters
  // when `rush_new_identities` other new identities (from any address)
  // already ticked it within `rush_window_seconds`. Ageing devices on other
  // routes does not help within history_age_seconds.
  int rush_new_identities = 5;
  int rush_window_seconds = 86400;

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
  // Seconds since the gym's ticks moved past the fit shown (0: current);
  // set while a background refit is under way (issue 34).
  int64_t age_seconds = 0;
  // Issue 32: the gym scale the grades above are written in ("" = the
  // route's own built-in scale): a route on a wall with a gym scale gets
  // that scale's labels (and its verdict against its label's range).
  std::string scale;
  // What the labels are made from (kept by the fit): the route's wall (0:
  // none), its setter's value on the axis and the felt median's value.
  int64_t wall_id = 0;
  std::optional<double> setter_value;
  double felt_median_value = 0;
};

// What predictions (issue 35, app/chances.h) read from a gym's cached fit of
// one discipline: the model's settings and the asked-for abilities and
// difficulties, copied out so the prediction runs without the cache's lock.
struct FitSnapshot {
  bool fitted = false;  // false: nothing fitted (no counted ticks); the rest unset
  grades::RatingParams params;
  grades::RatingModel model = grades::RatingModel::kTries;
  double prior_mean = 0, session_offset = 0, session_tries = 0;
  // Climbers of the query that the fit has (pooled new identities never).
  std::map<std::string, double> ability;
  // Routes of the query that the fit has: (difficulty, sd) on the axis.
  std::map<int64_t, std::pair<double, double>> difficulty;
  int64_t age_seconds = 0;  // as AscentGrade::age_seconds
};

// What a FitSnapshot copies out.
struct SnapshotQuery {
  std::vector<std::string> climbers;  // climber keys ("u:ID", "d:HASH")
  std::vector<int64_t> routes;
  // When set ("YYYY-MM-DD"): also the fit's climbers (no pooled identity)
  // whose last counted tick is on or after this day, most recent first, at
  // most max_active of them.
  std::string active_since;
  size_t max_active = 0;
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
  // count), hardest first; routes without a grade under "?"; a route on a
  // wall with a gym scale under its label (issue 32).
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
  // Issue 34, a tick's answer: as Ascent, but never fits on the caller's
  // thread nor waits for a fit: the kept fit of the route's gym and
  // discipline, a stale one with its age (its refit queued in the
  // background), or, when none is kept, the unfitted grade (fitted = false)
  // with the first fit queued in the background (one per gym and discipline
  // at a time, as every refit).
  Result<AscentGrade> KeptAscent(const Viewer& v, int64_t route_id);
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

  // Issue 35: the cached fit of (gym, discipline) as FitGym keeps it (a
  // signed-in reader's: fitted when missing or stale, as Ascent does),
  // copied for `q`. Never refits when a cached fit is current. Errors: the
  // store's, kInvalidInput for an unknown discipline.
  Result<FitSnapshot> Snapshot(int64_t gym_id, const std::string& discipline,
                               const SnapshotQuery& q);

  // Setters of the route's gym (head, setter) and the route's owner only:
  // every tick of the route (kPermission otherwise, kUnauthenticated when
  // not signed in). With `held_reasons`, why each held tick was held (tick
  // id -> a sentence naming the rule), worked out again from the ticks.
  Result<std::vector<Tick>> ForSetters(const Viewer& v, int64_t route_id,
                                       std::map<int64_t, std::string>* held_reasons = nullptr);
  // Setters: accepts (state "ok") or discards a tick of the route.
  // kNotFound for a tick of another route.
  Status Decide(const Viewer& v, int64_t route_id, int64_t tick_id, bool accept);

  // The logbook of the signed-in climber, or of the device cookie.
  Result<LogbookView> Mine(const Viewer& v, std::string_view participant_token);

  // Issue 34, costs before the work (app/read_costs.h): how many ticks a
  // reader of `route`'s ascent grade (anonymous or not) would fit itself:
  // 0 when the kept fit of its gym and discipline is current, is refitted in
  // the background or by a flight under way (the reader waits, reads
  // nothing), or the route is in no gym; else the gym's tick writes (an
  // upper bound of its ticks; one row read). Changes nothing. Errors: the
  // store's.
  Result<int64_t> ReaderFitTicks(const store::RouteRecord& route);

  // How many full fits (FitGym refits of a gym and discipline) this logbook
  // has run: for tests and benchmarks of the single-route update.
  // Thread-safe.
  uint64_t FullFits();
  // How many tick rows the full fits have read from the store (tests of
  // issue 34: a discipline's refit reads only its ticks). Thread-safe.
  uint64_t TicksRead();
  // Blocks until no refit is queued or under way (tests, benchmarks).
  // Thread-safe.
  void WaitForRefits();
  // How many fits are cached (tests). Thread-safe.
  size_t CachedFits();
  // The bytes the cached fits are charged (LogbookPolicy::fit_cache_bytes).
  // Thread-safe.
  int64_t CachedFitBytes();
  // Issue 34 (memory): a big gym's full fit (fit_background_min_ticks tick
  // writes or more) holds its ticks and problem for seconds, so at most one
  // runs at a time in the process, whichever logbook and thread runs it.
  // The most that ever ran at once in this process (tests). Thread-safe.
  static int MostBigFitsAtOnce();

  ~Logbook();
  Logbook(const Logbook&) = delete;
  Logbook& operator=(const Logbook&) = delete;

  // After sign-in: moves the device's ticks into the climber's logbook.
  // Returns how many moved (0 without a usable cookie). kUnauthenticated
  // when not signed in.
  Result<int> MergeDevice(const Viewer& v, std::string_view participant_token);

 private:
  // A fit's grades: those of the last full fit, shared by every copy, and
  // the routes updated since (issue 34: a tick's update copies only these,
  // not the gym's thousands of grades, while readers hold the old copy;
  // past kMaxChanged they are folded into a new shared base).
  struct Fit {
    static constexpr size_t kMaxChanged = 64;
    std::shared_ptr<const std::map<int64_t, AscentGrade>> base =
        std::make_shared<const std::map<int64_t, AscentGrade>>();
    std::map<int64_t, std::optional<AscentGrade>> changed;  // nullopt: no grade now
    // The grade of route `id`, or null.
    const AscentGrade* Find(int64_t id) const;
    // Sets (or, with nullopt, removes) the grade of route `id`.
    void Put(int64_t id, std::optional<AscentGrade> grade);
  };
  using Key = std::pair<int64_t, std::string>;  // (gym, discipline)
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
    int64_t fitted_ticks = 0;  // ticks the full fit counted
    bool kept = false;         // a gym with members and fit_keep_min_ticks
    int64_t stale_since = 0;   // clock time a reader first saw it stale; 0 = not
    int64_t bytes = 0;         // charged against fit_cache_bytes (its full fit's size)
  };
  // A tick written while a refit of its gym was under way: replayed into the
  // refit's state before the refit is published (so it is current at once).
  struct Replay {
    store::RouteRecord route;
    store::TickRecord saved;
    std::optional<store::TickRecord> old;
    store::TickVersion after;
    bool young = false;  // counted as a new identity's (pooled, one game)
  };
  // One refit of a key (single flight): readers that must wait wait on it.
  struct Flight {
    bool recording = false;  // ticks written from now on go to `replay`
    bool done = false;
    Status status = Status::Ok();
    std::vector<Replay> replay;
    bool keep = true;                     // false: not cached, the fit left in `result`
    std::shared_ptr<const Fit> result;  // the fit when !keep
  };
  // What a reader gets: the fit and its age.
  struct FitRead {
    std::shared_ptr<const Fit> fit;
    int64_t age_seconds = 0;
  };
  // The route when the viewer sees it (`reach` kOnTheWall: the climbers'
  // page /r/{id}, where a route on the wall is shown to anyone).
  Result<store::RouteRecord> Visible(const Viewer& v, int64_t route_id,
                                     store::Reach reach = store::Reach::kListed);
  Status RequireSetter(const Viewer& v, const store::RouteRecord& route);
  // The cached fit of the key, refitted as the policy says (inline, single
  // flight, or in the background with the stale one returned). With
  // `anonymous` a gym without members gets an empty fit and is not fitted,
  // and one with fewer than fit_anonymous_min_ticks tick writes is fitted
  // (microseconds) but not cached, so it evicts nothing.
  // Without `wait` (a tick's answer, issue 34) nothing is fitted on the
  // caller's thread: a kept entry is returned as it is (stale with its age,
  // its refit queued), and a missing one is queued for the background and
  // an empty fit returned.
  Result<FitRead> FitGym(int64_t gym_id, const std::string& discipline, bool anonymous,
                         bool wait = true);
  // Ascent (wait) and KeptAscent (!wait).
  Result<AscentGrade> AscentOf(const Viewer& v, int64_t route_id, bool wait);
  // Runs the flight of `key`: reads the ticks under the gym's tick lock, fits
  // off it, replays the ticks written meanwhile and publishes. Marks the
  // flight done (waking waiters).
  void RunFlight(const Key& key, const std::shared_ptr<Flight>& flight);
  Status DoFlight(const Key& key, Flight* flight);
  // Queues a background refit of `key` unless one is under way. Under mu_.
  void ScheduleLocked(const Key& key);
  void Worker();
  // The mutex serialising tick writes of a gym (and the refits' reads).
  std::mutex& TickLock(int64_t gym_id);
  // Replaces each grade of `grades` (route id -> grade) whose route the
  // gym's cached `discipline` fit has; the others stay as they are.
  Status FillAscents(int64_t gym_id, const std::string& discipline, bool anonymous,
                     std::map<int64_t, AscentGrade>* grades);
  // After a tick write under the gym's tick lock (`saved`, replacing `old`
  // when set, on `route`; the gym's tick version `before` and `after` it):
  // updates the cached fits of the route's gym in place when they were
  // current before it (docs/grades.md, "A new tick"), and records it for a
  // refit under way. Caller holds TickLock(gym), not mu_.
  void AbsorbTick(const store::RouteRecord& route, const store::TickRecord& saved,
                  const std::optional<store::TickRecord>& old,
                  const store::TickVersion& before, const store::TickVersion& after, bool young);
  // The tick write of Log and Decide under the gym's tick lock: `write`
  // stores it; the fit is updated after (`young`: the climber is new at the
  // gym for this route).
  Result<store::TickRecord> WriteTick(const store::RouteRecord& route,
                                      const std::optional<store::TickRecord>& old, bool young,
                                      const std::function<Result<store::TickRecord>()>& write);
  // Whether `climber_ticks` (one identity's) make it established at `gym`
  // for `route` at unix time `at` (see LogbookPolicy::history_routes).
  bool Established(const std::vector<store::TickRecord>& climber_ticks, int64_t gym,
                   int64_t route, int64_t at) const;
  // How many other new identities ticked `route` in the rush window ending
  // at `at` (only ticks of id below `before_id` when set; stops counting at
  // rush_new_identities).
  Result<int> NewIdentitiesOnRoute(int64_t route, int64_t gym, const std::string& except,
                                   int64_t at, std::optional<int64_t> before_id = std::nullopt);

  store::Store* store_;
  store::TickStore* ticks_;
  Clock* clock_;
  const LogbookPolicy policy_;
  std::mutex mu_;
  std::condition_variable flight_cv_;  // a flight finished
  std::condition_variable work_cv_;    // a refit was queued (or stopping_)
  std::map<Key, CachedFit> cache_;
  std::map<Key, std::shared_ptr<Flight>> flights_;  // refits under way or queued
  std::deque<Key> queue_;                           // background refits to run
  bool stopping_ = false;
  std::thread worker_;  // started with the first background refit
  uint64_t uses_ = 0;
  uint64_t full_fits_ = 0;
  uint64_t ticks_read_ = 0;  // tick rows the full fits read
  std::mutex locks_mu_;
  std::map<int64_t, std::unique_ptr<std::mutex>> tick_locks_;  // per gym
};

// The climber key of a viewer or device: "u:ID", else "d:HASH" of a valid
// token, else nullopt. Pure.
std::optional<std::string> ClimberKey(const Viewer& v, std::string_view participant_token);

}  // namespace sb::app

#endif  // SB_APP_LOGBOOK_H_
