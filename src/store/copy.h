// Whole-database operations behind `strangebeta db`: a summary of every
// table (rows and checksum), migration, and copying a gym's database from
// one backend to the other (SQLite file <-> PostgreSQL), checked by counts
// and checksums. The checksum is defined in docs/formats.md ("Database
// checksums"); it is the same for the same rows on either backend.
#ifndef SB_STORE_COPY_H_
#define SB_STORE_COPY_H_

#include <cstdint>
#include <string>
#include <vector>

#include "base/status.h"
#include "store/open.h"

namespace sb::store {

// One table of a summary.
struct TableSummary {
  std::string name;
  int64_t rows = 0;
  uint64_t checksum = 0;  // sum mod 2^64 of the rows' FNV-1a 64 (docs/formats.md)
  int64_t next_id = 0;    // the next id a new row takes; 0 for tables without `id`
  // The checksum without the columns the gym migration (schema 6) and later
  // ones added to older tables (docs/formats.md): equal before and after
  // `db migrate` when every row kept its values.
  uint64_t content_checksum = 0;
};

struct DatabaseSummary {
  std::string shown;    // the locator without password
  std::string backend;  // "sqlite" or "postgresql"
  int schema_version = 0;
  // SchemaTables() order; at another schema version, the ones the database has.
  std::vector<TableSummary> tables;
};

// Counts and checksums of an existing database, without changing it (no
// migration); at an older schema version, of the tables it has. A SQLite file must exist. Errors: kNotFound for a missing
// file, kInvalidInput for an unsupported URL, kIoError when it cannot be read.
Result<DatabaseSummary> Summarize(const std::string& db, const StoreOptions& options = {});

// Copies every row of every table of `from` into `to`, keeping ids and the
// id counters (ids are never reused after a move), in one transaction on
// `to`, then checks that the row counts and checksums of both agree (else
// nothing is written). `from` must be at this program's schema version;
// `to` is created or migrated to it and must hold no rows. Rows are read in
// one consistent snapshot; stop the servers on `from` first or they may go
// on writing there. Memory: the largest table is held at once.
// Errors: kNotFound (missing source file), kInvalidInput (source at another
// schema version, unsupported URL), kConflict (destination not empty),
// kIoError (database errors, naming the table), kInternal (a checksum
// mismatch after the copy).
Result<DatabaseSummary> CopyDatabase(const std::string& from, const std::string& to,
                                     const StoreOptions& options = {});

// Formats a summary as the text `db info` and `db copy` print.
std::string FormatSummary(const DatabaseSummary& s);

}  // namespace sb::store

#endif  // SB_STORE_COPY_H_
