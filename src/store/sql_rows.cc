#include "store/sql_rows.h"

#include <ctime>
#include <utility>

#include "base/date.h"
#include "gym/rules.h"

namespace sb::store::sql_rows {

std::string NowText() { return UtcTimeText(std::time(nullptr)); }

std::string Placeholders(int columns, size_t rows) {
  std::string one = "(";
  for (int i = 0; i < columns; ++i) one += i ? ", ?" : "?";
  one += ")";
  std::string out;
  out.reserve(rows * (one.size() + 2));
  for (size_t r = 0; r < rows; ++r) {
    if (r) out += ", ";
    out += one;
  }
  return out;
}

gym::RouteState RouteStateColumn(std::string_view text) {
  return gym::RouteStateOf(text).value_or(gym::RouteState::kDraft);
}

gym::Role RoleColumn(std::string_view text) {
  return gym::RoleOf(text).value_or(gym::Role::kClimber);
}

gym::TickState TickStateColumn(std::string_view text) {
  return gym::TickStateOf(text).value_or(gym::TickState::kHeld);
}

void AppendRouteRow(const RouteRecord& r, const std::string& now, std::string search_text,
                    int search_version, std::vector<sql::Value>* out) {
  const std::string& at = r.created_at.empty() ? now : r.created_at;
  sql::Value vals[kRouteColumns] = {sql::Nullable(r.owner_id), r.name, r.grade, r.setter, r.crdl,
                                    int64_t{r.move_count}, int64_t{r.is_public},
                                    int64_t{r.is_variation}, r.params_json, r.plan_json,
                                    int64_t{r.smooth}, at, at, r.colour, r.wall, r.set_on,
                                    r.grade_discipline, sql::Nullable(r.grade_value),
                                    int64_t{r.meta_version}, r.request_key,
                                    sql::Nullable(r.gym_id), sql::Nullable(r.wall_id),
                                    std::string(gym::NameOf(r.state)),
                                    r.planned_on, r.strip_on, sql::Nullable(r.original_id),
                                    std::move(search_text), int64_t{search_version},
                                    sql::Nullable(r.circuit_id)};
  for (sql::Value& v : vals) out->push_back(std::move(v));
}

}  // namespace sb::store::sql_rows
