// store::Store written once over the SQL layer (store/sql.h): the SQLite and
// the PostgreSQL backends are this class over one driver or the other, so
// they behave the same by construction; where the dialects differ the SQL is
// chosen by `pg_`.
#include <algorithm>
#include <atomic>
#include <cctype>
#include <climits>
#include <ctime>
#include <map>
#include <utility>

#include "base/fold.h"
#include "base/log.h"
#include "gym/rules.h"
#include "store/bulk_sql.h"
#include "store/bulk_store.h"
#include "store/count_store.h"
#include "store/gym_store.h"
#include "store/import_store.h"
#include "store/prediction_store.h"
#include "store/open.h"
#include "store/profile_store.h"
#include "store/scale_store.h"
#include "store/schema.h"
#include "store/sql.h"
#include "store/sql_rows.h"
#include "store/sqlite_store.h"
#include "store/target_sql.h"
#include "store/target_store.h"
#include "store/tick_fit_sql.h"
#include "store/tick_sql.h"
#include "store/tick_store.h"
#include "store/visibility.h"

namespace sb::store {

namespace {

using sql::Rows;
using sql::Value;
using sql::Violation;
using sql_rows::NowText;

// Connections to a SQLite file (OpenSqliteStore): four readers at once
// (the worker lanes' costly slots), one of them writing at a time.
constexpr int kSqliteConnections = 4;
// How long throttling attempts are kept (longer than any window).
constexpr int64_t kAttemptRetentionSeconds = 24 * 3600;
// How often (in the callers' clock) a process sweeps every key's old attempts.
constexpr int64_t kAttemptSweepSeconds = 60;

// The route columns ReadRoute reads, in its order; `crdl` and `plan_json`
// (large) are read as '' where a list does not need them.
std::string SelectRoutes(bool full) {
  return std::string("SELECT r.id, r.owner_id, coalesce(u.username, ''), r.name, r.grade, ") +
         "r.setter, " + (full ? "r.crdl" : "''") +
         ", r.is_public, r.is_variation, r.params_json, " + (full ? "r.plan_json" : "''") +
         ", r.smooth, r.created_at, r.updated_at, r.move_count, r.colour, r.wall, r.set_on, "
         "r.grade_discipline, r.grade_value, r.meta_version, r.request_key, "
         "r.gym_id, r.wall_id, coalesce(w.name, ''), r.state, r.planned_on, r.strip_on, "
         "r.original_id, r.revision, r.circuit_id, coalesce(ci.colour, '') "
         "FROM routes r LEFT JOIN users u ON u.id = r.owner_id "
         "LEFT JOIN walls w ON w.id = r.wall_id LEFT JOIN circuits ci ON ci.id = r.circuit_id";
}

// The version of the search text the store writes (routes.search_version):
// rows of an older one are folded again when the store opens.
constexpr int kSearchVersion = 1;

// What a route's text search looks in, case-folded (sb::FoldCase): its name
// and its CRDL (description, header, moves).
std::string SearchText(const std::string& name, const std::string& crdl) {
  return FoldCase(name + "\n" + crdl);
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
  r.colour = s.Text(i, 15);
  r.wall = s.Text(i, 16);
  r.set_on = s.Text(i, 17);
  r.grade_discipline = s.Text(i, 18);
  r.grade_value = s.OptDouble(i, 19);
  r.meta_version = static_cast<int>(s.Int(i, 20));
  r.request_key = s.Text(i, 21);
  r.gym_id = s.OptInt(i, 22);
  r.wall_id = s.OptInt(i, 23);
  r.wall_name = s.Text(i, 24);
  r.state = sql_rows::RouteStateColumn(s.Text(i, 25));
  r.planned_on = s.Text(i, 26);
  r.strip_on = s.Text(i, 27);
  r.original_id = s.OptInt(i, 28);
  r.revision = s.Int(i, 29);
  r.circuit_id = s.OptInt(i, 30);
  r.circuit_colour = s.Text(i, 31);
  return r;
}

SourceRoute ReadSource(const Rows& s, size_t i, size_t first) {
  SourceRoute sr;
  sr.route_id = s.Int(i, first);
  sr.is_public = s.Int(i, first + 1) != 0;
  sr.owner_id = s.OptInt(i, first + 2);
  sr.gym_id = s.OptInt(i, first + 3);
  sr.state = sql_rows::RouteStateColumn(s.Text(i, first + 4));
  return sr;
}

// The feedback columns ReadFeedback reads.
constexpr const char* kFeedbackSelect =
    "SELECT id, route_id, participant, instrument, answers, felt_grade, felt_canonical, "
    "felt_discipline, felt_value, comment, created_at, updated_at FROM feedback";

Result<std::vector<FeedbackRecord>> ReadFeedback(const Rows& s) {
  std::vector<FeedbackRecord> out;
  for (size_t i = 0; i < s.size(); ++i) {
    FeedbackRecord f;
    f.id = s.Int(i, 0);
    f.route_id = s.Int(i, 1);
    f.participant = s.Text(i, 2);
    f.instrument = s.Text(i, 3);
    Result<Answers> answers = DecodeAnswers(s.Text(i, 4));
    if (!answers.ok()) {
      return Status::IoError("feedback " + std::to_string(f.id) + ": " +
                             answers.status().message());
    }
    f.answers = std::move(answers).value();
    f.felt_grade = s.Text(i, 5);
    f.felt_canonical = s.Text(i, 6);
    f.felt_discipline = s.Text(i, 7);
    f.felt_value = s.OptDouble(i, 8);
    f.comment = s.Text(i, 9);
    f.created_at = s.Text(i, 10);
    f.updated_at = s.Text(i, 11);
    out.push_back(std::move(f));
  }
  return out;
}

// The study columns ReadStudy reads (the response count last).
constexpr const char* kStudySelect =
    "SELECT s.id, s.owner_id, coalesce(u.username, ''), s.name, s.instrument_json, "
    "s.demographics, s.ask_rank, s.ask_order, s.is_open, s.created_at, s.updated_at, "
    "(SELECT count(*) FROM study_responses r WHERE r.study_id = s.id) "
    "FROM studies s LEFT JOIN users u ON u.id = s.owner_id";

StudyRecord ReadStudy(const Rows& s, size_t i) {
  StudyRecord st;
  st.id = s.Int(i, 0);
  st.owner_id = s.Int(i, 1);
  st.owner_name = s.Text(i, 2);
  st.name = s.Text(i, 3);
  st.instrument_json = s.Text(i, 4);
  st.demographics = s.Int(i, 5) != 0;
  st.ask_rank = s.Int(i, 6) != 0;
  st.ask_order = s.Int(i, 7) != 0;
  st.is_open = s.Int(i, 8) != 0;
  st.created_at = s.Text(i, 9);
  st.updated_at = s.Text(i, 10);
  st.responses = static_cast<int>(s.Int(i, 11));
  return st;
}

// The advisory lock key of a study: its responses and definition change
// under it, so counts, seq numbers and the "has responses" check hold
// across processes.
std::string StudyKey(int64_t id) { return "study:" + std::to_string(id); }

VariationInput ReadInput(const Rows& s, size_t i, size_t first) {
  VariationInput vi;
  vi.route_id = s.OptInt(i, first);
  vi.name = s.Text(i, first + 1);
  vi.crdl = s.Text(i, first + 2);
  return vi;
}

class SqlStore final : public Store, public GymStore, public TickStore, public TargetStore,
                       public BulkStore, public ProfileStore, public ScaleStore,
                       public ImportStore,
                       public PredictionStore, public CountStore {
 public:
  explicit SqlStore(std::unique_ptr<sql::Pool> pool)
      : pool_(std::move(pool)), pg_(pool_->dialect() == sql::Dialect::kPostgres) {}

  // store::RunAtomically (store/import_store.h).
  Status Atomically(const std::function<Status()>& body) { return pool_->RunAtomically(body); }

  Status Migrate() {
    SB_ASSIGN_OR_RETURN(sql::Pool::Lease c, pool_->Acquire());
    SB_RETURN_IF_ERROR(sql::Migrate(*c));
    return RefreshSearchText(*c);
  }

  int SchemaVersion() override {
    Result<sql::Pool::Lease> c = pool_->Acquire();
    if (!c.ok()) return 0;
    Result<int> v = (*c)->SchemaVersion();
    return v.ok() ? *v : 0;
  }

  // -- bulk loading (issue 22; store/bulk_sql.cc) ----------------------------

  Result<std::vector<int64_t>> BulkInsertRoutes(const std::vector<RouteRecord>& routes) override {
    SB_ASSIGN_OR_RETURN(sql::Pool::Lease c, pool_->Acquire());
    return bulk_sql::InsertRoutes(*c, routes, {SearchText, kSearchVersion});
  }

  Status BulkInsertTicks(const std::vector<TickRecord>& ticks) override {
    SB_ASSIGN_OR_RETURN(sql::Pool::Lease c, pool_->Acquire());
    return bulk_sql::InsertTicks(*c, ticks);
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

  // -- profiles (issue 32) ----------------------------------------------------

  Result<ProfileRecord> GetProfile(int64_t user_id) override {
    SB_ASSIGN_OR_RETURN(sql::Pool::Lease c, pool_->Acquire());
    SB_ASSIGN_OR_RETURN(
        Rows r, c->Query("SELECT id, username, display_name, language FROM users WHERE id = ?",
                         {user_id}));
    if (r.empty()) return Status::NotFound("no user " + std::to_string(user_id));
    return ProfileRecord{r.Int(0, 0), r.Text(0, 1), r.Text(0, 2), r.Text(0, 3)};
  }

  Status SetProfile(int64_t user_id, const std::string& display_name,
                    const std::string& language) override {
    SB_ASSIGN_OR_RETURN(sql::Pool::Lease c, pool_->Acquire());
    SB_ASSIGN_OR_RETURN(Rows r, c->Query("UPDATE users SET display_name = ?, language = ? "
                                         "WHERE id = ? RETURNING id",
                                         {display_name, language, user_id}));
    if (r.empty()) return Status::NotFound("no user " + std::to_string(user_id));
    return Status::Ok();
  }

  Result<std::string> GetGymLanguage(int64_t gym_id) override {
    SB_ASSIGN_OR_RETURN(sql::Pool::Lease c, pool_->Acquire());
    SB_ASSIGN_OR_RETURN(Rows r, c->Query("SELECT language FROM gyms WHERE id = ?", {gym_id}));
    if (r.empty()) return Status::NotFound("no gym " + std::to_string(gym_id));
    return r.Text(0, 0);
  }

  Status SetGymLanguage(int64_t gym_id, const std::string& language) override {
    SB_ASSIGN_OR_RETURN(sql::Pool::Lease c, pool_->Acquire());
    SB_ASSIGN_OR_RETURN(Rows r, c->Query("UPDATE gyms SET language = ? WHERE id = ? RETURNING id",
                                         {language, gym_id}));
    if (r.empty()) return Status::NotFound("no gym " + std::to_string(gym_id));
    return Status::Ok();
  }

  Status SetPassword(int64_t user_id, const std::string& password_hash,
                     const std::string& keep_session) override {
    SB_ASSIGN_OR_RETURN(sql::Pool::Lease c, pool_->Acquire());
    return sql::RunInTransaction(*c, [&]() -> Status {
      SB_ASSIGN_OR_RETURN(Rows r, c->Query("UPDATE users SET password_hash = ? WHERE id = ? "
                                           "RETURNING id",
                                           {password_hash, user_id}));
      if (r.empty()) return Status::NotFound("no user " + std::to_string(user_id));
      SB_ASSIGN_OR_RETURN(Rows d, c->Query("DELETE FROM sessions WHERE user_id = ? AND "
                                           "id_hash <> ?",
                                           {user_id, keep_session}));
      (void)d;
      return Status::Ok();
    });
  }

  Status DeleteAccount(int64_t user_id, const std::string& anon_key) override {
    SB_ASSIGN_OR_RETURN(sql::Pool::Lease c, pool_->Acquire());
    return sql::RunInTransaction(*c, [&]() -> Status {
      // The ticks stay for the grades, no longer the account's.
      SB_ASSIGN_OR_RETURN(Rows t, c->Query("UPDATE ticks SET user_id = NULL, climber = ?, "
                                           "comment = '', revision = revision + 1 "
                                           "WHERE user_id = ? RETURNING id",
                                           {anon_key, user_id}));
      (void)t;
      SB_ASSIGN_OR_RETURN(Rows r, c->Query("DELETE FROM users WHERE id = ? RETURNING id",
                                           {user_id}));
      if (r.empty()) return Status::NotFound("no user " + std::to_string(user_id));
      return Status::Ok();
    });
  }

  // -- gym scales (issue 32) ------------------------------------------------

  Result<int64_t> InsertScale(const ScaleRecord& s) override {
    SB_ASSIGN_OR_RETURN(sql::Pool::Lease c, pool_->Acquire());
    return sql::InTransaction<int64_t>(*c, [&]() -> Result<int64_t> {
      SB_ASSIGN_OR_RETURN(Rows same, c->Query("SELECT id FROM gym_scales WHERE gym_id = ? AND "
                                              "lower(name) = lower(?)",
                                              {s.gym_id, s.name}));
      if (!same.empty()) return Status::Conflict("name: the gym has a scale \"" + s.name + "\"");
      Violation v;
      Result<Rows> r = c->Query("INSERT INTO gym_scales(gym_id, name, labels) "
                                "VALUES(?, ?, ?) RETURNING id",
                                {s.gym_id, s.name, s.labels}, &v);
      if (!r.ok() && v == Violation::kUnique) {
        return Status::Conflict("name: the gym has a scale \"" + s.name + "\"");
      }
      if (!r.ok()) return r.status().WithPrefix("insert scale");
      return r->Int(0, 0);
    });
  }

  Result<std::vector<ScaleRecord>> ListScales(int64_t gym_id) override {
    SB_ASSIGN_OR_RETURN(sql::Pool::Lease c, pool_->Acquire());
    SB_ASSIGN_OR_RETURN(Rows r, c->Query("SELECT id, gym_id, name, labels FROM gym_scales "
                                         "WHERE gym_id = ? ORDER BY id",
                                         {gym_id}));
    std::vector<ScaleRecord> out;
    for (size_t i = 0; i < r.size(); ++i) {
      out.push_back({r.Int(i, 0), r.Int(i, 1), r.Text(i, 2), r.Text(i, 3)});
    }
    return out;
  }

  // -- predicted grades (issue 33) ------------------------------------------

  Status SetPredictedGrade(int64_t route_id, const std::string& text) override {
    SB_ASSIGN_OR_RETURN(sql::Pool::Lease c, pool_->Acquire());
    SB_ASSIGN_OR_RETURN(
        Rows r, c->Query("UPDATE routes SET predicted_grade = ? WHERE id = ? RETURNING id",
                         {text, route_id}));
    if (r.empty()) return Status::NotFound("no route " + std::to_string(route_id));
    return Status::Ok();
  }

  Result<std::string> PredictedGrade(int64_t route_id) override {
    SB_ASSIGN_OR_RETURN(sql::Pool::Lease c, pool_->Acquire());
    SB_ASSIGN_OR_RETURN(Rows r, c->Query("SELECT predicted_grade FROM routes WHERE id = ?",
                                         {route_id}));
    if (r.empty()) return Status::NotFound("no route " + std::to_string(route_id));
    return r.Text(0, 0);
  }

  // -- import keys (issue 32) -----------------------------------------------

  Status SetImportKey(int64_t route_id, const std::string& key) override {
    SB_ASSIGN_OR_RETURN(sql::Pool::Lease c, pool_->Acquire());
    SB_ASSIGN_OR_RETURN(
        Rows r, c->Query("UPDATE routes SET import_key = ? WHERE id = ? RETURNING id",
                         {key, route_id}));
    if (r.empty()) return Status::NotFound("no route " + std::to_string(route_id));
    return Status::Ok();
  }

  Result<std::vector<std::pair<std::string, int64_t>>> ImportKeys(
      std::optional<int64_t> gym_id, std::optional<int64_t> owner_id,
      const std::string& prefix) override {
    SB_ASSIGN_OR_RETURN(sql::Pool::Lease c, pool_->Acquire());
    std::string q =
        "SELECT import_key, id FROM routes WHERE import_key <> '' AND import_key LIKE ?";
    // The prefixes are the app's constants ("id:", "crdl:"): no LIKE escapes.
    std::vector<Value> args{prefix + "%"};
    if (gym_id) {
      q += " AND gym_id = ?";
      args.push_back(*gym_id);
    } else {
      q += " AND gym_id IS NULL";
    }
    if (owner_id) {
      q += " AND owner_id = ?";
      args.push_back(*owner_id);
    }
    q += " ORDER BY id";
    SB_ASSIGN_OR_RETURN(Rows r, c->Query(q, args));
    std::vector<std::pair<std::string, int64_t>> out;
    for (size_t i = 0; i < r.size(); ++i) out.emplace_back(r.Text(i, 0), r.Int(i, 1));
    return out;
  }

  Result<std::string> WallScale(int64_t wall_id) override {
    SB_ASSIGN_OR_RETURN(sql::Pool::Lease c, pool_->Acquire());
    SB_ASSIGN_OR_RETURN(Rows r, c->Query("SELECT scale FROM walls WHERE id = ?", {wall_id}));
    if (r.empty()) return Status::NotFound("no wall " + std::to_string(wall_id));
    return r.Text(0, 0);
  }

  Status SetWallScale(int64_t wall_id, const std::string& scale) override {
    SB_ASSIGN_OR_RETURN(sql::Pool::Lease c, pool_->Acquire());
    SB_ASSIGN_OR_RETURN(Rows r, c->Query("UPDATE walls SET scale = ? WHERE id = ? RETURNING id",
                                         {scale, wall_id}));
    if (r.empty()) return Status::NotFound("no wall " + std::to_string(wall_id));
    return Status::Ok();
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
    std::vector<Value> params = {
        route.crdl, route.name, route.grade, route.setter, int64_t{route.is_public},
        int64_t{route.move_count}, NowText(), route.colour, route.wall, route.set_on,
        route.grade_discipline, sql::Nullable(route.grade_value), int64_t{route.meta_version},
        route.request_key, sql::Nullable(route.gym_id), sql::Nullable(route.wall_id),
        std::string(gym::NameOf(route.state)), route.planned_on, route.strip_on,
        sql::Nullable(route.original_id),
        SearchText(route.name, route.crdl), int64_t{kSearchVersion},
        sql::Nullable(route.circuit_id), route.id};
    // Issue 31: the revision is checked and bumped in the one statement.
    if (route.revision > 0) params.push_back(route.revision);
    SB_ASSIGN_OR_RETURN(
        Rows r,
        c->Query(std::string("UPDATE routes SET crdl = ?, name = ?, grade = ?, setter = ?, "
                             "is_public = ?, move_count = ?, updated_at = ?, colour = ?, "
                             "wall = ?, set_on = ?, grade_discipline = ?, grade_value = ?, "
                             "meta_version = ?, request_key = ?, gym_id = ?, wall_id = ?, "
                             "state = ?, planned_on = ?, strip_on = ?, original_id = ?, "
                             "search_text = ?, search_version = ?, circuit_id = ?, "
                             "revision = revision + 1 "
                             "WHERE id = ?") +
                     (route.revision > 0 ? " AND revision = ?" : "") + " RETURNING id",
                 params));
    if (r.empty()) {
      SB_ASSIGN_OR_RETURN(Rows e, c->Query("SELECT revision FROM routes WHERE id = ?", {route.id}));
      if (e.empty()) return Status::NotFound("no route " + std::to_string(route.id));
      return Status::Conflict("revision: the route was changed meanwhile (now revision " +
                              std::to_string(e.Int(0, 0)) + ")");
    }
    return Status::Ok();
  }

  Status UpdateRouteMetadata(const RouteRecord& route) override {
    SB_ASSIGN_OR_RETURN(sql::Pool::Lease c, pool_->Acquire());
    SB_ASSIGN_OR_RETURN(
        Rows r, c->Query("UPDATE routes SET name = ?, grade = ?, setter = ?, colour = ?, "
                         "wall = ?, set_on = ?, grade_discipline = ?, grade_value = ?, "
                         "meta_version = ? WHERE id = ? RETURNING id",
                         {route.name, route.grade, route.setter, route.colour, route.wall,
                          route.set_on, route.grade_discipline, sql::Nullable(route.grade_value),
                          int64_t{route.meta_version}, route.id}));
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
    SB_ASSIGN_OR_RETURN(Rows st, c->Query("SELECT user_id, name FROM route_setters "
                                          "WHERE route_id = ? ORDER BY position",
                                          {id}));
    for (size_t i = 0; i < st.size(); ++i) out.setters.push_back({st.OptInt(i, 0), st.Text(i, 1)});
    if (out.is_variation) {
      SB_ASSIGN_OR_RETURN(
          Rows src, c->Query("SELECT src.id, src.is_public, src.owner_id, src.gym_id, src.state "
                             "FROM route_sources s "
                             "JOIN routes src ON src.id = s.route_id WHERE s.variation_id = ? "
                             "ORDER BY src.id",
                             {id}));
      for (size_t i = 0; i < src.size(); ++i) out.sources.push_back(ReadSource(src, i, 0));
    }
    return out;
  }

  Result<std::vector<RouteRecord>> ListRoutes(const RouteFilter& f) override {
    SB_ASSIGN_OR_RETURN(sql::Pool::Lease c, pool_->Acquire());
    std::vector<Value> params;
    std::string sql = SelectRoutes(false) + FilterWhere(f, &params) + OrderBy(f.sort) +
                      " LIMIT ? OFFSET ?";
    params.push_back(int64_t{std::max(0, f.limit)});
    params.push_back(int64_t{std::max(0, f.offset)});
    SB_ASSIGN_OR_RETURN(Rows r, c->Query(sql, params));
    std::vector<RouteRecord> out;
    out.reserve(r.size());
    for (size_t i = 0; i < r.size(); ++i) out.push_back(ReadRoute(r, i));
    return out;
  }

  Result<int64_t> CountRoutes(const RouteFilter& f) override {
    SB_ASSIGN_OR_RETURN(sql::Pool::Lease c, pool_->Acquire());
    std::vector<Value> params;
    std::string sql = "SELECT count(*) FROM routes r LEFT JOIN users u ON u.id = r.owner_id" +
                      FilterWhere(f, &params);
    SB_ASSIGN_OR_RETURN(Rows r, c->Query(sql, params));
    return r.Int(0, 0);
  }

  Result<int64_t> FindVariationByKey(int64_t owner, const std::string& request_key) override {
    SB_ASSIGN_OR_RETURN(sql::Pool::Lease c, pool_->Acquire());
    SB_ASSIGN_OR_RETURN(
        Rows r, c->Query("SELECT id FROM routes WHERE owner_id = ? AND request_key = ? AND "
                         "request_key <> '' AND is_variation = 1 ORDER BY id DESC LIMIT 1",
                         {owner, request_key}));
    if (r.empty()) return Status::NotFound("no such variation");
    return r.Int(0, 0);
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
    SB_ASSIGN_OR_RETURN(
        Rows src, c->Query("SELECT s.variation_id, src.id, src.is_public, src.owner_id, src.gym_id, src.state "
                           "FROM route_sources s JOIN routes src ON src.id = s.route_id "
                           "JOIN routes r ON r.id = s.variation_id" +
                               where + " ORDER BY s.variation_id, src.id",
                           params));
    for (size_t i = 0; i < src.size(); ++i) {
      auto it = index.find(src.Int(i, 0));
      if (it != index.end()) out[it->second].sources.push_back(ReadSource(src, i, 1));
    }
    return out;
  }

  // -- climbers' feedback ---------------------------------------------------

  Result<int64_t> PutFeedback(const FeedbackRecord& f) override {
    SB_ASSIGN_OR_RETURN(sql::Pool::Lease c, pool_->Acquire());
    const std::string now = NowText();
    // One statement, so a concurrent submission of the same participant
    // cannot make a second row (UNIQUE (route_id, participant)).
    Violation v;
    Result<Rows> r = c->Query(
        "INSERT INTO feedback(route_id, participant, instrument, answers, felt_grade, "
        "felt_canonical, felt_discipline, felt_value, comment, created_at, updated_at) "
        "VALUES(?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?) ON CONFLICT(route_id, participant) DO UPDATE "
        "SET instrument = excluded.instrument, answers = excluded.answers, "
        "felt_grade = excluded.felt_grade, felt_canonical = excluded.felt_canonical, "
        "felt_discipline = excluded.felt_discipline, felt_value = excluded.felt_value, "
        "comment = excluded.comment, updated_at = excluded.updated_at RETURNING id",
        {f.route_id, f.participant, f.instrument, EncodeAnswers(f.answers), f.felt_grade,
         f.felt_canonical, f.felt_discipline, sql::Nullable(f.felt_value), f.comment, now, now},
        &v);
    if (!r.ok() && v == Violation::kForeignKey) {
      return Status::NotFound("no route " + std::to_string(f.route_id));
    }
    if (!r.ok()) return r.status().WithPrefix("put feedback");
    return r->Int(0, 0);
  }

  Result<std::optional<FeedbackRecord>> FindFeedback(int64_t route_id,
                                                     const std::string& participant) override {
    SB_ASSIGN_OR_RETURN(sql::Pool::Lease c, pool_->Acquire());
    SB_ASSIGN_OR_RETURN(Rows r, c->Query(std::string(kFeedbackSelect) +
                                             " WHERE route_id = ? AND participant = ?",
                                         {route_id, participant}));
    SB_ASSIGN_OR_RETURN(std::vector<FeedbackRecord> rows, ReadFeedback(r));
    if (rows.empty()) return std::optional<FeedbackRecord>();
    return std::optional<FeedbackRecord>(std::move(rows[0]));
  }

  Result<std::vector<FeedbackRecord>> ListFeedback(int64_t route_id) override {
    SB_ASSIGN_OR_RETURN(sql::Pool::Lease c, pool_->Acquire());
    SB_ASSIGN_OR_RETURN(
        Rows r, c->Query(std::string(kFeedbackSelect) + " WHERE route_id = ? ORDER BY id",
                         {route_id}));
    return ReadFeedback(r);
  }

  Result<std::vector<FeedbackRecord>> FeedbackOnRoutesOf(int64_t owner_id) override {
    SB_ASSIGN_OR_RETURN(sql::Pool::Lease c, pool_->Acquire());
    SB_ASSIGN_OR_RETURN(Rows r, c->Query(std::string(kFeedbackSelect) +
                                             " WHERE route_id IN (SELECT id FROM routes WHERE "
                                             "owner_id = ?) ORDER BY route_id, id",
                                         {owner_id}));
    return ReadFeedback(r);
  }

  // -- studies --------------------------------------------------------------

  Result<int64_t> InsertStudy(const StudyRecord& st) override {
    SB_ASSIGN_OR_RETURN(sql::Pool::Lease c, pool_->Acquire());
    return sql::InTransaction<int64_t>(*c, [&]() -> Result<int64_t> {
      const std::string now = NowText();
      Violation v;
      Result<Rows> r = c->Query(
          "INSERT INTO studies(owner_id, name, instrument_json, demographics, ask_rank, "
          "ask_order, is_open, created_at, updated_at) VALUES(?, ?, ?, ?, ?, ?, ?, ?, ?) "
          "RETURNING id",
          {st.owner_id, st.name, st.instrument_json, int64_t{st.demographics},
           int64_t{st.ask_rank}, int64_t{st.ask_order}, int64_t{st.is_open}, now, now},
          &v);
      if (!r.ok() && v == Violation::kForeignKey) {
        return Status::NotFound("no user " + std::to_string(st.owner_id));
      }
      if (!r.ok()) return r.status().WithPrefix("insert study");
      int64_t id = r->Int(0, 0);
      SB_RETURN_IF_ERROR(WriteStudyRoutes(*c, id, st.routes));
      return id;
    });
  }

  Status UpdateStudy(const StudyRecord& st, bool definition_changes) override {
    SB_ASSIGN_OR_RETURN(sql::Pool::Lease c, pool_->Acquire());
    return sql::RunInTransaction(*c, [&]() -> Status {
      SB_RETURN_IF_ERROR(c->LockKeys({StudyKey(st.id)}));
      SB_ASSIGN_OR_RETURN(
          Rows n, c->Query("SELECT (SELECT count(*) FROM study_responses WHERE study_id = s.id) "
                           "FROM studies s WHERE s.id = ?",
                           {st.id}));
      if (n.empty()) return Status::NotFound("no study " + std::to_string(st.id));
      if (definition_changes && n.Int(0, 0) > 0) {
        return Status::Conflict(
            "the study has responses: its routes, instrument and questions can no longer "
            "change");
      }
      SB_ASSIGN_OR_RETURN(
          Rows u, c->Query("UPDATE studies SET name = ?, instrument_json = ?, demographics = ?, "
                           "ask_rank = ?, ask_order = ?, is_open = ?, updated_at = ? "
                           "WHERE id = ?",
                           {st.name, st.instrument_json, int64_t{st.demographics},
                            int64_t{st.ask_rank}, int64_t{st.ask_order}, int64_t{st.is_open},
                            NowText(), st.id}));
      if (definition_changes) SB_RETURN_IF_ERROR(WriteStudyRoutes(*c, st.id, st.routes));
      return Status::Ok();
    });
  }

  Result<StudyRecord> GetStudy(int64_t id) override {
    SB_ASSIGN_OR_RETURN(sql::Pool::Lease c, pool_->Acquire());
    SB_ASSIGN_OR_RETURN(std::vector<StudyRecord> rows,
                        ReadStudies(*c, " WHERE s.id = ?", {id}));
    if (rows.empty()) return Status::NotFound("no study " + std::to_string(id));
    return std::move(rows[0]);
  }

  Result<std::vector<StudyRecord>> ListStudies(int64_t owner_id) override {
    SB_ASSIGN_OR_RETURN(sql::Pool::Lease c, pool_->Acquire());
    return ReadStudies(*c, " WHERE s.owner_id = ? ORDER BY s.id DESC", {owner_id});
  }

  Result<int> InsertStudyResponse(const StudyResponseRecord& r, int max_responses) override {
    SB_ASSIGN_OR_RETURN(sql::Pool::Lease c, pool_->Acquire());
    return sql::InTransaction<int>(*c, [&]() -> Result<int> {
      // Every process adding a response to this study waits here, so the
      // count, the limit and seq are read and written by one at a time.
      SB_RETURN_IF_ERROR(c->LockKeys({StudyKey(r.study_id)}));
      SB_ASSIGN_OR_RETURN(
          Rows s,
          c->Query("SELECT s.is_open, "
                   "(SELECT count(*) FROM study_responses WHERE study_id = s.id), "
                   "(SELECT coalesce(max(seq), 0) FROM study_responses WHERE study_id = s.id), "
                   "(SELECT count(*) FROM study_responses WHERE study_id = s.id AND "
                   "participant = ?) FROM studies s WHERE s.id = ?",
                   {r.participant, r.study_id}));
      if (s.empty()) return Status::NotFound("no study " + std::to_string(r.study_id));
      if (s.Int(0, 0) == 0) return Status::Conflict("this study is closed");
      if (s.Int(0, 3) > 0) return Status::Conflict("you have already answered this study");
      if (s.Int(0, 1) >= max_responses) {
        return Status::Conflict("this study has reached its limit of " +
                                std::to_string(max_responses) + " responses");
      }
      const int seq = static_cast<int>(s.Int(0, 2)) + 1;
      Violation v;
      Result<Rows> ins = c->Query(
          "INSERT INTO study_responses(study_id, participant, seq, ability, created_at, "
          "origin, state) VALUES(?, ?, ?, ?, ?, ?, ?) RETURNING id",
          {r.study_id, r.participant, int64_t{seq}, sql::Nullable(r.ability),
           r.created_at.empty() ? NowText() : r.created_at, r.origin, r.state},
          &v);
      if (!ins.ok() && v == Violation::kUnique) {
        return Status::Conflict("you have already answered this study");
      }
      if (!ins.ok()) return ins.status().WithPrefix("insert study response");
      const int64_t id = ins->Int(0, 0);
      for (const StudyAnswer& a : r.answers) {
        Result<Rows> w = c->Query(
            "INSERT INTO study_answers(response_id, position, answers, route_rank, climb_order) "
            "VALUES(?, ?, ?, ?, ?)",
            {id, int64_t{a.position}, EncodeAnswers(a.answers), sql::Nullable(a.rank),
             sql::Nullable(a.order)},
            &v);
        if (!w.ok() && v == Violation::kUnique) {
          return Status::InvalidInput("route " + std::to_string(a.position) + " answered twice");
        }
        if (!w.ok()) return w.status().WithPrefix("insert study answers");
      }
      for (const auto& [question, answer] : r.demographics) {
        Result<Rows> w = c->Query(
            "INSERT INTO study_demographics(response_id, question, answer) VALUES(?, ?, ?)",
            {id, question, answer}, &v);
        if (!w.ok() && v == Violation::kUnique) {
          return Status::InvalidInput(question + ": answered twice");
        }
        if (!w.ok()) return w.status().WithPrefix("insert study demographics");
      }
      return seq;
    });
  }

  Result<bool> HasStudyResponse(int64_t study_id, const std::string& participant) override {
    SB_ASSIGN_OR_RETURN(sql::Pool::Lease c, pool_->Acquire());
    SB_ASSIGN_OR_RETURN(
        Rows r, c->Query("SELECT 1 FROM study_responses WHERE study_id = ? AND participant = ?",
                         {study_id, participant}));
    return !r.empty();
  }

  Result<std::vector<StudyResponseRecord>> ListStudyResponses(int64_t study_id) override {
    SB_ASSIGN_OR_RETURN(sql::Pool::Lease c, pool_->Acquire());
    // One snapshot for the three reads (PostgreSQL reads each statement's
    // own otherwise; SQLite's read transaction is one anyway).
    return sql::InTransaction<std::vector<StudyResponseRecord>>(
        *c, [&]() -> Result<std::vector<StudyResponseRecord>> {
          if (pg_) SB_RETURN_IF_ERROR(c->Exec("SET TRANSACTION ISOLATION LEVEL REPEATABLE READ"));
          std::vector<StudyResponseRecord> out;
          std::map<int64_t, size_t> index;  // response id -> position in out
          SB_ASSIGN_OR_RETURN(
              Rows s, c->Query("SELECT id, study_id, participant, seq, ability, created_at, "
                               "origin, state FROM study_responses WHERE study_id = ? ORDER BY seq",
                               {study_id}));
          for (size_t i = 0; i < s.size(); ++i) {
            StudyResponseRecord r;
            r.id = s.Int(i, 0);
            r.study_id = s.Int(i, 1);
            r.participant = s.Text(i, 2);
            r.seq = static_cast<int>(s.Int(i, 3));
            r.ability = s.OptDouble(i, 4);
            r.created_at = s.Text(i, 5);
            r.origin = s.Text(i, 6);
            r.state = s.Text(i, 7);
            index[r.id] = out.size();
            out.push_back(std::move(r));
          }
          SB_ASSIGN_OR_RETURN(
              Rows a, c->Query("SELECT a.response_id, a.position, a.answers, a.route_rank, "
                               "a.climb_order FROM study_answers a JOIN study_responses r "
                               "ON r.id = a.response_id WHERE r.study_id = ? "
                               "ORDER BY a.response_id, a.position",
                               {study_id}));
          for (size_t i = 0; i < a.size(); ++i) {
            auto it = index.find(a.Int(i, 0));
            if (it == index.end()) continue;
            StudyAnswer ans;
            ans.position = static_cast<int>(a.Int(i, 1));
            Result<Answers> decoded = DecodeAnswers(a.Text(i, 2));
            if (!decoded.ok()) {
              return Status::IoError("study " + std::to_string(study_id) + ": " +
                                     decoded.status().message());
            }
            ans.answers = std::move(decoded).value();
            std::optional<int64_t> rank = a.OptInt(i, 3), order = a.OptInt(i, 4);
            if (rank) ans.rank = static_cast<int>(*rank);
            if (order) ans.order = static_cast<int>(*order);
            out[it->second].answers.push_back(std::move(ans));
          }
          // Demographics in question order, compared byte-wise on both backends.
          SB_ASSIGN_OR_RETURN(
              Rows d, c->Query(std::string("SELECT d.response_id, d.question, d.answer "
                                           "FROM study_demographics d JOIN study_responses r "
                                           "ON r.id = d.response_id WHERE r.study_id = ? "
                                           "ORDER BY d.response_id, d.question") +
                                   (pg_ ? " COLLATE \"C\"" : ""),
                               {study_id}));
          for (size_t i = 0; i < d.size(); ++i) {
            auto it = index.find(d.Int(i, 0));
            if (it != index.end()) {
              out[it->second].demographics.emplace_back(d.Text(i, 1), d.Text(i, 2));
            }
          }
          return out;
        });
  }

  Result<int> NewStudyIdentitiesSince(int64_t study_id, const std::string& origin,
                                      const std::string& since) override {
    SB_ASSIGN_OR_RETURN(sql::Pool::Lease c, pool_->Acquire());
    SB_ASSIGN_OR_RETURN(
        Rows r, c->Query("SELECT count(DISTINCT r.participant) FROM study_responses r "
                         "WHERE r.study_id = ? AND r.origin = ? AND r.created_at >= ? "
                         "AND NOT EXISTS (SELECT 1 FROM study_responses o "
                         "WHERE o.participant = r.participant AND o.created_at < ?)",
                         {study_id, origin, since, since}));
    return static_cast<int>(r.Int(0, 0));
  }

  Result<bool> StudyParticipantBefore(const std::string& participant,
                                      const std::string& since) override {
    SB_ASSIGN_OR_RETURN(sql::Pool::Lease c, pool_->Acquire());
    SB_ASSIGN_OR_RETURN(Rows r, c->Query("SELECT 1 FROM study_responses WHERE participant = ? "
                                         "AND created_at < ? LIMIT 1",
                                         {participant, since}));
    return !r.empty();
  }

  Status SetStudyResponseState(int64_t study_id, int64_t response_id,
                               const std::string& state) override {
    SB_ASSIGN_OR_RETURN(sql::Pool::Lease c, pool_->Acquire());
    SB_ASSIGN_OR_RETURN(Rows r, c->Query("UPDATE study_responses SET state = ? "
                                         "WHERE id = ? AND study_id = ? RETURNING id",
                                         {state, response_id, study_id}));
    if (r.empty()) {
      return Status::NotFound("study " + std::to_string(study_id) + " has no response " +
                              std::to_string(response_id));
    }
    return Status::Ok();
  }

  // -- ticks (TickStore, store/tick_sql.cc) --------------------------------

  Result<TickRecord> PutTick(const TickRecord& t) override {
    SB_ASSIGN_OR_RETURN(sql::Pool::Lease c, pool_->Acquire());
    return ticks_sql::PutTick(*c, t);
  }
  Result<TickRecord> GetTick(int64_t id) override {
    SB_ASSIGN_OR_RETURN(sql::Pool::Lease c, pool_->Acquire());
    return ticks_sql::GetTick(*c, id);
  }
  Result<std::vector<TickRecord>> RouteTicks(int64_t route_id) override {
    SB_ASSIGN_OR_RETURN(sql::Pool::Lease c, pool_->Acquire());
    return ticks_sql::RouteTicks(*c, route_id);
  }
  Result<std::vector<TickRecord>> GymTicks(int64_t gym_id) override {
    SB_ASSIGN_OR_RETURN(sql::Pool::Lease c, pool_->Acquire());
    return ticks_sql::GymTicks(*c, gym_id, ticks_sql::GymTickPage());
  }
  Result<std::vector<TickRecord>> GymDisciplineTicks(int64_t gym_id,
                                                     const std::string& discipline) override {
    SB_ASSIGN_OR_RETURN(sql::Pool::Lease c, pool_->Acquire());
    return ticks_sql::GymDisciplineTicks(*c, gym_id, discipline);
  }
  Status EachGymDisciplineTicksPage(
      int64_t gym_id, const std::string& discipline,
      const std::function<Status(std::vector<TickRecord>&)>& page) override {
    SB_ASSIGN_OR_RETURN(sql::Pool::Lease c, pool_->Acquire());
    return ticks_sql::EachGymDisciplineTicksPage(*c, gym_id, discipline, page);
  }
  Result<std::map<std::string, int64_t>> AgedRouteCounts(
      int64_t gym_id, const std::string& created_until) override {
    SB_ASSIGN_OR_RETURN(sql::Pool::Lease c, pool_->Acquire());
    return ticks_sql::AgedRouteCounts(*c, gym_id, created_until);
  }
  Result<std::vector<TickRecord>> ClimberTicks(const std::string& climber) override {
    SB_ASSIGN_OR_RETURN(sql::Pool::Lease c, pool_->Acquire());
    return ticks_sql::ClimberTicks(*c, climber);
  }
  Result<TickCounts> CountClimberTicks(const std::string& climber) override {
    SB_ASSIGN_OR_RETURN(sql::Pool::Lease c, pool_->Acquire());
    return ticks_sql::CountClimberTicks(*c, climber);
  }
  Result<TickCounts> CountRouteTicks(int64_t route_id) override {
    SB_ASSIGN_OR_RETURN(sql::Pool::Lease c, pool_->Acquire());
    return ticks_sql::CountRouteTicks(*c, route_id);
  }
  // -- counts before the work (store/count_store.h, issue 34) -----------------

  Result<int64_t> CountGymHistory(int64_t gym_id) override {
    return CountOf("SELECT count(*) FROM gym_history WHERE gym_id = ?", gym_id);
  }
  Result<int64_t> CountRouteHistory(int64_t route_id) override {
    return CountOf("SELECT count(*) FROM route_history WHERE route_id = ?", route_id);
  }
  Result<int64_t> CountRouteFeedback(int64_t route_id) override {
    return CountOf("SELECT count(*) FROM feedback WHERE route_id = ?", route_id);
  }
  Result<DriftCounts> CountDrift(int64_t owner_id) override {
    DriftCounts n;
    SB_ASSIGN_OR_RETURN(n.routes, CountOf("SELECT count(*) FROM routes WHERE owner_id = ?", owner_id));
    SB_ASSIGN_OR_RETURN(n.feedback,
                        CountOf("SELECT count(*) FROM feedback WHERE route_id IN "
                                "(SELECT id FROM routes WHERE owner_id = ?)",
                                owner_id));
    return n;
  }
  Result<int64_t> CountGymMembers(int64_t gym_id) override {
    return CountOf("SELECT count(*) FROM gym_members WHERE gym_id = ?", gym_id);
  }
  Result<int64_t> CountGymWalls(int64_t gym_id) override {
    return CountOf("SELECT count(*) FROM walls WHERE gym_id = ?", gym_id);
  }
  Result<int64_t> CountGymCircuits(int64_t gym_id) override {
    return CountOf("SELECT count(*) FROM circuits WHERE gym_id = ?", gym_id);
  }
  Result<int64_t> CountGymScales(int64_t gym_id) override {
    return CountOf("SELECT count(*) FROM gym_scales WHERE gym_id = ?", gym_id);
  }

  Result<TickVersion> GymTickVersion(int64_t gym_id) override {
    SB_ASSIGN_OR_RETURN(sql::Pool::Lease c, pool_->Acquire());
    return ticks_sql::GymTickVersion(*c, gym_id);
  }
  Status SetTickState(int64_t id, const std::string& state,
                      const std::string& updated_at) override {
    SB_ASSIGN_OR_RETURN(sql::Pool::Lease c, pool_->Acquire());
    return ticks_sql::SetTickState(*c, id, state, updated_at);
  }
  Result<int> MergeTicks(const std::string& from, const std::string& to,
                         int64_t user_id) override {
    SB_ASSIGN_OR_RETURN(sql::Pool::Lease c, pool_->Acquire());
    return ticks_sql::MergeTicks(*c, from, to, user_id);
  }
  Result<int> NewIdentitiesSince(int64_t route_id, const std::string& origin,
                                 const std::string& since) override {
    SB_ASSIGN_OR_RETURN(sql::Pool::Lease c, pool_->Acquire());
    return ticks_sql::NewIdentitiesSince(*c, route_id, origin, since);
  }

  // -- wall targets (TargetStore, store/target_sql.cc) -----------------------

  Status SetWallTargets(int64_t wall_id, const std::vector<TargetRecord>& targets,
                        int64_t revision) override {
    SB_ASSIGN_OR_RETURN(sql::Pool::Lease c, pool_->Acquire());
    return targets_sql::SetWallTargets(*c, wall_id, targets, revision);
  }
  Result<std::vector<TargetRecord>> WallTargets(int64_t wall_id) override {
    SB_ASSIGN_OR_RETURN(sql::Pool::Lease c, pool_->Acquire());
    return targets_sql::WallTargets(*c, wall_id);
  }
  Result<std::vector<TargetRecord>> GymTargets(int64_t gym_id) override {
    SB_ASSIGN_OR_RETURN(sql::Pool::Lease c, pool_->Acquire());
    return targets_sql::GymTargets(*c, gym_id);
  }
  Status SetDisciplineTargets(int64_t gym_id, const std::string& discipline,
                              const std::vector<DisciplineTargetRecord>& targets,
                              int64_t revision) override {
    SB_ASSIGN_OR_RETURN(sql::Pool::Lease c, pool_->Acquire());
    return targets_sql::SetDisciplineTargets(*c, gym_id, discipline, targets, revision);
  }
  Result<int64_t> DisciplineTargetsRevision(int64_t gym_id) override {
    SB_ASSIGN_OR_RETURN(sql::Pool::Lease c, pool_->Acquire());
    return targets_sql::DisciplineTargetsRevision(*c, gym_id);
  }
  Result<std::vector<DisciplineTargetRecord>> DisciplineTargets(int64_t gym_id) override {
    SB_ASSIGN_OR_RETURN(sql::Pool::Lease c, pool_->Acquire());
    return targets_sql::DisciplineTargets(*c, gym_id);
  }
  Result<std::vector<RouteTickSum>> GymTickSums(int64_t gym_id) override {
    SB_ASSIGN_OR_RETURN(sql::Pool::Lease c, pool_->Acquire());
    return targets_sql::GymTickSums(*c, gym_id);
  }
  Result<std::vector<RouteTickSum>> RouteTickSums(const std::vector<int64_t>& route_ids) override {
    SB_ASSIGN_OR_RETURN(sql::Pool::Lease c, pool_->Acquire());
    return targets_sql::RouteTickSums(*c, route_ids);
  }
  Result<std::vector<RouteTickSum>> StateTickSums(int64_t gym_id,
                                                  const std::string& route_state) override {
    SB_ASSIGN_OR_RETURN(sql::Pool::Lease c, pool_->Acquire());
    return targets_sql::StateTickSums(*c, gym_id, route_state);
  }

  // -- gyms (GymStore) ------------------------------------------------------

  Result<int64_t> CreateGym(const std::string& name, std::optional<int64_t> head) override {
    SB_ASSIGN_OR_RETURN(sql::Pool::Lease c, pool_->Acquire());
    return sql::InTransaction<int64_t>(*c, [&]() -> Result<int64_t> {
      SB_ASSIGN_OR_RETURN(Rows g, c->Query("INSERT INTO gyms(name, created_at) VALUES(?, ?) "
                                           "RETURNING id",
                                           {name, NowText()}));
      const int64_t id = g.Int(0, 0);
      if (head) {
        Violation v;
        Result<Rows> m = c->Query(
            "INSERT INTO gym_members(gym_id, user_id, role) VALUES(?, ?, ?)",
            {id, *head, std::string(gym::NameOf(gym::Role::kHead))},
            &v);
        if (!m.ok() && v == Violation::kForeignKey) {
          return Status::NotFound("no user " + std::to_string(*head));
        }
        if (!m.ok()) return m.status().WithPrefix("add head setter");
      }
      return id;
    });
  }

  Status RenameGym(int64_t id, const std::string& name, int64_t revision) override {
    SB_ASSIGN_OR_RETURN(sql::Pool::Lease c, pool_->Acquire());
    std::vector<Value> params = {name, id};
    if (revision > 0) params.push_back(revision);
    SB_ASSIGN_OR_RETURN(
        Rows r, c->Query(std::string("UPDATE gyms SET name = ?, revision = revision + 1 "
                                     "WHERE id = ?") +
                             (revision > 0 ? " AND revision = ?" : "") + " RETURNING id",
                         params));
    if (r.empty()) return Stale(*c, "gyms", id, "gym");
    return Status::Ok();
  }

  // After an UPDATE ... WHERE id = ? AND revision = ? wrote nothing:
  // kNotFound "no <what> N" when the row is gone, else kConflict.
  static Status Stale(sql::Connection& c, const std::string& table, int64_t id,
                      const std::string& what) {
    SB_ASSIGN_OR_RETURN(Rows e, c.Query("SELECT revision FROM " + table + " WHERE id = ?", {id}));
    if (e.empty()) return Status::NotFound("no " + what + " " + std::to_string(id));
    return Status::Conflict("revision: the " + what + " was changed meanwhile (now revision " +
                            std::to_string(e.Int(0, 0)) + ")");
  }

  Result<GymRecord> GetGym(int64_t id) override {
    SB_ASSIGN_OR_RETURN(sql::Pool::Lease c, pool_->Acquire());
    SB_ASSIGN_OR_RETURN(Rows r, c->Query("SELECT id, name, created_at, '', revision FROM gyms WHERE id = ?",
                                         {id}));
    if (r.empty()) return Status::NotFound("no gym " + std::to_string(id));
    return ReadGyms(r)[0];
  }

  Result<std::vector<GymRecord>> ListGyms() override {
    SB_ASSIGN_OR_RETURN(sql::Pool::Lease c, pool_->Acquire());
    SB_ASSIGN_OR_RETURN(Rows r, c->Query("SELECT id, name, created_at, '', revision FROM gyms ORDER BY id",
                                         {}));
    return ReadGyms(r);
  }

  Result<std::vector<GymRecord>> GymsOf(int64_t user_id) override {
    SB_ASSIGN_OR_RETURN(sql::Pool::Lease c, pool_->Acquire());
    SB_ASSIGN_OR_RETURN(
        Rows r, c->Query("SELECT g.id, g.name, g.created_at, m.role, g.revision FROM gyms g "
                         "JOIN gym_members m ON m.gym_id = g.id WHERE m.user_id = ? ORDER BY g.id",
                         {user_id}));
    return ReadGyms(r);
  }

  Status PutMember(int64_t gym_id, int64_t user_id, const std::string& role) override {
    SB_ASSIGN_OR_RETURN(sql::Pool::Lease c, pool_->Acquire());
    Violation v;
    Result<Rows> r = c->Query(
        "INSERT INTO gym_members(gym_id, user_id, role) VALUES(?, ?, ?) "
        "ON CONFLICT(gym_id, user_id) DO UPDATE SET role = excluded.role",
        {gym_id, user_id, role}, &v);
    if (!r.ok() && v == Violation::kForeignKey) {
      return Status::NotFound("no gym " + std::to_string(gym_id) + " or user " +
                              std::to_string(user_id));
    }
    if (!r.ok()) return r.status().WithPrefix("put member");
    return Status::Ok();
  }

  Result<std::vector<MemberRecord>> ListMembers(int64_t gym_id) override {
    SB_ASSIGN_OR_RETURN(sql::Pool::Lease c, pool_->Acquire());
    SB_ASSIGN_OR_RETURN(
        Rows r, c->Query("SELECT m.gym_id, m.user_id, u.username, m.role, u.display_name "
                         "FROM gym_members m JOIN users u ON u.id = m.user_id "
                         "WHERE m.gym_id = ? ORDER BY m.user_id",
                         {gym_id}));
    std::vector<MemberRecord> out;
    for (size_t i = 0; i < r.size(); ++i) {
      out.push_back({r.Int(i, 0), r.Int(i, 1), r.Text(i, 2), sql_rows::RoleColumn(r.Text(i, 3)),
                     r.Text(i, 4)});
    }
    return out;
  }

  Result<int64_t> InsertWall(const WallRecord& w) override {
    SB_ASSIGN_OR_RETURN(sql::Pool::Lease c, pool_->Acquire());
    Violation v;
    Result<Rows> r = c->Query(
        "INSERT INTO walls(gym_id, name, discipline, angle, position, reset_weeks, plan_x, "
        "plan_y, plan_w, plan_h) VALUES(?, ?, ?, ?, ?, ?, ?, ?, ?, ?) RETURNING id",
        {w.gym_id, w.name, w.discipline, w.angle, int64_t{w.position},
         sql::Nullable(w.reset_weeks), sql::Nullable(w.plan_x), sql::Nullable(w.plan_y),
         sql::Nullable(w.plan_w), sql::Nullable(w.plan_h)},
        &v);
    if (!r.ok() && v == Violation::kUnique) {
      return Status::Conflict("the gym has a wall named '" + w.name + "'");
    }
    if (!r.ok() && v == Violation::kForeignKey) {
      return Status::NotFound("no gym " + std::to_string(w.gym_id));
    }
    if (!r.ok()) return r.status().WithPrefix("insert wall");
    return r->Int(0, 0);
  }

  Status UpdateWall(const WallRecord& w, const RederiveRoute& rederive) override {
    SB_ASSIGN_OR_RETURN(sql::Pool::Lease c, pool_->Acquire());
    return sql::RunInTransaction(*c, [&]() -> Status {
      SB_RETURN_IF_ERROR(UpdateWallRow(*c, w));
      if (!rederive) return Status::Ok();
      SB_ASSIGN_OR_RETURN(
          Rows r, c->Query("SELECT id, crdl, grade_discipline, grade_value FROM routes "
                           "WHERE wall_id = ? ORDER BY id",
                           {w.id}));
      for (size_t i = 0; i < r.size(); ++i) {
        RouteAxis a;
        a.route_id = r.Int(i, 0);
        a.crdl = r.Text(i, 1);
        a.grade_discipline = r.Text(i, 2);
        a.grade_value = r.OptDouble(i, 3);
        if (!rederive(&a)) continue;
        SB_RETURN_IF_ERROR(
            c->Query("UPDATE routes SET grade_discipline = ?, grade_value = ? WHERE id = ?",
                     {a.grade_discipline, sql::Nullable(a.grade_value), a.route_id})
                .status());
      }
      return Status::Ok();
    });
  }

  // The wall row's update (UpdateWall), on `c`.
  static Status UpdateWallRow(sql::Connection& c, const WallRecord& w) {
    Violation v;
    Result<Rows> r = c.Query(
        std::string("UPDATE walls SET name = ?, discipline = ?, angle = ?, position = ?, "
                    "reset_weeks = ?, plan_x = ?, plan_y = ?, plan_w = ?, plan_h = ?, "
                    "revision = revision + 1 WHERE id = ?") +
            (w.revision > 0 ? " AND revision = ?" : "") + " RETURNING id",
        w.revision > 0
            ? std::vector<Value>{w.name, w.discipline, w.angle, int64_t{w.position},
                                 sql::Nullable(w.reset_weeks), sql::Nullable(w.plan_x),
                                 sql::Nullable(w.plan_y), sql::Nullable(w.plan_w),
                                 sql::Nullable(w.plan_h), w.id, w.revision}
            : std::vector<Value>{w.name, w.discipline, w.angle, int64_t{w.position},
                                 sql::Nullable(w.reset_weeks), sql::Nullable(w.plan_x),
                                 sql::Nullable(w.plan_y), sql::Nullable(w.plan_w),
                                 sql::Nullable(w.plan_h), w.id},
        &v);
    if (!r.ok() && v == Violation::kUnique) {
      return Status::Conflict("the gym has a wall named '" + w.name + "'");
    }
    if (!r.ok()) return r.status().WithPrefix("update wall");
    if (r->empty()) return Stale(c, "walls", w.id, "wall");
    return Status::Ok();
  }

  Status DeleteWall(int64_t id) override {
    SB_ASSIGN_OR_RETURN(sql::Pool::Lease c, pool_->Acquire());
    return sql::RunInTransaction(*c, [&]() -> Status {
      SB_ASSIGN_OR_RETURN(Rows w, c->Query("SELECT name FROM walls WHERE id = ?", {id}));
      if (w.empty()) return Status::NotFound("no wall " + std::to_string(id));
      SB_ASSIGN_OR_RETURN(Rows n, c->Query("SELECT count(*) FROM routes WHERE wall_id = ? AND "
                                           "state <> ?",
                                           {id, std::string(gym::NameOf(gym::RouteState::kStripped))}));
      if (n.Int(0, 0) > 0) {
        return Status::Conflict(std::to_string(n.Int(0, 0)) +
                                (n.Int(0, 0) == 1 ? " route is" : " routes are") +
                                " on the wall; strip or move them first");
      }
      // The archive keeps the wall's name as the routes' free-text wall.
      SB_RETURN_IF_ERROR(c->Query("UPDATE routes SET wall = ? WHERE wall_id = ? AND wall = ''",
                                  {w.Text(0, 0), id})
                             .status());
      SB_RETURN_IF_ERROR(c->Query("DELETE FROM walls WHERE id = ?", {id}).status());
      return Status::Ok();
    });
  }

  Status RemoveMember(int64_t gym_id, int64_t user_id) override {
    SB_ASSIGN_OR_RETURN(sql::Pool::Lease c, pool_->Acquire());
    SB_ASSIGN_OR_RETURN(Rows r, c->Query("DELETE FROM gym_members WHERE gym_id = ? AND "
                                         "user_id = ? RETURNING user_id",
                                         {gym_id, user_id}));
    if (r.empty()) return Status::NotFound("no member " + std::to_string(user_id));
    return Status::Ok();
  }

  Status UpdateCircuit(const CircuitRecord& ci) override {
    SB_ASSIGN_OR_RETURN(sql::Pool::Lease c, pool_->Acquire());
    Violation v;
    std::vector<Value> params = {ci.colour, ci.grade_from, ci.grade_to, ci.id};
    if (ci.revision > 0) params.push_back(ci.revision);
    Result<Rows> r = c->Query(
        std::string("UPDATE circuits SET colour = ?, grade_from = ?, grade_to = ?, "
                    "revision = revision + 1 WHERE id = ?") +
            (ci.revision > 0 ? " AND revision = ?" : "") + " RETURNING id",
        params, &v);
    if (!r.ok() && v == Violation::kUnique) {
      return Status::Conflict("the gym has a circuit '" + ci.colour + "'");
    }
    if (!r.ok()) return r.status().WithPrefix("update circuit");
    if (r->empty()) return Stale(*c, "circuits", ci.id, "circuit");
    return Status::Ok();
  }

  Status DeleteCircuit(int64_t id, std::optional<int64_t> user_id, const std::string& route_note,
                       int64_t* cleared) override {
    SB_ASSIGN_OR_RETURN(sql::Pool::Lease c, pool_->Acquire());
    return sql::RunInTransaction(*c, [&]() -> Status {
      // Issue 31: its routes keep their colour and lose the circuit, saying so.
      SB_ASSIGN_OR_RETURN(Rows routes,
                          c->Query("UPDATE routes SET circuit_id = NULL, revision = revision + 1 "
                                   "WHERE circuit_id = ? RETURNING id",
                                   {id}));
      if (!route_note.empty()) {
        for (size_t i = 0; i < routes.size(); ++i) {
          SB_RETURN_IF_ERROR(InsertHistory(*c, routes.Int(i, 0), user_id, route_note));
        }
      }
      if (cleared) *cleared = static_cast<int64_t>(routes.size());
      SB_ASSIGN_OR_RETURN(Rows r,
                          c->Query("DELETE FROM circuits WHERE id = ? RETURNING id", {id}));
      if (r.empty()) return Status::NotFound("no circuit " + std::to_string(id));
      return Status::Ok();
    });
  }

  Status AddGymHistory(int64_t gym_id, std::optional<int64_t> user_id,
                       const std::string& what) override {
    SB_ASSIGN_OR_RETURN(sql::Pool::Lease c, pool_->Acquire());
    return c
        ->Query("INSERT INTO gym_history(gym_id, user_id, at, what) VALUES(?, ?, ?, ?)",
                {gym_id, sql::Nullable(user_id), NowText(), what})
        .status();
  }

  Result<std::vector<GymHistoryRecord>> ListGymHistory(int64_t gym_id) override {
    SB_ASSIGN_OR_RETURN(sql::Pool::Lease c, pool_->Acquire());
    SB_ASSIGN_OR_RETURN(
        Rows r, c->Query("SELECT h.id, h.gym_id, h.user_id, coalesce(u.username, ''), h.at, "
                         "h.what FROM gym_history h LEFT JOIN users u ON u.id = h.user_id "
                         "WHERE h.gym_id = ? ORDER BY h.id",
                         {gym_id}));
    std::vector<GymHistoryRecord> out;
    for (size_t i = 0; i < r.size(); ++i) {
      out.push_back({r.Int(i, 0), r.Int(i, 1), r.OptInt(i, 2), r.Text(i, 3), r.Text(i, 4),
                     r.Text(i, 5)});
    }
    return out;
  }

  Result<WallRecord> GetWall(int64_t id) override {
    SB_ASSIGN_OR_RETURN(sql::Pool::Lease c, pool_->Acquire());
    SB_ASSIGN_OR_RETURN(Rows r, c->Query(std::string(kWallSelect) + " WHERE id = ?", {id}));
    if (r.empty()) return Status::NotFound("no wall " + std::to_string(id));
    return ReadWalls(r)[0];
  }

  Result<std::vector<WallRecord>> ListWalls(int64_t gym_id) override {
    SB_ASSIGN_OR_RETURN(sql::Pool::Lease c, pool_->Acquire());
    SB_ASSIGN_OR_RETURN(Rows r, c->Query(std::string(kWallSelect) +
                                             " WHERE gym_id = ? ORDER BY position, id",
                                         {gym_id}));
    return ReadWalls(r);
  }

  Result<int64_t> InsertCircuit(const CircuitRecord& ci) override {
    SB_ASSIGN_OR_RETURN(sql::Pool::Lease c, pool_->Acquire());
    Violation v;
    Result<Rows> r = c->Query(
        "INSERT INTO circuits(gym_id, colour, grade_from, grade_to) VALUES(?, ?, ?, ?) "
        "RETURNING id",
        {ci.gym_id, ci.colour, ci.grade_from, ci.grade_to}, &v);
    if (!r.ok() && v == Violation::kUnique) {
      return Status::Conflict("the gym has a circuit '" + ci.colour + "'");
    }
    if (!r.ok() && v == Violation::kForeignKey) {
      return Status::NotFound("no gym " + std::to_string(ci.gym_id));
    }
    if (!r.ok()) return r.status().WithPrefix("insert circuit");
    return r->Int(0, 0);
  }

  Result<std::vector<CircuitRecord>> ListCircuits(int64_t gym_id) override {
    SB_ASSIGN_OR_RETURN(sql::Pool::Lease c, pool_->Acquire());
    SB_ASSIGN_OR_RETURN(Rows r, c->Query("SELECT id, gym_id, colour, grade_from, grade_to, "
                                         "revision FROM circuits WHERE gym_id = ? ORDER BY id",
                                         {gym_id}));
    std::vector<CircuitRecord> out;
    for (size_t i = 0; i < r.size(); ++i) {
      out.push_back({r.Int(i, 0), r.Int(i, 1), r.Text(i, 2), r.Text(i, 3), r.Text(i, 4),
                     r.Int(i, 5)});
    }
    return out;
  }

  Status SetRouteSetters(int64_t route_id, const std::vector<RouteSetter>& setters,
                         std::optional<int64_t> user_id, const std::string& what) override {
    SB_ASSIGN_OR_RETURN(sql::Pool::Lease c, pool_->Acquire());
    return sql::RunInTransaction(*c, [&]() -> Status {
      SB_ASSIGN_OR_RETURN(Rows r, c->Query("SELECT id FROM routes WHERE id = ?", {route_id}));
      if (r.empty()) return Status::NotFound("no route " + std::to_string(route_id));
      SB_RETURN_IF_ERROR(WriteSetters(*c, route_id, setters));
      if (!what.empty()) SB_RETURN_IF_ERROR(InsertHistory(*c, route_id, user_id, what));
      return Status::Ok();
    });
  }

  Status AddHistory(int64_t route_id, std::optional<int64_t> user_id,
                    const std::string& what) override {
    SB_ASSIGN_OR_RETURN(sql::Pool::Lease c, pool_->Acquire());
    return InsertHistory(*c, route_id, user_id, what);
  }

  Result<std::vector<HistoryRecord>> ListHistory(int64_t route_id) override {
    SB_ASSIGN_OR_RETURN(sql::Pool::Lease c, pool_->Acquire());
    SB_ASSIGN_OR_RETURN(
        Rows r, c->Query("SELECT h.id, h.route_id, h.user_id, coalesce(u.username, ''), h.at, "
                         "h.what FROM route_history h LEFT JOIN users u ON u.id = h.user_id "
                         "WHERE h.route_id = ? ORDER BY h.id",
                         {route_id}));
    std::vector<HistoryRecord> out;
    for (size_t i = 0; i < r.size(); ++i) {
      out.push_back({r.Int(i, 0), r.Int(i, 1), r.OptInt(i, 2), r.Text(i, 3), r.Text(i, 4),
                     r.Text(i, 5)});
    }
    return out;
  }

  Result<std::optional<int64_t>> FindByOriginalId(int64_t gym_id, int64_t original_id,
                                                  std::optional<int64_t> owner) override {
    SB_ASSIGN_OR_RETURN(sql::Pool::Lease c, pool_->Acquire());
    SB_ASSIGN_OR_RETURN(
        Rows r, c->Query(std::string("SELECT min(id) FROM routes WHERE gym_id = ? AND "
                                     "original_id = ?") +
                             (owner ? " AND owner_id = ?" : ""),
                         owner ? std::vector<Value>{gym_id, original_id, *owner}
                               : std::vector<Value>{gym_id, original_id}));
    return r.OptInt(0, 0);
  }

 private:
  // The count of `query` (one "?" bound to `id`).
  Result<int64_t> CountOf(const char* query, int64_t id) {
    SB_ASSIGN_OR_RETURN(sql::Pool::Lease c, pool_->Acquire());
    SB_ASSIGN_OR_RETURN(Rows r, c->Query(query, {id}));
    return r.empty() ? 0 : r.Int(0, 0);
  }
  static std::vector<GymRecord> ReadGyms(const Rows& r) {
    std::vector<GymRecord> out;
    for (size_t i = 0; i < r.size(); ++i) {
      out.push_back({r.Int(i, 0), r.Text(i, 1), r.Text(i, 2), r.Text(i, 3), r.Int(i, 4)});
    }
    return out;
  }

  static constexpr const char* kWallSelect =
      "SELECT id, gym_id, name, discipline, angle, position, reset_weeks, plan_x, plan_y, "
      "plan_w, plan_h, revision, targets_revision FROM walls";

  static std::vector<WallRecord> ReadWalls(const Rows& r) {
    std::vector<WallRecord> out;
    auto opt = [&](size_t i, size_t col) -> std::optional<int> {
      std::optional<int64_t> v = r.OptInt(i, col);
      return v ? std::optional<int>(static_cast<int>(*v)) : std::nullopt;
    };
    for (size_t i = 0; i < r.size(); ++i) {
      WallRecord w;
      w.id = r.Int(i, 0);
      w.gym_id = r.Int(i, 1);
      w.name = r.Text(i, 2);
      w.discipline = r.Text(i, 3);
      w.angle = r.OptDouble(i, 4).value_or(0);
      w.position = static_cast<int>(r.Int(i, 5));
      w.reset_weeks = opt(i, 6);
      w.plan_x = opt(i, 7);
      w.plan_y = opt(i, 8);
      w.plan_w = opt(i, 9);
      w.plan_h = opt(i, 10);
      w.revision = r.Int(i, 11);
      w.targets_revision = r.Int(i, 12);
      out.push_back(std::move(w));
    }
    return out;
  }

  // Inside a transaction: the route's setters replace any stored ones.
  static Status WriteSetters(sql::Connection& c, int64_t route_id,
                             const std::vector<RouteSetter>& setters) {
    SB_ASSIGN_OR_RETURN(Rows d, c.Query("DELETE FROM route_setters WHERE route_id = ?",
                                        {route_id}));
    for (size_t i = 0; i < setters.size(); ++i) {
      Violation v;
      Result<Rows> in = c.Query(
          "INSERT INTO route_setters(route_id, position, user_id, name) VALUES(?, ?, ?, ?)",
          {route_id, static_cast<int64_t>(i), sql::Nullable(setters[i].user_id), setters[i].name},
          &v);
      if (!in.ok() && v == Violation::kForeignKey) {
        return Status::NotFound("setter: no user " +
                                std::to_string(setters[i].user_id.value_or(0)));
      }
      if (!in.ok()) return in.status().WithPrefix("insert route setter");
    }
    return Status::Ok();
  }

  static Status InsertHistory(sql::Connection& c, int64_t route_id,
                              std::optional<int64_t> user_id, const std::string& what) {
    Violation v;
    Result<Rows> r = c.Query(
        "INSERT INTO route_history(route_id, user_id, at, what) VALUES(?, ?, ?, ?)",
        {route_id, sql::Nullable(user_id), NowText(), what}, &v);
    if (!r.ok() && v == Violation::kForeignKey) {
      return Status::NotFound("no route " + std::to_string(route_id));
    }
    if (!r.ok()) return r.status().WithPrefix("insert route history");
    return Status::Ok();
  }

  // Folds the search text of every route written by an older store
  // (routes.search_version < kSearchVersion), in batches: the migration to
  // schema 6 cannot fold in SQL alike on both backends.
  static Status RefreshSearchText(sql::Connection& c) {
    constexpr int64_t kBatch = 500;
    for (;;) {
      SB_ASSIGN_OR_RETURN(Rows r, c.Query("SELECT id, name, crdl FROM routes WHERE "
                                          "search_version < ? ORDER BY id LIMIT ?",
                                          {int64_t{kSearchVersion}, kBatch}));
      if (r.empty()) return Status::Ok();
      SB_RETURN_IF_ERROR(sql::RunInTransaction(c, [&]() -> Status {
        for (size_t i = 0; i < r.size(); ++i) {
          SB_ASSIGN_OR_RETURN(
              Rows u, c.Query("UPDATE routes SET search_text = ?, search_version = ? WHERE id = ?",
                              {SearchText(r.Text(i, 1), r.Text(i, 2)), int64_t{kSearchVersion},
                               r.Int(i, 0)}));
        }
        return Status::Ok();
      }));
      if (static_cast<int64_t>(r.size()) < kBatch) return Status::Ok();
    }
  }

  // Case-insensitive substring test of `hay` against one parameter:
  // instr() in SQLite, strpos() in PostgreSQL.
  std::string Contains(const std::string& hay) const {
    return std::string(pg_ ? "strpos(" : "instr(") + "lower(" + hay + "), lower(?)) > 0";
  }

  // The WHERE clause of a route filter, its values appended to `params`.
  // Only variations have sources, so the sources' test is skipped for other
  // rows; CROSS JOIN makes SQLite walk a variation's few route_sources rows
  // first (with a plain JOIN and no ANALYZE statistics it scanned every
  // private route per listed row: seconds per page at 200,000 routes, issue
  // 22, docs/BENCHMARKS.md "A chain at scale"); PostgreSQL reads it as JOIN.
  // The visibility rule (store/visibility.h, the one place it is written):
  // the viewer sees the row, and every route it was made from.
  std::string FilterWhere(const RouteFilter& f, std::vector<Value>* params) const {
    const int64_t viewer = f.viewer.value_or(-1);
    int route_params = 0, source_params = 0;
    std::string w = " WHERE " + SeesSql("r", &route_params) +
                    " AND (r.is_variation = 0 OR NOT EXISTS (SELECT 1 FROM "
                    "route_sources s CROSS JOIN routes src WHERE src.id = s.route_id AND "
                    "s.variation_id = r.id AND NOT " +
                    SeesSql("src", &source_params) + "))";
    params->insert(params->end(), static_cast<size_t>(route_params + source_params), viewer);
    if (f.gym_id) {
      w += " AND r.gym_id = ?";
      params->push_back(*f.gym_id);
    }
    if (f.wall_id) {
      w += " AND r.wall_id = ?";
      params->push_back(*f.wall_id);
    }
    if (!f.state.empty()) {
      w += " AND r.state = ?";
      params->push_back(f.state);
    }
    if (f.circuit_id) {
      w += " AND r.circuit_id = ?";
      params->push_back(*f.circuit_id);
    }
    if (!f.colour.empty()) {
      w += " AND lower(r.colour) = lower(?)";
      params->push_back(f.colour);
    }
    if (!f.grade.empty()) {
      w += " AND lower(r.grade) = lower(?)";
      params->push_back(f.grade);
    }
    if (!f.setter.empty()) {
      w += " AND (" + Contains("r.setter") + " OR " + Contains("coalesce(u.username, '')") +
           " OR EXISTS (SELECT 1 FROM route_setters rs WHERE rs.route_id = r.id AND " +
           Contains("rs.name") + "))";
      params->insert(params->end(), 3, f.setter);
    }
    if (!f.text.empty()) {
      // The search text is case-folded in C++ (sb::FoldCase) at write time
      // and the needle here, so every script compares alike on both backends.
      w += std::string(" AND (") + (pg_ ? "strpos(r.search_text, ?) > 0" : "instr(r.search_text, ?) > 0") +
           " OR " + Contains("coalesce(u.username, '')") + ")";
      params->push_back(FoldCase(f.text));
      params->push_back(f.text);
    }
    if (!f.wall.empty()) {
      w += " AND " + Contains("r.wall");
      params->push_back(f.wall);
    }
    if (f.is_variation) w += *f.is_variation ? " AND r.is_variation = 1" : " AND r.is_variation = 0";
    if (f.owner) {
      w += " AND r.owner_id = ?";
      params->push_back(*f.owner);
    }
    if (f.public_only) w += " AND r.is_public = 1";
    if (f.not_gym_id) {
      w += " AND (r.gym_id IS NULL OR r.gym_id <> ?)";
      params->push_back(*f.not_gym_id);
    }
    if (!f.grade_discipline.empty()) {
      // public_only on SQLite: routes_public in id order, not the grade index
      // (the RouteFilter comment); `|| ''` and `+ 0` keep its planner off it.
      // PostgreSQL walks routes_public in id order by itself (10 ms), and the
      // same terms there misled its estimates (a bitmap scan and sort, 0.95 s).
      const bool off_index = f.public_only && !pg_;
      const std::string disc = off_index ? "r.grade_discipline || ''" : "r.grade_discipline";
      const std::string value = off_index ? "r.grade_value + 0" : "r.grade_value";
      w += " AND ((" + disc + " = ? AND r.grade_value IS NOT NULL";
      params->push_back(f.grade_discipline);
      if (f.grade_min) {
        w += " AND " + value + " >= ?";
        params->push_back(*f.grade_min);
      }
      if (f.grade_max) {
        w += " AND " + value + " <= ?";
        params->push_back(*f.grade_max);
      }
      w += ")";
      if (!f.grade_typed.empty()) {
        w += " OR lower(r.grade) = lower(?)";
        params->push_back(f.grade_typed);
      }
      w += ")";
    }
    return w;
  }

  // ORDER BY of a route list; text compared byte-wise on both backends
  // (PostgreSQL's database collation may differ: COLLATE "C").
  std::string OrderBy(RouteSort sort) const {
    const std::string c = pg_ ? " COLLATE \"C\"" : "";
    switch (sort) {
      case RouteSort::kNewest:
        return " ORDER BY r.id DESC";
      case RouteSort::kOldest:
        return " ORDER BY r.id ASC";
      case RouteSort::kName:
        return " ORDER BY lower(r.name)" + c + ", r.id";
      case RouteSort::kEasiest:
        return " ORDER BY (r.grade_value IS NULL), r.grade_discipline" + c +
               ", r.grade_value, r.id";
      case RouteSort::kHardest:
        return " ORDER BY (r.grade_value IS NULL), r.grade_discipline" + c +
               ", r.grade_value DESC, r.id";
      case RouteSort::kSetNewest:
        return " ORDER BY (r.set_on = ''), r.set_on" + c + " DESC, r.id DESC";
      case RouteSort::kSetOldest:
        return " ORDER BY (r.set_on = ''), r.set_on" + c + ", r.id";
    }
    return " ORDER BY r.id DESC";
  }

  // Inside a transaction: the study's routes replace any stored ones.
  static Status WriteStudyRoutes(sql::Connection& c, int64_t study_id,
                                 const std::vector<StudyRoute>& routes) {
    SB_ASSIGN_OR_RETURN(Rows d, c.Query("DELETE FROM study_routes WHERE study_id = ?", {study_id}));
    for (const StudyRoute& sr : routes) {
      Violation v;
      Result<Rows> in = c.Query(
          "INSERT INTO study_routes(study_id, position, route_id, name) VALUES(?, ?, ?, ?)",
          {study_id, int64_t{sr.position}, sql::Nullable(sr.route_id), sr.name}, &v);
      if (!in.ok() && v != Violation::kNone) {
        return Status::InvalidInput("study routes: position " + std::to_string(sr.position) +
                                    " twice or route " + std::to_string(sr.route_id.value_or(0)) +
                                    " unknown");
      }
      if (!in.ok()) return in.status().WithPrefix("insert study route");
    }
    return Status::Ok();
  }

  // The studies kStudySelect + `where` selects, with their routes.
  static Result<std::vector<StudyRecord>> ReadStudies(sql::Connection& c, const std::string& where,
                                                      std::vector<Value> params) {
    SB_ASSIGN_OR_RETURN(Rows s, c.Query(std::string(kStudySelect) + where, params));
    std::vector<StudyRecord> out;
    for (size_t i = 0; i < s.size(); ++i) {
      out.push_back(ReadStudy(s, i));
      SB_ASSIGN_OR_RETURN(Rows r, c.Query("SELECT position, route_id, name FROM study_routes "
                                          "WHERE study_id = ? ORDER BY position",
                                          {out.back().id}));
      for (size_t j = 0; j < r.size(); ++j) {
        StudyRoute sr;
        sr.position = static_cast<int>(r.Int(j, 0));
        sr.route_id = r.OptInt(j, 1);
        sr.name = r.Text(j, 2);
        out.back().routes.push_back(std::move(sr));
      }
    }
    return out;
  }

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
    std::vector<Value> row;
    row.reserve(sql_rows::kRouteColumns);
    sql_rows::AppendRouteRow(r, now, SearchText(r.name, r.crdl), kSearchVersion, &row);
    const std::string insert = std::string(sql_rows::kRouteInsert) +
                               sql_rows::Placeholders(sql_rows::kRouteColumns, 1) + " RETURNING id";
    SB_ASSIGN_OR_RETURN(Rows ins, c.Query(insert, row));
    int64_t id = ins.Int(0, 0);
    SB_RETURN_IF_ERROR(WriteSetters(c, id, r.setters));
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
    if (!r.inputs.empty()) {
      // Its sources: the inputs and, transitively, what they were made from.
      SB_ASSIGN_OR_RETURN(
          Rows src,
          c.Query("INSERT INTO route_sources(variation_id, route_id) "
                  "SELECT CAST(? AS BIGINT), route_id FROM variation_inputs "
                  "WHERE variation_id = ? AND route_id IS NOT NULL "
                  "UNION SELECT CAST(? AS BIGINT), s.route_id FROM route_sources s "
                  "JOIN variation_inputs vi ON s.variation_id = vi.route_id "
                  "WHERE vi.variation_id = ? ON CONFLICT DO NOTHING",
                  {id, id, id, id}));
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

GymStore* GymStoreOf(Store* store) { return dynamic_cast<GymStore*>(store); }

TickStore* TickStoreOf(Store* store) { return dynamic_cast<TickStore*>(store); }

TargetStore* TargetStoreOf(Store* store) { return dynamic_cast<TargetStore*>(store); }
BulkStore* BulkStoreOf(Store* store) { return dynamic_cast<BulkStore*>(store); }
ProfileStore* ProfileStoreOf(Store* store) { return dynamic_cast<ProfileStore*>(store); }
ScaleStore* ScaleStoreOf(Store* store) { return dynamic_cast<ScaleStore*>(store); }
ImportStore* ImportStoreOf(Store* store) { return dynamic_cast<ImportStore*>(store); }
PredictionStore* PredictionStoreOf(Store* store) {
  return dynamic_cast<PredictionStore*>(store);
}
CountStore* CountStoreOf(Store* store) { return dynamic_cast<CountStore*>(store); }

Status RunAtomically(Store* store, const std::function<Status()>& body) {
  if (auto* sql = dynamic_cast<SqlStore*>(store)) return sql->Atomically(body);
  return body();
}

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
  // Issue 34: a file database gets a few connections. With one, every
  // query of the server queued for it: a tick's one-row write waited for a
  // busy gym's fit reading its 250,000 ticks (seconds), and so did every
  // page. In WAL mode (sqlite_conn.cc) readers do not block the writer nor
  // each other; writers still take turns, in SQLite's own lock (a
  // transaction begins IMMEDIATE, so none upgrades a read lock), waiting up
  // to its busy timeout. An in-memory database is private to its
  // connection, so it keeps one. Callers queue for a connection up to a
  // minute, as long as any import may take.
  const bool in_memory = path.empty() || path == ":memory:" ||
                         (path.rfind("file:", 0) == 0 && path.find("memory") != std::string::npos);
  auto pool = sql::Pool::Create([path] { return sql::OpenSqlite(path); },
                                in_memory ? 1 : kSqliteConnections,
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
