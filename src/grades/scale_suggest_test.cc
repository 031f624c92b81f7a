// Issue 32: a gym scale's mapping suggested by ascents (grades/scale_suggest.h).
#include "grades/scale_suggest.h"

#include <gtest/gtest.h>

#include <cmath>

namespace sb::grades {
namespace {

const std::vector<LabelSpec> kTruth = {{"1", "VB", "V0"}, {"2", "V1", "V2"}, {"3", "V3", "V3"},
                                       {"4", "V4", "V5"}, {"5", "V6", "V7"}, {"6", "V8", "V12"}};
// The naive reading the issue complains of: label N is VN.
const std::vector<LabelSpec> kNaive = {{"1", "V1", "V1"}, {"2", "V2", "V2"}, {"3", "V3", "V3"},
                                       {"4", "V4", "V4"}, {"5", "V5", "V5"}, {"6", "V6", "V6"}};

TEST(SuggestLabelsTest, CutsWhereFewestRoutesFallOnTheWrongSideAscendingInTheLabelsLadder) {
  Result<GymScale> naive = MakeGymScale("Halle", kNaive);
  ASSERT_TRUE(naive.ok());
  // Ascent grades spread over each true range (label 3 = V3 only).
  std::vector<std::vector<double>> v = {
      {-0.9, -0.6, -0.3, 0.0, 0.2, 0.4},  {0.7, 1.0, 1.3, 1.6, 1.9, 2.2, 2.4},
      {2.6, 2.8, 3.0, 3.1, 3.3},           {3.7, 4.0, 4.4, 4.8, 5.2, 5.4},
      {5.6, 6.0, 6.5, 7.0, 7.3},           {7.8, 8.5, 9.0, 10.0, 11.0, 12.0}};
  Result<ScaleSuggestion> s = SuggestLabels(*naive, v);
  ASSERT_TRUE(s.ok()) << s.status().message();
  ASSERT_EQ(s->labels.size(), 6u);
  std::vector<std::string> got;
  for (const SuggestedLabel& l : s->labels) got.push_back(l.spec.from + ".." + l.spec.to);
  EXPECT_EQ(got, (std::vector<std::string>{"VB..V0", "V1..V2", "V3..V3", "V4..V5", "V6..V7",
                                           "V8..V12"}))
      << "labels as the ladder names them";
  EXPECT_EQ(s->labels[1].routes, 7);
  EXPECT_NEAR(s->labels[1].median, 1.6, 1e-9);
  EXPECT_TRUE(MakeGymScale("Halle", s->Specs()).ok());

  // A label with too few routes keeps its range; one whose routes read
  // easier than its predecessor's still ascends (it starts where that ends).
  v[2] = {3.0};
  v[4] = {1.0, 1.2, 1.4, 1.5, 1.6};
  s = SuggestLabels(*naive, v);
  ASSERT_TRUE(s.ok());
  EXPECT_TRUE(s->labels[2].kept);
  EXPECT_EQ(s->labels[2].spec.from, "V3");
  EXPECT_FALSE(s->labels[4].kept);
  Result<GymScale> made = MakeGymScale("Halle", s->Specs());
  ASSERT_TRUE(made.ok()) << made.status().message();
  for (size_t i = 1; i < made->labels.size(); ++i) {
    EXPECT_GE(made->labels[i].lo, made->labels[i - 1].hi);
  }
  EXPECT_EQ(SuggestLabels(*naive, {{1.0}}).status().code(), Status::Code::kInvalidInput);
}

TEST(SuggestLabelsTest, OnASyntheticGymTheSuggestionIsNearerTheTruthThanTheNaiveGuess) {
  Result<GymScale> truth = MakeGymScale("Halle", kTruth);
  Result<GymScale> naive = MakeGymScale("Halle", kNaive);
  ASSERT_TRUE(truth.ok() && naive.ok());
  ScaleSuggestParams p;
  p.routes = 200;
  p.ticks_per_route = 40;
  Result<ScaleSuggestEvaluation> ev = EvaluateScaleSuggestion(*truth, *naive, p);
  ASSERT_TRUE(ev.ok()) << ev.status().message();
  EXPECT_EQ(ev->routes, 200);
  EXPECT_EQ(ev->ticks, 8000);
  EXPECT_GT(ev->guess_bound_mae, 1.0);
  EXPECT_LT(ev->suggested_bound_mae, 0.75 * ev->guess_bound_mae);
  EXPECT_GE(ev->within_one, 0.9);
  EXPECT_TRUE(MakeGymScale("Halle", ev->suggestion.Specs()).ok());
}

TEST(SuggestLabelsTest, WithoutPriorTakesTheLabelsPullOut) {
  // Posterior sd 1/sqrt(2) with a prior of sd 1: the data weigh as much as
  // the prior, so the data alone sit as far past the fit as the prior sits
  // before it.
  std::optional<double> v = WithoutPrior(3.0, std::sqrt(0.5), 2.0, 1.0);
  ASSERT_TRUE(v.has_value());
  EXPECT_NEAR(*v, 4.0, 1e-9);
  EXPECT_FALSE(WithoutPrior(3.0, 0.95, 2.0, 1.0).has_value());  // ticks weigh too little
  EXPECT_FALSE(WithoutPrior(3.0, 0.0, 2.0, 1.0).has_value());
}

}  // namespace
}  // namespace sb::grades
