// The PostgreSQL driver of the store's SQL layer (store/sql.h), on libpq.
#include <libpq-fe.h>

#include <algorithm>
#include <charconv>
#include <cstdlib>
#include <map>

#include "base/hash.h"
#include "base/log.h"
#include "store/sql.h"

namespace sb::store::sql {

namespace {

// The type OID of float8 (DOUBLE PRECISION), pg_type.dat.
constexpr Oid kFloat8Oid = 701;

// Owns a PGresult.
struct ResultDeleter {
  void operator()(PGresult* r) const { PQclear(r); }
};
using PgResult = std::unique_ptr<PGresult, ResultDeleter>;

std::string Trimmed(const char* s) {
  std::string out = s ? s : "";
  while (!out.empty() && (out.back() == '\n' || out.back() == ' ')) out.pop_back();
  return out;
}

// `?` parameters numbered $1, $2, ... (the store's SQL has no `?` inside
// string literals; quoted text is copied as it is all the same).
std::string NumberParameters(std::string_view sql) {
  std::string out;
  out.reserve(sql.size() + 16);
  int n = 0;
  char quote = 0;
  for (char c : sql) {
    if (quote) {
      if (c == quote) quote = 0;
      out += c;
    } else if (c == '\'' || c == '"') {
      quote = c;
      out += c;
    } else if (c == '?') {
      out += '$' + std::to_string(++n);
    } else {
      out += c;
    }
  }
  return out;
}

class PgConnection final : public Connection {
 public:
  explicit PgConnection(PGconn* conn) : conn_(conn) {}
  ~PgConnection() override { PQfinish(conn_); }

  Dialect dialect() const override { return Dialect::kPostgres; }
  bool broken() const override { return broken_ || PQstatus(conn_) != CONNECTION_OK; }

  Result<Rows> Query(std::string_view sql, const std::vector<Value>& params,
                     Violation* violated) override {
    if (violated) *violated = Violation::kNone;
    SB_RETURN_IF_ERROR(CheckText(params));
    SB_ASSIGN_OR_RETURN(const std::string* name, Prepare(sql, static_cast<int>(params.size())));
    std::vector<std::string> text(params.size());
    std::vector<const char*> values(params.size(), nullptr);
    std::vector<int> lengths(params.size(), 0);
    for (size_t i = 0; i < params.size(); ++i) {
      if (const int64_t* v = std::get_if<int64_t>(&params[i])) {
        text[i] = std::to_string(*v);
      } else if (const std::string* t = std::get_if<std::string>(&params[i])) {
        text[i] = *t;
      } else if (const double* d = std::get_if<double>(&params[i])) {
        text[i] = DoubleText(*d);
      } else {
        continue;  // NULL
      }
      values[i] = text[i].c_str();
      lengths[i] = static_cast<int>(text[i].size());
    }
    PgResult r(PQexecPrepared(conn_, name->c_str(), static_cast<int>(params.size()),
                              values.data(), lengths.data(), nullptr, 0));
    SB_RETURN_IF_ERROR(Check(r.get(), violated));
    Rows out;
    int cols = PQnfields(r.get());
    int rows = PQntuples(r.get());
    for (int c = 0; c < cols; ++c) out.columns.push_back(PQfname(r.get(), c));
    out.rows.reserve(rows);
    // float8 columns are re-printed as the SQLite driver prints doubles
    // (DoubleText), so both backends give the same text for the same value.
    std::vector<bool> is_double(cols);
    for (int c = 0; c < cols; ++c) is_double[c] = PQftype(r.get(), c) == kFloat8Oid;
    for (int i = 0; i < rows; ++i) {
      std::vector<std::optional<std::string>> row(cols);
      for (int c = 0; c < cols; ++c) {
        if (PQgetisnull(r.get(), i, c)) continue;
        row[c] = std::string(PQgetvalue(r.get(), i, c), PQgetlength(r.get(), i, c));
        if (is_double[c]) {
          double v = 0;
          const std::string& t = *row[c];
          auto [end, ec] = std::from_chars(t.data(), t.data() + t.size(), v);
          if (ec == std::errc() && end == t.data() + t.size()) row[c] = DoubleText(v);
        }
      }
      out.rows.push_back(std::move(row));
    }
    return out;
  }

  Status Exec(std::string_view script) override {
    std::string sql(script);
    PgResult r(PQexec(conn_, sql.c_str()));
    return Check(r.get(), nullptr);
  }

  Status Begin() override { return Exec("BEGIN"); }
  Status Commit() override {
    PgResult r(PQexec(conn_, "COMMIT"));
    SB_RETURN_IF_ERROR(Check(r.get(), nullptr));
    // COMMIT of a transaction that failed answers ROLLBACK.
    if (std::string(PQcmdStatus(r.get())) == "ROLLBACK") {
      return Status::IoError("the transaction was rolled back");
    }
    return Status::Ok();
  }
  void Rollback() override {
    if (PQtransactionStatus(conn_) == PQTRANS_IDLE) return;
    Status st = Exec("ROLLBACK");
    if (!st.ok()) LogError("database rollback failed: " + st.message());
  }

  Status LockKeys(const std::vector<std::string>& keys) override {
    // One 64-bit advisory lock per key, taken in ascending order so two
    // transactions never wait for each other in a cycle.
    std::vector<int64_t> ids;
    for (const std::string& k : keys) ids.push_back(static_cast<int64_t>(Fnv1a64(k)));
    std::sort(ids.begin(), ids.end());
    ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
    for (int64_t id : ids) {
      SB_ASSIGN_OR_RETURN(Rows r, Query("SELECT pg_advisory_xact_lock(?::bigint)", {id}, nullptr));
    }
    return Status::Ok();
  }

  Result<int> SchemaVersion() override {
    SB_ASSIGN_OR_RETURN(Rows t, Query("SELECT to_regclass('schema_migrations')", {}, nullptr));
    if (t.IsNull(0, 0)) return 0;
    SB_ASSIGN_OR_RETURN(Rows r,
                        Query("SELECT coalesce(max(version), 0) FROM schema_migrations", {}, nullptr));
    return static_cast<int>(r.Int(0, 0));
  }
  Status SetSchemaVersion(int version) override {
    SB_RETURN_IF_ERROR(
        Exec("CREATE TABLE IF NOT EXISTS schema_migrations ("
             "version INTEGER PRIMARY KEY, applied_at TIMESTAMPTZ NOT NULL DEFAULT now())"));
    SB_ASSIGN_OR_RETURN(
        Rows r, Query("INSERT INTO schema_migrations(version) VALUES(?::integer)",
                      {int64_t{version}}, nullptr));
    return Status::Ok();
  }
  Status BeforeMigrations() override { return Status::Ok(); }
  Status CheckMigration() override { return Status::Ok(); }  // constraints hold at once
  Status AfterMigrations() override { return Status::Ok(); }

  Result<int64_t> NextId(const std::string& table) override {
    SB_ASSIGN_OR_RETURN(Rows m, Query("SELECT max(id) FROM " + table, {}, nullptr));
    int64_t next = m.Int(0, 0) + 1;
    SB_ASSIGN_OR_RETURN(Rows q, Query("SELECT pg_get_serial_sequence(?, 'id')", {table}, nullptr));
    if (q.IsNull(0, 0)) return next;
    SB_ASSIGN_OR_RETURN(Rows s, Query("SELECT last_value, is_called FROM " + q.Text(0, 0), {},
                                      nullptr));
    int64_t seq = s.Int(0, 0) + (s.Text(0, 1) == "t" ? 1 : 0);
    return std::max(next, seq);
  }
  Status SetNextId(const std::string& table, int64_t next) override {
    SB_ASSIGN_OR_RETURN(
        Rows r, Query("SELECT setval(pg_get_serial_sequence(?, 'id'), ?::bigint, false)",
                      {table, std::max<int64_t>(next, 1)}, nullptr));
    return Status::Ok();
  }

 private:
  // The name of the prepared statement for `sql`, preparing it on first use.
  Result<const std::string*> Prepare(std::string_view sql, int nparams) {
    std::string key(sql);
    auto it = prepared_.find(key);
    if (it != prepared_.end()) return &it->second;
    std::string name = "sb" + std::to_string(prepared_.size() + 1);
    PgResult r(PQprepare(conn_, name.c_str(), NumberParameters(sql).c_str(), nparams, nullptr));
    SB_RETURN_IF_ERROR(Check(r.get(), nullptr));
    return &prepared_.emplace(std::move(key), std::move(name)).first->second;
  }

  // The status of a result: OK for commands and rows; the server's reason
  // otherwise, classified by SQLSTATE.
  Status Check(PGresult* r, Violation* violated) {
    ExecStatusType st = r ? PQresultStatus(r) : PGRES_FATAL_ERROR;
    if (st == PGRES_COMMAND_OK || st == PGRES_TUPLES_OK || st == PGRES_EMPTY_QUERY) {
      return Status::Ok();
    }
    if (PQstatus(conn_) != CONNECTION_OK) broken_ = true;
    std::string state = r ? Trimmed(PQresultErrorField(r, PG_DIAG_SQLSTATE)) : "";
    std::string msg = r ? Trimmed(PQresultErrorField(r, PG_DIAG_MESSAGE_PRIMARY)) : "";
    if (msg.empty()) msg = Trimmed(PQerrorMessage(conn_));
    if (violated && state == "23505") *violated = Violation::kUnique;
    if (violated && state == "23503") *violated = Violation::kForeignKey;
    // Class 22 = data exception (invalid UTF-8, out-of-range values).
    if (state.rfind("22", 0) == 0) return Status::InvalidInput(msg);
    return Status::IoError(msg);
  }

  PGconn* conn_;
  bool broken_ = false;
  std::map<std::string, std::string> prepared_;  // SQL -> statement name
};

void IgnoreNotice(void*, const char*) {}

}  // namespace

Result<std::unique_ptr<Connection>> OpenPostgres(const std::string& url,
                                                 const PgSettings& settings) {
  // Defaults first: the URL's own parameters (expanded from "dbname") come
  // later and win; the PG* variables win over nothing given here.
  std::vector<const char*> keys, values;
  std::string timeout = std::to_string(settings.connect_timeout_seconds);
  if (!std::getenv("PGCONNECT_TIMEOUT")) {
    keys.push_back("connect_timeout");
    values.push_back(timeout.c_str());
  }
  if (!std::getenv("PGAPPNAME")) {
    keys.push_back("application_name");
    values.push_back("strangebeta");
  }
  keys.push_back("client_encoding");
  values.push_back("UTF8");
  // No JIT compilation (issue 34): the app's queries are short, and the
  // planner's estimates for the visibility terms of a route list (subplans
  // per row) pass jit_above_cost, so a day's report listing 10,500 routes
  // spent 3.8 s compiling against 0.4 s running. PGOPTIONS or the URL's
  // own `options` win over this.
  if (!std::getenv("PGOPTIONS")) {
    keys.push_back("options");
    values.push_back("-c jit=off");
  }
  keys.push_back("dbname");
  values.push_back(url.c_str());
  keys.push_back(nullptr);
  values.push_back(nullptr);
  PGconn* conn = PQconnectdbParams(keys.data(), values.data(), /*expand_dbname=*/1);
  if (!conn) return Status::IoError(RedactUrl(url) + ": out of memory");
  if (PQstatus(conn) != CONNECTION_OK) {
    std::string msg = Trimmed(PQerrorMessage(conn));
    PQfinish(conn);
    return Status::IoError("cannot connect to PostgreSQL at " + RedactUrl(url) + ": " + msg);
  }
  PQsetNoticeProcessor(conn, IgnoreNotice, nullptr);
  return std::unique_ptr<Connection>(std::make_unique<PgConnection>(conn));
}

}  // namespace sb::store::sql
