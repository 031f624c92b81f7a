// Issue 33: the report's predicted grades against the ascent grades of a
// setting day's variations (app/report_predicted.h), over a real store.
#include "app/report_predicted.h"

#include <gtest/gtest.h>

#include <memory>

#include "app/logbook_fixture.h"
#include "app/report.h"

namespace sb::app {
namespace {

using testing::LogbookFixture;

class ReportPredictedTest : public LogbookFixture {};

TEST_F(ReportPredictedTest, ASettingDaysVariationIsSetAgainstItsAscentGradeAfterFiveTicks) {
  Result<std::vector<GymRole>> roles = services_->gyms.RolesOf(setter_);
  ASSERT_TRUE(roles.ok());
  setter_.gyms = *roles;
  Wall w;
  w.gym_id = gym_;
  w.name = "Cave";
  Result<int64_t> wall = services_->gyms.AddWall(setter_, w);
  ASSERT_TRUE(wall.ok()) << wall.status().message();
  const std::vector<std::vector<std::string>> moves = {
      {"R small crimp", "L small crimp", "R sidepull", "L gaston", "R crimp", "L jug finish"},
      {"L sloper", "R small crimp", "L heel hook", "R pinch", "L crimp", "R top out"}};
  const char* grades[] = {"V3", "V4"};
  for (size_t i = 0; i < moves.size(); ++i) {
    GymFields f;
    f.gym = gym_;
    f.wall = std::to_string(*wall);
    f.state = "set";
    std::string crdl = "name: Input " + std::to_string(i) + "\ngrade: " + grades[i] + "\n---\n";
    for (const std::string& m : moves[i]) crdl += m + "\n";
    ASSERT_TRUE(services_->routes.Create(setter_, crdl, true, f).ok());
  }
  SettingDayRequest r;
  r.gym = gym_;
  r.date = "2023-12-01";  // the test clock's day is 2023-11-14
  r.walls = {*wall};
  r.slots = {{*wall, "V3", ""}};
  r.candidates = 1;
  Result<SettingDayProposal> p = services_->setting_days.Propose(setter_, r);
  ASSERT_TRUE(p.ok()) << p.status().message();
  ASSERT_FALSE(p->slots[0].candidates.empty()) << p->slots[0].note;
  const DayCandidate& c = p->slots[0].candidates[0];
  ASSERT_TRUE(c.score.predicted.known);
  AcceptRequest a;
  a.gym = gym_;
  a.date = r.date;
  a.wall = std::to_string(*wall);
  a.params_json = c.params_json;
  a.inputs = c.inputs;
  Result<int64_t> id = services_->setting_days.Accept(setter_, a);
  ASSERT_TRUE(id.ok()) << id.status().message();

  ReportQuery q;
  q.date = r.date;
  Result<GymReport> before = services_->reports.Report(setter_, gym_, q);
  ASSERT_TRUE(before.ok()) << before.status().message();
  ASSERT_EQ(before->predictions.days.size(), 1u);
  EXPECT_EQ(before->predictions.days[0].day, "2023-12-01");
  EXPECT_EQ(before->predictions.days[0].variations, 1);
  EXPECT_EQ(before->predictions.days[0].checked, 0);  // no ticks yet
  EXPECT_NE(before->predictions.verdict.find("none of the 1 variation has 5 ticks"),
            std::string::npos)
      << before->predictions.verdict;
  // Issue 34: the plan's cost counts the predicted_grades section (the
  // grammar once, the variation and its moves) before any of it is made.
  Result<ReportPlan> plan = services_->reports.Plan(setter_, gym_, q);
  ASSERT_TRUE(plan.ok()) << plan.status().message();
  EXPECT_EQ(plan->variations, 1);
  int variation_moves = -1;
  for (const store::RouteRecord& rr : plan->routes) {
    if (rr.is_variation) variation_moves = rr.move_count;
  }
  ASSERT_GT(variation_moves, 0);
  RenderCosts unpredicted;
  unpredicted.predict_grammar = 0;
  unpredicted.predict_per_variation = 0;
  unpredicted.plan_per_move = 0;
  Reports without(store_.get(), &services_->gyms, &services_->logbook, ReportLimits::kMaxRoutes,
                  unpredicted);
  Result<ReportPlan> plain = without.Plan(setter_, gym_, q);
  ASSERT_TRUE(plain.ok()) << plain.status().message();
  const RenderCosts costs;
  EXPECT_NEAR(plan->cost - plain->cost,
              costs.predict_grammar + costs.predict_per_variation + variation_moves * costs.plan_per_move,
              1e-6);
  const PredictedAgainstAscent& pr = before->predictions.days[0].routes.at(0);
  EXPECT_EQ(pr.id, *id);
  ASSERT_TRUE(pr.predicted.known) << pr.predicted.note;
  // Stored when it was accepted (schema 21): the prediction the gallery showed.
  EXPECT_TRUE(pr.stored);
  EXPECT_EQ(pr.predicted.basis, "stored when the candidate was accepted");
  EXPECT_DOUBLE_EQ(pr.predicted.value, c.score.predicted.value);
  EXPECT_DOUBLE_EQ(pr.predicted.lo, c.score.predicted.lo);
  EXPECT_DOUBLE_EQ(pr.predicted.hi, c.score.predicted.hi);

  // Set on its day, five climbers send it: its ascent grade is set against
  // the prediction.
  RouteEdit edit;
  edit.gym.state = "set";
  edit.gym.set_on = r.date;
  ASSERT_TRUE(services_->routes.Update(setter_, *id, edit).ok());
  LogbookPolicy policy;
  policy.history_routes = 0;
  Logbook book(store_.get(), &clock_, policy);
  for (int i = 0; i < 5; ++i) {
    Viewer v;
    v.address = "10.1.0." + std::to_string(i);
    TickInput in;
    in.outcome = "send";
    in.attempts = 2;
    Result<TickSaved> t = book.Log(v, *id, "", in);
    ASSERT_TRUE(t.ok()) << t.status().message();
  }
  Result<GymReport> after = services_->reports.Report(setter_, gym_, q);
  ASSERT_TRUE(after.ok()) << after.status().message();
  const PredictionDay& day = after->predictions.days.at(0);
  EXPECT_EQ(day.checked, 1);
  const PredictedAgainstAscent& checked = day.routes.at(0);
  ASSERT_TRUE(checked.ascent.fitted);
  EXPECT_EQ(checked.ascent.ticks, 5);
  EXPECT_NEAR(checked.error, checked.ascent.value - checked.predicted.value, 1e-9);
  EXPECT_NEAR(day.mean_abs_error, std::abs(checked.error), 1e-9);
  EXPECT_NE(after->predictions.verdict.find("1 of 1 variation with at least 5 ticks"),
            std::string::npos)
      << after->predictions.verdict;
}

// The stored form reads back to the same prediction; a damaged one names the
// field.
TEST(PredictionTextTest, RoundTripsAndNamesTheField) {
  PredictedGrade g;
  g.known = true;
  g.discipline = "bouldering";
  g.scale = "v";
  g.value = 3.123456789;
  g.lo = 2.1;
  g.hi = 4.2;
  g.sd = 0.8;
  g.new_moves = 7;
  g.moves = 20;
  const std::string text = PredictionText(g);
  Result<PredictedGrade> back = PredictionFromText(text);
  ASSERT_TRUE(back.ok()) << back.status().message();
  EXPECT_TRUE(back->known);
  EXPECT_EQ(back->value, g.value);
  EXPECT_EQ(back->lo, g.lo);
  EXPECT_EQ(back->hi, g.hi);
  EXPECT_EQ(back->new_moves, 7);
  EXPECT_EQ(back->moves, 20);
  EXPECT_EQ(back->grade, "V3");
  EXPECT_EQ(PredictionText(PredictedGrade{}), "");
  Result<PredictedGrade> bad = PredictionFromText("1 bouldering v x 1 2 3 4 5");
  ASSERT_FALSE(bad.ok());
  EXPECT_EQ(bad.status().message().rfind("predicted_grade:", 0), 0u) << bad.status().message();
}

}  // namespace
}  // namespace sb::app
