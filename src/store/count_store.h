// Issue 34, costs before the work: counts of the rows a page will read,
// taken before the reading (app/read_costs.h): a gym's and a route's
// history, a route's feedback, what the drift page reads for a setter, and
// the gym's lists (members, walls, circuits, scales).
// A separate interface over the same SQL layer (store/sql_store.cc
// implements it in the same object as Store, as store/prediction_store.h),
// so store/store.h stays as it is. Each count is one indexed COUNT query.
//
// No SQLite or libpq types appear in this header.
#ifndef SB_STORE_COUNT_STORE_H_
#define SB_STORE_COUNT_STORE_H_

#include <cstdint>

#include "base/status.h"
#include "store/store.h"

namespace sb::store {

// What GET /drift reads for a setter (ClimberFeedback::Drift): every route
// they own, read whole, and the feedback rows on them.
struct DriftCounts {
  int64_t routes = 0;
  int64_t feedback = 0;
};

// Thread-safe like Store. Unknown ids count 0. Errors: kIoError.
class CountStore {
 public:
  virtual ~CountStore() = default;
  // Rows of GymStore::ListGymHistory(gym_id).
  virtual Result<int64_t> CountGymHistory(int64_t gym_id) = 0;
  // Rows of GymStore::ListHistory(route_id).
  virtual Result<int64_t> CountRouteHistory(int64_t route_id) = 0;
  // Rows of FeedbackStore::ListFeedback(route_id).
  virtual Result<int64_t> CountRouteFeedback(int64_t route_id) = 0;
  // Rows of RouteStore::AllRoutes(owner_id) and of
  // FeedbackStore::FeedbackOnRoutesOf(owner_id).
  virtual Result<DriftCounts> CountDrift(int64_t owner_id) = 0;
  // Rows of the gym's lists (issue 34): GymStore::ListMembers, ListWalls,
  // ListCircuits and ScaleStore::ListGymScales of `gym_id`.
  virtual Result<int64_t> CountGymMembers(int64_t gym_id) = 0;
  virtual Result<int64_t> CountGymWalls(int64_t gym_id) = 0;
  virtual Result<int64_t> CountGymCircuits(int64_t gym_id) = 0;
  virtual Result<int64_t> CountGymScales(int64_t gym_id) = 0;
};

// The CountStore of a store opened by store::OpenStore (both backends);
// nullptr for a Store that does not implement it. Not owned.
CountStore* CountStoreOf(Store* store);

}  // namespace sb::store

#endif  // SB_STORE_COUNT_STORE_H_
