// The database schema of both backends in one description: the versioned
// migrations (store/schema.cc, kMigrations), written once in SQL with a few
// dialect tokens, plus the steps that only one dialect needs. Documented in
// docs/web.md ("Database schema") and docs/deploy.md.
#ifndef SB_STORE_SCHEMA_H_
#define SB_STORE_SCHEMA_H_

#include <string>
#include <vector>

#include "base/status.h"
#include "store/sql.h"

namespace sb::store {

// The schema version this program writes (the number of migrations).
inline constexpr int kSchemaVersion = 23;

// The tables of the schema in the order their rows can be inserted (every
// table after the tables it refers to): what `db copy` moves and checksums.
// The version bookkeeping (PRAGMA user_version, schema_migrations) is not
// part of it.
const std::vector<std::string>& SchemaTables();

namespace sql {

// Migration `version` (1..kSchemaVersion) as the statements `dialect` runs,
// tokens expanded (tests and docs).
std::string MigrationSql(int version, Dialect dialect);

// Brings the database of `c` to kSchemaVersion (or `target` when lower),
// each migration in its own transaction. Several processes may migrate one
// database at once: each migration re-reads the version under the write
// lock (SQLite) or an advisory lock (PostgreSQL) and is applied once.
// Errors: kInvalidInput when the database is newer than this program;
// kIoError "migration N: ..." when a migration fails (nothing of it stays).
Status Migrate(Connection& c, int target = kSchemaVersion);

}  // namespace sql
}  // namespace sb::store

#endif  // SB_STORE_SCHEMA_H_
