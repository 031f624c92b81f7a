// The SQLite backend of store::Store (the embedded default; store/open.h
// opens either backend by locator).
#ifndef SB_STORE_SQLITE_STORE_H_
#define SB_STORE_SQLITE_STORE_H_

#include <memory>
#include <string>

#include "base/status.h"
#include "store/schema.h"  // kSchemaVersion
#include "store/store.h"

namespace sb::store {

// Opens (creating when absent) the SQLite database at `path`, switches it to
// WAL with foreign keys on, and applies the versioned migrations
// (kSchemaVersion, store/schema.h). The parent directory must exist.
// ":memory:" gives a private in-memory database (tests). Errors: kIoError
// naming the path, or kInvalidInput when the file is newer than this
// program's schema. The returned store serialises access through one
// connection; it is safe to use from many threads (and other processes may
// open the same file: writers take turns, waiting up to 5 s).
Result<std::unique_ptr<Store>> OpenSqliteStore(const std::string& path);

}  // namespace sb::store

#endif  // SB_STORE_SQLITE_STORE_H_
