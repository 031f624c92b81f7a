#include "store/copy.h"

#include <algorithm>
#include <cinttypes>
#include <cstdio>
#include <filesystem>
#include <numeric>

#include "base/hash.h"
#include "store/schema.h"
#include "store/sql.h"

namespace sb::store {

namespace {

using sql::Rows;

// A raw connection to `db` (no migration). A SQLite file must exist unless
// `create` is set.
Result<std::unique_ptr<sql::Connection>> Connect(const std::string& db, const StoreOptions& o,
                                                 bool create) {
  if (IsPostgresUrl(db)) {
    sql::PgSettings settings;
    settings.connect_timeout_seconds = o.connect_timeout_seconds;
    return sql::OpenPostgres(db, settings);
  }
  if (IsDatabaseUrl(db)) {
    return Status::InvalidInput("database '" + DisplayName(db) +
                                "': not a PostgreSQL URL (postgresql://... or postgres://...)");
  }
  std::error_code ec;
  if (!create && !std::filesystem::exists(db, ec)) {
    return Status::NotFound(db + ": no such database file");
  }
  return sql::OpenSqlite(db);
}

// The canonical text of one row (docs/formats.md, "Database checksums"):
// columns in ascending name order, each "name=" then "-" for NULL or
// "<bytes>:<value>", then ";".
std::string CanonicalRow(const Rows& r, size_t row, const std::vector<size_t>& order) {
  std::string out;
  for (size_t c : order) {
    out += r.columns[c];
    out += '=';
    if (r.IsNull(row, c)) {
      out += '-';
    } else {
      const std::string& v = r.Text(row, c);
      out += std::to_string(v.size());
      out += ':';
      out += v;
    }
    out += ';';
  }
  return out;
}

std::vector<size_t> ColumnsByName(const Rows& r) {
  std::vector<size_t> order(r.columns.size());
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(),
            [&](size_t a, size_t b) { return r.columns[a] < r.columns[b]; });
  return order;
}

// Columns that a migration from schema 6 on (the gym, issue 21) added to a
// table older than it. A table's content checksum leaves them out, so it
// reads the same before and after `db migrate` when every row kept every
// value it had (docs/formats.md, "Database checksums"). A migration that adds
// a column to an existing table adds it here.
const std::vector<std::string>& AddedColumns(const std::string& table) {
  static const std::vector<std::string> kRoutes = {
      "gym_id",      "wall_id", "state", "planned_on", "strip_on", "original_id",
      "search_text", "search_version", "revision",
      // Schema 20 (issue 32): the import key.
      "import_key",
      // Schema 21 (issue 33): the grade predicted at accept time.
      "predicted_grade",
      // Schema 22 (issue 31): the route's circuit.
      "circuit_id"};
  static const std::vector<std::string> kStudies = {"gym_id"};
  // Schema 14 (issue 31): the revisions.
  static const std::vector<std::string> kRevision = {"revision"};
  // Schema 18 (issue 32): the gym's default language.
  static const std::vector<std::string> kRevisions = {"revision", "targets_revision", "language"};
  // Schema 16 and 17 (issue 32): the account's profile; the wall's scale.
  static const std::vector<std::string> kUsers = {"display_name", "language"};
  static const std::vector<std::string> kWalls = {"revision", "targets_revision", "scale"};
  static const std::vector<std::string> kNone;
  if (table == "routes") return kRoutes;
  if (table == "studies") return kStudies;
  if (table == "users") return kUsers;
  if (table == "walls") return kWalls;
  if (table == "gyms") return kRevisions;
  if (table == "circuits") return kRevision;
  return kNone;
}

Result<TableSummary> SummarizeTable(sql::Connection& c, const std::string& table) {
  TableSummary t;
  t.name = table;
  Result<Rows> r = c.Query("SELECT * FROM " + table, {});
  if (!r.ok()) return r.status().WithPrefix("table " + table);
  std::vector<size_t> order = ColumnsByName(*r);
  std::vector<size_t> content;
  const std::vector<std::string>& added = AddedColumns(table);
  for (size_t col : order) {
    if (std::find(added.begin(), added.end(), r->columns[col]) == added.end()) {
      content.push_back(col);
    }
  }
  t.rows = static_cast<int64_t>(r->size());
  for (size_t i = 0; i < r->size(); ++i) {
    t.checksum += Fnv1a64(CanonicalRow(*r, i, order));
    t.content_checksum += Fnv1a64(CanonicalRow(*r, i, content));
  }
  if (std::find(r->columns.begin(), r->columns.end(), "id") != r->columns.end()) {
    Result<int64_t> next = c.NextId(table);
    if (!next.ok()) return next.status().WithPrefix("table " + table);
    t.next_id = *next;
  }
  return t;
}

// Whether the database of `c` has a table of that name.
Result<bool> HasTable(sql::Connection& c, const std::string& table) {
  const char* sql = c.dialect() == sql::Dialect::kPostgres
                        ? "SELECT count(*) FROM information_schema.tables WHERE "
                          "table_schema = current_schema() AND table_name = ?"
                        : "SELECT count(*) FROM sqlite_master WHERE type = 'table' AND name = ?";
  SB_ASSIGN_OR_RETURN(Rows r, c.Query(sql, {table}));
  return r.Int(0, 0) > 0;
}

// The summary of the database of `c`: every table of this program's schema;
// at another schema version, those of them it has (so `db info` before and
// after `db migrate` can be compared).
Result<DatabaseSummary> SummarizeConnection(sql::Connection& c, const std::string& db) {
  DatabaseSummary s;
  s.shown = DisplayName(db);
  s.backend = sql::DialectName(c.dialect());
  SB_ASSIGN_OR_RETURN(s.schema_version, c.SchemaVersion());
  for (const std::string& table : SchemaTables()) {
    if (s.schema_version != kSchemaVersion) {
      SB_ASSIGN_OR_RETURN(bool has, HasTable(c, table));
      if (!has) continue;
    }
    SB_ASSIGN_OR_RETURN(TableSummary t, SummarizeTable(c, table));
    s.tables.push_back(std::move(t));
  }
  return s;
}

// Starts a read of one consistent snapshot of the source.
Status BeginSnapshot(sql::Connection& c) {
  if (c.dialect() == sql::Dialect::kPostgres) {
    return c.Exec("BEGIN ISOLATION LEVEL REPEATABLE READ READ ONLY");
  }
  return c.Exec("BEGIN");  // SQLite: a read transaction sees one snapshot
}

// Copies the rows of one table (inside the destination's transaction).
Status CopyTable(sql::Connection& from, sql::Connection& to, const std::string& table) {
  Result<Rows> r = from.Query("SELECT * FROM " + table, {});
  if (!r.ok()) return r.status().WithPrefix("reading table " + table);
  std::string cols, marks;
  for (size_t c = 0; c < r->columns.size(); ++c) {
    cols += (c ? ", " : "") + r->columns[c];
    marks += c ? ", ?" : "?";
  }
  const std::string insert = "INSERT INTO " + table + "(" + cols + ") VALUES(" + marks + ")";
  std::vector<sql::Value> values(r->columns.size());
  for (size_t i = 0; i < r->size(); ++i) {
    for (size_t c = 0; c < r->columns.size(); ++c) {
      values[c] = r->IsNull(i, c) ? sql::Value() : sql::Value(r->Text(i, c));
    }
    Result<Rows> w = to.Query(insert, values);
    if (!w.ok()) {
      return w.status().WithPrefix("writing table " + table + " row " + std::to_string(i + 1));
    }
  }
  return Status::Ok();
}

}  // namespace

Result<DatabaseSummary> Summarize(const std::string& db, const StoreOptions& options) {
  SB_ASSIGN_OR_RETURN(std::unique_ptr<sql::Connection> c, Connect(db, options, false));
  SB_RETURN_IF_ERROR(BeginSnapshot(*c));
  Result<DatabaseSummary> s = SummarizeConnection(*c, db);
  c->Rollback();
  return s;
}

Result<DatabaseSummary> CopyDatabase(const std::string& from, const std::string& to,
                                     const StoreOptions& options) {
  const std::string src_name = DisplayName(from), dst_name = DisplayName(to);
  SB_ASSIGN_OR_RETURN(std::unique_ptr<sql::Connection> src, Connect(from, options, false));
  SB_ASSIGN_OR_RETURN(int version, src->SchemaVersion());
  if (version != kSchemaVersion) {
    return Status::InvalidInput(
        src_name + ": schema version " + std::to_string(version) + ", this program's is " +
        std::to_string(kSchemaVersion) +
        (version < kSchemaVersion ? "; run 'strangebeta db migrate --db' on it first"
                                  : "; use the newer program"));
  }
  SB_ASSIGN_OR_RETURN(std::unique_ptr<sql::Connection> dst, Connect(to, options, true));
  Status migrated = sql::Migrate(*dst);
  if (!migrated.ok()) return migrated.WithPrefix(dst_name);

  SB_RETURN_IF_ERROR(BeginSnapshot(*src));
  Result<DatabaseSummary> before = SummarizeConnection(*src, from);
  if (!before.ok()) {
    src->Rollback();
    return before.status().WithPrefix(src_name);
  }
  Result<DatabaseSummary> after = sql::InTransaction<DatabaseSummary>(
      *dst, [&]() -> Result<DatabaseSummary> {
        for (const std::string& table : SchemaTables()) {
          SB_ASSIGN_OR_RETURN(Rows n, dst->Query("SELECT count(*) FROM " + table, {}));
          if (n.Int(0, 0) != 0) {
            return Status::Conflict(dst_name + ": not empty (" + n.Text(0, 0) + " rows in " +
                                    table + "); copy into an empty database");
          }
        }
        // The gym_versions triggers (schema 13) stay off on PostgreSQL while
        // rows are copied (each would update its gym's row once per copied
        // row in one transaction); gym_versions is copied like any table
        // (its trigger-made rows dropped first, on SQLite).
        const bool pg = dst->dialect() == sql::Dialect::kPostgres;
        for (const TableSummary& t : before->tables) {
          if (pg) SB_RETURN_IF_ERROR(dst->Exec("ALTER TABLE " + t.name + " DISABLE TRIGGER USER"));
        }
        for (const TableSummary& t : before->tables) {
          if (t.name == "gym_versions") {
            SB_RETURN_IF_ERROR(dst->Exec("DELETE FROM gym_versions"));
          }
          SB_RETURN_IF_ERROR(CopyTable(*src, *dst, t.name));
          if (t.next_id > 0) SB_RETURN_IF_ERROR(dst->SetNextId(t.name, t.next_id));
        }
        for (const TableSummary& t : before->tables) {
          if (pg) SB_RETURN_IF_ERROR(dst->Exec("ALTER TABLE " + t.name + " ENABLE TRIGGER USER"));
        }
        SB_ASSIGN_OR_RETURN(DatabaseSummary s, SummarizeConnection(*dst, to));
        for (size_t i = 0; i < s.tables.size(); ++i) {
          const TableSummary &a = before->tables[i], &b = s.tables[i];
          if (a.rows != b.rows || a.checksum != b.checksum) {
            return Status::Internal("table " + a.name + " differs after the copy (" +
                                    std::to_string(a.rows) + " rows -> " +
                                    std::to_string(b.rows) + "); nothing was written");
          }
          // Id counters carry over, except into SQLite tables without
          // AUTOINCREMENT (users), which always take max(id) + 1.
          if (b.next_id < a.next_id && dst->dialect() == sql::Dialect::kPostgres) {
            return Status::Internal("table " + a.name + ": next id " + std::to_string(b.next_id) +
                                    " after the copy, " + std::to_string(a.next_id) + " before");
          }
        }
        return s;
      });
  src->Rollback();
  if (!after.ok() && after.status().code() == Status::Code::kIoError) {
    return after.status().WithPrefix(dst_name);
  }
  return after;
}

std::string FormatSummary(const DatabaseSummary& s) {
  std::string out = "database: " + s.shown + " (" + s.backend + ")\n";
  out += "schema version: " + std::to_string(s.schema_version) + " (this program: " +
         std::to_string(kSchemaVersion) + ")\n";
  if (s.tables.empty()) return out;
  char line[160];
  std::snprintf(line, sizeof line, "%-18s %10s  %-16s  %-7s  %s\n", "table", "rows", "checksum",
                "next id", "content");
  out += line;
  for (const TableSummary& t : s.tables) {
    std::string next = t.next_id > 0 ? std::to_string(t.next_id) : "-";
    std::snprintf(line, sizeof line, "%-18s %10" PRId64 "  %016" PRIx64 "  %-7s  %016" PRIx64 "\n",
                  t.name.c_str(), t.rows, t.checksum, next.c_str(), t.content_checksum);
    out += line;
  }
  return out;
}

}  // namespace sb::store
