#include "store/sqlite_store.h"

#include <sqlite3.h>

#include <algorithm>
#include <ctime>
#include <map>
#include <mutex>
#include <string_view>
#include <utility>

#include "base/log.h"

namespace sb::store {

namespace {

// Migrations, applied in order; PRAGMA user_version holds how many ran.
// Never edit a released entry: append a new one.
const char* const kMigrations[] = {
    // 1: the base schema.
    R"sql(
CREATE TABLE users (
  id            INTEGER PRIMARY KEY,
  username      TEXT NOT NULL UNIQUE COLLATE NOCASE,
  password_hash TEXT NOT NULL,
  created_at    TEXT NOT NULL
);
CREATE TABLE sessions (
  id_hash    TEXT PRIMARY KEY,
  user_id    INTEGER NOT NULL REFERENCES users(id) ON DELETE CASCADE,
  csrf       TEXT NOT NULL,
  created_at INTEGER NOT NULL,
  expires_at INTEGER NOT NULL
);
CREATE TABLE login_failures (
  key TEXT NOT NULL,
  at  INTEGER NOT NULL
);
CREATE TABLE routes (
  id           INTEGER PRIMARY KEY,
  owner_id     INTEGER REFERENCES users(id) ON DELETE SET NULL,
  name         TEXT NOT NULL,
  grade        TEXT NOT NULL DEFAULT '',
  setter       TEXT NOT NULL DEFAULT '',
  crdl         TEXT NOT NULL,
  move_count   INTEGER NOT NULL DEFAULT 0,
  is_public    INTEGER NOT NULL DEFAULT 1,
  is_variation INTEGER NOT NULL DEFAULT 0,
  params_json  TEXT NOT NULL DEFAULT '',
  plan_json    TEXT NOT NULL DEFAULT '',
  created_at   TEXT NOT NULL,
  updated_at   TEXT NOT NULL
);
CREATE TABLE variation_inputs (
  variation_id INTEGER NOT NULL REFERENCES routes(id) ON DELETE CASCADE,
  position     INTEGER NOT NULL,
  route_id     INTEGER REFERENCES routes(id) ON DELETE SET NULL,
  name         TEXT NOT NULL,
  crdl         TEXT NOT NULL,
  PRIMARY KEY (variation_id, position)
);
)sql",
    // 2: indexes for the list filters and log-in throttling; smoothing flag.
    R"sql(
CREATE INDEX routes_owner ON routes(owner_id);
CREATE INDEX routes_public ON routes(is_public, id);
CREATE INDEX variation_inputs_route ON variation_inputs(route_id);
CREATE INDEX sessions_user ON sessions(user_id);
CREATE INDEX login_failures_key ON login_failures(key, at);
ALTER TABLE routes ADD COLUMN smooth INTEGER NOT NULL DEFAULT 0;
)sql",
    // 3: route ids are never reused (AUTOINCREMENT): a deleted private
    // variation's id can no longer name a new row that caches or links keyed
    // by id would show in its place. SQLite cannot add AUTOINCREMENT in place,
    // so the table is rebuilt (foreign keys are off while migrations run).
    // Log-in failures become throttling attempts.
    R"sql(
CREATE TABLE routes_new (
  id           INTEGER PRIMARY KEY AUTOINCREMENT,
  owner_id     INTEGER REFERENCES users(id) ON DELETE SET NULL,
  name         TEXT NOT NULL,
  grade        TEXT NOT NULL DEFAULT '',
  setter       TEXT NOT NULL DEFAULT '',
  crdl         TEXT NOT NULL,
  move_count   INTEGER NOT NULL DEFAULT 0,
  is_public    INTEGER NOT NULL DEFAULT 1,
  is_variation INTEGER NOT NULL DEFAULT 0,
  params_json  TEXT NOT NULL DEFAULT '',
  plan_json    TEXT NOT NULL DEFAULT '',
  created_at   TEXT NOT NULL,
  updated_at   TEXT NOT NULL,
  smooth       INTEGER NOT NULL DEFAULT 0
);
INSERT INTO routes_new(id, owner_id, name, grade, setter, crdl, move_count, is_public,
                       is_variation, params_json, plan_json, created_at, updated_at, smooth)
  SELECT id, owner_id, name, grade, setter, crdl, move_count, is_public, is_variation,
         params_json, plan_json, created_at, updated_at, smooth FROM routes;
DROP TABLE routes;
ALTER TABLE routes_new RENAME TO routes;
CREATE INDEX routes_owner ON routes(owner_id);
CREATE INDEX routes_public ON routes(is_public, id);
ALTER TABLE login_failures RENAME TO attempts;
)sql",
    // 4: route metadata (hold colour, wall, date set, the grade's discipline
    // and normalised value; filled by the application layer, meta_version
    // says which version filled a row), the request digest of a variation
    // (the same request twice finds the first), and every route a variation
    // was made from, transitively (the visibility rule checks them all).
    R"sql(
ALTER TABLE routes ADD COLUMN colour TEXT NOT NULL DEFAULT '';
ALTER TABLE routes ADD COLUMN wall TEXT NOT NULL DEFAULT '';
ALTER TABLE routes ADD COLUMN set_on TEXT NOT NULL DEFAULT '';
ALTER TABLE routes ADD COLUMN grade_discipline TEXT NOT NULL DEFAULT '';
ALTER TABLE routes ADD COLUMN grade_value REAL;
ALTER TABLE routes ADD COLUMN meta_version INTEGER NOT NULL DEFAULT 0;
ALTER TABLE routes ADD COLUMN request_key TEXT NOT NULL DEFAULT '';
CREATE INDEX routes_grade ON routes(grade_discipline, grade_value);
CREATE INDEX routes_request ON routes(owner_id, request_key);
CREATE TABLE route_sources (
  variation_id INTEGER NOT NULL REFERENCES routes(id) ON DELETE CASCADE,
  route_id     INTEGER NOT NULL REFERENCES routes(id) ON DELETE CASCADE,
  PRIMARY KEY (variation_id, route_id)
);
CREATE INDEX route_sources_route ON route_sources(route_id);
WITH RECURSIVE closure(variation_id, route_id) AS (
  SELECT variation_id, route_id FROM variation_inputs WHERE route_id IS NOT NULL
  UNION
  SELECT c.variation_id, vi.route_id FROM closure c
    JOIN variation_inputs vi ON vi.variation_id = c.route_id
    WHERE vi.route_id IS NOT NULL)
INSERT OR IGNORE INTO route_sources(variation_id, route_id)
  SELECT variation_id, route_id FROM closure WHERE variation_id <> route_id;
)sql",
    // 5: climbers' feedback on routes, and studies (docs/web.md). Plain SQL
    // so every backend can port it: answers are text (store::EncodeAnswers),
    // participants are token hashes, every multi-row change is one
    // transaction.
    R"sql(
CREATE TABLE feedback (
  id              INTEGER PRIMARY KEY AUTOINCREMENT,
  route_id        INTEGER NOT NULL REFERENCES routes(id) ON DELETE CASCADE,
  participant     TEXT NOT NULL,
  instrument      TEXT NOT NULL,
  answers         TEXT NOT NULL,
  felt_grade      TEXT NOT NULL DEFAULT '',
  felt_canonical  TEXT NOT NULL DEFAULT '',
  felt_discipline TEXT NOT NULL DEFAULT '',
  felt_value      DOUBLE PRECISION,
  comment         TEXT NOT NULL DEFAULT '',
  created_at      TEXT NOT NULL,
  updated_at      TEXT NOT NULL,
  UNIQUE (route_id, participant)
);
CREATE TABLE studies (
  id              INTEGER PRIMARY KEY AUTOINCREMENT,
  owner_id        INTEGER NOT NULL REFERENCES users(id) ON DELETE CASCADE,
  name            TEXT NOT NULL,
  instrument_json TEXT NOT NULL,
  demographics    INTEGER NOT NULL DEFAULT 1,
  ask_rank        INTEGER NOT NULL DEFAULT 1,
  ask_order       INTEGER NOT NULL DEFAULT 1,
  is_open         INTEGER NOT NULL DEFAULT 1,
  created_at      TEXT NOT NULL,
  updated_at      TEXT NOT NULL
);
CREATE INDEX studies_owner ON studies(owner_id, id);
CREATE TABLE study_routes (
  study_id INTEGER NOT NULL REFERENCES studies(id) ON DELETE CASCADE,
  position INTEGER NOT NULL,
  route_id INTEGER REFERENCES routes(id) ON DELETE SET NULL,
  name     TEXT NOT NULL,
  PRIMARY KEY (study_id, position)
);
CREATE INDEX study_routes_route ON study_routes(route_id);
CREATE TABLE study_responses (
  id          INTEGER PRIMARY KEY AUTOINCREMENT,
  study_id    INTEGER NOT NULL REFERENCES studies(id) ON DELETE CASCADE,
  participant TEXT NOT NULL,
  seq         INTEGER NOT NULL,
  ability     DOUBLE PRECISION,
  created_at  TEXT NOT NULL,
  UNIQUE (study_id, participant),
  UNIQUE (study_id, seq)
);
CREATE TABLE study_answers (
  response_id INTEGER NOT NULL REFERENCES study_responses(id) ON DELETE CASCADE,
  position    INTEGER NOT NULL,
  answers     TEXT NOT NULL,
  route_rank  INTEGER,
  climb_order INTEGER,
  PRIMARY KEY (response_id, position)
);
CREATE TABLE study_demographics (
  response_id INTEGER NOT NULL REFERENCES study_responses(id) ON DELETE CASCADE,
  question    TEXT NOT NULL,
  answer      TEXT NOT NULL,
  PRIMARY KEY (response_id, question)
);
)sql",
};
static_assert(sizeof(kMigrations) / sizeof(kMigrations[0]) == kSchemaVersion);

std::string NowText() {
  std::time_t t = std::time(nullptr);
  std::tm tm{};
  gmtime_r(&t, &tm);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%d %H:%M:%S", &tm);
  return buf;
}

// A prepared statement, finalised on scope exit.
class Stmt {
 public:
  Stmt(sqlite3* db, std::string_view sql) : db_(db) {
    rc_ = sqlite3_prepare_v2(db, sql.data(), static_cast<int>(sql.size()), &s_, nullptr);
  }
  ~Stmt() { sqlite3_finalize(s_); }
  Stmt(const Stmt&) = delete;
  Stmt& operator=(const Stmt&) = delete;

  bool prepared() const { return rc_ == SQLITE_OK; }
  Stmt& Bind(int i, int64_t v) {
    sqlite3_bind_int64(s_, i, v);
    return *this;
  }
  Stmt& Bind(int i, const std::string& v) {
    sqlite3_bind_text(s_, i, v.data(), static_cast<int>(v.size()), SQLITE_TRANSIENT);
    return *this;
  }
  Stmt& Bind(int i, double v) {
    sqlite3_bind_double(s_, i, v);
    return *this;
  }
  Stmt& Bind(int i, std::optional<double> v) {
    if (v) {
      sqlite3_bind_double(s_, i, *v);
    } else {
      sqlite3_bind_null(s_, i);
    }
    return *this;
  }
  Stmt& Bind(int i, std::optional<int64_t> v) {
    if (v) {
      sqlite3_bind_int64(s_, i, *v);
    } else {
      sqlite3_bind_null(s_, i);
    }
    return *this;
  }
  Stmt& Bind(int i, std::optional<int> v) {
    return Bind(i, v ? std::optional<int64_t>(*v) : std::nullopt);
  }
  // SQLITE_ROW, SQLITE_DONE or an error code.
  int Step() { return prepared() ? sqlite3_step(s_) : rc_; }
  int64_t Int(int col) { return sqlite3_column_int64(s_, col); }
  double Double(int col) { return sqlite3_column_double(s_, col); }
  std::optional<int> OptInt(int col) {
    if (IsNull(col)) return std::nullopt;
    return static_cast<int>(Int(col));
  }
  std::optional<double> OptDouble(int col) {
    if (IsNull(col)) return std::nullopt;
    return Double(col);
  }
  bool IsNull(int col) { return sqlite3_column_type(s_, col) == SQLITE_NULL; }
  std::string Text(int col) {
    const unsigned char* p = sqlite3_column_text(s_, col);
    int n = sqlite3_column_bytes(s_, col);
    return p ? std::string(reinterpret_cast<const char*>(p), n) : std::string();
  }
  Status Error(std::string_view what) const {
    return Status::IoError(std::string(what) + ": " + sqlite3_errmsg(db_));
  }

 private:
  sqlite3* db_;
  sqlite3_stmt* s_ = nullptr;
  int rc_;
};

class SqliteStore final : public Store {
 public:
  explicit SqliteStore(sqlite3* db) : db_(db) {}
  ~SqliteStore() override { sqlite3_close_v2(db_); }

  Status Init() {
    SB_RETURN_IF_ERROR(Exec("PRAGMA busy_timeout = 5000"));
    {
      // In-memory databases answer "memory"; that is fine. A database that
      // cannot switch (read-only, locked) is refused by the first write.
      Stmt s(db_, "PRAGMA journal_mode = WAL");
      if (int rc = s.Step(); rc != SQLITE_ROW && rc != SQLITE_DONE) return s.Error("journal mode");
    }
    SB_RETURN_IF_ERROR(Exec("PRAGMA synchronous = NORMAL"));
    int version = SchemaVersionLocked();
    if (version > kSchemaVersion) {
      return Status::InvalidInput("database schema version " + std::to_string(version) +
                                  " is newer than this program's (" +
                                  std::to_string(kSchemaVersion) + ")");
    }
    // Migrations that rebuild a table need foreign keys off (dropping the old
    // table must not cascade); they are checked before each commit.
    SB_RETURN_IF_ERROR(Exec("PRAGMA foreign_keys = OFF"));
    for (int v = version; v < kSchemaVersion; ++v) {
      SB_RETURN_IF_ERROR(Exec("BEGIN IMMEDIATE"));
      Status st = Exec(kMigrations[v]);
      if (st.ok()) st = ForeignKeysHold();
      if (st.ok()) st = Exec("PRAGMA user_version = " + std::to_string(v + 1));
      if (st.ok()) st = Exec("COMMIT");
      if (!st.ok()) {
        Rollback();
        return Status::IoError("migration " + std::to_string(v + 1) + ": " + st.message());
      }
    }
    return Exec("PRAGMA foreign_keys = ON");
  }

  int SchemaVersion() override {
    std::lock_guard<std::mutex> lock(mu_);
    return SchemaVersionLocked();
  }

  Result<int64_t> CreateUser(const std::string& username,
                             const std::string& password_hash) override {
    std::lock_guard<std::mutex> lock(mu_);
    Stmt s(db_, "INSERT INTO users(username, password_hash, created_at) VALUES(?,?,?)");
    s.Bind(1, username).Bind(2, password_hash).Bind(3, NowText());
    int rc = s.Step();
    if (rc == SQLITE_CONSTRAINT) return Status::Conflict("username '" + username + "' is taken");
    if (rc != SQLITE_DONE) return s.Error("create user");
    return static_cast<int64_t>(sqlite3_last_insert_rowid(db_));
  }

  Result<User> FindUserByName(const std::string& username) override {
    std::lock_guard<std::mutex> lock(mu_);
    Stmt s(db_, "SELECT id, username, password_hash, created_at FROM users WHERE username = ?");
    s.Bind(1, username);
    return ReadUser(s, "no user '" + username + "'");
  }

  Result<User> FindUser(int64_t id) override {
    std::lock_guard<std::mutex> lock(mu_);
    Stmt s(db_, "SELECT id, username, password_hash, created_at FROM users WHERE id = ?");
    s.Bind(1, id);
    return ReadUser(s, "no user " + std::to_string(id));
  }

  Result<int64_t> CountUsers() override {
    std::lock_guard<std::mutex> lock(mu_);
    Stmt s(db_, "SELECT COUNT(*) FROM users");
    if (s.Step() != SQLITE_ROW) return s.Error("count users");
    return s.Int(0);
  }

  Status CreateSession(const Session& session) override {
    std::lock_guard<std::mutex> lock(mu_);
    {
      // Expired sessions are dropped here so the table stays small.
      Stmt d(db_, "DELETE FROM sessions WHERE expires_at <= ?");
      d.Bind(1, static_cast<int64_t>(std::time(nullptr)));
      if (d.Step() != SQLITE_DONE) return d.Error("drop expired sessions");
    }
    Stmt s(db_,
           "INSERT INTO sessions(id_hash, user_id, csrf, created_at, expires_at) "
           "VALUES(?,?,?,?,?)");
    s.Bind(1, session.id_hash)
        .Bind(2, session.user_id)
        .Bind(3, session.csrf)
        .Bind(4, static_cast<int64_t>(std::time(nullptr)))
        .Bind(5, session.expires_at);
    if (s.Step() != SQLITE_DONE) return s.Error("create session");
    return Status::Ok();
  }

  Result<Session> FindSession(const std::string& id_hash, int64_t now) override {
    std::lock_guard<std::mutex> lock(mu_);
    Stmt s(db_,
           "SELECT s.id_hash, s.user_id, u.username, s.csrf, s.expires_at FROM sessions s "
           "JOIN users u ON u.id = s.user_id WHERE s.id_hash = ? AND s.expires_at > ?");
    s.Bind(1, id_hash).Bind(2, now);
    int rc = s.Step();
    if (rc == SQLITE_DONE) return Status::NotFound("no such session");
    if (rc != SQLITE_ROW) return s.Error("find session");
    Session out;
    out.id_hash = s.Text(0);
    out.user_id = s.Int(1);
    out.username = s.Text(2);
    out.csrf = s.Text(3);
    out.expires_at = s.Int(4);
    return out;
  }

  Status DeleteSession(const std::string& id_hash) override {
    std::lock_guard<std::mutex> lock(mu_);
    Stmt s(db_, "DELETE FROM sessions WHERE id_hash = ?");
    s.Bind(1, id_hash);
    if (s.Step() != SQLITE_DONE) return s.Error("delete session");
    return Status::Ok();
  }

  Result<std::vector<AttemptCount>> RecordAttempts(const std::vector<std::string>& keys,
                                                   int64_t now, int64_t since) override {
    std::lock_guard<std::mutex> lock(mu_);
    SB_RETURN_IF_ERROR(Exec("BEGIN IMMEDIATE"));
    Result<std::vector<AttemptCount>> out = RecordAttemptsLocked(keys, now, since);
    Status st = out.ok() ? Exec("COMMIT") : out.status();
    if (!st.ok()) {
      Rollback();
      return st;
    }
    return out;
  }

  Status UndoAttempts(const std::vector<std::string>& keys, int64_t at) override {
    std::lock_guard<std::mutex> lock(mu_);
    for (const std::string& key : keys) {
      Stmt s(db_,
             "DELETE FROM attempts WHERE rowid = (SELECT rowid FROM attempts WHERE key = ? AND "
             "at = ? ORDER BY rowid DESC LIMIT 1)");
      s.Bind(1, key).Bind(2, at);
      if (s.Step() != SQLITE_DONE) return s.Error("undo attempt");
    }
    return Status::Ok();
  }

  Status ClearAttempts(const std::string& key) override {
    std::lock_guard<std::mutex> lock(mu_);
    Stmt s(db_, "DELETE FROM attempts WHERE key = ?");
    s.Bind(1, key);
    if (s.Step() != SQLITE_DONE) return s.Error("clear attempts");
    return Status::Ok();
  }

  Result<int64_t> InsertRoute(const RouteRecord& route) override {
    std::lock_guard<std::mutex> lock(mu_);
    SB_RETURN_IF_ERROR(Exec("BEGIN IMMEDIATE"));
    Result<int64_t> id = InsertLocked(route, {});
    Status st = id.ok() ? Exec("COMMIT") : id.status();
    if (!st.ok()) {
      Rollback();
      return st;
    }
    return id;
  }

  Result<std::vector<int64_t>> InsertRoutes(const std::vector<RouteRecord>& routes) override {
    std::lock_guard<std::mutex> lock(mu_);
    SB_RETURN_IF_ERROR(Exec("BEGIN IMMEDIATE"));
    std::vector<int64_t> ids;
    ids.reserve(routes.size());
    Status st;
    for (const RouteRecord& r : routes) {
      Result<int64_t> id = InsertLocked(r, ids);
      if (!id.ok()) {
        st = id.status();
        break;
      }
      ids.push_back(*id);
    }
    if (st.ok()) st = Exec("COMMIT");
    if (!st.ok()) {
      Rollback();
      return st;
    }
    return ids;
  }

  Status UpdateRoute(const RouteRecord& route) override {
    std::lock_guard<std::mutex> lock(mu_);
    Stmt s(db_,
           "UPDATE routes SET crdl = ?, name = ?, grade = ?, setter = ?, is_public = ?, "
           "move_count = ?, updated_at = ?, colour = ?, wall = ?, set_on = ?, "
           "grade_discipline = ?, grade_value = ?, meta_version = ?, request_key = ? WHERE id = ?");
    s.Bind(1, route.crdl)
        .Bind(2, route.name)
        .Bind(3, route.grade)
        .Bind(4, route.setter)
        .Bind(5, static_cast<int64_t>(route.is_public))
        .Bind(6, static_cast<int64_t>(route.move_count))
        .Bind(7, NowText())
        .Bind(8, route.colour)
        .Bind(9, route.wall)
        .Bind(10, route.set_on)
        .Bind(11, route.grade_discipline)
        .Bind(12, route.grade_value)
        .Bind(13, static_cast<int64_t>(route.meta_version))
        .Bind(14, route.request_key)
        .Bind(15, route.id);
    if (s.Step() != SQLITE_DONE) return s.Error("update route");
    if (sqlite3_changes(db_) == 0) return Status::NotFound("no route " + std::to_string(route.id));
    return Status::Ok();
  }

  Status UpdateRouteMetadata(const RouteRecord& route) override {
    std::lock_guard<std::mutex> lock(mu_);
    Stmt s(db_,
           "UPDATE routes SET name = ?, grade = ?, setter = ?, colour = ?, wall = ?, set_on = ?, "
           "grade_discipline = ?, grade_value = ?, meta_version = ? WHERE id = ?");
    s.Bind(1, route.name)
        .Bind(2, route.grade)
        .Bind(3, route.setter)
        .Bind(4, route.colour)
        .Bind(5, route.wall)
        .Bind(6, route.set_on)
        .Bind(7, route.grade_discipline)
        .Bind(8, route.grade_value)
        .Bind(9, static_cast<int64_t>(route.meta_version))
        .Bind(10, route.id);
    if (s.Step() != SQLITE_DONE) return s.Error("update route metadata");
    if (sqlite3_changes(db_) == 0) return Status::NotFound("no route " + std::to_string(route.id));
    return Status::Ok();
  }

  Status DeleteRoute(int64_t id) override {
    std::lock_guard<std::mutex> lock(mu_);
    Stmt s(db_, "DELETE FROM routes WHERE id = ?");
    s.Bind(1, id);
    if (s.Step() != SQLITE_DONE) return s.Error("delete route");
    if (sqlite3_changes(db_) == 0) return Status::NotFound("no route " + std::to_string(id));
    return Status::Ok();
  }

  Result<RouteRecord> GetRoute(int64_t id) override {
    std::lock_guard<std::mutex> lock(mu_);
    std::string sql = std::string(kSelect) + " WHERE r.id = ?";
    Stmt s(db_, sql);
    s.Bind(1, id);
    int rc = s.Step();
    if (rc == SQLITE_DONE) return Status::NotFound("no route " + std::to_string(id));
    if (rc != SQLITE_ROW) return s.Error("get route");
    RouteRecord r = ReadRoute(s, true);
    SB_RETURN_IF_ERROR(ReadLinks(&r));
    return r;
  }

  Result<std::vector<RouteRecord>> ListRoutes(const RouteFilter& f) override {
    std::lock_guard<std::mutex> lock(mu_);
    Where w = FilterWhere(f);
    size_t n = 2 + w.texts.size() + w.numbers.size();
    std::string sql = std::string(kSelect) + w.sql + OrderBy(f.sort) + " LIMIT ?" +
                      std::to_string(n) + " OFFSET ?" + std::to_string(n + 1);
    Stmt s(db_, sql);
    BindWhere(s, f, w);
    s.Bind(static_cast<int>(n), static_cast<int64_t>(std::max(0, f.limit)));
    s.Bind(static_cast<int>(n + 1), static_cast<int64_t>(std::max(0, f.offset)));
    std::vector<RouteRecord> out;
    int rc;
    while ((rc = s.Step()) == SQLITE_ROW) out.push_back(ReadRoute(s, false));
    if (rc != SQLITE_DONE) return s.Error("list routes");
    return out;
  }

  Result<int64_t> CountRoutes(const RouteFilter& f) override {
    std::lock_guard<std::mutex> lock(mu_);
    Where w = FilterWhere(f);
    Stmt s(db_, "SELECT COUNT(*) FROM routes r LEFT JOIN users u ON u.id = r.owner_id" + w.sql);
    BindWhere(s, f, w);
    if (s.Step() != SQLITE_ROW) return s.Error("count routes");
    return s.Int(0);
  }

  Result<int64_t> FindVariationByKey(int64_t owner, const std::string& request_key) override {
    std::lock_guard<std::mutex> lock(mu_);
    Stmt s(db_,
           "SELECT id FROM routes WHERE owner_id = ? AND request_key = ? AND request_key <> '' "
           "AND is_variation = 1 ORDER BY id DESC LIMIT 1");
    s.Bind(1, owner).Bind(2, request_key);
    int rc = s.Step();
    if (rc == SQLITE_DONE) return Status::NotFound("no such variation");
    if (rc != SQLITE_ROW) return s.Error("find variation");
    return s.Int(0);
  }

  Result<std::vector<RouteRecord>> AllRoutes(std::optional<int64_t> owner) override {
    std::lock_guard<std::mutex> lock(mu_);
    std::string sql = std::string(kSelect);
    if (owner) sql += " WHERE r.owner_id = ?1";
    sql += " ORDER BY r.id";
    Stmt s(db_, sql);
    if (owner) s.Bind(1, *owner);
    std::vector<RouteRecord> out;
    int rc;
    while ((rc = s.Step()) == SQLITE_ROW) out.push_back(ReadRoute(s, true));
    if (rc != SQLITE_DONE) return s.Error("all routes");
    for (RouteRecord& r : out) SB_RETURN_IF_ERROR(ReadLinks(&r));
    return out;
  }

  // ---- climbers' feedback ----------------------------------------------------

  Result<int64_t> PutFeedback(const FeedbackRecord& f) override {
    std::lock_guard<std::mutex> lock(mu_);
    std::string now = NowText();
    // One statement, so a concurrent submission of the same participant
    // cannot make a second row (UNIQUE (route_id, participant)).
    Stmt s(db_,
           "INSERT INTO feedback(route_id, participant, instrument, answers, felt_grade, "
           "felt_canonical, felt_discipline, felt_value, comment, created_at, updated_at) "
           "VALUES(?,?,?,?,?,?,?,?,?,?,?) ON CONFLICT(route_id, participant) DO UPDATE SET "
           "instrument = excluded.instrument, answers = excluded.answers, "
           "felt_grade = excluded.felt_grade, felt_canonical = excluded.felt_canonical, "
           "felt_discipline = excluded.felt_discipline, felt_value = excluded.felt_value, "
           "comment = excluded.comment, updated_at = excluded.updated_at");
    s.Bind(1, f.route_id)
        .Bind(2, f.participant)
        .Bind(3, f.instrument)
        .Bind(4, EncodeAnswers(f.answers))
        .Bind(5, f.felt_grade)
        .Bind(6, f.felt_canonical)
        .Bind(7, f.felt_discipline)
        .Bind(8, f.felt_value)
        .Bind(9, f.comment)
        .Bind(10, now)
        .Bind(11, now);
    int rc = s.Step();
    if (rc == SQLITE_CONSTRAINT) {
      return Status::NotFound("no route " + std::to_string(f.route_id));
    }
    if (rc != SQLITE_DONE) return s.Error("put feedback");
    Stmt id(db_, "SELECT id FROM feedback WHERE route_id = ? AND participant = ?");
    id.Bind(1, f.route_id).Bind(2, f.participant);
    if (id.Step() != SQLITE_ROW) return id.Error("put feedback");
    return id.Int(0);
  }

  Result<std::optional<FeedbackRecord>> FindFeedback(int64_t route_id,
                                                     const std::string& participant) override {
    std::lock_guard<std::mutex> lock(mu_);
    Stmt s(db_, std::string(kFeedbackSelect) + " WHERE route_id = ? AND participant = ?");
    s.Bind(1, route_id).Bind(2, participant);
    SB_ASSIGN_OR_RETURN(std::vector<FeedbackRecord> rows, ReadFeedbackRows(s));
    if (rows.empty()) return std::optional<FeedbackRecord>();
    return std::optional<FeedbackRecord>(std::move(rows[0]));
  }

  Result<std::vector<FeedbackRecord>> ListFeedback(int64_t route_id) override {
    std::lock_guard<std::mutex> lock(mu_);
    Stmt s(db_, std::string(kFeedbackSelect) + " WHERE route_id = ? ORDER BY id");
    s.Bind(1, route_id);
    return ReadFeedbackRows(s);
  }

  Result<std::vector<FeedbackRecord>> FeedbackOnRoutesOf(int64_t owner_id) override {
    std::lock_guard<std::mutex> lock(mu_);
    Stmt s(db_, std::string(kFeedbackSelect) +
                    " WHERE route_id IN (SELECT id FROM routes WHERE owner_id = ?) "
                    "ORDER BY route_id, id");
    s.Bind(1, owner_id);
    return ReadFeedbackRows(s);
  }

  // ---- studies ---------------------------------------------------------------

  Result<int64_t> InsertStudy(const StudyRecord& st) override {
    std::lock_guard<std::mutex> lock(mu_);
    SB_RETURN_IF_ERROR(Exec("BEGIN IMMEDIATE"));
    Result<int64_t> id = InsertStudyLocked(st);
    Status done = id.ok() ? Exec("COMMIT") : id.status();
    if (!done.ok()) {
      Rollback();
      return done;
    }
    return id;
  }

  Status UpdateStudy(const StudyRecord& st, bool definition_changes) override {
    std::lock_guard<std::mutex> lock(mu_);
    SB_RETURN_IF_ERROR(Exec("BEGIN IMMEDIATE"));
    Status done = UpdateStudyLocked(st, definition_changes);
    if (done.ok()) done = Exec("COMMIT");
    if (!done.ok()) Rollback();
    return done;
  }

  Result<StudyRecord> GetStudy(int64_t id) override {
    std::lock_guard<std::mutex> lock(mu_);
    Stmt s(db_, std::string(kStudySelect) + " WHERE s.id = ?");
    s.Bind(1, id);
    SB_ASSIGN_OR_RETURN(std::vector<StudyRecord> rows, ReadStudies(s));
    if (rows.empty()) return Status::NotFound("no study " + std::to_string(id));
    return std::move(rows[0]);
  }

  Result<std::vector<StudyRecord>> ListStudies(int64_t owner_id) override {
    std::lock_guard<std::mutex> lock(mu_);
    Stmt s(db_, std::string(kStudySelect) + " WHERE s.owner_id = ? ORDER BY s.id DESC");
    s.Bind(1, owner_id);
    return ReadStudies(s);
  }

  Result<int> InsertStudyResponse(const StudyResponseRecord& r, int max_responses) override {
    std::lock_guard<std::mutex> lock(mu_);
    SB_RETURN_IF_ERROR(Exec("BEGIN IMMEDIATE"));
    Result<int> seq = InsertStudyResponseLocked(r, max_responses);
    Status done = seq.ok() ? Exec("COMMIT") : seq.status();
    if (!done.ok()) {
      Rollback();
      return done;
    }
    return seq;
  }

  Result<bool> HasStudyResponse(int64_t study_id, const std::string& participant) override {
    std::lock_guard<std::mutex> lock(mu_);
    Stmt s(db_, "SELECT 1 FROM study_responses WHERE study_id = ? AND participant = ?");
    s.Bind(1, study_id).Bind(2, participant);
    int rc = s.Step();
    if (rc == SQLITE_ROW) return true;
    if (rc == SQLITE_DONE) return false;
    return s.Error("find study response");
  }

  Result<std::vector<StudyResponseRecord>> ListStudyResponses(int64_t study_id) override {
    std::lock_guard<std::mutex> lock(mu_);
    std::vector<StudyResponseRecord> out;
    std::map<int64_t, size_t> index;  // response id -> position in out
    {
      Stmt s(db_,
             "SELECT id, study_id, participant, seq, ability, created_at FROM study_responses "
             "WHERE study_id = ? ORDER BY seq");
      s.Bind(1, study_id);
      int rc;
      while ((rc = s.Step()) == SQLITE_ROW) {
        StudyResponseRecord r;
        r.id = s.Int(0);
        r.study_id = s.Int(1);
        r.participant = s.Text(2);
        r.seq = static_cast<int>(s.Int(3));
        r.ability = s.OptDouble(4);
        r.created_at = s.Text(5);
        index[r.id] = out.size();
        out.push_back(std::move(r));
      }
      if (rc != SQLITE_DONE) return s.Error("list study responses");
    }
    Stmt a(db_,
           "SELECT a.response_id, a.position, a.answers, a.route_rank, a.climb_order "
           "FROM study_answers a JOIN study_responses r ON r.id = a.response_id "
           "WHERE r.study_id = ? ORDER BY a.response_id, a.position");
    a.Bind(1, study_id);
    int rc;
    while ((rc = a.Step()) == SQLITE_ROW) {
      auto it = index.find(a.Int(0));
      if (it == index.end()) continue;
      StudyAnswer ans;
      ans.position = static_cast<int>(a.Int(1));
      Result<Answers> decoded = DecodeAnswers(a.Text(2));
      if (!decoded.ok())
        return Status::IoError("study " + std::to_string(study_id) + ": " +
                               decoded.status().message());
      ans.answers = std::move(decoded).value();
      ans.rank = a.OptInt(3);
      ans.order = a.OptInt(4);
      out[it->second].answers.push_back(std::move(ans));
    }
    if (rc != SQLITE_DONE) return a.Error("list study answers");
    Stmt d(db_,
           "SELECT d.response_id, d.question, d.answer FROM study_demographics d "
           "JOIN study_responses r ON r.id = d.response_id WHERE r.study_id = ? "
           "ORDER BY d.response_id, d.question");
    d.Bind(1, study_id);
    while ((rc = d.Step()) == SQLITE_ROW) {
      auto it = index.find(d.Int(0));
      if (it != index.end()) out[it->second].demographics.emplace_back(d.Text(1), d.Text(2));
    }
    if (rc != SQLITE_DONE) return d.Error("list study demographics");
    return out;
  }

 private:
  static constexpr const char* kSelect =
      "SELECT r.id, r.owner_id, COALESCE(u.username, ''), r.name, r.grade, r.setter, r.crdl, "
      "r.is_public, r.is_variation, r.params_json, r.plan_json, r.smooth, r.created_at, "
      "r.updated_at, r.move_count, r.colour, r.wall, r.set_on, r.grade_discipline, "
      "r.grade_value, r.meta_version, r.request_key "
      "FROM routes r LEFT JOIN users u ON u.id = r.owner_id";

  // The visibility rule in SQL (?1 = the viewer, -1 for none): the row is
  // public or the viewer's, and so is every route it was made from. The
  // application layer's app::IsVisible is the same rule over RouteRecord.
  static constexpr const char* kVisible =
      "(r.is_public = 1 OR r.owner_id = ?1) AND NOT EXISTS (SELECT 1 FROM route_sources s "
      "JOIN routes src ON src.id = s.route_id WHERE s.variation_id = r.id AND src.is_public = 0 "
      "AND (src.owner_id IS NULL OR src.owner_id <> ?1))";

  static RouteRecord ReadRoute(Stmt& s, bool full) {
    RouteRecord r;
    r.id = s.Int(0);
    if (!s.IsNull(1)) r.owner_id = s.Int(1);
    r.owner_name = s.Text(2);
    r.name = s.Text(3);
    r.grade = s.Text(4);
    r.setter = s.Text(5);
    if (full) r.crdl = s.Text(6);
    r.is_public = s.Int(7) != 0;
    r.is_variation = s.Int(8) != 0;
    r.params_json = s.Text(9);
    if (full) r.plan_json = s.Text(10);
    r.smooth = s.Int(11) != 0;
    r.created_at = s.Text(12);
    r.updated_at = s.Text(13);
    r.move_count = static_cast<int>(s.Int(14));
    r.colour = s.Text(15);
    r.wall = s.Text(16);
    r.set_on = s.Text(17);
    r.grade_discipline = s.Text(18);
    if (!s.IsNull(19)) r.grade_value = s.Double(19);
    r.meta_version = static_cast<int>(s.Int(20));
    r.request_key = s.Text(21);
    return r;
  }

  // Inputs and sources of a variation (no-op for routes).
  Status ReadLinks(RouteRecord* r) {
    if (!r->is_variation) return Status::Ok();
    Stmt in(db_,
            "SELECT route_id, name, crdl FROM variation_inputs WHERE variation_id = ? "
            "ORDER BY position");
    in.Bind(1, r->id);
    int rc;
    while ((rc = in.Step()) == SQLITE_ROW) {
      VariationInput vi;
      if (!in.IsNull(0)) vi.route_id = in.Int(0);
      vi.name = in.Text(1);
      vi.crdl = in.Text(2);
      r->inputs.push_back(std::move(vi));
    }
    if (rc != SQLITE_DONE) return in.Error("get variation inputs");
    Stmt src(db_,
             "SELECT src.id, src.is_public, src.owner_id FROM route_sources s JOIN routes src "
             "ON src.id = s.route_id WHERE s.variation_id = ? ORDER BY src.id");
    src.Bind(1, r->id);
    while ((rc = src.Step()) == SQLITE_ROW) {
      SourceRoute sr;
      sr.route_id = src.Int(0);
      sr.is_public = src.Int(1) != 0;
      if (!src.IsNull(2)) sr.owner_id = src.Int(2);
      r->sources.push_back(sr);
    }
    if (rc != SQLITE_DONE) return src.Error("get variation sources");
    return Status::Ok();
  }

  // The WHERE clause and its bound values of a route filter (parameter 1 is
  // the viewer; the others are numbered from 2).
  struct Where {
    std::string sql;
    std::vector<std::string> texts;  // bound as ?2, ?3, ... in order
    std::vector<double> numbers;     // bound after the texts
  };
  static Where FilterWhere(const RouteFilter& f) {
    Where w;
    w.sql = std::string(" WHERE ") + kVisible;
    auto text = [&](const std::string& v) {
      w.texts.push_back(v);
      return "?" + std::to_string(1 + w.texts.size());
    };
    if (!f.grade.empty()) w.sql += " AND r.grade = " + text(f.grade) + " COLLATE NOCASE";
    if (!f.setter.empty()) {
      std::string p = text(f.setter);
      w.sql += " AND (instr(lower(r.setter), lower(" + p + ")) > 0 OR instr(lower(ifnull(" +
               "u.username,'')), lower(" + p + ")) > 0)";
    }
    if (!f.text.empty()) {
      std::string p = text(f.text);
      w.sql += " AND (instr(lower(r.name), lower(" + p + ")) > 0 OR instr(lower(r.crdl), lower(" +
               p + ")) > 0 OR instr(lower(ifnull(u.username,'')), lower(" + p + ")) > 0)";
    }
    if (!f.wall.empty()) w.sql += " AND instr(lower(r.wall), lower(" + text(f.wall) + ")) > 0";
    if (f.is_variation) {
      w.sql += *f.is_variation ? " AND r.is_variation = 1" : " AND r.is_variation = 0";
    }
    if (f.owner) w.sql += " AND r.owner_id = " + std::to_string(*f.owner);
    if (!f.grade_discipline.empty()) {
      w.sql += " AND r.grade_discipline = " + text(f.grade_discipline) +
               " AND r.grade_value IS NOT NULL";
      size_t first = 2 + w.texts.size();
      if (f.grade_min) {
        w.sql += " AND r.grade_value >= ?" + std::to_string(first + w.numbers.size());
        w.numbers.push_back(*f.grade_min);
      }
      if (f.grade_max) {
        w.sql += " AND r.grade_value <= ?" + std::to_string(first + w.numbers.size());
        w.numbers.push_back(*f.grade_max);
      }
    }
    return w;
  }
  static void BindWhere(Stmt& s, const RouteFilter& f, const Where& w) {
    s.Bind(1, f.viewer.value_or(-1));
    int i = 2;
    for (const std::string& t : w.texts) s.Bind(i++, t);
    for (double d : w.numbers) s.Bind(i++, d);
  }
  static const char* OrderBy(RouteSort sort) {
    switch (sort) {
      case RouteSort::kNewest: return " ORDER BY r.id DESC";
      case RouteSort::kOldest: return " ORDER BY r.id ASC";
      case RouteSort::kName: return " ORDER BY r.name COLLATE NOCASE, r.id";
      case RouteSort::kEasiest:
        return " ORDER BY (r.grade_value IS NULL), r.grade_discipline, r.grade_value, r.id";
      case RouteSort::kHardest:
        return " ORDER BY (r.grade_value IS NULL), r.grade_discipline, r.grade_value DESC, r.id";
    }
    return " ORDER BY r.id DESC";
  }

  static constexpr const char* kFeedbackSelect =
      "SELECT id, route_id, participant, instrument, answers, felt_grade, felt_canonical, "
      "felt_discipline, felt_value, comment, created_at, updated_at FROM feedback";

  static Result<std::vector<FeedbackRecord>> ReadFeedbackRows(Stmt& s) {
    std::vector<FeedbackRecord> out;
    int rc;
    while ((rc = s.Step()) == SQLITE_ROW) {
      FeedbackRecord f;
      f.id = s.Int(0);
      f.route_id = s.Int(1);
      f.participant = s.Text(2);
      f.instrument = s.Text(3);
      Result<Answers> answers = DecodeAnswers(s.Text(4));
      if (!answers.ok()) {
        return Status::IoError("feedback " + std::to_string(f.id) + ": " +
                               answers.status().message());
      }
      f.answers = std::move(answers).value();
      f.felt_grade = s.Text(5);
      f.felt_canonical = s.Text(6);
      f.felt_discipline = s.Text(7);
      f.felt_value = s.OptDouble(8);
      f.comment = s.Text(9);
      f.created_at = s.Text(10);
      f.updated_at = s.Text(11);
      out.push_back(std::move(f));
    }
    if (rc != SQLITE_DONE) return s.Error("read feedback");
    return out;
  }

  static constexpr const char* kStudySelect =
      "SELECT s.id, s.owner_id, COALESCE(u.username, ''), s.name, s.instrument_json, "
      "s.demographics, s.ask_rank, s.ask_order, s.is_open, s.created_at, s.updated_at, "
      "(SELECT COUNT(*) FROM study_responses r WHERE r.study_id = s.id) "
      "FROM studies s LEFT JOIN users u ON u.id = s.owner_id";

  // The studies of a prepared kStudySelect, with their routes.
  Result<std::vector<StudyRecord>> ReadStudies(Stmt& s) {
    std::vector<StudyRecord> out;
    int rc;
    while ((rc = s.Step()) == SQLITE_ROW) {
      StudyRecord st;
      st.id = s.Int(0);
      st.owner_id = s.Int(1);
      st.owner_name = s.Text(2);
      st.name = s.Text(3);
      st.instrument_json = s.Text(4);
      st.demographics = s.Int(5) != 0;
      st.ask_rank = s.Int(6) != 0;
      st.ask_order = s.Int(7) != 0;
      st.is_open = s.Int(8) != 0;
      st.created_at = s.Text(9);
      st.updated_at = s.Text(10);
      st.responses = static_cast<int>(s.Int(11));
      out.push_back(std::move(st));
    }
    if (rc != SQLITE_DONE) return s.Error("read studies");
    for (StudyRecord& st : out) {
      Stmt r(db_,
             "SELECT position, route_id, name FROM study_routes WHERE study_id = ? "
             "ORDER BY position");
      r.Bind(1, st.id);
      while ((rc = r.Step()) == SQLITE_ROW) {
        StudyRoute sr;
        sr.position = static_cast<int>(r.Int(0));
        if (!r.IsNull(1)) sr.route_id = r.Int(1);
        sr.name = r.Text(2);
        st.routes.push_back(std::move(sr));
      }
      if (rc != SQLITE_DONE) return r.Error("read study routes");
    }
    return out;
  }

  // Inside a transaction: the study's routes replace any stored ones.
  Status WriteStudyRoutes(int64_t study_id, const std::vector<StudyRoute>& routes) {
    Stmt d(db_, "DELETE FROM study_routes WHERE study_id = ?");
    d.Bind(1, study_id);
    if (d.Step() != SQLITE_DONE) return d.Error("replace study routes");
    for (const StudyRoute& sr : routes) {
      Stmt in(db_, "INSERT INTO study_routes(study_id, position, route_id, name) VALUES(?,?,?,?)");
      in.Bind(1, study_id)
          .Bind(2, static_cast<int64_t>(sr.position))
          .Bind(3, sr.route_id)
          .Bind(4, sr.name);
      int rc = in.Step();
      if (rc == SQLITE_CONSTRAINT) {
        return Status::InvalidInput("study routes: position " + std::to_string(sr.position) +
                                    " twice or route " + std::to_string(sr.route_id.value_or(0)) +
                                    " unknown");
      }
      if (rc != SQLITE_DONE) return in.Error("insert study route");
    }
    return Status::Ok();
  }

  Result<int64_t> InsertStudyLocked(const StudyRecord& st) {
    std::string now = NowText();
    Stmt s(db_,
           "INSERT INTO studies(owner_id, name, instrument_json, demographics, ask_rank, "
           "ask_order, is_open, created_at, updated_at) VALUES(?,?,?,?,?,?,?,?,?)");
    s.Bind(1, st.owner_id)
        .Bind(2, st.name)
        .Bind(3, st.instrument_json)
        .Bind(4, static_cast<int64_t>(st.demographics))
        .Bind(5, static_cast<int64_t>(st.ask_rank))
        .Bind(6, static_cast<int64_t>(st.ask_order))
        .Bind(7, static_cast<int64_t>(st.is_open))
        .Bind(8, now)
        .Bind(9, now);
    int rc = s.Step();
    if (rc == SQLITE_CONSTRAINT) return Status::NotFound("no user " + std::to_string(st.owner_id));
    if (rc != SQLITE_DONE) return s.Error("insert study");
    int64_t id = sqlite3_last_insert_rowid(db_);
    SB_RETURN_IF_ERROR(WriteStudyRoutes(id, st.routes));
    return id;
  }

  Status UpdateStudyLocked(const StudyRecord& st, bool definition_changes) {
    Stmt c(db_,
           "SELECT (SELECT COUNT(*) FROM study_responses WHERE study_id = s.id) FROM studies s "
           "WHERE s.id = ?");
    c.Bind(1, st.id);
    int rc = c.Step();
    if (rc == SQLITE_DONE) return Status::NotFound("no study " + std::to_string(st.id));
    if (rc != SQLITE_ROW) return c.Error("update study");
    if (definition_changes && c.Int(0) > 0) {
      return Status::Conflict(
          "the study has responses: its routes, instrument and questions can no longer change");
    }
    Stmt s(db_,
           "UPDATE studies SET name = ?, instrument_json = ?, demographics = ?, ask_rank = ?, "
           "ask_order = ?, is_open = ?, updated_at = ? WHERE id = ?");
    s.Bind(1, st.name)
        .Bind(2, st.instrument_json)
        .Bind(3, static_cast<int64_t>(st.demographics))
        .Bind(4, static_cast<int64_t>(st.ask_rank))
        .Bind(5, static_cast<int64_t>(st.ask_order))
        .Bind(6, static_cast<int64_t>(st.is_open))
        .Bind(7, NowText())
        .Bind(8, st.id);
    if (s.Step() != SQLITE_DONE) return s.Error("update study");
    if (definition_changes) SB_RETURN_IF_ERROR(WriteStudyRoutes(st.id, st.routes));
    return Status::Ok();
  }

  Result<int> InsertStudyResponseLocked(const StudyResponseRecord& r, int max_responses) {
    Stmt c(db_,
           "SELECT s.is_open, (SELECT COUNT(*) FROM study_responses WHERE study_id = s.id), "
           "(SELECT COALESCE(MAX(seq), 0) FROM study_responses WHERE study_id = s.id), "
           "(SELECT COUNT(*) FROM study_responses WHERE study_id = s.id AND participant = ?) "
           "FROM studies s WHERE s.id = ?");
    c.Bind(1, r.participant).Bind(2, r.study_id);
    int rc = c.Step();
    if (rc == SQLITE_DONE) return Status::NotFound("no study " + std::to_string(r.study_id));
    if (rc != SQLITE_ROW) return c.Error("insert study response");
    if (c.Int(0) == 0) return Status::Conflict("this study is closed");
    if (c.Int(3) > 0) return Status::Conflict("you have already answered this study");
    if (c.Int(1) >= max_responses) {
      return Status::Conflict("this study has reached its limit of " +
                              std::to_string(max_responses) + " responses");
    }
    int seq = static_cast<int>(c.Int(2)) + 1;
    Stmt s(db_,
           "INSERT INTO study_responses(study_id, participant, seq, ability, created_at) "
           "VALUES(?,?,?,?,?)");
    s.Bind(1, r.study_id)
        .Bind(2, r.participant)
        .Bind(3, static_cast<int64_t>(seq))
        .Bind(4, r.ability)
        .Bind(5, NowText());
    rc = s.Step();
    if (rc == SQLITE_CONSTRAINT) return Status::Conflict("you have already answered this study");
    if (rc != SQLITE_DONE) return s.Error("insert study response");
    int64_t id = sqlite3_last_insert_rowid(db_);
    for (const StudyAnswer& a : r.answers) {
      Stmt in(db_,
              "INSERT INTO study_answers(response_id, position, answers, route_rank, climb_order) "
              "VALUES(?,?,?,?,?)");
      in.Bind(1, id)
          .Bind(2, static_cast<int64_t>(a.position))
          .Bind(3, EncodeAnswers(a.answers))
          .Bind(4, a.rank)
          .Bind(5, a.order);
      rc = in.Step();
      if (rc == SQLITE_CONSTRAINT) {
        return Status::InvalidInput("route " + std::to_string(a.position) + " answered twice");
      }
      if (rc != SQLITE_DONE) return in.Error("insert study answers");
    }
    for (const auto& [question, answer] : r.demographics) {
      Stmt in(db_, "INSERT INTO study_demographics(response_id, question, answer) VALUES(?,?,?)");
      in.Bind(1, id).Bind(2, question).Bind(3, answer);
      rc = in.Step();
      if (rc == SQLITE_CONSTRAINT) {
        return Status::InvalidInput(question + ": answered twice");
      }
      if (rc != SQLITE_DONE) return in.Error("insert study demographics");
    }
    return seq;
  }

  Result<User> ReadUser(Stmt& s, const std::string& not_found) {
    int rc = s.Step();
    if (rc == SQLITE_DONE) return Status::NotFound(not_found);
    if (rc != SQLITE_ROW) return s.Error("find user");
    User u;
    u.id = s.Int(0);
    u.username = s.Text(1);
    u.password_hash = s.Text(2);
    u.created_at = s.Text(3);
    return u;
  }

  // Inside a transaction. `batch` = ids already inserted by this call.
  Result<int64_t> InsertLocked(const RouteRecord& r, const std::vector<int64_t>& batch) {
    std::string now = r.created_at.empty() ? NowText() : r.created_at;
    Stmt s(db_,
           "INSERT INTO routes(owner_id, name, grade, setter, crdl, move_count, is_public, "
           "is_variation, params_json, plan_json, smooth, created_at, updated_at, colour, wall, "
           "set_on, grade_discipline, grade_value, meta_version, request_key) "
           "VALUES(?,?,?,?,?,?,?,?,?,?,?,?,?,?,?,?,?,?,?,?)");
    s.Bind(1, r.owner_id)
        .Bind(2, r.name)
        .Bind(3, r.grade)
        .Bind(4, r.setter)
        .Bind(5, r.crdl)
        .Bind(6, static_cast<int64_t>(r.move_count))
        .Bind(7, static_cast<int64_t>(r.is_public))
        .Bind(8, static_cast<int64_t>(r.is_variation))
        .Bind(9, r.params_json)
        .Bind(10, r.plan_json)
        .Bind(11, static_cast<int64_t>(r.smooth))
        .Bind(12, now)
        .Bind(13, now)
        .Bind(14, r.colour)
        .Bind(15, r.wall)
        .Bind(16, r.set_on)
        .Bind(17, r.grade_discipline)
        .Bind(18, r.grade_value)
        .Bind(19, static_cast<int64_t>(r.meta_version))
        .Bind(20, r.request_key);
    if (s.Step() != SQLITE_DONE) return s.Error("insert route");
    int64_t id = sqlite3_last_insert_rowid(db_);
    for (size_t i = 0; i < r.inputs.size(); ++i) {
      const VariationInput& vi = r.inputs[i];
      std::optional<int64_t> rid = vi.route_id;
      if (vi.batch_index) {
        if (*vi.batch_index < 0 || static_cast<size_t>(*vi.batch_index) >= batch.size()) {
          return Status::InvalidInput("variation input refers to a later route of the batch");
        }
        rid = batch[*vi.batch_index];
      }
      Stmt in(db_,
              "INSERT INTO variation_inputs(variation_id, position, route_id, name, crdl) "
              "VALUES(?,?,?,?,?)");
      in.Bind(1, id)
          .Bind(2, static_cast<int64_t>(i))
          .Bind(3, rid)
          .Bind(4, vi.name)
          .Bind(5, vi.crdl);
      int rc = in.Step();
      if (rc == SQLITE_CONSTRAINT) {
        return Status::NotFound("variation input route " + std::to_string(rid.value_or(0)) +
                                " does not exist");
      }
      if (rc != SQLITE_DONE) return in.Error("insert variation input");
    }
    if (!r.inputs.empty()) {
      // Its sources: the inputs and, transitively, what they were made from.
      Stmt src(db_,
               "INSERT OR IGNORE INTO route_sources(variation_id, route_id) "
               "SELECT ?1, route_id FROM variation_inputs WHERE variation_id = ?1 AND "
               "route_id IS NOT NULL UNION SELECT ?1, s.route_id FROM route_sources s JOIN "
               "variation_inputs vi ON s.variation_id = vi.route_id WHERE vi.variation_id = ?1");
      src.Bind(1, id);
      if (src.Step() != SQLITE_DONE) return src.Error("insert variation sources");
    }
    return id;
  }

  Result<std::vector<AttemptCount>> RecordAttemptsLocked(const std::vector<std::string>& keys,
                                                         int64_t now, int64_t since) {
    // Old entries are dropped here so the table stays small.
    Stmt d(db_, "DELETE FROM attempts WHERE at < ?");
    d.Bind(1, now - kAttemptRetentionSeconds);
    if (d.Step() != SQLITE_DONE) return d.Error("drop old attempts");
    std::vector<AttemptCount> out;
    for (const std::string& key : keys) {
      AttemptCount c;
      Stmt prev(db_, "SELECT COUNT(*), ifnull(MAX(at), 0) FROM attempts WHERE key = ? AND at >= ?");
      prev.Bind(1, key).Bind(2, since);
      if (prev.Step() != SQLITE_ROW) return prev.Error("count attempts");
      c.count = static_cast<int>(prev.Int(0)) + 1;
      c.previous_at = prev.Int(1);
      Stmt ins(db_, "INSERT INTO attempts(key, at) VALUES(?,?)");
      ins.Bind(1, key).Bind(2, now);
      if (ins.Step() != SQLITE_DONE) return ins.Error("record attempt");
      out.push_back(c);
    }
    return out;
  }

  // Ends the open transaction after a failure. A failed ROLLBACK cannot be
  // reported to the caller (who already has the first error): it is logged.
  void Rollback() {
    Status st = Exec("ROLLBACK");
    if (!st.ok()) LogError("database rollback failed: " + st.message());
  }

  // The foreign keys of every row hold (checked while they are off).
  Status ForeignKeysHold() {
    Stmt s(db_, "PRAGMA foreign_key_check");
    int rc = s.Step();
    if (rc == SQLITE_DONE) return Status::Ok();
    if (rc == SQLITE_ROW) return Status::Internal("a foreign key does not hold in " + s.Text(0));
    return s.Error("foreign key check");
  }

  int SchemaVersionLocked() {
    Stmt s(db_, "PRAGMA user_version");
    return s.Step() == SQLITE_ROW ? static_cast<int>(s.Int(0)) : 0;
  }

  Status Exec(const std::string& sql) {
    char* err = nullptr;
    if (sqlite3_exec(db_, sql.c_str(), nullptr, nullptr, &err) != SQLITE_OK) {
      std::string msg = err ? err : sqlite3_errmsg(db_);
      sqlite3_free(err);
      return Status::IoError(msg);
    }
    return Status::Ok();
  }

  // How long throttling attempts are kept (longer than any window).
  static constexpr int64_t kAttemptRetentionSeconds = 24 * 3600;

  sqlite3* db_;
  std::mutex mu_;
};

}  // namespace

Result<std::unique_ptr<Store>> OpenSqliteStore(const std::string& path) {
  sqlite3* db = nullptr;
  int rc =
      sqlite3_open_v2(path.c_str(), &db,
                      SQLITE_OPEN_READWRITE | SQLITE_OPEN_CREATE | SQLITE_OPEN_FULLMUTEX, nullptr);
  if (rc != SQLITE_OK) {
    std::string msg = db ? sqlite3_errmsg(db) : "out of memory";
    sqlite3_close_v2(db);
    return Status::IoError(path + ": " + msg);
  }
  auto store = std::make_unique<SqliteStore>(db);
  Status st = store->Init();
  if (!st.ok()) {
    if (st.code() == Status::Code::kInvalidInput)
      return Status::InvalidInput(path + ": " + st.message());
    return Status::IoError(path + ": " + st.message());
  }
  return std::unique_ptr<Store>(std::move(store));
}

}  // namespace sb::store
