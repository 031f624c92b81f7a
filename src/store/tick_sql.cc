#include "store/tick_sql.h"

#include <algorithm>
#include <atomic>
#include <optional>
#include <utility>

#include "store/tick_page.h"
#include "store/sql_rows.h"

namespace sb::store::ticks_sql {

namespace {

using sql::Rows;
using sql::Violation;

constexpr const char* kSelect =
    "SELECT id, route_id, gym_id, climber, user_id, origin, day, outcome, attempts, stars, "
    "felt_grade, felt_discipline, felt_value, comment, state, created_at, updated_at, revision "
    "FROM ticks";

std::optional<int> OptInt32(const Rows& r, size_t i, size_t col) {
  std::optional<int64_t> v = r.OptInt(i, col);
  return v ? std::optional<int>(static_cast<int>(*v)) : std::nullopt;
}

// Appends the rows' ticks to `out`.
void ReadInto(const Rows& r, std::vector<TickRecord>& out) {
  for (size_t i = 0; i < r.size(); ++i) {
    TickRecord t;
    t.id = r.Int(i, 0);
    t.route_id = r.Int(i, 1);
    t.gym_id = r.Int(i, 2);
    t.climber = r.Text(i, 3);
    t.user_id = r.OptInt(i, 4);
    t.origin = r.Text(i, 5);
    t.day = r.Text(i, 6);
    t.outcome = r.Text(i, 7);
    t.attempts = OptInt32(r, i, 8);
    t.stars = OptInt32(r, i, 9);
    t.felt_grade = r.Text(i, 10);
    t.felt_discipline = r.Text(i, 11);
    t.felt_value = r.OptDouble(i, 12);
    t.comment = r.Text(i, 13);
    t.state = sql_rows::TickStateColumn(r.Text(i, 14));
    t.created_at = r.Text(i, 15);
    t.updated_at = r.Text(i, 16);
    t.revision = static_cast<int>(r.Int(i, 17));
    out.push_back(std::move(t));
  }
}

std::vector<TickRecord> Read(const Rows& r) {
  std::vector<TickRecord> out;
  out.reserve(r.size());
  ReadInto(r, out);
  return out;
}

std::atomic<int64_t> gym_tick_page{kGymTickPage};

}  // namespace

int64_t GymTickPage() { return gym_tick_page.load(); }

Result<TickRecord> PutTick(sql::Connection& c, const TickRecord& t) {
  Violation v;
  Result<Rows> r = c.Query(
      "INSERT INTO ticks(route_id, gym_id, climber, user_id, origin, day, outcome, attempts, "
      "stars, felt_grade, felt_discipline, felt_value, comment, state, created_at, updated_at) "
      "VALUES(?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?) "
      "ON CONFLICT(route_id, climber, day) DO UPDATE SET outcome = excluded.outcome, "
      "attempts = excluded.attempts, stars = excluded.stars, felt_grade = excluded.felt_grade, "
      "felt_discipline = excluded.felt_discipline, felt_value = excluded.felt_value, "
      "comment = excluded.comment, state = excluded.state, updated_at = excluded.updated_at, "
      "revision = ticks.revision + 1 RETURNING id",
      {t.route_id, t.gym_id, t.climber, sql::Nullable(t.user_id), t.origin, t.day, t.outcome,
       sql::Nullable(t.attempts), sql::Nullable(t.stars), t.felt_grade, t.felt_discipline,
       sql::Nullable(t.felt_value), t.comment, std::string(gym::NameOf(t.state)), t.created_at,
       t.updated_at},
      &v);
  if (!r.ok() && v == Violation::kForeignKey) {
    return Status::NotFound("no route " + std::to_string(t.route_id) + " in gym " +
                            std::to_string(t.gym_id));
  }
  if (!r.ok()) return r.status().WithPrefix("put tick");
  return GetTick(c, r->Int(0, 0));
}

Result<TickRecord> GetTick(sql::Connection& c, int64_t id) {
  SB_ASSIGN_OR_RETURN(Rows r, c.Query(std::string(kSelect) + " WHERE id = ?", {id}));
  if (r.empty()) return Status::NotFound("no tick " + std::to_string(id));
  return Read(r)[0];
}

Result<std::vector<TickRecord>> RouteTicks(sql::Connection& c, int64_t route_id) {
  SB_ASSIGN_OR_RETURN(Rows r, c.Query(std::string(kSelect) +
                                          " WHERE route_id = ? ORDER BY day, id",
                                      {route_id}));
  return Read(r);
}

Result<std::vector<TickRecord>> GymTicks(sql::Connection& c, int64_t gym_id, int64_t page) {
  // Issue 34 (memory under load): read in pages of `page` ticks by id (a
  // keyset on (gym_id, id), the index ticks_gym_id of schema 23, on both
  // backends), so the text rows of a big gym (250,000 ticks: ~200 MB as
  // Rows, and on PostgreSQL libpq's result besides) are never all held
  // beside the records made of them: one page of rows at a time. Each tick
  // is read once, in id order; a tick written meanwhile is in a later page
  // or not at all (the fit's replay, app/logbook.cc, tells which).
  page = std::max<int64_t>(1, page);
  // Sized once from a count of the gym's ticks in any state (an index-only
  // read: 50 ms for 250,000 on PostgreSQL): grown by doubling, the vector of
  // 250,000 records (100 MB) would be held one and a half times over while
  // it moves. Ticks written between the count and the last page get the
  // slack.
  SB_ASSIGN_OR_RETURN(Rows n, c.Query("SELECT count(*) FROM ticks WHERE gym_id = ?", {gym_id}));
  const int64_t count = n.empty() ? 0 : n.Int(0, 0);
  std::vector<TickRecord> out;
  out.reserve(static_cast<size_t>(count + count / 64 + 16));
  int64_t after = 0;
  for (;;) {
    SB_ASSIGN_OR_RETURN(Rows r, c.Query(std::string(kSelect) +
                                            " WHERE gym_id = ? AND state = 'ok' AND id > ? "
                                            "ORDER BY gym_id, id LIMIT ?",
                                        {gym_id, after, page}));
    const size_t got = r.size();
    ReadInto(r, out);
    r = Rows();  // the page's text rows go before the next page is read
    if (got == 0) break;
    after = out.back().id;
    if (static_cast<int64_t>(got) < page) break;
  }
  return out;
}

Result<std::vector<TickRecord>> ClimberTicks(sql::Connection& c, const std::string& climber) {
  SB_ASSIGN_OR_RETURN(
      Rows r, c.Query(std::string(kSelect) +
                          " WHERE climber = ? AND state <> 'discarded' ORDER BY day DESC, id",
                      {climber}));
  return Read(r);
}

namespace {
TickCounts ReadCounts(const Rows& r) {
  TickCounts n;
  if (r.empty()) return n;
  n.ticks = r.OptInt(0, 0).value_or(0);
  n.routes = r.OptInt(0, 1).value_or(0);
  n.gyms = r.OptInt(0, 2).value_or(0);
  n.held = r.OptInt(0, 3).value_or(0);
  return n;
}
constexpr const char* kCounts =
    "SELECT COUNT(*), COUNT(DISTINCT route_id), COUNT(DISTINCT gym_id), "
    "COALESCE(SUM(CASE WHEN state = 'held' THEN 1 ELSE 0 END), 0) FROM ticks";
}  // namespace

Result<TickCounts> CountClimberTicks(sql::Connection& c, const std::string& climber) {
  SB_ASSIGN_OR_RETURN(Rows r, c.Query(std::string(kCounts) +
                                          " WHERE climber = ? AND state <> 'discarded'",
                                      {climber}));
  return ReadCounts(r);
}

Result<TickCounts> CountRouteTicks(sql::Connection& c, int64_t route_id) {
  SB_ASSIGN_OR_RETURN(Rows r, c.Query(std::string(kCounts) + " WHERE route_id = ?", {route_id}));
  return ReadCounts(r);
}

Result<TickVersion> GymTickVersion(sql::Connection& c, int64_t gym_id) {
  SB_ASSIGN_OR_RETURN(Rows r, c.Query("SELECT tick_version, data_version FROM gym_versions "
                                      "WHERE gym_id = ?",
                                      {gym_id}));
  if (r.empty()) return TickVersion{};
  return TickVersion{r.Int(0, 0), r.Int(0, 1)};
}

Status SetTickState(sql::Connection& c, int64_t id, const std::string& state,
                    const std::string& updated_at) {
  SB_ASSIGN_OR_RETURN(Rows r, c.Query("UPDATE ticks SET state = ?, updated_at = ?, "
                                      "revision = revision + 1 WHERE id = ? RETURNING id",
                                      {state, updated_at, id}));
  if (r.empty()) return Status::NotFound("no tick " + std::to_string(id));
  return Status::Ok();
}

Result<int> MergeTicks(sql::Connection& c, const std::string& from, const std::string& to,
                       int64_t user_id) {
  if (from == to) return 0;
  return sql::InTransaction<int>(c, [&]() -> Result<int> {
    // Where both have a tick on a route and day, the one updated last stays
    // (ties: the account's).
    SB_ASSIGN_OR_RETURN(
        Rows older_mine,
        c.Query("DELETE FROM ticks WHERE climber = ? AND EXISTS (SELECT 1 FROM ticks d "
                "WHERE d.climber = ? AND d.route_id = ticks.route_id AND d.day = ticks.day "
                "AND d.updated_at > ticks.updated_at) RETURNING id",
                {to, from}));
    SB_ASSIGN_OR_RETURN(
        Rows older_device,
        c.Query("DELETE FROM ticks WHERE climber = ? AND EXISTS (SELECT 1 FROM ticks u "
                "WHERE u.climber = ? AND u.route_id = ticks.route_id AND u.day = ticks.day) "
                "RETURNING id",
                {from, to}));
    SB_ASSIGN_OR_RETURN(Rows moved,
                        c.Query("UPDATE ticks SET climber = ?, user_id = ?, "
                                "revision = revision + 1 WHERE climber = ? RETURNING id",
                                {to, user_id, from}));
    (void)older_mine;
    (void)older_device;
    return static_cast<int>(moved.size());
  });
}

Result<int> NewIdentitiesSince(sql::Connection& c, int64_t route_id, const std::string& origin,
                               const std::string& since) {
  SB_ASSIGN_OR_RETURN(
      Rows r, c.Query("SELECT count(DISTINCT t.climber) FROM ticks t WHERE t.route_id = ? "
                      "AND t.origin = ? AND t.created_at >= ? AND t.user_id IS NULL "
                      "AND NOT EXISTS (SELECT 1 FROM ticks o WHERE o.climber = t.climber "
                      "AND o.created_at < ?)",
                      {route_id, origin, since, since}));
  return static_cast<int>(r.Int(0, 0));
}

}  // namespace sb::store::ticks_sql

namespace sb::store {

int64_t SetGymTickPageForTesting(int64_t page) {
  return ticks_sql::gym_tick_page.exchange(std::max<int64_t>(1, page));
}

}  // namespace sb::store
