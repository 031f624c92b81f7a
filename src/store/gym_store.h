// The gyms' records (schema 6, issue 21): gyms, their members, walls and
// circuits, and what a route's life on the wall adds beside its row (its
// setters and history). A separate interface from store::Store, over the same
// SQL layer (store/sql_store.cc implements both in one object), so the store
// is split per kind of record as it grows. The schema is documented in
// docs/web.md ("Gyms").
//
// No SQLite or libpq types appear in this header.
#ifndef SB_STORE_GYM_STORE_H_
#define SB_STORE_GYM_STORE_H_

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "base/status.h"
#include "gym/records.h"
#include "store/store.h"

namespace sb::store {

// A gym. `role` is the caller's role in it where a call says so ("" else).
struct GymRecord {
  int64_t id = 0;
  std::string name;
  std::string created_at;  // "YYYY-MM-DD HH:MM:SS" UTC
  std::string role;
  int64_t revision = 0;  // schema 14 (issue 31): one more on every rename
};

// A member, a wall and a circuit of a gym: one struct each, shared with the
// application layer (gym/records.h).
using MemberRecord = gym::Member;
using WallRecord = gym::Wall;
using CircuitRecord = gym::Circuit;

// One change of a gym's set-up (walls, circuits, members, its name) by a
// head setter (schema 14, issue 31).
struct GymHistoryRecord {
  int64_t id = 0;
  int64_t gym_id = 0;
  std::optional<int64_t> user_id;
  std::string username;  // read only: "" once the account is deleted
  std::string at;        // "YYYY-MM-DD HH:MM:SS" UTC
  std::string what;
};

// One change of a route: who (nullopt once the account is deleted), when and what.
struct HistoryRecord {
  int64_t id = 0;
  int64_t route_id = 0;
  std::optional<int64_t> user_id;
  std::string username;  // read only: the account's name, "" when none
  std::string at;        // "YYYY-MM-DD HH:MM:SS" UTC (set by AddHistory)
  std::string what;
};

// What UpdateWall hands its `rederive` callback for each route on the wall:
// the route's CRDL and the stored discipline columns the app derives from it
// and the wall (app/discipline.h), for the callback to recompute.
struct RouteAxis {
  int64_t route_id = 0;
  std::string crdl;
  std::string grade_discipline;
  std::optional<double> grade_value;
};
// Recomputes `route`'s discipline columns for the wall as updated; returns
// whether they changed (the row is written only then). Must not touch the
// store (it runs inside UpdateWall's transaction).
using RederiveRoute = std::function<bool(RouteAxis* route)>;

// Thread-safe like Store; every multi-row change is atomic. Errors: kNotFound
// for unknown ids, kConflict for taken names, kIoError for storage failures.
class GymStore {
 public:
  virtual ~GymStore() = default;

  // Creates a gym with `head` as its head setter (one transaction); returns
  // its id. kNotFound when the user does not exist. `head` = nullopt creates
  // a gym without members (the install's first gym).
  virtual Result<int64_t> CreateGym(const std::string& name, std::optional<int64_t> head) = 0;
  // Renames a gym; kNotFound when absent; with `revision` > 0, kConflict
  // unless that is the stored revision (checked and bumped in one UPDATE).
  virtual Status RenameGym(int64_t id, const std::string& name, int64_t revision = 0) = 0;
  virtual Result<GymRecord> GetGym(int64_t id) = 0;
  // Every gym in id order (role "").
  virtual Result<std::vector<GymRecord>> ListGyms() = 0;
  // The gyms `user_id` is a member of, in id order, with the user's role.
  virtual Result<std::vector<GymRecord>> GymsOf(int64_t user_id) = 0;

  // Adds a member or changes the role of one; kNotFound for an unknown gym
  // or user.
  virtual Status PutMember(int64_t gym_id, int64_t user_id, const std::string& role) = 0;
  // A gym's members, by user id.
  virtual Result<std::vector<MemberRecord>> ListMembers(int64_t gym_id) = 0;
  // Removes a member (issue 31); kNotFound when `user_id` is no member.
  virtual Status RemoveMember(int64_t gym_id, int64_t user_id) = 0;

  // Walls. InsertWall ignores `id` and returns the new one; kConflict when
  // the gym has a wall of that name. UpdateWall replaces every field but
  // gym_id (kNotFound, kConflict as InsertWall); with `rederive`, in the
  // same transaction, it calls `rederive` on every route whose wall_id is
  // the wall's and writes the discipline columns of those it changed (a
  // wall's new discipline reaches its routes at once, issue 21).
  virtual Result<int64_t> InsertWall(const WallRecord& wall) = 0;
  virtual Status UpdateWall(const WallRecord& wall, const RederiveRoute& rederive) = 0;
  Status UpdateWall(const WallRecord& wall) { return UpdateWall(wall, nullptr); }
  virtual Result<WallRecord> GetWall(int64_t id) = 0;
  // A gym's walls by position, then id.
  virtual Result<std::vector<WallRecord>> ListWalls(int64_t gym_id) = 0;
  // Removes a wall (issue 31), in one transaction: kConflict "N routes are
  // on it" while routes not stripped have its wall_id; the stripped ones
  // keep the wall's name as their free-text wall. kNotFound when absent.
  virtual Status DeleteWall(int64_t id) = 0;

  // Circuits. kConflict when the gym has a circuit of that colour.
  virtual Result<int64_t> InsertCircuit(const CircuitRecord& circuit) = 0;
  // A gym's circuits by id.
  virtual Result<std::vector<CircuitRecord>> ListCircuits(int64_t gym_id) = 0;
  // Replaces a circuit's colour and range (issue 31); kNotFound, kConflict
  // for a taken colour or (revision > 0) a revision not the stored one.
  virtual Status UpdateCircuit(const CircuitRecord& circuit) = 0;
  // Removes a circuit; kNotFound when absent. Routes keep their colour.
  // Issue 31: in the same transaction the routes set in it lose their
  // circuit_id (their revision moves by one), each gets `route_note` in its
  // history by `user_id` (none when empty), and `*cleared` (if given) is how
  // many they were.
  virtual Status DeleteCircuit(int64_t id, std::optional<int64_t> user_id = std::nullopt,
                               const std::string& route_note = "",
                               int64_t* cleared = nullptr) = 0;

  // The gym's history (issue 31): appends one row (at = now); lists them,
  // oldest first.
  virtual Status AddGymHistory(int64_t gym_id, std::optional<int64_t> user_id,
                               const std::string& what) = 0;
  virtual Result<std::vector<GymHistoryRecord>> ListGymHistory(int64_t gym_id) = 0;

  // Replaces a route's setters and appends one history row `what` by
  // `user_id` (when `what` is not empty), in one transaction; kNotFound for
  // an unknown route.
  virtual Status SetRouteSetters(int64_t route_id, const std::vector<RouteSetter>& setters,
                                 std::optional<int64_t> user_id, const std::string& what) = 0;
  // Appends one history row to a route (at = now).
  virtual Status AddHistory(int64_t route_id, std::optional<int64_t> user_id,
                            const std::string& what) = 0;
  // A route's history, oldest first.
  virtual Result<std::vector<HistoryRecord>> ListHistory(int64_t route_id) = 0;
  // The id of the route of `gym_id` imported with the original site's id
  // `original_id` (by `owner` only, when given); nullopt when none.
  virtual Result<std::optional<int64_t>> FindByOriginalId(int64_t gym_id, int64_t original_id,
                                                          std::optional<int64_t> owner) = 0;
};

// The GymStore of a store opened by store::OpenStore (both backends
// implement it); nullptr for a Store that does not. Does not transfer
// ownership.
GymStore* GymStoreOf(Store* store);

}  // namespace sb::store

#endif  // SB_STORE_GYM_STORE_H_
