// store::Store written once over the SQL layer (store/sql.h): the SQLite and
// the PostgreSQL backends are this class over one driver or the other, so
// they behave the same by construction; where the dialects differ the SQL is
// chosen by `pg_`.
#include <atomic>
#include <cctype>
#include <climits>
#include <ctime>
#include <map>
#include <utility>

#include "base/log.h"
#include "store/open.h"
#include "store/schema.h"
#include "store/sql.h"
#include "store/sqlite_store.h"

namespace sb::store {

namespace {

using sql::Rows;
using sql::Value;
using sql::Violation;

std::string NowText() {
  std::time_t t = std::time(nullptr);
  std::tm tm{};
  gmtime_r(&t, &tm);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%d %H:%M:%S", &tm);
  return buf;
}

// How long throttling attempts are kept (longer than any window).
constexpr int64_t kAttemptRetentionSeconds = 24 * 3600;
// How often (in the callers' clock) a process sweeps every key's old attempts.
constexpr int64_t kAttemptSweepSeconds = 60;

// The route columns read by kSelect, in ReadRoute's order; `crdl` and
// `plan_json` (large) are read as '' where a list does not need them.
std::string SelectRoutes(bool full) {
  return std::string("SELECT r.id, r.owner_id, coalesce(u.username, ''), r.name, r.grade, ") +
         "r.setter, " + (full ? "r.crdl" : "''") +
         ", r.is_public, r.is_variation, r.params_json, " + (full ? "r.plan_json" : "''") +
         ", r.smooth, r.created_at, r.updated_at, r.move_count "
         "FROM routes r LEFT JOIN users u ON u.id = r.owner_id";
}

RouteRecord ReadRoute(const Rows& s, size_t i) {
  RouteRecord r;
  r.id = s.Int(i, 0);
  r.owner_id = s.OptInt(i, 1);
  r.owner_name = s.Text(i, 2);
  r.name = s.Text(i, 3);
  r.grade = s.Text(i, 4);
  r.setter = s.Text(i, 5);
  r.crdl = s.Text(i, 6);
  r.is_public = s.Int(i, 7) != 0;
  r.is_variation = s.Int(i, 8) != 0;
  r.params_json = s.Text(i, 9);
  r.plan_json = s.Text(i, 10);
  r.smooth = s.Int(i, 11) != 0;
  r.created_at = s.Text(i, 12);
  r.updated_at = s.Text(i, 13);
  r.move_count = static_cast<int>(s.Int(i, 14));
  return r;
}

VariationInput ReadInput(const Rows& s, size_t i, size_t first) {
  VariationInput vi;
  vi.route_id = s.OptInt(i, first);
  vi.name = s.Text(i, first + 1);
  vi.crdl = s.Text(i, first + 2);
  return vi;
}

class SqlStore final : public Store {
 public:
  explicit SqlStore(std::unique_ptr<sql::Pool> pool)
      : pool_(std::move(pool)), pg_(pool_->dialect() == sql::Dialect::kPostgres) {}

  Status Migrate() {
    SB_ASSIGN_OR_RETURN(sql::Pool::Lease c, pool_->Acquire());
    return sql::Migrate(*c);
  }

  int SchemaVersion() override {
    Result<sql::Pool::Lease> c = pool_->Acquire();
    if (!c.ok()) return 0;
    Result<int> v = (*c)->SchemaVersion();
    return v.ok() ? *v : 0;
  }

  // -- accounts -------------------------------------------------------------

  Result<int64_t> CreateUser(const std::string& username,
                             const std::string& password_hash) override {
    SB_ASSIGN_OR_RETURN(sql::Pool::Lease c, pool_->Acquire());
    Violation v;
    Result<Rows> r = c->Query(
        "INSERT INTO users(username, password_hash, created_at) VALUES(?, ?, ?) RETURNING id",
        {username, password_hash, NowText()}, &v);
    if (!r.ok() && v == Violation::kUnique) {
      return Status::Conflict("username '" + username + "' is taken");
    }
    if (!r.ok()) return r.status().WithPrefix("create user");
    return r->Int(0, 0);
  }

  Result<User> FindUserByName(const std::string& username) override {
    // SQLite's column collates NOCASE; PostgreSQL's unique index is on lower().
    return FindUserWhere(pg_ ? "lower(username) = lower(?)" : "username = ?", username,
                         "no user '" + username + "'");
  }

  Result<User> FindUser(int64_t id) override {
    return FindUserWhere("id = ?", id, "no user " + std::to_string(id));
  }

  Result<int64_t> CountUsers() override {
    SB_ASSIGN_OR_RETURN(sql::Pool::Lease c, pool_->Acquire());
    SB_ASSIGN_OR_RETURN(Rows r, c->Query("SELECT count(*) FROM users", {}));
    return r.Int(0, 0);
  }

  // -- sessions -------------------------------------------------------------

  Status CreateSession(const Session& session) override {
    SB_ASSIGN_OR_RETURN(sql::Pool::Lease c, pool_->Acquire());
    const int64_t now = std::time(nullptr);
    // Expired sessions are dropped here so the table stays small.
    SB_ASSIGN_OR_RETURN(Rows d, c->Query("DELETE FROM sessions WHERE expires_at <= ?", {now}));
    SB_ASSIGN_OR_RETURN(
        Rows r, c->Query("INSERT INTO sessions(id_hash, user_id, csrf, created_at, expires_at) "
                         "VALUES(?, ?, ?, ?, ?)",
                         {session.id_hash, session.user_id, session.csrf, now,
                          session.expires_at}));
    return Status::Ok();
  }

  Result<Session> FindSession(const std::string& id_hash, int64_t now) override {
    SB_ASSIGN_OR_RETURN(sql::Pool::Lease c, pool_->Acquire());
    SB_ASSIGN_OR_RETURN(
        Rows r, c->Query("SELECT s.id_hash, s.user_id, u.username, s.csrf, s.expires_at "
                         "FROM sessions s JOIN users u ON u.id = s.user_id "
                         "WHERE s.id_hash = ? AND s.expires_at > ?",
                         {id_hash, now}));
    if (r.empty()) return Status::NotFound("no such session");
    Session out;
    out.id_hash = r.Text(0, 0);
    out.user_id = r.Int(0, 1);
    out.username = r.Text(0, 2);
    out.csrf = r.Text(0, 3);
    out.expires_at = r.Int(0, 4);
    return out;
  }

  Status DeleteSession(const std::string& id_hash) override {
    SB_ASSIGN_OR_RETURN(sql::Pool::Lease c, pool_->Acquire());
    SB_ASSIGN_OR_RETURN(Rows r, c->Query("DELETE FROM sessions WHERE id_hash = ?", {id_hash}));
    return Status::Ok();
  }

  // -- throttling -----------------------------------------------------------

  Result<std::vector<AttemptCount>> RecordAttempts(const std::vector<std::string>& keys,
                                                   int64_t now, int64_t since) override {
    SB_ASSIGN_OR_RETURN(sql::Pool::Lease c, pool_->Acquire());
    SweepAttempts(*c, now);
    return sql::InTransaction<std::vector<AttemptCount>>(
        *c, [&]() -> Result<std::vector<AttemptCount>> {
          // Every process that counts one of these keys waits here, so N
          // concurrent attempts see the counts 1..N.
          SB_RETURN_IF_ERROR(c->LockKeys(keys));
          std::vector<AttemptCount> out;
          for (const std::string& key : keys) {
            SB_ASSIGN_OR_RETURN(Rows d, c->Query("DELETE FROM attempts WHERE key = ? AND at < ?",
                                                 {key, now - kAttemptRetentionSeconds}));
            SB_ASSIGN_OR_RETURN(
                Rows prev, c->Query("SELECT count(*), coalesce(max(at), 0) FROM attempts "
                                    "WHERE key = ? AND at >= ?",
                                    {key, since}));
            AttemptCount n;
            n.count = static_cast<int>(prev.Int(0, 0)) + 1;
            n.previous_at = prev.Int(0, 1);
            SB_ASSIGN_OR_RETURN(Rows ins,
                                c->Query("INSERT INTO attempts(key, at) VALUES(?, ?)", {key, now}));
            out.push_back(n);
          }
          return out;
        });
  }

  Status UndoAttempts(const std::vector<std::string>& keys, int64_t at) override {
    SB_ASSIGN_OR_RETURN(sql::Pool::Lease c, pool_->Acquire());
    // One row per key: SQLite names rows by rowid, PostgreSQL by ctid.
    const char* sql =
        pg_ ? "DELETE FROM attempts WHERE ctid = (SELECT ctid FROM attempts "
              "WHERE key = ? AND at = ? LIMIT 1)"
            : "DELETE FROM attempts WHERE rowid = (SELECT rowid FROM attempts "
              "WHERE key = ? AND at = ? ORDER BY rowid DESC LIMIT 1)";
    return sql::RunInTransaction(*c, [&]() -> Status {
      // Under the keys' locks, two undoing processes never pick the same row.
      SB_RETURN_IF_ERROR(c->LockKeys(keys));
      for (const std::string& key : keys) {
        SB_ASSIGN_OR_RETURN(Rows r, c->Query(sql, {key, at}));
      }
      return Status::Ok();
    });
  }

  Status ClearAttempts(const std::string& key) override {
    SB_ASSIGN_OR_RETURN(sql::Pool::Lease c, pool_->Acquire());
    SB_ASSIGN_OR_RETURN(Rows r, c->Query("DELETE FROM attempts WHERE key = ?", {key}));
    return Status::Ok();
  }

  // -- routes ---------------------------------------------------------------

  Result<int64_t> InsertRoute(const RouteRecord& route) override {
    SB_ASSIGN_OR_RETURN(sql::Pool::Lease c, pool_->Acquire());
    return sql::InTransaction<int64_t>(*c, [&] { return InsertOne(*c, route, {}); });
  }

  Result<std::vector<int64_t>> InsertRoutes(const std::vector<RouteRecord>& routes) override {
    SB_ASSIGN_OR_RETURN(sql::Pool::Lease c, pool_->Acquire());
    return sql::InTransaction<std::vector<int64_t>>(
        *c, [&]() -> Result<std::vector<int64_t>> {
          std::vector<int64_t> ids;
          ids.reserve(routes.size());
          for (const RouteRecord& r : routes) {
            SB_ASSIGN_OR_RETURN(int64_t id, InsertOne(*c, r, ids));
            ids.push_back(id);
          }
          return ids;
        });
  }

  Status UpdateRoute(const RouteRecord& route) override {
    SB_ASSIGN_OR_RETURN(sql::Pool::Lease c, pool_->Acquire());
    SB_ASSIGN_OR_RETURN(
        Rows r, c->Query("UPDATE routes SET crdl = ?, name = ?, grade = ?, setter = ?, "
                         "is_public = ?, move_count = ?, updated_at = ? WHERE id = ? RETURNING id",
                         {route.crdl, route.name, route.grade, route.setter,
                          int64_t{route.is_public}, int64_t{route.move_count}, NowText(),
                          route.id}));
    if (r.empty()) return Status::NotFound("no route " + std::to_string(route.id));
    return Status::Ok();
  }

  Status DeleteRoute(int64_t id) override {
    SB_ASSIGN_OR_RETURN(sql::Pool::Lease c, pool_->Acquire());
    SB_ASSIGN_OR_RETURN(Rows r, c->Query("DELETE FROM routes WHERE id = ? RETURNING id", {id}));
    if (r.empty()) return Status::NotFound("no route " + std::to_string(id));
    return Status::Ok();
  }

  Result<RouteRecord> GetRoute(int64_t id) override {
    SB_ASSIGN_OR_RETURN(sql::Pool::Lease c, pool_->Acquire());
    SB_ASSIGN_OR_RETURN(Rows r, c->Query(SelectRoutes(true) + " WHERE r.id = ?", {id}));
    if (r.empty()) return Status::NotFound("no route " + std::to_string(id));
    RouteRecord out = ReadRoute(r, 0);
    SB_ASSIGN_OR_RETURN(Rows in, c->Query("SELECT route_id, name, crdl FROM variation_inputs "
                                          "WHERE variation_id = ? ORDER BY position",
                                          {id}));
    for (size_t i = 0; i < in.size(); ++i) out.inputs.push_back(ReadInput(in, i, 0));
    return out;
  }

  Result<std::vector<RouteRecord>> ListRoutes(const RouteFilter& f) override {
    SB_ASSIGN_OR_RETURN(sql::Pool::Lease c, pool_->Acquire());
    // Case-insensitive substring: instr() in SQLite, strpos() in PostgreSQL.
    auto contains = [&](const std::string& hay) {
      return std::string(pg_ ? "strpos(" : "instr(") + "lower(" + hay + "), lower(?)) > 0";
    };
    std::string sql = SelectRoutes(false) + " WHERE (r.is_public = 1 OR r.owner_id = ?)";
    std::vector<Value> params = {f.viewer.value_or(-1)};
    if (!f.grade.empty()) {
      sql += " AND lower(r.grade) = lower(?)";
      params.push_back(f.grade);
    }
    if (!f.setter.empty()) {
      sql += " AND (" + contains("r.setter") + " OR " + contains("coalesce(u.username, '')") + ")";
      params.push_back(f.setter);
      params.push_back(f.setter);
    }
    if (!f.text.empty()) {
      sql += " AND (" + contains("r.name") + " OR " + contains("r.crdl") + ")";
      params.push_back(f.text);
      params.push_back(f.text);
    }
    if (f.is_variation) sql += *f.is_variation ? " AND r.is_variation = 1" : " AND r.is_variation = 0";
    sql += " ORDER BY r.id DESC LIMIT ?";
    params.push_back(int64_t{f.limit});
    SB_ASSIGN_OR_RETURN(Rows r, c->Query(sql, params));
    std::vector<RouteRecord> out;
    out.reserve(r.size());
    for (size_t i = 0; i < r.size(); ++i) out.push_back(ReadRoute(r, i));
    return out;
  }

  Result<std::vector<RouteRecord>> AllRoutes(std::optional<int64_t> owner) override {
    SB_ASSIGN_OR_RETURN(sql::Pool::Lease c, pool_->Acquire());
    std::vector<Value> params;
    std::string where;
    if (owner) {
      where = " WHERE r.owner_id = ?";
      params.push_back(*owner);
    }
    SB_ASSIGN_OR_RETURN(Rows r, c->Query(SelectRoutes(true) + where + " ORDER BY r.id", params));
    std::vector<RouteRecord> out;
    std::map<int64_t, size_t> index;
    for (size_t i = 0; i < r.size(); ++i) {
      out.push_back(ReadRoute(r, i));
      index[out.back().id] = i;
    }
    // All inputs in one query; rows of variations made since the first
    // query (PostgreSQL reads each statement's own snapshot) are ignored.
    SB_ASSIGN_OR_RETURN(
        Rows in, c->Query("SELECT i.variation_id, i.route_id, i.name, i.crdl "
                          "FROM variation_inputs i JOIN routes r ON r.id = i.variation_id" +
                              where + " ORDER BY i.variation_id, i.position",
                          params));
    for (size_t i = 0; i < in.size(); ++i) {
      auto it = index.find(in.Int(i, 0));
      if (it != index.end()) out[it->second].inputs.push_back(ReadInput(in, i, 1));
    }
    return out;
  }

 private:
  Result<User> FindUserWhere(const std::string& where, Value key, const std::string& not_found) {
    SB_ASSIGN_OR_RETURN(sql::Pool::Lease c, pool_->Acquire());
    SB_ASSIGN_OR_RETURN(
        Rows r, c->Query("SELECT id, username, password_hash, created_at FROM users WHERE " + where,
                         {std::move(key)}));
    if (r.empty()) return Status::NotFound(not_found);
    User u;
    u.id = r.Int(0, 0);
    u.username = r.Text(0, 1);
    u.password_hash = r.Text(0, 2);
    u.created_at = r.Text(0, 3);
    return u;
  }

  // Inside a transaction. `batch` = ids already inserted by this call.
  static Result<int64_t> InsertOne(sql::Connection& c, const RouteRecord& r,
                                   const std::vector<int64_t>& batch) {
    std::string now = r.created_at.empty() ? NowText() : r.created_at;
    SB_ASSIGN_OR_RETURN(
        Rows ins,
        c.Query("INSERT INTO routes(owner_id, name, grade, setter, crdl, move_count, is_public, "
                "is_variation, params_json, plan_json, smooth, created_at, updated_at) "
                "VALUES(?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?) RETURNING id",
                {sql::Nullable(r.owner_id), r.name, r.grade, r.setter, r.crdl,
                 int64_t{r.move_count}, int64_t{r.is_public}, int64_t{r.is_variation},
                 r.params_json, r.plan_json, int64_t{r.smooth}, now, now}));
    int64_t id = ins.Int(0, 0);
    for (size_t i = 0; i < r.inputs.size(); ++i) {
      const VariationInput& vi = r.inputs[i];
      std::optional<int64_t> rid = vi.route_id;
      if (vi.batch_index) {
        if (*vi.batch_index < 0 || static_cast<size_t>(*vi.batch_index) >= batch.size()) {
          return Status::InvalidInput("variation input refers to a later route of the batch");
        }
        rid = batch[*vi.batch_index];
      }
      Violation v;
      Result<Rows> in = c.Query(
          "INSERT INTO variation_inputs(variation_id, position, route_id, name, crdl) "
          "VALUES(?, ?, ?, ?, ?)",
          {id, static_cast<int64_t>(i), sql::Nullable(rid), vi.name, vi.crdl}, &v);
      if (!in.ok() && v == Violation::kForeignKey) {
        return Status::NotFound("variation input route " + std::to_string(rid.value_or(0)) +
                                " does not exist");
      }
      if (!in.ok()) return in.status().WithPrefix("insert variation input");
    }
    return id;
  }

  // Drops every key's attempts older than the retention, at most once per
  // kAttemptSweepSeconds per process, outside any transaction (on
  // PostgreSQL concurrent sweeps then never hold row locks while they wait
  // for a key lock). Hygiene only: counting drops a key's old rows itself.
  void SweepAttempts(sql::Connection& c, int64_t now) {
    int64_t last = last_sweep_.load();
    if (now - last < kAttemptSweepSeconds && now >= last) return;
    if (!last_sweep_.compare_exchange_strong(last, now)) return;
    Result<Rows> r =
        c.Query("DELETE FROM attempts WHERE at < ?", {now - kAttemptRetentionSeconds});
    if (!r.ok()) LogError("dropping old throttling attempts: " + r.status().message());
  }

  std::unique_ptr<sql::Pool> pool_;
  const bool pg_;
  std::atomic<int64_t> last_sweep_{INT64_MIN / 2};
};

bool IsSchemeChar(char c) {
  return std::isalnum(static_cast<unsigned char>(c)) || c == '+' || c == '-' || c == '.';
}

// Wraps a pool in the store and migrates it; errors name `shown`.
Result<std::unique_ptr<Store>> StoreOver(Result<std::unique_ptr<sql::Pool>> pool,
                                         const std::string& shown) {
  if (!pool.ok()) return pool.status();
  auto store = std::make_unique<SqlStore>(std::move(pool).value());
  Status st = store->Migrate();
  if (!st.ok()) {
    if (st.code() == Status::Code::kInvalidInput) return Status::InvalidInput(shown + ": " + st.message());
    return Status::IoError(shown + ": " + st.message());
  }
  return std::unique_ptr<Store>(std::move(store));
}

}  // namespace

bool IsDatabaseUrl(std::string_view db) {
  size_t colon = db.find(':');
  if (colon == std::string_view::npos || colon < 2) return false;
  if (!std::isalpha(static_cast<unsigned char>(db[0]))) return false;
  for (size_t i = 1; i < colon; ++i) {
    if (!IsSchemeChar(db[i])) return false;
  }
  return true;
}

bool IsPostgresUrl(std::string_view db) {
  return db.rfind("postgresql://", 0) == 0 || db.rfind("postgres://", 0) == 0;
}

std::string DisplayName(const std::string& db) {
  return IsDatabaseUrl(db) ? sql::RedactUrl(db) : db;
}

Result<std::unique_ptr<Store>> OpenSqliteStore(const std::string& path) {
  // One connection: SQLite has one writer at a time anyway, and callers
  // queue for it (up to a minute, as long as any import may take).
  auto pool = sql::Pool::Create([path] { return sql::OpenSqlite(path); }, 1,
                                std::chrono::milliseconds(60000));
  return StoreOver(std::move(pool), path);
}

Result<std::unique_ptr<Store>> OpenPostgresStore(const std::string& url,
                                                 const StoreOptions& options) {
  if (options.pool_size < 1 || options.pool_size > kMaxPoolSize) {
    return Status::InvalidInput("pool size: expected 1.." + std::to_string(kMaxPoolSize));
  }
  sql::PgSettings settings;
  settings.connect_timeout_seconds = options.connect_timeout_seconds;
  auto pool = sql::Pool::Create([url, settings] { return sql::OpenPostgres(url, settings); },
                                options.pool_size, std::chrono::milliseconds(options.pool_wait_ms));
  return StoreOver(std::move(pool), sql::RedactUrl(url));
}

Result<std::unique_ptr<Store>> OpenStore(const std::string& db, const StoreOptions& options) {
  if (IsPostgresUrl(db)) return OpenPostgresStore(db, options);
  if (IsDatabaseUrl(db)) {
    return Status::InvalidInput(
        "database '" + DisplayName(db) +
        "': not a PostgreSQL URL (postgresql://... or postgres://...) and not taken as a file "
        "name; write ./" + db.substr(0, db.find(':')) + ":... for a SQLite file with a colon");
  }
  return OpenSqliteStore(db);
}

}  // namespace sb::store
