// The store's SQL layer (internal to src/store): one connection interface with
// a SQLite and a PostgreSQL driver, and a bounded pool of connections.
//
// The store's logic (store/sql_store.cc), the migrations (store/schema.cc)
// and `db copy` (store/copy.cc) are written once against this interface; the
// drivers (sqlite_conn.cc, pg_conn.cc) are the only files that see SQLite or
// libpq types. SQL is written with `?` parameters (the PostgreSQL driver
// numbers them $1, $2, ...); where the two dialects must differ the caller
// asks `dialect()`.
#ifndef SB_STORE_SQL_H_
#define SB_STORE_SQL_H_

#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "base/status.h"

namespace sb::store::sql {

enum class Dialect { kSqlite, kPostgres };

// "sqlite" or "postgresql".
const char* DialectName(Dialect d);

// A statement parameter: NULL, an integer, text or a double.
using Value = std::variant<std::monostate, int64_t, std::string, double>;

// Nullable parameters.
inline Value Nullable(std::optional<int64_t> v) { return v ? Value(*v) : Value(); }
inline Value Nullable(std::optional<int> v) { return v ? Value(int64_t{*v}) : Value(); }
inline Value Nullable(std::optional<double> v) { return v ? Value(*v) : Value(); }

// A double as both drivers pass it and read it back as text: the shortest
// decimal that reads back to the same double (std::to_chars), so values
// round-trip exactly and print the same on either backend.
std::string DoubleText(double v);

// The rows of a query, every cell as text (integers in decimal) or NULL.
struct Rows {
  std::vector<std::string> columns;
  std::vector<std::vector<std::optional<std::string>>> rows;

  bool empty() const { return rows.empty(); }
  size_t size() const { return rows.size(); }
  bool IsNull(size_t row, size_t col) const { return !rows[row][col].has_value(); }
  // The cell as text ("" for NULL).
  const std::string& Text(size_t row, size_t col) const;
  // The cell as an integer (0 for NULL or non-numbers).
  int64_t Int(size_t row, size_t col) const;
  std::optional<int64_t> OptInt(size_t row, size_t col) const;
  // The cell as a double; nullopt for NULL (0 for non-numbers).
  std::optional<double> OptDouble(size_t row, size_t col) const;
};

// OK when every text parameter can be stored by both backends alike:
// well-formed UTF-8 without NUL bytes (PostgreSQL refuses anything else, so
// SQLite is held to the same rule). Errors: kInvalidInput naming the byte.
Status CheckText(const std::vector<Value>& params);

// Which constraint a failed statement broke, when it broke one.
enum class Violation { kNone, kUnique, kForeignKey };

// One database connection. Not thread-safe: one thread at a time (the pool
// hands each connection to one caller).
class Connection {
 public:
  virtual ~Connection() = default;
  virtual Dialect dialect() const = 0;

  // Runs one statement with `?` parameters and returns its rows (empty for
  // statements without results). Errors: kIoError with the database's
  // message; kInvalidInput for text CheckText refuses and values the
  // database refuses; `*violated` (when given) says which constraint failed.
  virtual Result<Rows> Query(std::string_view sql, const std::vector<Value>& params,
                             Violation* violated = nullptr) = 0;
  // Runs a script of statements without parameters (DDL, migrations).
  virtual Status Exec(std::string_view script) = 0;

  // Transactions. Begin takes the write lock at once on SQLite (BEGIN
  // IMMEDIATE), so a transaction never fails half-way for a lock it could
  // not upgrade; on PostgreSQL it is READ COMMITTED. Rollback never fails
  // (a failure is logged).
  virtual Status Begin() = 0;
  virtual Status Commit() = 0;
  virtual void Rollback() = 0;

  // Inside a transaction: serialises every transaction that locks one of
  // `keys` until it ends (across processes). PostgreSQL takes advisory
  // transaction locks in sorted order; SQLite's write lock already
  // serialises all writers, so it does nothing.
  virtual Status LockKeys(const std::vector<std::string>& keys) = 0;

  // The schema version (migrations applied); inside a migration's
  // transaction SetSchemaVersion records the next one. SQLite keeps it in
  // PRAGMA user_version, PostgreSQL in the table schema_migrations.
  virtual Result<int> SchemaVersion() = 0;
  virtual Status SetSchemaVersion(int version) = 0;
  // Brackets the migrations: SQLite turns foreign keys off (a migration may
  // rebuild a table) and checks them before each commit.
  virtual Status BeforeMigrations() = 0;
  virtual Status CheckMigration() = 0;
  virtual Status AfterMigrations() = 0;
  // The first id a new row of `table` (with an integer `id` primary key)
  // may take without reusing one ever handed out, and the means to raise it
  // (db copy carries it over so ids are never reused after a move).
  virtual Result<int64_t> NextId(const std::string& table) = 0;
  virtual Status SetNextId(const std::string& table, int64_t next) = 0;

  // The connection can no longer be used (the server went away); the pool
  // replaces it.
  virtual bool broken() const = 0;
};

// Opens a SQLite connection (creating the file when absent) with WAL,
// foreign keys on, busy_timeout 5 s. Errors: kIoError naming the path.
Result<std::unique_ptr<Connection>> OpenSqlite(const std::string& path);

// Connection settings for PostgreSQL beyond the URL.
struct PgSettings {
  // Seconds to wait for the server at connect (when neither the URL nor
  // PGCONNECT_TIMEOUT says): an unreachable server is an error at start-up.
  int connect_timeout_seconds = 10;
};

// Opens a PostgreSQL connection from a libpq URL (postgresql://... or
// postgres://...; missing parts come from the PG* environment variables and
// ~/.pgpass as libpq does). Errors: kIoError with libpq's reason and the URL
// without its password.
Result<std::unique_ptr<Connection>> OpenPostgres(const std::string& url,
                                                 const PgSettings& settings);

// The URL with any password replaced by "***" (for messages and logs).
std::string RedactUrl(const std::string& url);

// A bounded pool of connections to one database. The first connection is
// opened by Create (so a database that cannot be reached is an error at
// once), others when needed, up to `size`. Thread-safe.
class Pool {
 public:
  using Factory = std::function<Result<std::unique_ptr<Connection>>()>;

  // A connection lent to one caller; returned to the pool when destroyed.
  // Inside RunAtomically a lease borrows the thread's pinned connection
  // (owns nothing).
  class Lease {
   public:
    Lease(Pool* pool, std::unique_ptr<Connection> conn) : pool_(pool), conn_(std::move(conn)) {}
    explicit Lease(Connection* borrowed) : pool_(nullptr), borrowed_(borrowed) {}
    Lease(Lease&&) = default;
    Lease& operator=(Lease&&) = delete;
    ~Lease() {
      if (conn_) pool_->Release(std::move(conn_));
    }
    Connection* operator->() { return borrowed_ ? borrowed_ : conn_.get(); }
    Connection& operator*() { return *operator->(); }

   private:
    Pool* pool_;
    std::unique_ptr<Connection> conn_;
    Connection* borrowed_ = nullptr;
  };

  // Errors: the factory's, for the first connection.
  static Result<std::unique_ptr<Pool>> Create(Factory factory, int size,
                                              std::chrono::milliseconds wait);
  Dialect dialect() const { return dialect_; }
  // A free connection, waiting up to `wait` for one. Errors: kIoError when
  // none frees up in time or a new one cannot be opened. On a thread inside
  // RunAtomically: that call's connection, whose Begin/Commit/Rollback are
  // savepoints (a store call's own transaction nests in the outer one).
  Result<Lease> Acquire();
  // Runs `body` with every Acquire of this pool on the calling thread
  // lending one connection in one transaction: committed when `body`
  // succeeds, rolled back (nothing `body` wrote stays) when it or the commit
  // fails, returning that error. On PostgreSQL each statement outside a
  // store call's own transaction runs in a savepoint, so a statement that
  // fails (and is handled) does not end the transaction. Not reentrant: a
  // nested call runs `body` inside the outer transaction.
  Status RunAtomically(const std::function<Status()>& body);

 private:
  Pool(Factory factory, int size, std::chrono::milliseconds wait)
      : factory_(std::move(factory)), size_(size), wait_(wait) {}
  void Release(std::unique_ptr<Connection> conn);

  Factory factory_;
  const int size_;
  const std::chrono::milliseconds wait_;
  Dialect dialect_ = Dialect::kSqlite;
  std::mutex mu_;
  std::condition_variable freed_;
  std::vector<std::unique_ptr<Connection>> idle_;
  int open_ = 0;  // connections in existence (idle or lent)
};

// Runs `body` in a transaction on `c`: commits when it succeeds, rolls back
// when it (or the commit) fails and returns that error.
template <typename T, typename F>
Result<T> InTransaction(Connection& c, F&& body) {
  SB_RETURN_IF_ERROR(c.Begin());
  Result<T> r = body();
  Status st = r.ok() ? c.Commit() : r.status();
  if (!st.ok()) {
    c.Rollback();
    return st;
  }
  return r;
}

// The same for a body that returns only a Status.
template <typename F>
Status RunInTransaction(Connection& c, F&& body) {
  SB_RETURN_IF_ERROR(c.Begin());
  Status st = body();
  if (st.ok()) st = c.Commit();
  if (!st.ok()) c.Rollback();
  return st;
}

}  // namespace sb::store::sql

#endif  // SB_STORE_SQL_H_
