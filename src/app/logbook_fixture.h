// Test-only: the one fixture of the logbook suites (logbook_test.cc,
// report_test.cc): AppTest's database and services, a user "setter" who owns
// a gym "Gym", and that gym's bouldering routes as the setter puts them up.
#ifndef SB_APP_LOGBOOK_FIXTURE_H_
#define SB_APP_LOGBOOK_FIXTURE_H_

#include <gtest/gtest.h>

#include <cstdint>
#include <string>

#include "app/app_test_util.h"
#include "grades/scale.h"
#include "store/gym_store.h"
#include "store/store.h"

namespace sb::app::testing {

// AppTest plus setter_ and gym_. A suite's SetUp calls LogbookFixture::SetUp()
// first and returns when IsSkipped() || HasFatalFailure().
class LogbookFixture : public AppTest {
 protected:
  void SetUp() override {
    AppTest::SetUp();
    if (IsSkipped() || HasFatalFailure()) return;
    setter_ = User("setter");
    Result<int64_t> gym = store::GymStoreOf(store_.get())->CreateGym("Gym", setter_.user_id);
    ASSERT_TRUE(gym.ok()) << gym.status().message();
    gym_ = *gym;
  }

  // A public route of gym_ in state "set", owned by setter_, with one move and
  // its bouldering grade `grade` (grade_value set where ParseGrade reads it).
  // Not stored: see Insert.
  store::RouteRecord GymRoute(const std::string& name, const std::string& grade) const {
    store::RouteRecord r;
    r.owner_id = setter_.user_id;
    r.name = name;
    r.grade = grade;
    r.crdl = "name: " + name + "\ngrade: " + grade + "\n---\nR jug\n";
    r.move_count = 1;
    r.is_public = true;
    r.gym_id = gym_;
    r.state = gym::RouteState::kSet;
    r.grade_discipline = "bouldering";
    Result<grades::Grade> g = grades::ParseGrade(grade, {});
    if (g.ok()) r.grade_value = g->value;
    return r;
  }

  // Stores `r`: its id, or 0 with a failure recorded.
  int64_t Insert(const store::RouteRecord& r) {
    Result<int64_t> id = store_->InsertRoute(r);
    EXPECT_TRUE(id.ok()) << id.status().message();
    return id.ok() ? *id : 0;
  }

  Viewer setter_;
  int64_t gym_ = 0;
};

}  // namespace sb::app::testing

#endif  // SB_APP_LOGBOOK_FIXTURE_H_
