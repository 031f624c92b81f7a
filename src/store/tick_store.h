// The climbers' logbook (schema 7, issue 23): ticks of routes. A separate
// interface from store::Store over the same SQL layer (store/sql_store.cc
// implements it in the same object as Store and GymStore). The table is
// documented in docs/web.md ("Logbook").
//
// No SQLite or libpq types appear in this header.
#ifndef SB_STORE_TICK_STORE_H_
#define SB_STORE_TICK_STORE_H_

#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "base/status.h"
#include "gym/records.h"
#include "store/store.h"

namespace sb::store {

// One tick of the logbook: one struct, shared with the application layer
// (gym/records.h).
using TickRecord = gym::Tick;

// A gym's data versions (table gym_versions, schema 13; one row read):
// cache keys. `ticks` moves on every write of the gym's ticks (the fits over
// them); `data` on every write that changes what the gym's dashboard or wall
// pages show (routes, walls, circuits, members, targets, feedback, setters,
// ticks). Both only grow; 0 for a gym without a row (no such gym).
struct TickVersion {
  int64_t ticks = 0;
  int64_t data = 0;
  bool operator==(const TickVersion&) const = default;
};

// What a page that reads a climber's or a route's ticks will read, counted
// before the reading (issue 34: costs from counts; app/read_costs.h).
struct TickCounts {
  int64_t ticks = 0;   // rows the read returns (see each method)
  int64_t routes = 0;  // distinct routes among them
  int64_t gyms = 0;    // distinct gyms among them
  int64_t held = 0;    // of them, in state "held"
};

// Thread-safe like Store. Errors: kNotFound for unknown ids, kIoError for
// storage failures.
class TickStore {
 public:
  virtual ~TickStore() = default;

  // Inserts the tick, or, when the climber already has one on that route and
  // day, replaces its outcome, attempts, stars, felt grade, comment, state
  // and updated_at (keeping id and created_at). Returns the stored row.
  // kNotFound for an unknown route or gym.
  virtual Result<TickRecord> PutTick(const TickRecord& tick) = 0;
  // A tick by id; kNotFound when absent.
  virtual Result<TickRecord> GetTick(int64_t id) = 0;
  // A route's ticks (every state), by day then id.
  virtual Result<std::vector<TickRecord>> RouteTicks(int64_t route_id) = 0;
  // A gym's ticks in state "ok", by id.
  virtual Result<std::vector<TickRecord>> GymTicks(int64_t gym_id) = 0;
  // A climber's ticks (every state but "discarded"), newest day first, then id.
  virtual Result<std::vector<TickRecord>> ClimberTicks(const std::string& climber) = 0;
  // Counts of what ClimberTicks(climber) returns (every state but
  // "discarded"): one indexed COUNT query, no rows read.
  virtual Result<TickCounts> CountClimberTicks(const std::string& climber) = 0;
  // Counts of what RouteTicks(route_id) returns (every state; routes and
  // gyms are 1 when it has any): one indexed COUNT query.
  virtual Result<TickCounts> CountRouteTicks(int64_t route_id) = 0;
  // The gym's data versions (one row; see TickVersion).
  virtual Result<TickVersion> GymTickVersion(int64_t gym_id) = 0;
  // Sets a tick's state (and updated_at); kNotFound when absent.
  virtual Status SetTickState(int64_t id, const std::string& state,
                              const std::string& updated_at) = 0;
  // Moves every tick of `from` to `to` (user `user_id`), in one transaction;
  // where `to` already has a tick on the same route and day, the one updated
  // last is kept. Returns how many ticks moved.
  virtual Result<int> MergeTicks(const std::string& from, const std::string& to,
                                 int64_t user_id) = 0;
  // How many distinct device climbers ticked `route_id` from `origin` at or
  // after `since`, counting only climbers whose first tick anywhere is at or
  // after `since` (new identities). Times are "YYYY-MM-DD HH:MM:SS".
  virtual Result<int> NewIdentitiesSince(int64_t route_id, const std::string& origin,
                                         const std::string& since) = 0;

  // Issue 34, the fit's reads (app/logbook.cc): a gym's ticks in state "ok"
  // on its routes of `discipline` ("bouldering" includes routes without a
  // grade discipline), by id, with only the fields a fit counts set (id,
  // route_id, gym_id, climber, day, outcome, attempts, felt_discipline,
  // felt_value, state, created_at, revision; the rest default).
  virtual Result<std::vector<TickRecord>> GymDisciplineTicks(int64_t gym_id,
                                                             const std::string& discipline) = 0;
  // The same ticks in the same order, handed to `page` one page at a time
  // (the page GymTicks reads, store/tick_page.h) instead of held as one
  // vector (issue 34, memory: the fit keeps ~48 bytes of each, not a record
  // and its strings). `page` may move from the records; it must not call
  // this store (a connection is held while it runs). A non-OK status from
  // `page` stops the read and is returned.
  virtual Status EachGymDisciplineTicksPage(
      int64_t gym_id, const std::string& discipline,
      const std::function<Status(std::vector<TickRecord>& page)>& page) = 0;
  // Per climber of the gym (any discipline): how many distinct routes it
  // has ticks in state "ok" on created at or before `created_until`
  // ("YYYY-MM-DD HH:MM:SS"); climbers with none are absent. One grouped
  // query (a row per climber, not per tick).
  virtual Result<std::map<std::string, int64_t>> AgedRouteCounts(
      int64_t gym_id, const std::string& created_until) = 0;
};

// The TickStore of a store opened by store::OpenStore (both backends);
// nullptr for a Store that does not implement it. Not owned.
TickStore* TickStoreOf(Store* store);

}  // namespace sb::store

#endif  // SB_STORE_TICK_STORE_H_
