// The SQLite backend of store::Store.
#ifndef SB_STORE_SQLITE_STORE_H_
#define SB_STORE_SQLITE_STORE_H_

#include <memory>
#include <string>

#include "base/status.h"
#include "store/store.h"

namespace sb::store {

// Opens (creating when absent) the SQLite database at `path`, switches it to
// WAL with foreign keys on, and applies the versioned migrations
// (kSchemaVersion). The parent directory must exist. ":memory:" gives a
// private in-memory database (tests). Errors: kIoError naming the path, or
// kInvalidInput when the file is newer than this program's schema.
// The returned store serialises access through one connection and a mutex;
// it is safe to use from many threads.
Result<std::unique_ptr<Store>> OpenSqliteStore(const std::string& path);

// The schema version this program writes.
inline constexpr int kSchemaVersion = 5;

}  // namespace sb::store

#endif  // SB_STORE_SQLITE_STORE_H_
