// Opening the route database by its locator: a SQLite file name (the
// embedded default) or a PostgreSQL URL.
//
//   Result<std::unique_ptr<Store>> s = store::OpenStore("postgresql://sb@db/gym");
//
// No SQLite or libpq types appear in this header.
#ifndef SB_STORE_OPEN_H_
#define SB_STORE_OPEN_H_

#include <memory>
#include <string>
#include <string_view>

#include "base/status.h"
#include "store/store.h"

namespace sb::store {

// Settings of the connection to the database (docs/deploy.md).
struct StoreOptions {
  // PostgreSQL connections one process keeps (at most): requests beyond it
  // wait for a free one. SQLite always uses one connection (one writer).
  // 8 serves the default 32 workers (most of a request's time is not spent
  // in the database); the server's max_connections (100 by default) bounds
  // processes x pool size.
  int pool_size = 8;
  // How long a request waits for a free connection before it fails
  // (kIoError, a 500): longer than any single statement should take.
  int pool_wait_ms = 30000;
  // Seconds to wait for the PostgreSQL server at connect (unless the URL or
  // PGCONNECT_TIMEOUT says): an unreachable server fails start-up quickly.
  int connect_timeout_seconds = 10;
};

// Limits of StoreOptions::pool_size: at least one connection; more than 256
// per process exhausts any server's max_connections.
inline constexpr int kMaxPoolSize = 256;

// True when `db` names a database by URL ("scheme:" at the start: letters,
// digits, '+', '-', '.', at least two characters, then ':') rather than a file;
// such an argument is never opened as a file name (write ./a:b.db for a file
// whose name has a colon).
bool IsDatabaseUrl(std::string_view db);

// True for the PostgreSQL URLs OpenStore accepts: postgresql://... or
// postgres://... (libpq's syntax; missing parts from the PG* environment
// variables, so "postgresql://" alone takes everything from them).
bool IsPostgresUrl(std::string_view db);

// `db` for messages and logs: a URL without its password.
std::string DisplayName(const std::string& db);

// Opens the database named by `db`: a PostgreSQL URL (IsPostgresUrl) or a
// SQLite file (created when absent; its directory must exist), and applies
// the migrations. Errors: kInvalidInput for another URL scheme, a pool size
// out of 1..kMaxPoolSize, or a database newer than this program; kIoError
// naming the database (without password) when it cannot be opened or
// reached. The store is thread-safe.
Result<std::unique_ptr<Store>> OpenStore(const std::string& db, const StoreOptions& options = {});

// The PostgreSQL backend by itself (OpenStore picks it for postgresql:// URLs).
Result<std::unique_ptr<Store>> OpenPostgresStore(const std::string& url,
                                                 const StoreOptions& options = {});

}  // namespace sb::store

#endif  // SB_STORE_OPEN_H_
