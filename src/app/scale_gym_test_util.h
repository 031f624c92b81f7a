// Shared by the app tests of gym scales and of a gym's own route list
// (scales_test.cc, gym_import_test.cc): a head setter's gym "Kletterhalle"
// with its gym scale "Halle 1-6" (kHalle: six labels over VB to V12), on
// both backends as every AppTest. Tests only.
#ifndef SB_APP_SCALE_GYM_TEST_UTIL_H_
#define SB_APP_SCALE_GYM_TEST_UTIL_H_

#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

#include "app/app_test_util.h"
#include "app/scales.h"
#include "grades/gym_scale.h"

namespace sb::app::testing {

// The labels of the gym scale "Halle 1-6", each over a range of V grades.
inline const std::vector<grades::LabelSpec> kHalle = {{"1", "VB", "V0"}, {"2", "V1", "V2"},
                                                      {"3", "V3", "V3"}, {"4", "V4", "V5"},
                                                      {"5", "V6", "V7"}, {"6", "V8", "V12"}};

// An AppTest whose "head" (head_) made the gym "Kletterhalle" (gym_) and its
// scale "Halle 1-6".
class ScaleGymTest : public AppTest {
 protected:
  void SetUp() override {
    AppTest::SetUp();
    if (IsSkipped()) return;
    head_ = User("head");
    Result<int64_t> g = services_->gyms.Create(head_, "Kletterhalle");
    ASSERT_TRUE(g.ok()) << g.status().message();
    gym_ = *g;
    Result<int64_t> s = services_->scales.Add(head_, gym_, "Halle 1-6", kHalle);
    ASSERT_TRUE(s.ok()) << s.status().message();
  }

  Viewer head_;
  int64_t gym_ = 0;
};

}  // namespace sb::app::testing

#endif  // SB_APP_SCALE_GYM_TEST_UTIL_H_
