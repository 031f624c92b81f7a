#include "store/bulk_sql.h"

#include <algorithm>
#include <string_view>
#include <utility>

#include "store/sql_rows.h"

namespace sb::store::bulk_sql {

namespace {

using sql::Rows;
using sql::Value;
using sql::Violation;
using sql_rows::kRouteColumns;
using sql_rows::kRouteInsert;
using sql_rows::NowText;
using sql_rows::Placeholders;

constexpr int kSetterColumns = 4;
constexpr int kBulkSetterRows = 2000;  // 8,000 parameters (see kBulkRouteRows)

constexpr int kTickColumns = 16;
constexpr std::string_view kTickInsert =
    "INSERT INTO ticks(route_id, gym_id, climber, user_id, origin, day, outcome, attempts, "
    "stars, felt_grade, felt_discipline, felt_value, comment, state, created_at, updated_at) "
    "VALUES ";

// The error of a failed bulk statement, by the constraint it broke.
Status Failed(const Status& st, Violation v, const char* what) {
  if (v == Violation::kForeignKey) {
    return Status::NotFound(std::string(what) + ": a referenced row does not exist (" +
                            st.message() + ")");
  }
  if (v == Violation::kUnique) {
    return Status::Conflict(std::string(what) + ": a row repeats a unique key (" + st.message() +
                            ")");
  }
  return st.WithPrefix(what);
}

}  // namespace

Result<std::vector<int64_t>> InsertRoutes(sql::Connection& c,
                                          const std::vector<RouteRecord>& routes,
                                          const SearchRule& search) {
  for (size_t i = 0; i < routes.size(); ++i) {
    if (!routes[i].inputs.empty()) {
      return Status::InvalidInput("bulk routes[" + std::to_string(i) +
                                  "]: variations with inputs go through InsertRoutes");
    }
  }
  const std::string now = NowText();
  return sql::InTransaction<std::vector<int64_t>>(c, [&]() -> Result<std::vector<int64_t>> {
    std::vector<int64_t> ids;
    ids.reserve(routes.size());
    std::vector<Value> params;
    for (size_t first = 0; first < routes.size(); first += kBulkRouteRows) {
      const size_t n = std::min(routes.size() - first, static_cast<size_t>(kBulkRouteRows));
      params.clear();
      params.reserve(n * kRouteColumns);
      for (size_t i = first; i < first + n; ++i) {
        const RouteRecord& r = routes[i];
        sql_rows::AppendRouteRow(r, now, search.text(r.name, r.crdl), search.version, &params);
      }
      Violation v = Violation::kNone;
      Result<Rows> ins = c.Query(std::string(kRouteInsert) + Placeholders(kRouteColumns, n) +
                                     " RETURNING id",
                                 params, &v);
      if (!ins.ok()) return Failed(ins.status(), v, "bulk insert routes");
      if (ins->size() != n) return Status::Internal("bulk insert routes: ids missing");
      // Both backends number the rows of one INSERT in VALUES order; RETURNING's
      // own order is not promised, so the ids are sorted.
      std::vector<int64_t> got;
      got.reserve(n);
      for (size_t i = 0; i < n; ++i) got.push_back(ins->Int(i, 0));
      std::sort(got.begin(), got.end());
      ids.insert(ids.end(), got.begin(), got.end());
    }
    // The setters, many rows per statement.
    size_t rows = 0;
    params.clear();
    auto flush = [&]() -> Status {
      if (rows == 0) return Status::Ok();
      Violation v = Violation::kNone;
      Result<Rows> r = c.Query("INSERT INTO route_setters(route_id, position, user_id, name) "
                               "VALUES " + Placeholders(kSetterColumns, rows),
                               params, &v);
      params.clear();
      rows = 0;
      return r.ok() ? Status::Ok() : Failed(r.status(), v, "bulk insert route setters");
    };
    for (size_t i = 0; i < routes.size(); ++i) {
      for (size_t p = 0; p < routes[i].setters.size(); ++p) {
        const RouteSetter& s = routes[i].setters[p];
        params.push_back(ids[i]);
        params.push_back(static_cast<int64_t>(p));
        params.push_back(sql::Nullable(s.user_id));
        params.push_back(s.name);
        if (++rows == kBulkSetterRows) SB_RETURN_IF_ERROR(flush());
      }
    }
    SB_RETURN_IF_ERROR(flush());
    return ids;
  });
}

Status InsertTicks(sql::Connection& c, const std::vector<TickRecord>& ticks) {
  return sql::RunInTransaction(c, [&]() -> Status {
    std::vector<Value> params;
    for (size_t first = 0; first < ticks.size(); first += kBulkTickRows) {
      const size_t n = std::min(ticks.size() - first, static_cast<size_t>(kBulkTickRows));
      params.clear();
      params.reserve(n * kTickColumns);
      for (size_t i = first; i < first + n; ++i) {
        const TickRecord& t = ticks[i];
        Value vals[kTickColumns] = {t.route_id, t.gym_id, t.climber, sql::Nullable(t.user_id),
                                    t.origin, t.day, t.outcome, sql::Nullable(t.attempts),
                                    sql::Nullable(t.stars), t.felt_grade, t.felt_discipline,
                                    sql::Nullable(t.felt_value), t.comment,
                                    std::string(gym::NameOf(t.state)),
                                    t.created_at, t.updated_at};
        for (Value& v : vals) params.push_back(std::move(v));
      }
      Violation v = Violation::kNone;
      Result<Rows> r =
          c.Query(std::string(kTickInsert) + Placeholders(kTickColumns, n), params, &v);
      if (!r.ok()) return Failed(r.status(), v, "bulk insert ticks");
    }
    return Status::Ok();
  });
}

}  // namespace sb::store::bulk_sql
