// The setter's workflow as a service: facts of the input moves, a plain
// variation when nothing is asked, the IC search when a constraint is.
#include "app/setting.h"

#include <gtest/gtest.h>

#include "crdl/route.h"
#include "difficulty/difficulty.h"

namespace sb::app {
namespace {

std::vector<chaos::InputRoute> Inputs() {
  auto a = ParseCrdl("name: A\n---\nR jug\nL small crimp (crux)\nR sloper\nL pinch\nR match\n",
                     "a.crdl");
  auto b = ParseCrdl("name: B\n---\nL undercling\nR gaston\nL pocket\nR jug finish\n", "b.crdl");
  EXPECT_TRUE(a.ok() && b.ok());
  return {{"A", std::move(*a)}, {"B", std::move(*b)}};
}

TEST(Setting, InputFactsCarryTheCruxFlagsAndOneEstimatePerMove) {
  std::vector<bool> is_match = {true};
  auto f = InputFacts(Inputs(), /*match_grammar=*/false, &is_match);
  ASSERT_TRUE(f.ok()) << f.status().message();
  EXPECT_EQ(f->crux,
            (std::vector<bool>{false, true, false, false, false, false, false, false, false}));
  EXPECT_TRUE(is_match.empty());  // the text rule needs no flags
  if (!difficulty::DefaultModelPath().empty()) {
    EXPECT_EQ(f->difficulty.size(), 9u);
  }
}

TEST(Setting, GrammarMatchRuleGivesOneFlagPerMove) {
  std::vector<bool> is_match;
  auto f = InputFacts(Inputs(), /*match_grammar=*/true, &is_match);
  ASSERT_TRUE(f.ok()) << f.status().message();
  ASSERT_EQ(is_match.size(), 9u);
  EXPECT_TRUE(is_match[4]);  // "match"
  EXPECT_FALSE(is_match[0]);
}

TEST(Setting, WithoutConstraintsItIsExactlyVary) {
  chaos::VaryParams p;
  auto plain = chaos::Vary(Inputs(), p);
  ASSERT_TRUE(plain.ok());
  auto out = VaryWithSetting(Inputs(), p, SettingRequest{});
  ASSERT_TRUE(out.ok()) << out.status().message();
  EXPECT_FALSE(out->search.has_value());
  ASSERT_EQ(out->variation.moves.size(), plain->moves.size());
  for (size_t i = 0; i < plain->moves.size(); ++i) {
    EXPECT_EQ(out->variation.moves[i].text, plain->moves[i].text) << i;
    EXPECT_EQ(out->variation.mapping[i], plain->mapping[i]) << i;
  }
  EXPECT_FALSE(out->warnings.summary.message.empty());
}

TEST(Setting, DropInnerFinishesLeavesNoInputsFinishMidRoute) {
  auto a = ParseCrdl("name: A\n---\nR jug\nL crimp\nR jug finish\nL top out\n", "a.crdl");
  auto b = ParseCrdl("name: B\n---\nL undercling\nR gaston\nL match finish\n", "b.crdl");
  auto c = ParseCrdl("name: C\n---\nR finish jug\n", "c.crdl");
  ASSERT_TRUE(a.ok() && b.ok() && c.ok());
  std::vector<chaos::InputRoute> in = {{"A", *a}, {"C", *c}, {"B", *b}};
  EXPECT_EQ(DropInnerFinishes(&in), 2);
  ASSERT_EQ(in[0].route.moves.size(), 2u);  // "jug finish" and "top out" gone
  EXPECT_EQ(in[0].route.moves.back().text, "crimp");
  EXPECT_EQ(in[1].route.moves.size(), 1u);  // one move is always kept
  EXPECT_EQ(in[2].route.moves.size(), 3u);  // the last input keeps its finish
  // Asked of VaryWithSetting: no finish of A reaches the variation; without
  // it, the identity-like default variation carries A's finish.
  chaos::VaryParams p;
  SettingRequest drop;
  drop.drop_inner_finishes = true;
  std::vector<chaos::InputRoute> ab = {{"A", *a}, {"B", *b}};
  auto with = VaryWithSetting(ab, p, drop);
  ASSERT_TRUE(with.ok()) << with.status().message();
  for (const chaos::VariedMove& m : with->variation.moves) {
    EXPECT_NE(m.text, "jug finish");
    EXPECT_NE(m.text, "top out");
  }
  auto without = VaryWithSetting(ab, p, SettingRequest{});
  ASSERT_TRUE(without.ok());
  EXPECT_EQ(without->variation.moves.size(), 7u);
  EXPECT_EQ(with->variation.moves.size(), 5u);
}

TEST(Setting, DropInnerStartsLeavesNoInnerStartAndKeepsTheJoinAlternating) {
  auto a = ParseCrdl("name: A\n---\nR jug\nL crimp\nR sloper\n", "a.crdl");
  auto b = ParseCrdl("name: B\n---\nL palm start\nR gaston\nL pocket\nR jug finish\n",
                     "b.crdl");
  auto c = ParseCrdl("name: C\n---\nL edge\n", "c.crdl");
  ASSERT_TRUE(a.ok() && b.ok() && c.ok());
  std::vector<chaos::InputRoute> in = {{"A", *a}, {"C", *c}, {"B", *b}};
  EXPECT_EQ(DropInnerStarts(&in), 1);
  EXPECT_EQ(in[0].route.moves.size(), 3u);  // the first input keeps its start
  EXPECT_EQ(in[0].first_move, 0);
  EXPECT_EQ(in[1].route.moves.size(), 1u);  // one move is always kept
  ASSERT_EQ(in[2].route.moves.size(), 3u);
  EXPECT_EQ(in[2].first_move, 1);
  EXPECT_EQ(in[2].route.moves.front().text, "gaston");
  // C ends with L and B now starts with R: B's hands are kept. After A (ends
  // with R), B's "R gaston" would repeat the hand: mirrored.
  EXPECT_EQ(in[2].route.moves.front().hand, Hand::kRight);
  std::vector<chaos::InputRoute> ab = {{"A", *a}, {"B", *b}};
  EXPECT_EQ(DropInnerStarts(&ab), 1);
  EXPECT_EQ(ab[1].route.moves.front().hand, Hand::kLeft);
  EXPECT_EQ(ab[1].route.moves.back().hand, Hand::kLeft);
  // Asked of VaryWithSetting: B's start is gone, no start-mid-route warning,
  // and the plan numbers B's moves as its file does.
  SettingRequest drop;
  drop.drop_inner_starts = true;
  std::vector<chaos::InputRoute> ab2 = {{"A", *a}, {"B", *b}};
  auto with = VaryWithSetting(ab2, chaos::VaryParams{}, drop);
  ASSERT_TRUE(with.ok()) << with.status().message();
  EXPECT_EQ(with->variation.moves.size(), 6u);
  for (const chaos::VariedMove& m : with->variation.moves) EXPECT_NE(m.text, "palm start");
  for (const plan::Warning& w : with->warnings.warnings) {
    EXPECT_EQ(w.message.find("start of B"), std::string::npos) << w.message;
  }
  // keep-start cannot take B's new first move for a start.
  drop.constraints.keep_start = true;
  auto kept = VaryWithSetting(ab2, chaos::VaryParams{}, drop);
  ASSERT_TRUE(kept.ok()) << kept.status().message();
  EXPECT_EQ(kept->variation.moves.front().text, "jug");
}

TEST(Setting, ConstraintsRunTheSearchAndHold) {
  SettingRequest req;
  req.constraints.keep_start = true;
  req.constraints.keep_finish = true;
  auto out = VaryWithSetting(Inputs(), chaos::VaryParams{}, req);
  ASSERT_TRUE(out.ok()) << out.status().message();
  ASSERT_TRUE(out->search.has_value());
  for (const chaos::ConstraintOutcome& c : out->search->outcomes) EXPECT_TRUE(c.held);
  EXPECT_EQ(out->variation.moves.front().text, "jug");
  EXPECT_EQ(out->variation.moves.back().text, "jug finish");
  EXPECT_TRUE(out->search->variation.moves.empty());  // moved into out->variation
}

TEST(Setting, AnUnmetConstraintIsNotFoundNamingIt) {
  SettingRequest req;
  req.constraints.crux_window = chaos::CruxWindow{0.0, 0.01};
  req.grid.radius = 2;
  auto out = VaryWithSetting(Inputs(), chaos::VaryParams{}, req);
  ASSERT_FALSE(out.ok());
  EXPECT_EQ(out.status().code(), Status::Code::kNotFound);
  EXPECT_NE(out.status().message().find("crux-window"), std::string::npos)
      << out.status().message();
}

}  // namespace
}  // namespace sb::app
