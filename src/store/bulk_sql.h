// The SQL of store::BulkStore, written once for both backends over
// sql::Connection; store/sql_store.cc forwards to these. Internal to the
// store module.
#ifndef SB_STORE_BULK_SQL_H_
#define SB_STORE_BULK_SQL_H_

#include <functional>
#include <string>
#include <vector>

#include "store/bulk_store.h"
#include "store/sql.h"

namespace sb::store::bulk_sql {

// How the store fills routes.search_text and search_version (sql_store.cc
// owns the rule; passed in so there is one).
struct SearchRule {
  std::function<std::string(const std::string& name, const std::string& crdl)> text;
  int version = 0;
};

// As BulkStore::BulkInsertRoutes / BulkInsertTicks, on connection `c`
// (each in its own transaction).
Result<std::vector<int64_t>> InsertRoutes(sql::Connection& c, const std::vector<RouteRecord>& routes,
                                          const SearchRule& search);
Status InsertTicks(sql::Connection& c, const std::vector<TickRecord>& ticks);

}  // namespace sb::store::bulk_sql

#endif  // SB_STORE_BULK_SQL_H_
