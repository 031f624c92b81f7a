// The head setter's targets per wall (schema 8, issue 22): how many routes
// of each grade band a wall should carry, and what share of its moves each
// style should have. A separate interface from store::Store over the same SQL
// layer (store/sql_store.cc implements it in the same object as Store); the
// table is documented in docs/setting.md ("The dashboard"). The application
// layer (app/dashboard.h) validates targets; the store keeps what it gets.
//
// No SQLite or libpq types appear in this header.
#ifndef SB_STORE_TARGET_STORE_H_
#define SB_STORE_TARGET_STORE_H_

#include <cstdint>
#include <string>
#include <vector>

#include "base/status.h"
#include "store/store.h"

namespace sb::store {

// One target of a wall. kind "grade": `name` is a band as the gym writes it
// ("V3", "5.10", "6B+") and `value` a route count; kind "style": `name` a
// style name (language/styles.h) and `value` a share of moves in 0..1.
struct TargetRecord {
  int64_t wall_id = 0;
  std::string kind;  // "grade" or "style"
  std::string name;
  double value = 0;
  bool operator==(const TargetRecord&) const = default;
};

// One target of a gym per discipline (schema 12, issue 22: "a target count
// per grade band per wall or discipline"): as TargetRecord, for every wall of
// `discipline` ("bouldering" or "roped") of the gym together.
struct DisciplineTargetRecord {
  int64_t gym_id = 0;
  std::string discipline;
  std::string kind;  // "grade" or "style"
  std::string name;
  double value = 0;
  bool operator==(const DisciplineTargetRecord&) const = default;
};

// The climbers' ticks of one route summed (the dashboard's "ticks" and
// "stars"): unheld ticks (state "ok"), how many gave stars, their sum.
struct RouteTickSum {
  int64_t route_id = 0;
  int64_t ticks = 0;
  int64_t star_votes = 0;
  int64_t star_sum = 0;
};

// Ids per query of TargetStore::RouteTickSums: well under SQLite's limit of
// bound parameters (32,766) and PostgreSQL's (65,535), and a short statement.
inline constexpr size_t kTickSumIdsPerQuery = 500;

// Thread-safe like Store. Errors: kNotFound for unknown walls, kIoError for
// storage failures.
class TargetStore {
 public:
  virtual ~TargetStore() = default;

  // Replaces every target of `wall_id` by `targets` (their wall_id is
  // ignored) in one transaction. kNotFound for an unknown wall;
  // kInvalidInput for a kind other than "grade"/"style" or a name twice.
  // Issue 31: moves the wall's targets_revision by one in the same
  // transaction; with `revision` > 0, kConflict unless that is the stored one.
  virtual Status SetWallTargets(int64_t wall_id, const std::vector<TargetRecord>& targets,
                                int64_t revision = 0) = 0;
  // A wall's targets by kind then name (none for an unknown wall).
  virtual Result<std::vector<TargetRecord>> WallTargets(int64_t wall_id) = 0;
  // The targets of every wall of `gym_id`, by wall id, kind, name.
  virtual Result<std::vector<TargetRecord>> GymTargets(int64_t gym_id) = 0;
  // Replaces every target of `gym_id` for `discipline` by `targets` (their
  // gym_id and discipline are ignored) in one transaction. kNotFound for an
  // unknown gym; kInvalidInput for a discipline other than
  // "bouldering"/"roped", a kind other than "grade"/"style" or a name twice.
  // Issue 31: moves the gym's targets revision (gyms.targets_revision, one
  // for both disciplines) by one in the same transaction, and its data
  // version (the dashboard's cache key); with `revision` > 0, kConflict
  // ("revision: ...") unless that is the stored one.
  virtual Status SetDisciplineTargets(int64_t gym_id, const std::string& discipline,
                                      const std::vector<DisciplineTargetRecord>& targets,
                                      int64_t revision = 0) = 0;
  // The gym's targets per discipline, by discipline, kind, name (byte order).
  virtual Result<std::vector<DisciplineTargetRecord>> DisciplineTargets(int64_t gym_id) = 0;
  // The revision of the gym's discipline targets (issue 31); kNotFound for
  // an unknown gym.
  virtual Result<int64_t> DisciplineTargetsRevision(int64_t gym_id) = 0;
  // The tick sums of every ticked route of `gym_id`, by route id (one
  // aggregate query: a gym has up to ~250,000 ticks).
  virtual Result<std::vector<RouteTickSum>> GymTickSums(int64_t gym_id) = 0;
  // As GymTickSums for the gym's routes in `route_state` only ("set": the
  // dashboard's routes on the wall), by route id. Reads the ticks of those
  // routes through their route key, not every tick of the gym (issue 22:
  // 60 ms instead of 550 ms for a gym of 500 routes on the wall and 250,000
  // ticks, docs/BENCHMARKS.md "Dashboard and wall page, one request").
  virtual Result<std::vector<RouteTickSum>> StateTickSums(int64_t gym_id,
                                                          const std::string& route_state) = 0;
  // As GymTickSums for the routes `route_ids` only (any gym; unknown or
  // unticked ids absent), by route id: a setting day's input pools (issue 22),
  // read through the ticks' route key in queries of at most
  // kTickSumIdsPerQuery ids, not every tick of the gym.
  virtual Result<std::vector<RouteTickSum>> RouteTickSums(
      const std::vector<int64_t>& route_ids) = 0;
};

// The TargetStore of a store opened by store::OpenStore (both backends);
// nullptr for a Store that does not implement it. Not owned.
TargetStore* TargetStoreOf(Store* store);

}  // namespace sb::store

#endif  // SB_STORE_TARGET_STORE_H_
