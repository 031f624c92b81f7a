// The SQL of the fit's tick reads (issue 34: a discipline's refit reads only
// that discipline's ticks, and only the columns a fit counts), written once
// for both backends over sql::Connection; store/sql_store.cc forwards the
// TickStore methods of the same names to these. Internal to the store
// module (kept apart from tick_sql.cc, the logbook's other SQL).
#ifndef SB_STORE_TICK_FIT_SQL_H_
#define SB_STORE_TICK_FIT_SQL_H_

#include <cstdint>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "store/sql.h"
#include "store/tick_store.h"

namespace sb::store::ticks_sql {

// As TickStore::GymDisciplineTicks, EachGymDisciplineTicksPage and
// AgedRouteCounts, on `c`.
Result<std::vector<TickRecord>> GymDisciplineTicks(sql::Connection& c, int64_t gym_id,
                                                   const std::string& discipline);
Status EachGymDisciplineTicksPage(sql::Connection& c, int64_t gym_id, const std::string& discipline,
                                  const std::function<Status(std::vector<TickRecord>&)>& page);
Result<std::map<std::string, int64_t>> AgedRouteCounts(sql::Connection& c, int64_t gym_id,
                                                       const std::string& created_until);

}  // namespace sb::store::ticks_sql

#endif  // SB_STORE_TICK_FIT_SQL_H_
