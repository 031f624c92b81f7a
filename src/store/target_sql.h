// The SQL of store::TargetStore (schema 8), written once for both backends
// over sql::Connection; store/sql_store.cc forwards to these. Internal to
// the store module.
#ifndef SB_STORE_TARGET_SQL_H_
#define SB_STORE_TARGET_SQL_H_

#include <vector>

#include "store/sql.h"
#include "store/target_store.h"

namespace sb::store::targets_sql {

// As the TargetStore methods of the same names, on connection `c`.
Status SetWallTargets(sql::Connection& c, int64_t wall_id,
                      const std::vector<TargetRecord>& targets, int64_t revision);
Result<std::vector<TargetRecord>> WallTargets(sql::Connection& c, int64_t wall_id);
Result<std::vector<TargetRecord>> GymTargets(sql::Connection& c, int64_t gym_id);
Status SetDisciplineTargets(sql::Connection& c, int64_t gym_id, const std::string& discipline,
                            const std::vector<DisciplineTargetRecord>& targets, int64_t revision);
Result<int64_t> DisciplineTargetsRevision(sql::Connection& c, int64_t gym_id);
Result<std::vector<DisciplineTargetRecord>> DisciplineTargets(sql::Connection& c, int64_t gym_id);
Result<std::vector<RouteTickSum>> GymTickSums(sql::Connection& c, int64_t gym_id);
Result<std::vector<RouteTickSum>> RouteTickSums(sql::Connection& c,
                                                const std::vector<int64_t>& route_ids);
Result<std::vector<RouteTickSum>> StateTickSums(sql::Connection& c, int64_t gym_id,
                                                const std::string& route_state);

}  // namespace sb::store::targets_sql

#endif  // SB_STORE_TARGET_SQL_H_
