// Labelled files, per-group models and cross-validated recognition.
#include "markov/classify.h"

#include <gtest/gtest.h>

#include <random>
#include <string>
#include <vector>

namespace sb::markov {
namespace {

TEST(ParseLabelled, FormatAndErrors) {
  auto r = ParseLabelled("# comment\nalice\ta b c\n\nbob\t  d e\r\n", "f.tsv");
  ASSERT_TRUE(r.ok());
  ASSERT_EQ(r->size(), 2u);
  EXPECT_EQ((*r)[0].label, "alice");
  EXPECT_EQ((*r)[0].tokens, (std::vector<std::string>{"a", "b", "c"}));
  EXPECT_EQ((*r)[1].line, 4);
  auto no_tab = ParseLabelled("alice a b\n", "f.tsv");
  ASSERT_FALSE(no_tab.ok());
  EXPECT_EQ(no_tab.status().message(), "f.tsv:1:1: expected 'label<TAB>tokens'");
  auto empty = ParseLabelled("x\ta\ny\t \n", "f.tsv");
  ASSERT_FALSE(empty.ok());
  EXPECT_EQ(empty.status().message(), "f.tsv:2:3: route has no tokens");
}

// Two "climbers" with different habits: A alternates jug/crimp, B repeats
// slopers and pinches. Cross-validated recognition must find them.
TEST(CrossValidate, SeparatesDistinctStyles) {
  std::mt19937_64 rng(1);
  std::vector<LabelledRoute> routes;
  for (int i = 0; i < 40; ++i) {
    LabelledRoute r;
    r.label = i % 2 ? "A" : "B";
    for (int m = 0; m < 8; ++m) {
      const bool noise = rng() % 5 == 0;
      if (r.label == "A")
        r.tokens.push_back(noise ? "sloper" : (m % 2 ? "jug" : "crimp"));
      else
        r.tokens.push_back(noise ? "jug" : (m % 3 ? "sloper" : "pinch"));
    }
    routes.push_back(r);
  }
  for (Algorithm alg : {Algorithm::kDeCtw, Algorithm::kPpmC, Algorithm::kMarkov}) {
    auto rep = CrossValidate(routes, {alg, 2, 2, 1.0}, 5);
    ASSERT_TRUE(rep.ok()) << rep.status().message();
    EXPECT_EQ(rep->routes, 40u);
    EXPECT_GE(rep->accuracy, 0.95) << AlgorithmName(alg);
    EXPECT_DOUBLE_EQ(rep->majority_accuracy, 0.5);
    EXPECT_NE(FormatReport(*rep).find("accuracy"), std::string::npos);
  }
  EXPECT_FALSE(CrossValidate(routes, {Algorithm::kDeCtw, 2, 2, 1.0}, 1).ok());
}

TEST(TrainGroups, OneModelPerLabelSharedVocabulary) {
  std::vector<LabelledRoute> routes = {{"b", {"x", "y"}, 1}, {"a", {"y", "z"}, 2}, {"b", {"z"}, 3}};
  auto g = TrainGroups(routes, {Algorithm::kPpmC, 2, 2, 1.0});
  ASSERT_TRUE(g.ok());
  EXPECT_EQ(g->labels, (std::vector<std::string>{"a", "b"}));
  EXPECT_EQ(g->models[1].training().size(), 3u);
  EXPECT_EQ(g->models[0].vocabulary().tokens(), g->models[1].vocabulary().tokens());
  std::vector<const TokenModel*> ptrs = {&g->models[0], &g->models[1]};
  auto c = Classify(ptrs, {"x", "y"});
  ASSERT_TRUE(c.ok());
  EXPECT_EQ(c->best, 1u);
}

}  // namespace
}  // namespace sb::markov
