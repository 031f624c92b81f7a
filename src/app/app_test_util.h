// Shared by the app module's tests: a fresh store (a SQLite file in a
// temporary directory, or a PostgreSQL database when $SB_TEST_BACKEND is
// "postgresql": ctest runs every app test on both), a clock that does not
// wait, and logged-in viewers.
#ifndef SB_APP_APP_TEST_UTIL_H_
#define SB_APP_APP_TEST_UTIL_H_

#include <gtest/gtest.h>
#include <unistd.h>

#include <atomic>
#include <filesystem>
#include <memory>
#include <mutex>
#include <string>

#include "app/clock.h"
#include "app/options.h"
#include "app/services.h"
#include "store/open.h"
#include "store/store_test_util.h"

namespace sb::app::testing {

// Time that moves only when told to; Sleep returns at once and is recorded.
class FakeClock final : public Clock {
 public:
  int64_t Now() override { return now_; }
  void Sleep(double seconds) override {
    std::lock_guard<std::mutex> lock(mu_);
    slept_ += seconds;
    longest_ = std::max(longest_, seconds);
  }
  void Advance(int64_t seconds) { now_ += seconds; }
  double slept() {
    std::lock_guard<std::mutex> lock(mu_);
    return slept_;
  }
  double longest() {
    std::lock_guard<std::mutex> lock(mu_);
    return longest_;
  }

 private:
  std::atomic<int64_t> now_{1'700'000'000};
  std::mutex mu_;
  double slept_ = 0, longest_ = 0;
};

// A store in a fresh database (removed at the end; dir_ is a scratch
// directory removed with it) and the services over it, with the cheapest
// password hashing.
class AppTest : public ::testing::Test {
 protected:
  void SetUp() override {
    db_ = std::make_unique<store::testing::TestDatabase>(
        store::testing::BackendFromEnvironment(), "app");
    SB_REQUIRE_DATABASE(*db_);
    dir_ = db_->dir();
    Reopen();
  }
  void TearDown() override {
    services_.reset();
    store_.reset();
    db_.reset();
  }
  // (Re)creates the services over the same database with `options`.
  void Reopen(Options options = TestOptions()) {
    services_.reset();
    store_.reset();
    Result<std::unique_ptr<store::Store>> s = store::OpenStore(db_->locator());
    ASSERT_TRUE(s.ok()) << s.status().message();
    store_ = std::move(s).value();
    services_ = std::make_unique<Services>(store_.get(), options, &clock_);
  }
  static Options TestOptions() {
    Options o;
    o.fast_password_hashing = true;
    return o;
  }
  // Signs a user up and returns them as a viewer from `address`.
  Viewer User(const std::string& name, const std::string& address = "10.0.0.1") {
    Result<app::User> u = services_->accounts.SignUp(name, "password123", address);
    EXPECT_TRUE(u.ok()) << u.status().message();
    Viewer v;
    if (u.ok()) v.user_id = u->id;
    v.username = name;
    v.address = address;
    return v;
  }
  int64_t AddRoute(const Viewer& v, const std::string& crdl, bool pub = true) {
    Result<int64_t> id = services_->routes.Create(v, crdl, pub);
    EXPECT_TRUE(id.ok()) << id.status().message();
    return id.ok() ? *id : 0;
  }

  std::unique_ptr<store::testing::TestDatabase> db_;
  std::filesystem::path dir_;
  FakeClock clock_;
  std::unique_ptr<store::Store> store_;
  std::unique_ptr<Services> services_;
};

inline constexpr char kCrimpLadder[] =
    "name: Crimp Ladder\n"
    "grade: V4\n"
    "setter: Carol\n"
    "A ladder of crimps.\n"
    "---\n"
    "R small crimp\n"
    "L small crimp (crux)\n"
    "R match\n"
    "L sloper\n"
    "R jug\n"
    "L jug finish\n";

inline constexpr char kSlabDance[] =
    "name: Slab Dance\n"
    "grade: 5.9\n"
    "---\n"
    "L smear\n"
    "R high step\n"
    "L pinch\n"
    "R gaston\n"
    "L crimp\n";

}  // namespace sb::app::testing

#endif  // SB_APP_APP_TEST_UTIL_H_
