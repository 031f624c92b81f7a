// Issue 32 (route lists as gyms have them): the key an import recognises a
// route by (schema 20, routes.import_key): "id:<text>" for a gym list's own
// id of the route, "crdl:<16 hex digits>" for the content hash of an
// imported CRDL file. A separate interface over the same SQL layer
// (store/sql_store.cc implements it in the same object as Store), so the
// route record of store/store.h stays as it is.
//
// No SQLite or libpq types appear in this header.
#ifndef SB_STORE_IMPORT_STORE_H_
#define SB_STORE_IMPORT_STORE_H_

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "base/status.h"
#include "store/store.h"

namespace sb::store {

class ImportStore {
 public:
  virtual ~ImportStore() = default;
  // Sets route `route_id`'s import key ("" removes it). kNotFound for an
  // unknown route.
  virtual Status SetImportKey(int64_t route_id, const std::string& key) = 0;
  // The (key, route id) pairs of the routes with a key starting with
  // `prefix`: of gym `gym_id` when given, else the personal routes (no gym)
  // of `owner_id`; also only `owner_id`'s when both are given. Ordered by
  // route id.
  virtual Result<std::vector<std::pair<std::string, int64_t>>> ImportKeys(
      std::optional<int64_t> gym_id, std::optional<int64_t> owner_id,
      const std::string& prefix) = 0;
};

// The ImportStore of a store opened by store::OpenStore (both backends);
// nullptr for a Store that does not implement it. Not owned.
ImportStore* ImportStoreOf(Store* store);

// Runs `body` in one transaction of `store`: every call `body` makes on
// `store` (any of its interfaces: Store, GymStore, ImportStore, ...) from the
// calling thread goes to one connection, committed when `body` returns OK and
// rolled back when it (or the commit) fails, so nothing it wrote stays;
// returns that error. A store call's own transaction nests as a savepoint.
// Other threads' writes wait meanwhile (SQLite) or see nothing until the
// commit (PostgreSQL). A store not opened by store::OpenStore runs `body` as
// it is. `body` must not hand store work to other threads.
Status RunAtomically(Store* store, const std::function<Status()>& body);

}  // namespace sb::store

#endif  // SB_STORE_IMPORT_STORE_H_
