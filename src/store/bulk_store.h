// Bulk loading (issue 22): many routes or ticks written with multi-row
// INSERTs in one transaction, for generators and imports of whole chains
// (app/synth_chain.h). A separate interface from store::Store over the same
// SQL layer (store/bulk_sql.cc; store/sql_store.cc implements it in the same
// object as Store, GymStore and TickStore).
//
// No SQLite or libpq types appear in this header.
#ifndef SB_STORE_BULK_STORE_H_
#define SB_STORE_BULK_STORE_H_

#include <cstdint>
#include <vector>

#include "base/status.h"
#include "store/store.h"
#include "store/tick_store.h"

namespace sb::store {

// Rows per multi-row INSERT statement: 28 route columns x 500 = 14,000
// parameters, under SQLite's 32,766 bound-parameter limit (PostgreSQL's is
// 65,535); larger statements gain nothing measurable.
inline constexpr int kBulkRouteRows = 500;
// 16 tick columns x 1,000 = 16,000 parameters (same limits).
inline constexpr int kBulkTickRows = 1000;

// Thread-safe like Store. Errors: kNotFound when a referenced row (owner,
// gym, wall, route, user) does not exist, kIoError for storage failures,
// kInvalidInput for text either backend refuses. Nothing of a call is
// written when it fails (one transaction).
class BulkStore {
 public:
  virtual ~BulkStore() = default;

  // Inserts routes (not variations: `inputs` must be empty, else
  // kInvalidInput) with their `setters`, in one transaction, and returns the
  // new ids in input order. Unlike Store::InsertRoute, `created_at` is kept
  // when set (updated_at = created_at), so generated data is reproducible;
  // the search text is filled as InsertRoute fills it.
  virtual Result<std::vector<int64_t>> BulkInsertRoutes(
      const std::vector<RouteRecord>& routes) = 0;
  // Inserts ticks as given (revision 1), in one transaction. A tick that
  // repeats a (route, climber, day) of the table or of the call fails the
  // whole call (kConflict).
  virtual Status BulkInsertTicks(const std::vector<TickRecord>& ticks) = 0;
};

// The BulkStore of a store opened by store::OpenStore (both backends);
// nullptr for a Store that does not implement it. Not owned.
BulkStore* BulkStoreOf(Store* store);

}  // namespace sb::store

#endif  // SB_STORE_BULK_STORE_H_
