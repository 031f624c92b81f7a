// Helpers the store's SQL files share (sql_store.cc, bulk_sql.cc): the time
// text the store writes, "(?, ...)" placeholder lists, and the one routes
// INSERT (its columns and the row a RouteRecord is written as). Internal to
// the store module.
#ifndef SB_STORE_SQL_ROWS_H_
#define SB_STORE_SQL_ROWS_H_

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include "gym/rules.h"
#include "store/sql.h"
#include "store/store.h"

namespace sb::store::sql_rows {

// The current UTC time as "YYYY-MM-DD HH:MM:SS" (the created_at/updated_at
// text of every table). Thread-safe.
std::string NowText();

// "(?, ?, ..., ?)" with `columns` parameters, repeated `rows` times,
// comma-separated. Pure.
std::string Placeholders(int columns, size_t rows);

// The number of columns of kRouteInsert, and of each RouteRow.
inline constexpr int kRouteColumns = 29;
// "INSERT INTO routes(...) VALUES " (the column list RouteRow fills); the
// caller appends Placeholders(kRouteColumns, n) and any RETURNING clause.
inline constexpr std::string_view kRouteInsert =
    "INSERT INTO routes(owner_id, name, grade, setter, crdl, move_count, is_public, "
    "is_variation, params_json, plan_json, smooth, created_at, updated_at, colour, "
    "wall, set_on, grade_discipline, grade_value, meta_version, request_key, "
    "gym_id, wall_id, state, planned_on, strip_on, original_id, search_text, "
    "search_version, circuit_id) VALUES ";

// The gym's enums from their stored names (gym/rules.h's names, the text of
// the state and role columns; the app writes them with gym::NameOf). A name
// no value has (the schema's CHECKs and the app write none) reads as the
// least of each: a draft route, a climber, a held tick. Pure.
gym::RouteState RouteStateColumn(std::string_view text);
gym::Role RoleColumn(std::string_view text);
gym::TickState TickStateColumn(std::string_view text);

// Appends the kRouteColumns parameters of route `r` to `out`, in
// kRouteInsert's order: created_at and updated_at are `now` where
// r.created_at is empty, the state's name, search_text and
// search_version as given (the store's search rule). Pure.
void AppendRouteRow(const RouteRecord& r, const std::string& now, std::string search_text,
                    int search_version, std::vector<sql::Value>* out);

}  // namespace sb::store::sql_rows

#endif  // SB_STORE_SQL_ROWS_H_
