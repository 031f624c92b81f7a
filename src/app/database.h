// Opening the database the app runs on, and whole-database operations
// (`strangebeta db`), for web and CLI: they hold an app::Database and build
// app::Services on it, never a store type (issue 21).
//
//   Result<std::unique_ptr<app::Database>> db = app::OpenDatabase("var/strangebeta.db");
//   app::Services services(db->get(), app::Options{});
#ifndef SB_APP_DATABASE_H_
#define SB_APP_DATABASE_H_

#include <memory>
#include <string>
#include <string_view>

#include "app/types.h"
#include "base/status.h"
#include "store/copy.h"
#include "store/open.h"
#include "store/store.h"

namespace sb::app {

// Connection settings (pool size, waits; docs/deploy.md).
using DatabaseOptions = store::StoreOptions;
// Rows and checksum per table, as `db info` prints them (docs/formats.md).
using DatabaseSummary = store::DatabaseSummary;

// The largest pool DatabaseOptions::pool_size may ask for (more exhausts any
// PostgreSQL server's max_connections).
inline constexpr int kMaxDatabasePool = store::kMaxPoolSize;

// Opens (creating a SQLite file when absent) and migrates the database named
// by `db`: a SQLite file name or a postgresql:// URL. The caller owns it.
// Errors: kInvalidInput for another URL scheme, a bad pool size or a newer
// schema; kIoError naming the database (without password).
Result<std::unique_ptr<Database>> OpenDatabase(const std::string& db,
                                               const DatabaseOptions& options = {});

// True when `db` is a URL rather than a file name. Pure.
bool IsDatabaseUrl(std::string_view db);
// `db` for messages: a URL without its password. Pure.
std::string DatabaseDisplayName(const std::string& db);

// Counts and checksums per table of an existing database, changing nothing.
// Errors: kNotFound (missing file), kInvalidInput, kIoError.
Result<DatabaseSummary> SummarizeDatabase(const std::string& db,
                                          const DatabaseOptions& options = {});
// Copies every row of `from` into the empty `to` and checks counts and
// checksums (store/copy.h, CopyDatabase, for the errors).
Result<DatabaseSummary> CopyDatabase(const std::string& from, const std::string& to,
                                     const DatabaseOptions& options = {});
// The text `db info` and `db copy` print for a summary. Pure.
std::string FormatDatabaseSummary(const DatabaseSummary& s);

}  // namespace sb::app

#endif  // SB_APP_DATABASE_H_
