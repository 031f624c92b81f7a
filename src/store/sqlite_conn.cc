// The SQLite driver of the store's SQL layer (store/sql.h).
#include <sqlite3.h>

#include <map>

#include "base/log.h"
#include "store/sql.h"

namespace sb::store::sql {

namespace {

// How long a writer waits for another connection's write lock (another
// process's, or since issue 34 another of this store's connections, which
// before queued up to a minute for the store's one connection): a minute.
constexpr int kBusyTimeoutMs = 60000;

class SqliteConnection final : public Connection {
 public:
  explicit SqliteConnection(sqlite3* db) : db_(db) {}
  ~SqliteConnection() override {
    for (auto& [sql, stmt] : cache_) sqlite3_finalize(stmt);
    sqlite3_close_v2(db_);
  }

  Dialect dialect() const override { return Dialect::kSqlite; }
  bool broken() const override { return false; }

  Result<Rows> Query(std::string_view sql, const std::vector<Value>& params,
                     Violation* violated) override {
    if (violated) *violated = Violation::kNone;
    SB_RETURN_IF_ERROR(CheckText(params));
    SB_ASSIGN_OR_RETURN(sqlite3_stmt * s, Prepare(sql));
    Rows out;
    int rc = Bind(s, params);
    if (rc != SQLITE_OK) {
      sqlite3_reset(s);
      sqlite3_clear_bindings(s);
      return Status::Internal("cannot bind " + std::to_string(params.size()) +
                              " parameters to: " + std::string(sql));
    }
    {
      int n = sqlite3_column_count(s);
      for (int i = 0; i < n; ++i) out.columns.push_back(sqlite3_column_name(s, i));
      while ((rc = sqlite3_step(s)) == SQLITE_ROW) {
        std::vector<std::optional<std::string>> row(n);
        for (int i = 0; i < n; ++i) {
          int type = sqlite3_column_type(s, i);
          if (type == SQLITE_NULL) continue;
          if (type == SQLITE_FLOAT) {
            row[i] = DoubleText(sqlite3_column_double(s, i));
            continue;
          }
          const unsigned char* p = sqlite3_column_text(s, i);
          row[i] = std::string(reinterpret_cast<const char*>(p), sqlite3_column_bytes(s, i));
        }
        out.rows.push_back(std::move(row));
      }
    }
    Status st;
    if (rc != SQLITE_DONE) {
      int ext = sqlite3_extended_errcode(db_);
      if (violated && (ext == SQLITE_CONSTRAINT_UNIQUE || ext == SQLITE_CONSTRAINT_PRIMARYKEY)) {
        *violated = Violation::kUnique;
      } else if (violated && ext == SQLITE_CONSTRAINT_FOREIGNKEY) {
        *violated = Violation::kForeignKey;
      }
      st = Status::IoError(sqlite3_errmsg(db_));
    }
    sqlite3_reset(s);
    sqlite3_clear_bindings(s);
    if (!st.ok()) return st;
    return out;
  }

  Status Exec(std::string_view script) override {
    std::string sql(script);
    char* err = nullptr;
    if (sqlite3_exec(db_, sql.c_str(), nullptr, nullptr, &err) != SQLITE_OK) {
      std::string msg = err ? err : sqlite3_errmsg(db_);
      sqlite3_free(err);
      return Status::IoError(msg);
    }
    return Status::Ok();
  }

  Status Begin() override { return Exec("BEGIN IMMEDIATE"); }
  Status Commit() override { return Exec("COMMIT"); }
  void Rollback() override {
    if (sqlite3_get_autocommit(db_)) return;  // nothing open (SQLite ended it)
    Status st = Exec("ROLLBACK");
    if (!st.ok()) LogError("database rollback failed: " + st.message());
  }
  Status LockKeys(const std::vector<std::string>&) override { return Status::Ok(); }

  Result<int> SchemaVersion() override {
    SB_ASSIGN_OR_RETURN(Rows r, Query("PRAGMA user_version", {}, nullptr));
    return r.empty() ? 0 : static_cast<int>(r.Int(0, 0));
  }
  Status SetSchemaVersion(int version) override {
    return Exec("PRAGMA user_version = " + std::to_string(version));
  }
  Status BeforeMigrations() override { return Exec("PRAGMA foreign_keys = OFF"); }
  Status CheckMigration() override {
    SB_ASSIGN_OR_RETURN(Rows r, Query("PRAGMA foreign_key_check", {}, nullptr));
    if (!r.empty()) return Status::Internal("a foreign key does not hold in " + r.Text(0, 0));
    return Status::Ok();
  }
  Status AfterMigrations() override { return Exec("PRAGMA foreign_keys = ON"); }

  Result<int64_t> NextId(const std::string& table) override {
    SB_ASSIGN_OR_RETURN(Rows m, Query("SELECT max(id) FROM " + table, {}, nullptr));
    int64_t next = m.Int(0, 0) + 1;
    SB_ASSIGN_OR_RETURN(bool autoinc, IsAutoincrement(table));
    if (autoinc) {
      SB_ASSIGN_OR_RETURN(Rows s,
                          Query("SELECT seq FROM sqlite_sequence WHERE name = ?", {table}, nullptr));
      if (!s.empty()) next = std::max(next, s.Int(0, 0) + 1);
    }
    return next;
  }
  Status SetNextId(const std::string& table, int64_t next) override {
    SB_ASSIGN_OR_RETURN(bool autoinc, IsAutoincrement(table));
    if (!autoinc) return Status::Ok();  // SQLite takes max(id) + 1
    SB_ASSIGN_OR_RETURN(Rows s,
                        Query("UPDATE sqlite_sequence SET seq = ? WHERE name = ? RETURNING seq",
                              {next - 1, table}, nullptr));
    if (s.empty()) {
      SB_ASSIGN_OR_RETURN(Rows i, Query("INSERT INTO sqlite_sequence(name, seq) VALUES(?, ?)",
                                        {table, next - 1}, nullptr));
    }
    return Status::Ok();
  }

  Status Init() {
    sqlite3_extended_result_codes(db_, 1);
    SB_RETURN_IF_ERROR(Exec("PRAGMA busy_timeout = " + std::to_string(kBusyTimeoutMs)));
    // In-memory databases answer "memory"; that is fine. A database that
    // cannot switch (read-only, locked) is refused by the first write.
    SB_ASSIGN_OR_RETURN(Rows wal, Query("PRAGMA journal_mode = WAL", {}, nullptr));
    SB_RETURN_IF_ERROR(Exec("PRAGMA synchronous = NORMAL"));
    return Exec("PRAGMA foreign_keys = ON");
  }

 private:
  Result<sqlite3_stmt*> Prepare(std::string_view sql) {
    std::string key(sql);
    auto it = cache_.find(key);
    if (it != cache_.end()) return it->second;
    sqlite3_stmt* s = nullptr;
    int rc = sqlite3_prepare_v3(db_, key.data(), static_cast<int>(key.size()),
                                SQLITE_PREPARE_PERSISTENT, &s, nullptr);
    if (rc != SQLITE_OK) return Status::IoError(sqlite3_errmsg(db_));
    // Statements are few (the store's SQL is fixed text); PRAGMAs and DDL
    // are not worth keeping.
    if (key.rfind("PRAGMA", 0) == 0 || cache_.size() >= kMaxCachedStatements) {
      temporary_.reset(s);
      return s;
    }
    cache_.emplace(std::move(key), s);
    return s;
  }

  int Bind(sqlite3_stmt* s, const std::vector<Value>& params) {
    if (static_cast<int>(params.size()) != sqlite3_bind_parameter_count(s)) return SQLITE_RANGE;
    for (size_t i = 0; i < params.size(); ++i) {
      int idx = static_cast<int>(i) + 1;
      int rc = SQLITE_OK;
      if (const int64_t* v = std::get_if<int64_t>(&params[i])) {
        rc = sqlite3_bind_int64(s, idx, *v);
      } else if (const std::string* t = std::get_if<std::string>(&params[i])) {
        rc = sqlite3_bind_text64(s, idx, t->data(), t->size(), SQLITE_TRANSIENT, SQLITE_UTF8);
      } else if (const double* d = std::get_if<double>(&params[i])) {
        rc = sqlite3_bind_double(s, idx, *d);
      } else {
        rc = sqlite3_bind_null(s, idx);
      }
      if (rc != SQLITE_OK) return rc;
    }
    return SQLITE_OK;
  }

  Result<bool> IsAutoincrement(const std::string& table) {
    SB_ASSIGN_OR_RETURN(
        Rows r, Query("SELECT sql FROM sqlite_master WHERE type = 'table' AND name = ?", {table},
                      nullptr));
    return !r.empty() && r.Text(0, 0).find("AUTOINCREMENT") != std::string::npos;
  }

  struct Finalizer {
    void operator()(sqlite3_stmt* s) const { sqlite3_finalize(s); }
  };
  // Prepared statements kept for reuse (the store's SQL is a fixed set).
  static constexpr size_t kMaxCachedStatements = 256;

  sqlite3* db_;
  std::map<std::string, sqlite3_stmt*> cache_;
  std::unique_ptr<sqlite3_stmt, Finalizer> temporary_;  // the last uncached statement
};

}  // namespace

Result<std::unique_ptr<Connection>> OpenSqlite(const std::string& path) {
  sqlite3* db = nullptr;
  int rc = sqlite3_open_v2(path.c_str(), &db, SQLITE_OPEN_READWRITE | SQLITE_OPEN_CREATE, nullptr);
  if (rc != SQLITE_OK) {
    std::string msg = db ? sqlite3_errmsg(db) : "out of memory";
    sqlite3_close_v2(db);
    return Status::IoError(path + ": " + msg);
  }
  auto conn = std::make_unique<SqliteConnection>(db);
  Status st = conn->Init();
  if (!st.ok()) return Status::IoError(path + ": " + st.message());
  return std::unique_ptr<Connection>(std::move(conn));
}

}  // namespace sb::store::sql
