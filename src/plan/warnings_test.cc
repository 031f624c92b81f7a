#include "plan/warnings.h"

#include <gtest/gtest.h>

namespace sb::plan {
namespace {

Move M(Hand h, std::string text, bool crux = false) {
  Move m;
  m.hand = h;
  m.text = std::move(text);
  m.crux = crux;
  return m;
}

// A: R matched start, L small crimp (crux), R jug finish.
// B: L pinch start, R Small Crimp!, L sloper.
std::vector<chaos::InputRoute> Inputs() {
  Route a, b;
  a.moves = {M(Hand::kRight, "matched start"), M(Hand::kLeft, "small crimp", true),
             M(Hand::kRight, "jug finish")};
  b.moves = {M(Hand::kLeft, "pinch start"), M(Hand::kRight, "Small Crimp!"),
             M(Hand::kLeft, "sloper")};
  return {{"A", a}, {"B", b}};
}

chaos::Variation Make(std::vector<int> k) {
  chaos::Variation v;
  v.inputs = Inputs();
  std::vector<chaos::VariedMove> prepared = chaos::PrepareMoves(v.inputs);
  v.mapping = k;
  for (size_t j = 0; j < k.size(); ++j) {
    chaos::VariedMove m = prepared[k[j]];
    m.changed = k[j] != static_cast<int>(j);
    v.moves.push_back(m);
  }
  return v;
}

std::vector<Warning> OfKind(const PlanWarnings& w, WarningKind k) {
  std::vector<Warning> out;
  for (const Warning& x : w.warnings) {
    if (x.kind == k) out.push_back(x);
  }
  return out;
}

TEST(WarningsTest, FlagsWhatASetterWouldFindAtTheWall) {
  chaos::Variation v = Make({1, 4, 1, 0, 2, 4});
  PlanWarnings w = Warn(v, {chaos::CruxFlags(v.inputs), {}});

  auto rep = OfKind(w, WarningKind::kRepeatedMove);
  ASSERT_EQ(rep.size(), 1u);  // "small crimp", "Small Crimp!", "small crimp"
  EXPECT_EQ(rep[0].first, 0);
  EXPECT_EQ(rep[0].last, 2);
  EXPECT_EQ(rep[0].count, 3);
  EXPECT_EQ(rep[0].message, "moves 1-3: \"small crimp\" 3 times in a row");

  auto hands = OfKind(w, WarningKind::kSameHand);
  ASSERT_EQ(hands.size(), 1u);  // L R L R R R
  EXPECT_EQ(hands[0].message, "moves 4-6: right hand 3 times in a row");

  auto finish = OfKind(w, WarningKind::kNoFinish);
  ASSERT_EQ(finish.size(), 1u);
  EXPECT_EQ(finish[0].message,
            "the route ends on \"Small Crimp!\" (move 2 of B), not on the last move of an input");

  auto crux = OfKind(w, WarningKind::kEarlyCrux);
  ASSERT_EQ(crux.size(), 1u);  // position 0 (centre 1/12); position 2 is past the first fifth
  EXPECT_EQ(crux[0].first, 0);
  EXPECT_EQ(crux[0].message, "move 1: crux \"small crimp\" in the first fifth of the route");

  auto start = OfKind(w, WarningKind::kStartAwayFromStart);
  ASSERT_EQ(start.size(), 1u);
  EXPECT_EQ(start[0].message, "move 4: \"matched start\" is the start of A, away from the start");

  // Ordered by kind, then position.
  for (size_t i = 1; i < w.warnings.size(); ++i) {
    EXPECT_LE(static_cast<int>(w.warnings[i - 1].kind), static_cast<int>(w.warnings[i].kind));
  }

  const ChangeSummary& c = w.summary;
  EXPECT_EQ(c.moves, 6);
  EXPECT_EQ(c.changed, 6);
  EXPECT_EQ(c.text_changed, 5);  // position 2: "Small Crimp!" where the input has "small crimp"
  EXPECT_EQ(c.displacement, 11);
  EXPECT_DOUBLE_EQ(c.change, 11.0 / 6.0);
  EXPECT_EQ(c.farthest, 3);
  // Issue 33: the one change count (NewMoveCount) leads the summary.
  EXPECT_EQ(c.new_moves, NewMoveCount(v.moves, v.inputs).new_moves);
  EXPECT_GT(c.new_moves, 0);
  EXPECT_EQ(c.message,
            std::to_string(c.new_moves) +
                " of 6 moves new against the inputs; source position moved for 6 (paper's "
                "measure); 5 differ in text from the input at their "
                "position; moves travelled 1.83 positions on average (change), at most 3");
}

TEST(WarningsTest, TheInputsThemselvesWarnOnlyWhereTheyJoin) {
  chaos::Variation v = Make({0, 1, 2, 3, 4, 5});
  PlanWarnings w = Warn(v, {chaos::CruxFlags(v.inputs), {}});
  ASSERT_EQ(w.warnings.size(), 2u) << w.warnings[0].message;
  EXPECT_EQ(w.warnings[0].kind, WarningKind::kStartAwayFromStart);  // B's start at move 4
  EXPECT_EQ(w.warnings[1].kind, WarningKind::kFinishMidRoute);      // A's finish at move 3
  EXPECT_EQ(w.warnings[1].message, "move 3: \"jug finish\" is a finish move, mid-route (3 moves follow)");
  EXPECT_EQ(w.summary.changed, 0);
  EXPECT_EQ(w.summary.text_changed, 0);
  EXPECT_EQ(w.summary.change, 0.0);
}

TEST(WarningsTest, CruxesFromTheEstimateWhereNoneIsFlagged) {
  chaos::Variation v = Make({5, 1, 2, 3, 4, 0});
  chaos::MoveFacts f;
  f.difficulty = {0.1, 0.2, 0.1, 0.1, 0.1, 0.8};  // B's "sloper" is the hardest
  auto crux = OfKind(Warn(v, f), WarningKind::kEarlyCrux);
  ASSERT_EQ(crux.size(), 1u);
  EXPECT_EQ(crux[0].message, "move 1: hardest move \"sloper\" in the first fifth of the route");
  // Without facts (or with facts of the wrong size) nothing is known of cruxes.
  EXPECT_TRUE(OfKind(Warn(v), WarningKind::kEarlyCrux).empty());
  f.difficulty.pop_back();
  EXPECT_TRUE(OfKind(Warn(v, f), WarningKind::kEarlyCrux).empty());
}

TEST(WarningsTest, HandSwapsAndBlanksAreReadFromTheMoves) {
  chaos::Variation v = Make({0, 1, 2, 3, 4, 5});
  v.moves[1].hand = Hand::kRight;  // R R R L R L
  auto hands = OfKind(Warn(v), WarningKind::kSameHand);
  ASSERT_EQ(hands.size(), 1u);
  EXPECT_EQ(hands[0].message, "moves 1-3: right hand 3 times in a row");
  v.moves[5] = chaos::VariedMove{};  // a blank (Dabby's rule) at the end
  v.mapping[5] = -1;
  auto finish = OfKind(Warn(v), WarningKind::kNoFinish);
  ASSERT_EQ(finish.size(), 1u);
  EXPECT_EQ(finish[0].message, "the route ends on a blank, not on the last move of an input");
  EXPECT_EQ(Warn(v).summary.text_changed, 1);
}

TEST(ProfileTest, CarriesFactsFromTheSourcesAndFindsTheHardestStretch) {
  chaos::Variation v = Make({1, 4, 1, 0, 2, 5});
  chaos::MoveFacts f{chaos::CruxFlags(v.inputs), {0.1, 0.5, 0.2, 0.3, 0.4, 0.9}};
  DifficultyProfile p = Profile(v, f);
  EXPECT_EQ(p.crux, (std::vector<bool>{true, false, true, false, false, false}));
  EXPECT_EQ(p.difficulty, (std::vector<double>{0.5, 0.4, 0.5, 0.1, 0.2, 0.9}));
  // A fifth of 6 moves is one move: the hardest is the last.
  EXPECT_EQ(p.hardest_first, 5);
  EXPECT_EQ(p.hardest_last, 5);
  EXPECT_DOUBLE_EQ(p.hardest_mean, 0.9);
  // Without estimates: flags only, no stretch.
  DifficultyProfile q = Profile(v, {chaos::CruxFlags(v.inputs), {}});
  EXPECT_TRUE(q.difficulty.empty());
  EXPECT_EQ(q.hardest_first, -1);
  EXPECT_EQ(q.crux, p.crux);
}

TEST(ProfileTest, StretchesAreAFifthOfTheRouteEarliestOnTies) {
  Route r;
  for (int i = 0; i < 10; ++i) r.moves.push_back(M(i % 2 ? Hand::kLeft : Hand::kRight, "m"));
  chaos::Variation v;
  v.inputs = {{"R", r}};
  v.moves = chaos::PrepareMoves(v.inputs);
  for (int i = 0; i < 10; ++i) v.mapping.push_back(i);
  chaos::MoveFacts f;
  f.difficulty = {0.1, 0.6, 0.6, 0.1, 0.1, 0.1, 0.6, 0.6, 0.1, 0.1};
  DifficultyProfile p = Profile(v, f);
  EXPECT_EQ(p.hardest_first, 1);  // two-move stretches; 1-2 and 6-7 tie
  EXPECT_EQ(p.hardest_last, 2);
  EXPECT_DOUBLE_EQ(p.hardest_mean, 0.6);
}

// Routes made of one move text per line, hands alternating from R unless
// given as "L:"/"R:" prefixes.
Route RouteOf(const std::vector<std::string>& texts) {
  Route r;
  for (size_t i = 0; i < texts.size(); ++i) {
    std::string t = texts[i];
    Hand h = i % 2 ? Hand::kLeft : Hand::kRight;
    if (t.rfind("L:", 0) == 0 || t.rfind("R:", 0) == 0) {
      h = t[0] == 'L' ? Hand::kLeft : Hand::kRight;
      t = t.substr(2);
    }
    r.moves.push_back(M(h, t));
  }
  return r;
}

chaos::Variation FromMapping(std::vector<chaos::InputRoute> inputs, const std::vector<int>& k) {
  chaos::Variation v;
  v.inputs = std::move(inputs);
  std::vector<chaos::VariedMove> prepared = chaos::PrepareMoves(v.inputs);
  v.mapping = k;
  for (size_t j = 0; j < k.size(); ++j) {
    chaos::VariedMove m = prepared[k[j]];
    m.changed = k[j] != static_cast<int>(j);
    v.moves.push_back(m);
  }
  return v;
}

TEST(FinishMoveTest, ReadsFinishAndTopOutMoves) {
  for (const char* t : {"jug finish", "Throw to top to finish", "top out", "match finish",
                        "Topout", "top-out the boulder", "go to the top", "Finish!",
                        "finishing hold", "clip the anchors"}) {
    EXPECT_TRUE(IsFinishMoveText(t)) << t;
  }
  for (const char* t : {"sloper", "top of the flake", "matched start", "stop and chalk",
                        "finger crack", ""}) {
    EXPECT_FALSE(IsFinishMoveText(t)) << t;
  }
  EXPECT_TRUE(IsMatchOnlyText("match"));
  EXPECT_TRUE(IsMatchOnlyText("Match hands on the finish"));
  EXPECT_FALSE(IsMatchOnlyText("match and throw to crimp"));
  EXPECT_FALSE(IsMatchOnlyText("jug"));
}

TEST(FinishMoveTest, AFinishFirstOrMidRouteIsAWarningAtTheEndItIsNot) {
  Route a = RouteOf({"pinch start", "crimp", "sloper", "jug finish", "match"});
  Route b = RouteOf({"undercling start", "Throw to top to finish"});
  std::vector<chaos::InputRoute> in = {{"A", a}, {"B", b}};
  // "jug finish" first, "Throw to top to finish" mid-route, then A's end.
  chaos::Variation v = FromMapping(in, {3, 1, 6, 2, 3, 4});
  auto f = OfKind(Warn(v), WarningKind::kFinishMidRoute);
  ASSERT_EQ(f.size(), 2u);
  EXPECT_EQ(f[0].first, 0);
  EXPECT_EQ(f[0].message, "move 1: \"jug finish\" is a finish move, at the start (5 moves follow)");
  EXPECT_EQ(f[1].first, 2);
  // The input as it is: the finish then a match ends the route, no warning.
  EXPECT_TRUE(OfKind(Warn(FromMapping(in, {0, 1, 2, 3, 4})), WarningKind::kFinishMidRoute).empty());
  // Two finish moves in a row at the end: none either.
  EXPECT_TRUE(
      OfKind(Warn(FromMapping(in, {0, 1, 2, 3, 6})), WarningKind::kFinishMidRoute).empty());
}

TEST(RunWarningsTest, RunsUpToWhatTheInputsHaveAreFine) {
  // The input climbs three "small crimp" in a row, and three right hands.
  Route a = RouteOf({"R:pinch", "R:small crimp", "R:small crimp", "L:small crimp", "R:jug"});
  std::vector<chaos::InputRoute> in = {{"A", a}};
  // small crimp x3 (as the input), hands R R R L R: no run warning.
  chaos::Variation same = FromMapping(in, {0, 1, 2, 3, 4});
  EXPECT_TRUE(OfKind(Warn(same), WarningKind::kRepeatedMove).empty());
  EXPECT_TRUE(OfKind(Warn(same), WarningKind::kSameHand).empty());
  // small crimp x4: one more than the input has.
  chaos::Variation more = FromMapping(in, {0, 1, 2, 3, 1, 4});
  auto rep = OfKind(Warn(more), WarningKind::kRepeatedMove);
  ASSERT_EQ(rep.size(), 1u);
  EXPECT_EQ(rep[0].count, 4);
  EXPECT_EQ(rep[0].message,
            "moves 2-5: \"small crimp\" 4 times in a row (the inputs have it at most 3 times)");
  // Right hand four times: one more than the input has.
  chaos::Variation hands = FromMapping(in, {0, 1, 2, 1, 4});
  auto h = OfKind(Warn(hands), WarningKind::kSameHand);
  ASSERT_EQ(h.size(), 1u);
  EXPECT_EQ(h[0].count, 5);
  EXPECT_EQ(h[0].message,
            "moves 1-5: right hand 5 times in a row (the inputs have one hand at most 3 times)");
}

TEST(WarningKindTest, Names) {
  EXPECT_STREQ(WarningKindName(WarningKind::kFinishMidRoute), "finish-mid-route");
  EXPECT_STREQ(WarningKindName(WarningKind::kRepeatedMove), "repeated-move");
  EXPECT_STREQ(WarningKindName(WarningKind::kStartAwayFromStart), "start-mid-route");
}

}  // namespace
}  // namespace sb::plan
