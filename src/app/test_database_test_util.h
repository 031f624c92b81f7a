// Test-only: a fresh database per test on either backend ($SB_TEST_BACKEND
// "postgresql" or SQLite), for the tests of modules above app (web, cli)
// that may not name store types. See store/store_test_util.h.
#ifndef SB_APP_TEST_DATABASE_TEST_UTIL_H_
#define SB_APP_TEST_DATABASE_TEST_UTIL_H_

#include "store/store_test_util.h"

namespace sb::app::testing {

// A scratch database (removed with the object): locator(), dir(), and
// SB_REQUIRE_DATABASE(db) in SetUp skips when its backend is unavailable.
using TestDatabase = store::testing::TestDatabase;
// The backend $SB_TEST_BACKEND names (SQLite by default).
using store::testing::BackendFromEnvironment;

}  // namespace sb::app::testing

#endif  // SB_APP_TEST_DATABASE_TEST_UTIL_H_
