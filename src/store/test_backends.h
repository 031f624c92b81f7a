// Test-only: the one fixture of the store's two-backend suites. Each test gets
// a fresh database (store_test_util.h's TestDatabase) on the backend of its
// parameter (INSTANTIATE_TEST_SUITE_P with testing::Backends()) and, as the
// suite asks, the store opened on it and a gym "G".
#ifndef SB_STORE_TEST_BACKENDS_H_
#define SB_STORE_TEST_BACKENDS_H_

#include <gtest/gtest.h>

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <utility>

#include "store/gym_store.h"
#include "store/open.h"
#include "store/store.h"
#include "store/store_test_util.h"

namespace sb::store::testing {

// What BackendTest::SetUp makes besides the database.
enum class Make {
  kDatabase,     // the database only; tests open stores with Open()
  kStore,        // store_ opened on it
  kStoreAndGym,  // store_ and gym_, a gym "G" without an owner
};

// A parameterised fixture over Backend. SetUp skips the test when PostgreSQL
// is not installed and fails it when the database or the store cannot be
// had; then it calls SetUpStore(), the suite's own set-up (not called after a
// skip or a fatal failure).
class BackendTest : public ::testing::TestWithParam<Backend> {
 protected:
  // `tag` names the database's scratch directory (sb_db_<tag>_...).
  explicit BackendTest(const std::string& tag = "t", Make make = Make::kStore)
      : db_(GetParam(), tag), make_(make) {}

  void SetUp() override {
    SB_REQUIRE_DATABASE(db_);
    if (make_ != Make::kDatabase) {
      Result<std::unique_ptr<Store>> s = OpenStore(db_.locator());
      ASSERT_TRUE(s.ok()) << s.status().message();
      store_ = std::move(s).value();
    }
    if (make_ == Make::kStoreAndGym) {
      Result<int64_t> g = GymStoreOf(store_.get())->CreateGym("G", std::nullopt);
      ASSERT_TRUE(g.ok()) << g.status().message();
      gym_ = *g;
    }
    SetUpStore();
  }

  // The suite's set-up, after the database (and store_, gym_) are there.
  virtual void SetUpStore() {}

  // A new store on db_; nullptr (with a failure recorded) when it cannot open.
  std::unique_ptr<Store> Open() {
    Result<std::unique_ptr<Store>> s = OpenStore(db_.locator());
    EXPECT_TRUE(s.ok()) << s.status().message();
    return s.ok() ? std::move(s).value() : nullptr;
  }

  TestDatabase db_;
  std::unique_ptr<Store> store_;  // with Make::kStore and kStoreAndGym
  int64_t gym_ = 0;               // with Make::kStoreAndGym

 private:
  Make make_;
};

}  // namespace sb::store::testing

#endif  // SB_STORE_TEST_BACKENDS_H_
