// Issue 34: the costs of reads that grow with the data (app/read_costs.h)
// are made from counts before the reading and grow with what will be read;
// RenderCosts::Validate() names a bad constant.
#include "app/read_costs.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "app/logbook_fixture.h"

namespace sb::app {
namespace {

using testing::LogbookFixture;

TEST(RenderCostsTest, ValidateNamesTheBadField) {
  EXPECT_TRUE(RenderCosts{}.Validate().ok());
  RenderCosts c;
  c.fit_per_tick = -1;
  Status s = c.Validate();
  EXPECT_EQ(s.code(), Status::Code::kInvalidInput);
  EXPECT_NE(s.message().find("fit_per_tick"), std::string::npos) << s.message();
  c = RenderCosts{};
  c.study_per_answer = std::nan("");
  EXPECT_NE(c.Validate().message().find("study_per_answer"), std::string::npos);
  ReadCosts refused(nullptr, nullptr, c, RenderBudgetPolicy());
  EXPECT_EQ(refused.LogbookCost(Viewer{}, "").status().code(), Status::Code::kInvalidInput);
}

class ReadCostsTest : public LogbookFixture {};

TEST_F(ReadCostsTest, CostsGrowWithTheRowsCountedBeforeTheReading) {
  const RenderCosts k;
  const BudgetPolicy budget = RenderBudgetPolicy();
  Logbook& book = services_->logbook;
  ReadCosts rc(store_.get(), &book, k, budget);
  const int64_t a = Insert(GymRoute("A", "V3")), b = Insert(GymRoute("B", "V4"));
  Viewer climber = User("climber", "10.0.0.7");
  Result<double> none = rc.LogbookCost(climber, "");
  ASSERT_TRUE(none.ok()) << none.status().message();
  EXPECT_EQ(*none, 0);  // no ticks, no gyms
  TickInput in;
  in.outcome = "send";
  in.attempts = 2;
  ASSERT_TRUE(book.Log(climber, a, "", in).ok());
  ASSERT_TRUE(book.Log(climber, b, "", in).ok());
  // Two ticks, two routes read, one gym's "not tried yet" list.
  EXPECT_DOUBLE_EQ(*rc.LogbookCost(climber, ""),
                   2 * k.row_per_read + 2 * k.route_read + kUntriedRoutesPerGym * k.list_per_row);
  // A route's ticks: its owner reads them; another climber is refused
  // before reading, so costs nothing.
  EXPECT_DOUBLE_EQ(*rc.RouteTicksCost(setter_, a), k.row_per_read);
  EXPECT_EQ(*rc.RouteTicksCost(climber, a), 0);
  // The ascent: once the kept fit is current, only the chances' own ticks.
  ASSERT_TRUE(book.Ascent(setter_, a).ok());
  EXPECT_DOUBLE_EQ(*rc.AscentCost(climber, a, false), 2 * k.row_per_read);
  // After a restart no fit is kept: the reader would fit the gym's ticks.
  Logbook fresh(store_.get(), &clock_);
  ReadCosts cold(store_.get(), &fresh, k, budget);
  Viewer anon;
  anon.address = "10.0.0.9";
  std::optional<int64_t> gym;
  EXPECT_GE(*cold.AscentCost(anon, a, false, &gym), 2 * k.fit_per_tick);
  EXPECT_EQ(gym, gym_);
  ASSERT_TRUE(fresh.Ascent(setter_, a).ok());
  EXPECT_EQ(*cold.AscentCost(anon, a, false), 0);
  // A route no one sees costs nothing (the service answers 404).
  EXPECT_EQ(*rc.AscentCost(anon, 987654, false), 0);
  // A study: responses x routes answer rows.
  Study st;
  st.responses = 3;
  st.routes.resize(2);
  EXPECT_DOUBLE_EQ(rc.StudyCost(st), 6 * k.study_per_answer);
}

}  // namespace
}  // namespace sb::app
