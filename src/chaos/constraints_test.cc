#include "chaos/constraints.h"

#include <gtest/gtest.h>

namespace sb::chaos {
namespace {

Move M(Hand h, std::string text, bool crux = false) {
  Move m;
  m.hand = h;
  m.text = std::move(text);
  m.crux = crux;
  return m;
}

// Route A: R jug start, L crimp (crux), R jug finish. Route B: L pinch, R sloper, L pinch.
std::vector<InputRoute> TwoRoutes() {
  Route a, b;
  a.moves = {M(Hand::kRight, "jug start"), M(Hand::kLeft, "crimp", true),
             M(Hand::kRight, "jug finish")};
  b.moves = {M(Hand::kLeft, "pinch"), M(Hand::kRight, "sloper"), M(Hand::kLeft, "Pinch!")};
  return {{"A", a}, {"B", b}};
}

ConstraintChecker Make(const Constraints& c, MoveFacts facts, int max_repeat = 0) {
  auto inputs = TwoRoutes();
  auto checker = ConstraintChecker::Make(PrepareMoves(inputs), inputs, facts, c, max_repeat);
  EXPECT_TRUE(checker.ok()) << checker.status().message();
  return std::move(*checker);
}

TEST(CruxWindowTest, ParsesFractionsAndRejectsTheRest) {
  auto w = ParseCruxWindow("0.5,0.9");
  ASSERT_TRUE(w.ok());
  EXPECT_DOUBLE_EQ(w->begin, 0.5);
  EXPECT_DOUBLE_EQ(w->end, 0.9);
  EXPECT_TRUE(ParseCruxWindow(" 0 , 1 ").ok());
  for (const char* bad :
       {"0.9,0.5", "a,b", "0.5", "0.1,0.2,0.3", "-0.1,0.5", "0.5,1.5", ",", "nan,1", "0.5x,0.9"}) {
    auto r = ParseCruxWindow(bad);
    EXPECT_FALSE(r.ok()) << bad;
    EXPECT_NE(r.status().message().find(bad), std::string::npos) << r.status().message();
  }
}

TEST(CruxWindowTest, AMoveIsInsideWhenItsCentreIs) {
  CruxWindow w{0.5, 0.9};
  // n = 10: centres 0.05, 0.15, ..., 0.95.
  std::vector<int> inside;
  for (int j = 0; j < 10; ++j) {
    if (w.Contains(j, 10)) inside.push_back(j);
  }
  EXPECT_EQ(inside, (std::vector<int>{5, 6, 7, 8}));
  EXPECT_FALSE(w.Contains(0, 0));
}

TEST(ConstraintCheckerTest, NothingAskedNothingFails) {
  ConstraintChecker c = Make({}, {});
  EXPECT_EQ(c.requested(), 0u);
  int k[6] = {5, 5, 5, 5, 5, 5};
  EXPECT_EQ(c.Failures(k), 0u);
}

TEST(ConstraintCheckerTest, KeepStartAcceptsAnyInputsFirstMove) {
  Constraints cs;
  cs.keep_start = true;
  ConstraintChecker c = Make(cs, {});
  int from_a[6] = {0, 1, 2, 3, 4, 5}, from_b[6] = {3, 1, 2, 3, 4, 5}, mid[6] = {1, 1, 2, 3, 4, 5};
  EXPECT_EQ(c.Failures(from_a), 0u);
  EXPECT_EQ(c.Failures(from_b), 0u);
  EXPECT_EQ(c.Failures(mid), ConstraintBit(Constraint::kKeepStart));
  int blank[6] = {-1, 1, 2, 3, 4, 5};
  EXPECT_EQ(c.Failures(blank), ConstraintBit(Constraint::kKeepStart));
}

TEST(ConstraintCheckerTest, KeepFinishAcceptsAnyInputsLastMove) {
  Constraints cs;
  cs.keep_finish = true;
  ConstraintChecker c = Make(cs, {});
  int ends_a[6] = {0, 1, 2, 3, 4, 2}, ends_b[6] = {0, 1, 2, 3, 4, 5},
      ends_mid[6] = {0, 1, 2, 3, 4, 4};
  EXPECT_EQ(c.Failures(ends_a), 0u);
  EXPECT_EQ(c.Failures(ends_b), 0u);
  EXPECT_EQ(c.Failures(ends_mid), ConstraintBit(Constraint::kKeepFinish));
}

TEST(ConstraintCheckerTest, CruxWindowNeedsEveryCruxInsideAndAtLeastOne) {
  Constraints cs;
  cs.crux_window = CruxWindow{0.5, 1.0};  // n = 6: positions 3, 4, 5
  ConstraintChecker c = Make(cs, {CruxFlags(TwoRoutes()), {}});
  EXPECT_TRUE(c.cruxes_flagged());
  EXPECT_EQ(c.cruxes(), (std::vector<int>{1}));
  const uint32_t bit = ConstraintBit(Constraint::kCruxWindow);
  int inside[6] = {0, 0, 2, 3, 1, 5};
  int also_early[6] = {1, 0, 2, 3, 1, 5};
  int none[6] = {0, 0, 2, 3, 4, 5};
  int at_edge[6] = {0, 0, 2, 1, 4, 5};  // position 3: centre 3.5/6 = 0.583
  EXPECT_EQ(c.Failures(inside), 0u);
  EXPECT_EQ(c.Failures(also_early), bit);
  EXPECT_EQ(c.Failures(none), bit);
  EXPECT_EQ(c.Failures(at_edge), 0u);
}

TEST(ConstraintCheckerTest, CruxWindowFallsBackToTheHardestMoveByTheEstimate) {
  Constraints cs;
  cs.crux_window = CruxWindow{0.0, 0.5};
  MoveFacts f;
  f.difficulty = {0.1, 0.2, 0.3, 0.9, 0.4, 0.9};  // tie: the lowest index (3) is the hardest
  ConstraintChecker c = Make(cs, f);
  EXPECT_FALSE(c.cruxes_flagged());
  EXPECT_EQ(c.cruxes(), (std::vector<int>{3}));
  int k[6] = {3, 1, 2, 0, 4, 5};
  EXPECT_EQ(c.Failures(k), 0u);
  int late[6] = {0, 1, 2, 3, 4, 5};
  EXPECT_EQ(c.Failures(late), ConstraintBit(Constraint::kCruxWindow));
}

TEST(ConstraintCheckerTest, CruxWindowWithoutCruxesOrEstimatesIsAnError) {
  Constraints cs;
  cs.crux_window = CruxWindow{0.5, 0.9};
  auto inputs = TwoRoutes();
  for (Route* r : {&inputs[0].route, &inputs[1].route}) {
    for (Move& m : r->moves) m.crux = false;
  }
  auto c = ConstraintChecker::Make(PrepareMoves(inputs), inputs, {CruxFlags(inputs), {}}, cs, 0);
  ASSERT_FALSE(c.ok());
  EXPECT_NE(c.status().message().find("crux-window"), std::string::npos);
}

TEST(ConstraintCheckerTest, FactsOfTheWrongSizeAreRejected) {
  auto inputs = TwoRoutes();
  MoveFacts f;
  f.crux = {true, false};
  auto c = ConstraintChecker::Make(PrepareMoves(inputs), inputs, f, {}, 0);
  ASSERT_FALSE(c.ok());
  EXPECT_NE(c.status().message().find("crux flags"), std::string::npos);
  f.crux.clear();
  f.difficulty = {0.5};
  EXPECT_FALSE(ConstraintChecker::Make(PrepareMoves(inputs), inputs, f, {}, 0).ok());
}

TEST(ConstraintCheckerTest, MaxRepeatCountsRunsOfTheSameTextIgnoringCaseAndPunctuation) {
  ConstraintChecker c = Make({}, {}, 2);
  EXPECT_EQ(c.requested(), ConstraintBit(Constraint::kMaxRepeat));
  int two[6] = {3, 5, 0, 1, 2, 4};    // "pinch", "Pinch!": a run of 2
  int three[6] = {3, 5, 3, 1, 2, 4};  // a run of 3
  EXPECT_EQ(c.Failures(two), 0u);
  EXPECT_EQ(c.Failures(three), ConstraintBit(Constraint::kMaxRepeat));
}

TEST(ConstraintCheckerTest, AlternateHandsReadsEachSourcesHand) {
  Constraints cs;
  cs.alternate_hands = true;
  ConstraintChecker c = Make(cs, {});
  // Hands by source: 0 R, 1 L, 2 R, 3 L, 4 R, 5 L.
  int alternating[6] = {0, 1, 2, 3, 4, 5}, twice[6] = {0, 2, 1, 3, 4, 5};
  EXPECT_EQ(c.Failures(alternating), 0u);
  EXPECT_EQ(c.Failures(twice), ConstraintBit(Constraint::kAlternateHands));
}

TEST(ConstraintCheckerTest, TargetEffectAndChangeWithinTolerance) {
  Constraints cs;
  cs.target_effect = 2;
  cs.target_change = 1;
  ConstraintChecker c = Make(cs, {});
  int swap_neighbours[6] = {1, 0, 2, 3, 4, 5};  // effect 2, change 1
  int far[6] = {5, 1, 2, 3, 4, 0};              // effect 2, change 5
  int none[6] = {0, 1, 2, 3, 4, 5};             // effect 0
  EXPECT_EQ(c.Failures(swap_neighbours), 0u);
  EXPECT_EQ(c.Failures(far), ConstraintBit(Constraint::kChange));
  EXPECT_EQ(c.Failures(none),
            ConstraintBit(Constraint::kEffect) | ConstraintBit(Constraint::kChange));
  MappingChange m = MeasureChange(far, 6);
  EXPECT_EQ(m.effect, 2);
  EXPECT_EQ(m.displacement, 10);
  EXPECT_DOUBLE_EQ(m.change(), 5.0);
  int blank[2] = {-1, 1};
  EXPECT_EQ(MeasureChange(blank, 2).effect, 1);
}

TEST(ConstraintCheckerTest, InvalidConstraintsAreRejected) {
  Constraints cs;
  cs.crux_window = CruxWindow{0.8, 0.2};
  EXPECT_FALSE(cs.Validate().ok());
  cs.crux_window.reset();
  cs.target_effect = -1;
  EXPECT_NE(cs.Validate().message().find("effect"), std::string::npos);
}

TEST(ConstraintCheckerTest, ReportExplainsEachRequestedConstraint) {
  Constraints cs;
  cs.keep_start = cs.keep_finish = cs.alternate_hands = true;
  cs.crux_window = CruxWindow{0.5, 1.0};
  auto inputs = TwoRoutes();
  ConstraintChecker c = Make(cs, {CruxFlags(inputs), {}}, 2);
  Variation v;
  v.inputs = inputs;
  v.mapping = {3, 2, 0, 1, 4, 5};
  std::vector<VariedMove> prepared = PrepareMoves(inputs);
  for (int k : v.mapping) v.moves.push_back(prepared[k]);
  std::vector<ConstraintOutcome> r = c.Report(v);
  ASSERT_EQ(r.size(), 5u);
  EXPECT_EQ(r[0].constraint, Constraint::kKeepStart);
  EXPECT_TRUE(r[0].held);
  EXPECT_EQ(r[0].detail, "starts with \"pinch\" (move 1 of B)");
  EXPECT_TRUE(r[1].held);  // keep-finish: "Pinch!" is B's last move
  EXPECT_EQ(r[2].constraint, Constraint::kCruxWindow);
  EXPECT_TRUE(r[2].held) << r[2].detail;
  EXPECT_EQ(r[2].detail, "flagged cruxes at move 4; window moves 4-6");
  EXPECT_EQ(r[3].constraint, Constraint::kMaxRepeat);
  EXPECT_TRUE(r[3].held);
  EXPECT_EQ(r[4].constraint, Constraint::kAlternateHands);
  EXPECT_FALSE(r[4].held);  // hands L R R L R L
  EXPECT_EQ(r[4].detail, "same hand at moves 2-3");
  EXPECT_EQ(c.Failures(v.mapping.data()), ConstraintBit(Constraint::kAlternateHands));
}

TEST(AlternateHandsTest, KeepsTheStartsHandWhenAsked) {
  std::vector<VariedMove> m(4);
  // L L R L: R L R L swaps only the start; L R L R swaps the other three.
  m[0].hand = m[1].hand = m[3].hand = Hand::kLeft;
  m[2].hand = Hand::kRight;
  std::vector<VariedMove> fewest = m, last = m;
  EXPECT_EQ(AlternateHands(&last, false, /*keep_last_hand=*/true), 1);  // R L R L
  EXPECT_EQ(last[3].hand, Hand::kLeft);
  EXPECT_EQ(AlternateHands(&fewest), 1);
  EXPECT_EQ(fewest[0].hand, Hand::kRight);
  EXPECT_EQ(AlternateHands(&m, /*keep_first_hand=*/true), 3);
  EXPECT_EQ(m[0].hand, Hand::kLeft);
  EXPECT_TRUE(m[0].notes.empty());
  EXPECT_EQ(m[1].hand, Hand::kRight);
  EXPECT_EQ(m[2].hand, Hand::kLeft);
  EXPECT_EQ(m[3].hand, Hand::kRight);
}

// Both ends kept (issue 22): hands of the same parity alternate throughout;
// of different parity, both ends keep their hands and one same-hand pair is
// placed where it swaps fewest moves.
TEST(AlternateHandsTest, KeepsBothEndsHandsWithOneSameHandPairWhereParityDemands) {
  const Hand L = Hand::kLeft, R = Hand::kRight;
  auto make = [](std::vector<Hand> hands) {
    std::vector<VariedMove> m(hands.size());
    for (size_t j = 0; j < hands.size(); ++j) m[j].hand = hands[j];
    return m;
  };
  auto hands = [](const std::vector<VariedMove>& m) {
    std::vector<Hand> h;
    for (const VariedMove& x : m) h.push_back(x.hand);
    return h;
  };
  // Same parity (L ... R over 4 moves): L R L R, no pair.
  std::vector<VariedMove> same = make({L, L, L, R});
  int at = 7;
  EXPECT_EQ(AlternateHands(&same, true, true, &at), 1);
  EXPECT_EQ(at, -1);
  EXPECT_EQ(hands(same), (std::vector<Hand>{L, R, L, R}));
  // Different parity (L ... L over 6 moves): splits after 1..5 swap 3, 2, 3,
  // 2, 1 moves; the pair goes at moves 5-6 and only move 3 is swapped.
  std::vector<VariedMove> diff = make({L, R, R, R, L, L});
  EXPECT_EQ(AlternateHands(&diff, true, true, &at), 1);
  EXPECT_EQ(at, 5);
  EXPECT_EQ(hands(diff), (std::vector<Hand>{L, R, L, R, L, L}));
  EXPECT_TRUE(diff[0].notes.empty() && diff[5].notes.empty());
  EXPECT_EQ(diff[2].notes, (std::vector<std::string>{"(hand swapped)"}));
  // Without keep-finish the finish's hand is swapped instead (no pair).
  std::vector<VariedMove> first_only = make({L, R, R, R, L, L});
  EXPECT_EQ(AlternateHands(&first_only, true, false, &at), 2);
  EXPECT_EQ(at, -1);
  EXPECT_EQ(first_only[5].hand, R);

  // Every hand sequence of 2..9 moves: the ends keep their hands, at most one
  // same-hand pair (exactly one when the parity differs), swaps noted.
  for (int n = 2; n <= 9; ++n) {
    for (int bits = 0; bits < (1 << n); ++bits) {
      std::vector<Hand> in;
      for (int j = 0; j < n; ++j) in.push_back((bits >> j) & 1 ? R : L);
      std::vector<VariedMove> m = make(in);
      const int swaps = AlternateHands(&m, true, true, &at);
      const bool differ = (in[0] == in[n - 1]) != ((n - 1) % 2 == 0);
      EXPECT_EQ(m[0].hand, in[0]);
      EXPECT_EQ(m[n - 1].hand, in[n - 1]);
      int pairs = 0, noted = 0, changed = 0;
      for (int j = 0; j < n; ++j) {
        if (j > 0 && m[j].hand == m[j - 1].hand) {
          ++pairs;
          EXPECT_EQ(at, j);
        }
        noted += !m[j].notes.empty();
        changed += m[j].hand != in[j];
      }
      EXPECT_EQ(pairs, differ ? 1 : 0) << "n " << n << " bits " << bits;
      EXPECT_EQ(at >= 0, differ);
      EXPECT_EQ(noted, swaps);
      EXPECT_EQ(changed, swaps);
    }
  }
}

TEST(AlternateHandsTest, SwapsTheFewestMovesAndNotesThem) {
  std::vector<VariedMove> m(4);
  for (auto& x : m) x.hand = Hand::kRight;
  m[3].hand = Hand::kLeft;  // R R R L: pattern R L R L needs one swap
  EXPECT_EQ(AlternateHands(&m), 1);
  EXPECT_EQ(m[1].hand, Hand::kLeft);
  ASSERT_EQ(m[1].notes.size(), 1u);
  EXPECT_EQ(m[1].notes[0], "(hand swapped)");
  EXPECT_TRUE(m[0].notes.empty() && m[2].notes.empty() && m[3].notes.empty());

  std::vector<VariedMove> tie(2);
  tie[0].hand = tie[1].hand = Hand::kLeft;  // a tie keeps the first move's hand
  EXPECT_EQ(AlternateHands(&tie), 1);
  EXPECT_EQ(tie[0].hand, Hand::kLeft);
  EXPECT_EQ(tie[1].hand, Hand::kRight);

  std::vector<VariedMove> fine(3);
  fine[1].hand = Hand::kLeft;
  EXPECT_EQ(AlternateHands(&fine), 0);
}

}  // namespace
}  // namespace sb::chaos
