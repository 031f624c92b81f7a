// The SQL of store::TickStore (schema 7), written once for both backends
// over sql::Connection; store/sql_store.cc forwards to these. Internal to
// the store module.
#ifndef SB_STORE_TICK_SQL_H_
#define SB_STORE_TICK_SQL_H_

#include <string>
#include <vector>

#include "store/sql.h"
#include "store/tick_store.h"

namespace sb::store::ticks_sql {

// As the TickStore methods of the same names, on connection `c`.
Result<TickRecord> PutTick(sql::Connection& c, const TickRecord& tick);
Result<TickRecord> GetTick(sql::Connection& c, int64_t id);
Result<std::vector<TickRecord>> RouteTicks(sql::Connection& c, int64_t route_id);
// GymTicks reads in pages of `page` ticks (keyset on (gym_id, id)): the same
// rows in the same order whatever the page; tests pass small pages.
inline constexpr int64_t kGymTickPage = 10000;
// The page SqlStore's GymTicks reads with: kGymTickPage unless a test set
// another (SetGymTickPageForTesting, store/tick_page.h).
int64_t GymTickPage();
Result<std::vector<TickRecord>> GymTicks(sql::Connection& c, int64_t gym_id,
                                         int64_t page = kGymTickPage);
Result<std::vector<TickRecord>> ClimberTicks(sql::Connection& c, const std::string& climber);
Result<TickCounts> CountClimberTicks(sql::Connection& c, const std::string& climber);
Result<TickCounts> CountRouteTicks(sql::Connection& c, int64_t route_id);
Result<TickVersion> GymTickVersion(sql::Connection& c, int64_t gym_id);
Status SetTickState(sql::Connection& c, int64_t id, const std::string& state,
                    const std::string& updated_at);
Result<int> MergeTicks(sql::Connection& c, const std::string& from, const std::string& to,
                       int64_t user_id);
Result<int> NewIdentitiesSince(sql::Connection& c, int64_t route_id, const std::string& origin,
                               const std::string& since);

}  // namespace sb::store::ticks_sql

#endif  // SB_STORE_TICK_SQL_H_
