#include "app/candidates.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>

#include "app/setting_day.h"
#include "app/variations.h"
#include "base/files.h"
#include "crdl/route.h"
#include "plan/plan.h"
#include "plan/warnings.h"

namespace sb::app {
namespace {

// Pair x level combinations of the 36 met with no warning at the setting
// day's search radius, measured 2026-11-28 with the IC picker, moves compared
// hand-blind (docs/setting.md "Novelty the setter chooses": `new` is out of
// reach on every pair, each saying why): a floor against regressions, in
// all and per level (close, mix, new; measured again 15:00 UTC, engineer
// day7: 11, 9 and 0 of 12; docs/BENCHMARKS.md "what blocks `new`").
constexpr int kNoveltyMetAtLeast = 20;
constexpr int kNoveltyMetPerLevelAtLeast[3] = {11, 9, 0};

Move M(Hand h, std::string text) {
  Move m;
  m.hand = h;
  m.text = std::move(text);
  return m;
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

// A: R pinch start, L small crimp, R small crimp, L sloper, R jug finish.
std::vector<chaos::InputRoute> Inputs() {
  Route a;
  a.moves = {M(Hand::kRight, "pinch start"), M(Hand::kLeft, "small crimp"),
             M(Hand::kRight, "small crimp"), M(Hand::kLeft, "sloper"),
             M(Hand::kRight, "jug finish")};
  return {{"A", a}};
}

TEST(CandidateFilterTest, RejectsAFinishFirstOrMidRouteAndLongerRuns) {
  std::vector<std::string> why;
  // The input itself passes.
  EXPECT_FALSE(RejectedByFilter(plan::Warn(FromMapping(Inputs(), {0, 1, 2, 3, 4})), &why));
  EXPECT_TRUE(why.empty());
  // The finish first.
  why.clear();
  EXPECT_TRUE(RejectedByFilter(plan::Warn(FromMapping(Inputs(), {4, 1, 2, 3, 4})), &why));
  ASSERT_EQ(why.size(), 1u);
  EXPECT_EQ(why[0], "rejected: a finish move before the end (1 move)");
  // The finish mid-route.
  EXPECT_TRUE(RejectedByFilter(plan::Warn(FromMapping(Inputs(), {0, 1, 4, 3, 4})), nullptr));
  // "small crimp" three times in a row where the input has it twice.
  why.clear();
  EXPECT_TRUE(RejectedByFilter(plan::Warn(FromMapping(Inputs(), {0, 1, 2, 1, 4})), &why));
  ASSERT_EQ(why.size(), 1u);
  EXPECT_EQ(why[0], "rejected: a move repeated more often in a row than in its inputs (1 run)");
  // One hand twice in a row (R R L L R) where the input alternates: two runs.
  why.clear();
  EXPECT_TRUE(RejectedByFilter(plan::Warn(FromMapping(Inputs(), {0, 2, 3, 1, 4})), &why));
  EXPECT_EQ(why, (std::vector<std::string>{
                     "rejected: one hand more often in a row than in its inputs (2 runs)"}));
}

// The one same-hand pair the kept ends' parity demands (issue 22) is excused
// when asked; a second run, or a longer one, is not.
TEST(CandidateFilterTest, ExcusesOnlyOneSameHandPair) {
  Route r;
  r.moves = {M(Hand::kRight, "pinch"), M(Hand::kLeft, "crimp"), M(Hand::kRight, "sloper"),
             M(Hand::kLeft, "pocket"),  M(Hand::kRight, "edge"), M(Hand::kLeft, "jug finish")};
  std::vector<chaos::InputRoute> in = {{"A", r}};
  // L R L R R L: one pair (moves 4-5).
  const plan::PlanWarnings one = plan::Warn(FromMapping(in, {1, 0, 3, 2, 4, 5}));
  std::vector<std::string> why;
  EXPECT_TRUE(RejectedByFilter(one, &why));
  EXPECT_EQ(why, (std::vector<std::string>{
                     "rejected: one hand more often in a row than in its inputs (1 run)"}));
  why.clear();
  EXPECT_FALSE(RejectedByFilter(one, &why, /*excuse_one_hand_pair=*/true));
  EXPECT_TRUE(why.empty());
  // R R L L R (two pairs) and R L R R R L (a run of three) stay rejected.
  EXPECT_TRUE(RejectedByFilter(plan::Warn(FromMapping(Inputs(), {0, 2, 3, 1, 4})), nullptr, true));
  EXPECT_TRUE(RejectedByFilter(plan::Warn(FromMapping(in, {0, 1, 2, 4, 2, 5})), nullptr, true));
}

TEST(CandidateSlotTest, Validates) {
  EXPECT_TRUE((CandidateSlot{"V3", "", "heel hook"}).Validate().ok());
  Status s = CandidateSlot{"", "", "jazz hands"}.Validate();
  EXPECT_FALSE(s.ok());
  EXPECT_EQ(s.message().rfind("style:", 0), 0u) << s.message();
  EXPECT_FALSE((CandidateSlot{"", "V5", ""}).Validate().ok());
}

class ScorerTest : public ::testing::Test {
 protected:
  void SetUp() override {
    auto s = CandidateScorer::Make(CandidateSlot{"V3", "V4", "crimp"});
    if (!s.ok()) GTEST_SKIP() << "grammar or model missing: " << s.status().message();
  }
};

plan::RoutePlan PlanOf(const chaos::Variation& v, const std::string& estimate) {
  plan::RoutePlan p;
  p.variation = v;
  p.warnings = plan::Warn(v);
  plan::PlanGrades g;
  g.discipline = "bouldering";
  g.scale = "v";
  g.estimate = estimate;
  p.grades = g;
  return p;
}

TEST_F(ScorerTest, ScoresEachPartAndSaysWhy) {
  auto scorer = CandidateScorer::Make(CandidateSlot{"V3", "V4", "crimp"});
  ASSERT_TRUE(scorer.ok());
  chaos::Variation clean = FromMapping(Inputs(), {0, 1, 2, 3, 4});
  CandidateScore in = scorer->Score(PlanOf(clean, "V4"));
  // The input itself scores in full but is no variation (CandidateChangeTest).
  EXPECT_TRUE(in.rejected);
  EXPECT_EQ(in.reasons[0], "rejected: same as input A");
  in.reasons.erase(in.reasons.begin());
  EXPECT_DOUBLE_EQ(in.warnings_part, kScoreNoWarnings);
  EXPECT_DOUBLE_EQ(in.grade_part, kScoreGrade);
  EXPECT_DOUBLE_EQ(in.style_part, kScoreStyle);
  EXPECT_EQ(in.style_moves, 2);
  // The input itself is exactly as smooth as the input.
  EXPECT_NEAR(in.bits_per_move, in.input_bits_per_move, 1e-9);
  EXPECT_NEAR(in.smooth_part, kScoreSmooth, 1e-6);
  EXPECT_NEAR(in.score, 100.0, 1e-6);
  EXPECT_EQ(in.reasons[0], "no warnings");
  EXPECT_EQ(in.reasons[1], "estimated V4 inside band V3-V4");
  EXPECT_EQ(in.reasons[2], "crimp on 2 moves");

  // One band above: half the grade part; two: none.
  EXPECT_DOUBLE_EQ(scorer->Score(PlanOf(clean, "V5")).grade_part, kScoreGrade / 2);
  CandidateScore far = scorer->Score(PlanOf(clean, "V7"));
  EXPECT_DOUBLE_EQ(far.grade_part, 0.0);
  EXPECT_EQ(far.reasons[2], "estimated V7 3 bands outside band V3-V4");  // after "same as input A"

  // A finish first: rejected, with warnings, less smooth, no crimp lost.
  CandidateScore bad = scorer->Score(PlanOf(FromMapping(Inputs(), {4, 3, 0, 3, 4}), "V3"));
  EXPECT_TRUE(bad.rejected);
  EXPECT_LT(bad.warnings_part, kScoreNoWarnings);
  EXPECT_FALSE(bad.warnings.empty());
  EXPECT_DOUBLE_EQ(bad.style_part, 0.0);  // no crimp in it
  EXPECT_LT(bad.score, in.score);
}

// Issue 22: "a variation a setter could set" must change its inputs. A
// candidate equal to an input, or the inputs one after the other (one new
// move, where the second begins), ranks with the rejected, the reason said;
// any other says how many of its moves are new.
TEST(CandidateChangeTest, RejectsAnInputOrAConcatenationAndSaysWhatChanged) {
  Route b;
  b.moves = {M(Hand::kLeft, "gaston start"), M(Hand::kRight, "pocket"),
             M(Hand::kLeft, "heel hook"), M(Hand::kRight, "jug finish")};
  std::vector<chaos::InputRoute> two = Inputs();
  two.push_back({"B", b});
  // The input itself.
  chaos::Variation same = FromMapping(two, {0, 1, 2, 3, 4});
  MoveChange c = ChangeAgainstInputs(same.moves, two);
  EXPECT_EQ(c.same_as, "A");
  EXPECT_EQ(c.new_moves, 0);
  // A then B: B's start after A's finish is the one new move.
  c = ChangeAgainstInputs(FromMapping(two, {0, 1, 2, 3, 4, 5, 6, 7, 8}).moves, two);
  EXPECT_EQ(c.same_as, "");
  EXPECT_EQ(c.new_moves, 1);
  EXPECT_EQ(c.moves, 9);
  // Reordered: R pinch start, R small crimp, L small crimp, L sloper, R jug
  // finish: the two small crimps swapped are the same moves by text (hands
  // ignored), so nothing follows another than in A.
  c = ChangeAgainstInputs(FromMapping(two, {0, 2, 1, 3, 4}).moves, two);
  EXPECT_EQ(c.new_moves, 0);
  // R pinch start, L sloper, R small crimp, L small crimp, R jug finish:
  // sloper after the start, small crimp after sloper and jug finish after
  // small crimp are new.
  c = ChangeAgainstInputs(FromMapping(two, {0, 3, 2, 1, 4}).moves, two);
  EXPECT_EQ(c.new_moves, 3);
  EXPECT_EQ(c.moves, 5);
  // Moves compare by what the hand does, not by which hand (issue 33): a
  // hand relabelled to alternate hands (the setters' own fix) is no new move
  // (L pinch start is A's R pinch start), nor is a change of case or
  // punctuation; a start no input has is new, and so is the move after it.
  chaos::Variation other = FromMapping(two, {0, 1, 2, 3, 4});
  other.moves[0].hand = Hand::kLeft;
  other.moves[0].notes.push_back("(hand swapped)");
  EXPECT_EQ(ChangeAgainstInputs(other.moves, two).new_moves, 0);
  EXPECT_EQ(ChangeAgainstInputs(other.moves, two).same_as, "");  // not the input itself
  other.moves[1].text = "Small crimp!";
  EXPECT_EQ(ChangeAgainstInputs(other.moves, two).new_moves, 0);
  other.moves[0].text = "gaston";
  EXPECT_EQ(ChangeAgainstInputs(other.moves, two).new_moves, 2);
  // A match carried with its predecessor is not new: "match" after "jug"
  // in the input, shown as "(match?)" with the other hand's move's text.
  Route m;
  m.moves = {M(Hand::kLeft, "jug"), M(Hand::kRight, "match"), M(Hand::kRight, "crimp")};
  const std::vector<chaos::InputRoute> with_match = {{"M", m}};
  chaos::Variation mv = FromMapping(with_match, {0, 1, 2});
  ASSERT_EQ(mv.moves[1].notes, std::vector<std::string>{"(match?)"});
  EXPECT_EQ(ChangeAgainstInputs(mv.moves, with_match).new_moves, 0);

  auto scorer = CandidateScorer::Make(CandidateSlot{});
  if (!scorer.ok()) GTEST_SKIP() << "grammar or model missing: " << scorer.status().message();
  auto reasons = [](const CandidateScore& s) {
    std::string all;
    for (const std::string& r : s.reasons) all += r + "|";
    return all;
  };
  CandidateScore s = scorer->Score(PlanOf(same, ""));
  EXPECT_TRUE(s.rejected);
  EXPECT_NE(reasons(s).find("rejected: same as input A|"), std::string::npos) << reasons(s);
  s = scorer->Score(PlanOf(FromMapping(two, {0, 1, 2, 3, 5, 6, 7, 8}), ""));  // A's finish dropped
  EXPECT_TRUE(s.rejected);
  EXPECT_EQ(s.new_moves, 1);
  EXPECT_NE(reasons(s).find("rejected: 1 of 8 moves new against its inputs (at least 2 asked"),
            std::string::npos)
      << reasons(s);
  s = scorer->Score(PlanOf(FromMapping(two, {0, 6, 1, 2, 3, 4}), ""));
  EXPECT_EQ(s.new_moves, 2);
  EXPECT_NE(reasons(s).find("2 of 6 moves new against its inputs|"), std::string::npos)
      << reasons(s);
  EXPECT_EQ(reasons(s).find("rejected: 2 of"), std::string::npos) << reasons(s);
}

TEST(RankTest, KeptFirstThenScoreThenOrder) {
  std::vector<Candidate> c(4);
  c[0].score.score = 90, c[0].score.rejected = true, c[0].index = 0;
  c[1].score.score = 50, c[1].index = 1;
  c[2].score.score = 70, c[2].index = 2;
  c[3].score.score = 70, c[3].index = 3;
  RankCandidates(&c);
  EXPECT_EQ(c[0].index, 2);
  EXPECT_EQ(c[1].index, 3);
  EXPECT_EQ(c[2].index, 1);
  EXPECT_EQ(c[3].index, 0);
}

// The bundled examples `make run` varies (crimp ladder + slab dance), and a
// pair whose ends' hands are of the other parity (campus rail + crimp ladder:
// every candidate was rejected for keep-finish before issue 22's fix): every
// kept candidate of the setter's gallery starts and ends like a route, with
// the input's start and finish hands, has no finish move before the end and
// no hand run longer than its inputs' but the one same-hand pair the ends'
// parity demands; the ranking is deterministic.
TEST(GalleryTest, KeptCandidatesPassTheFilter) {
  SettingRequest req;
  chaos::VaryParams params;
  ApplySetterPreset(&params, &req);
  EXPECT_EQ(params.mapping.max_repeat, kSetterMaxRepeat);
  EXPECT_TRUE(req.constraints.keep_start && req.constraints.keep_finish &&
              req.constraints.alternate_hands);
  int with_pair = 0;
  for (const auto& files : {std::vector<const char*>{"crimp-ladder", "slab-dance"},
                            std::vector<const char*>{"campus-rail", "crimp-ladder"}}) {
    std::vector<chaos::InputRoute> in;
    for (const char* f : files) {
      const std::string path = FindDataFile(std::string("examples/") + f + ".crdl");
      if (path.empty()) GTEST_SKIP() << "bundled examples missing";
      auto r = ReadCrdlFile(path);
      ASSERT_TRUE(r.ok()) << r.status().message();
      in.push_back({r->Name("x"), *r});
    }
    if (!CandidateScorer::Make({}).ok()) GTEST_SKIP() << "grammar or model missing";
    SCOPED_TRACE(std::string(files[0]) + " + " + files[1]);
    // The second pair with the setting day's search radius: cheaper, and
    // what a slot's gallery uses.
    SettingRequest r = req;
    if (files[0] != std::string("crimp-ladder")) r.grid.radius = kDaySearchRadius;
    auto g = MakeGallery(in, params, r, {}, {});
    ASSERT_TRUE(g.ok()) << g.status().message();
    ASSERT_FALSE(g->empty());
    int kept = 0;
    for (const Candidate& c : *g) {
      if (c.score.rejected) continue;
      ++kept;
      const auto& moves = c.plan.variation.moves;
      const int n = static_cast<int>(moves.size());
      // No finish move with a non-finish, non-match move after it.
      for (int j = 0; j + 1 < n; ++j) {
        if (!plan::IsFinishMoveText(moves[j].text)) continue;
        for (int k = j + 1; k < n; ++k) {
          EXPECT_TRUE(plan::IsFinishMoveText(moves[k].text) || plan::IsMatchOnlyText(moves[k].text))
              << "move " << j + 1 << " \"" << moves[j].text << "\" then \"" << moves[k].text << "\"";
        }
      }
      // No hand run longer than the inputs' longest (1: the examples
      // alternate) but one pair, where alternate-hands says it is not held.
      int pairs = 0;
      for (int j = 1; j < n; ++j) pairs += moves[j].hand == moves[j - 1].hand;
      EXPECT_LE(pairs, 1);
      ASSERT_TRUE(c.plan.search.has_value());
      for (const chaos::ConstraintOutcome& o : c.plan.search->constraints) {
        EXPECT_EQ(o.held, o.constraint != chaos::Constraint::kAlternateHands || pairs == 0)
            << chaos::ConstraintName(o.constraint) << ": " << o.detail;
      }
      with_pair += pairs;
      // Starts with an input's start, ends with an input's finish, hands kept
      // (the inputs as varied: drop-inner-starts drops Slab Dance's start and
      // mirrors its hands after Crimp Ladder's right-hand last move).
      ASSERT_TRUE(moves.front().source && moves.back().source);
      const auto& varied = c.plan.variation.inputs;
      ASSERT_EQ(varied.size(), in.size());
      EXPECT_EQ(varied[1].first_move, 1);
      EXPECT_EQ(varied[1].route.moves.size() + 1, in[1].route.moves.size());
      const Route& first = varied[moves.front().source->route].route;
      const Route& last = varied[moves.back().source->route].route;
      EXPECT_EQ(varied[moves.front().source->route].first_move, 0);
      EXPECT_EQ(moves.front().source->move, 0);
      EXPECT_EQ(moves.front().hand, first.moves.front().hand);
      EXPECT_EQ(moves.back().source->move, static_cast<int>(last.moves.size()) - 1);
      EXPECT_EQ(moves.back().hand, last.moves.back().hand);
    }
    EXPECT_GT(kept, 0);
    if (files[0] == std::string("crimp-ladder")) {
      // Deterministic.
      auto again = MakeGallery(in, params, req, {}, {});
      ASSERT_TRUE(again.ok());
      EXPECT_EQ(GalleryReport(*g), GalleryReport(*again));
    }
  }
  EXPECT_GT(with_pair, 0);  // the second pair's parity demands one
}

TEST(NoveltyTest, LevelsNamesAndBands) {
  EXPECT_EQ(NoveltyOf(6, 20), Novelty::kClose);   // 30%
  EXPECT_EQ(NoveltyOf(7, 21), Novelty::kMix);     // exactly a third
  EXPECT_EQ(NoveltyOf(14, 21), Novelty::kMix);    // exactly two thirds
  EXPECT_EQ(NoveltyOf(15, 21), Novelty::kNew);
  EXPECT_EQ(NoveltyOf(0, 0), Novelty::kClose);
  for (Novelty n : {Novelty::kClose, Novelty::kMix, Novelty::kNew}) {
    auto back = ParseNovelty(NoveltyName(n));
    ASSERT_TRUE(back.ok());
    EXPECT_EQ(*back, n);
  }
  EXPECT_EQ(*ParseNovelty("NEW"), Novelty::kNew);
  auto bad = ParseNovelty("wild");
  ASSERT_FALSE(bad.ok());
  EXPECT_EQ(bad.status().message().rfind("novelty:", 0), 0u) << bad.status().message();
}

// The one change count (issue 33): the plan's summary, its header and the
// gallery's reasons give the same number.
TEST(NoveltyTest, TheChangeCountIsOneNumber) {
  const std::string a = FindDataFile("examples/crimp-ladder.crdl");
  const std::string b = FindDataFile("examples/slab-dance.crdl");
  if (a.empty() || b.empty()) GTEST_SKIP() << "bundled examples missing";
  if (!CandidateScorer::Make({}).ok()) GTEST_SKIP() << "grammar or model missing";
  std::vector<chaos::InputRoute> in;
  for (const std::string& f : {a, b}) {
    auto r = ReadCrdlFile(f);
    ASSERT_TRUE(r.ok());
    in.push_back({r->Name("x"), *r});
  }
  SettingRequest req;
  chaos::VaryParams params;
  ApplySetterPreset(&params, &req);
  req.grid.radius = kDaySearchRadius;
  auto g = MakeGallery(in, params, req, {}, {});
  ASSERT_TRUE(g.ok()) << g.status().message();
  for (const Candidate& c : *g) {
    ASSERT_TRUE(c.plan.warnings.has_value());
    EXPECT_EQ(c.plan.warnings->summary.new_moves, c.score.new_moves);
    const std::string text = plan::Render(c.plan, plan::Format::kText);
    EXPECT_NE(text.find(std::to_string(c.score.new_moves) + " new against the inputs"),
              std::string::npos);
  }
}

// Issue 33: each novelty level's best candidate lands in its band of changed
// moves with no warnings on the bundled example pairs (each example with the
// next of its discipline, as scripts/setting_gallery_check.sh pairs them),
// or the gallery says why not.
TEST(NoveltyTest, EachLevelsBestLandsInItsBandOnTheExamplePairs) {
  if (!CandidateScorer::Make({}).ok()) GTEST_SKIP() << "grammar or model missing";
  const std::vector<std::vector<std::string>> sets = {
      {"beginner-jugs", "campus-rail", "crimp-ladder", "dyno-problem", "pinch-prow",
       "sloper-arete"},
      {"edge-crack", "pocket-traverse", "roof-jugs", "slab-dance", "undercling-flake",
       "volume-mantle"}};
  int met = 0, total = 0;
  int met_level[3] = {0, 0, 0};
  std::string misses;
  for (const auto& names : sets) {
    for (size_t i = 0; i < names.size(); ++i) {
      std::vector<chaos::InputRoute> in;
      for (const std::string& f : {names[i], names[(i + 1) % names.size()]}) {
        const std::string path = FindDataFile("examples/" + f + ".crdl");
        if (path.empty()) GTEST_SKIP() << "bundled examples missing";
        auto r = ReadCrdlFile(path);
        ASSERT_TRUE(r.ok()) << r.status().message();
        in.push_back({r->Name("x"), *r});
      }
      for (Novelty level : {Novelty::kClose, Novelty::kMix, Novelty::kNew}) {
        SCOPED_TRACE(names[i] + " + " + names[(i + 1) % names.size()] + ", " + NoveltyName(level));
        SettingRequest req;
        chaos::VaryParams params;
        ApplySetterPreset(&params, &req);
        req.grid.radius = kDaySearchRadius;
        GalleryOptions go;
        go.novelty = level;
        std::string note;
        auto g = MakeGallery(in, params, req, {}, go, &note);
        ASSERT_TRUE(g.ok()) << g.status().message();
        const Candidate& best = g->front();
        const bool ok = !best.score.rejected && best.score.novelty == level &&
                        best.score.warnings.empty();
        // The best is made again from what is stored of it (its IC, skip and
        // search radius: 0 at the picker's ICs), move for move.
        {
          chaos::VaryParams p = params;
          p.var_ic = best.searched_from;
          p.skip = best.skip;
          SettingRequest at = req;
          at.grid.radius = best.search_radius;
          SmoothingOutcome outcome;
          auto again = BuildPlan(in, p, at, SmoothingRequest{}, &outcome);
          ASSERT_TRUE(again.ok()) << again.status().message();
          ASSERT_EQ(again->variation.moves.size(), best.plan.variation.moves.size());
          for (size_t j = 0; j < again->variation.moves.size(); ++j) {
            EXPECT_EQ(again->variation.moves[j].text, best.plan.variation.moves[j].text);
            EXPECT_EQ(again->variation.moves[j].hand, best.plan.variation.moves[j].hand);
          }
        }
        ++total;
        if (ok) {
          ++met;
          ++met_level[static_cast<int>(level)];
          EXPECT_EQ(note, "");
          // The band, from the counts themselves.
          const double share = double(best.score.new_moves) / best.score.moves;
          if (level == Novelty::kClose) {
            EXPECT_LT(share, 1.0 / 3);
          } else if (level == Novelty::kMix) {
            EXPECT_TRUE(share >= 1.0 / 3 && share <= 2.0 / 3);
          } else {
            EXPECT_GT(share, 2.0 / 3);
          }
        } else {
          misses += names[i] + "/" + NoveltyName(level) + " ";
          std::printf("%s + %s, %s: %s\n", names[i].c_str(), names[(i + 1) % names.size()].c_str(),
                      NoveltyName(level), note.c_str());
          // Not met: never silently, the note says why and what to try,
          // with what the IC picker saw (how many ICs, how many meet the
          // constraints, the shares of new moves reached).
          EXPECT_NE(note.find("the IC picker scanned"), std::string::npos) << note;
          EXPECT_NE(note.find("try "), std::string::npos) << note;
        }
      }
    }
  }
  std::printf("novelty levels met with no warnings: %d of %d (close %d, mix %d, new %d of 12; "
              "missed: %s)\n",
              met, total, met_level[0], met_level[1], met_level[2], misses.c_str());
  EXPECT_GE(met, kNoveltyMetAtLeast);
  for (int l = 0; l < 3; ++l) {
    EXPECT_GE(met_level[l], kNoveltyMetPerLevelAtLeast[l]) << NoveltyName(static_cast<Novelty>(l));
  }
}

// Issue 33: a level the inputs cannot reach is said so in a setter's words,
// with the measured figures (docs/BENCHMARKS.md, "what blocks `new`"): on
// campus rail + crimp ladder no variation within the setter's rules changes
// more than 9 of its 18 moves, so `new` is out of reach; the sentence is a
// catalog message (translated by id) and the note begins with it.
TEST(NoveltyTest, AnUnreachableLevelIsSaidInASettersWords) {
  if (!CandidateScorer::Make({}).ok()) GTEST_SKIP() << "grammar or model missing";
  std::vector<chaos::InputRoute> in;
  for (const char* f : {"campus-rail", "crimp-ladder"}) {
    const std::string path = FindDataFile(std::string("examples/") + f + ".crdl");
    if (path.empty()) GTEST_SKIP() << "bundled examples missing";
    auto r = ReadCrdlFile(path);
    ASSERT_TRUE(r.ok()) << r.status().message();
    in.push_back({r->Name("x"), *r});
  }
  SettingRequest req;
  chaos::VaryParams params;
  ApplySetterPreset(&params, &req);
  req.grid.radius = kDaySearchRadius;
  GalleryOptions go;
  go.novelty = Novelty::kNew;
  std::string note;
  Message said;
  auto g = MakeGallery(in, params, req, {}, go, &note, &said);
  ASSERT_TRUE(g.ok()) << g.status().message();
  const Candidate& best = g->front();
  EXPECT_NE(best.score.novelty, Novelty::kNew);
  EXPECT_EQ(said.kind, Message::Kind::kMessage);
  EXPECT_EQ(said.id,
            "No variation of these routes changes more than two thirds of the moves within the "
            "setter's rules (the most changed: {1} of {2}); showing the best of the others "
            "instead ({3})");
  EXPECT_EQ(said.English(),
            "No variation of these routes changes more than two thirds of the moves within the "
            "setter's rules (the most changed: 9 of 18); showing the best of the others instead "
            "(" + std::to_string(best.score.new_moves) + " of 18 moves changed)");
  EXPECT_EQ(best.score.new_moves, 5);  // measured: the best of the others
  EXPECT_EQ(note.rfind(said.English() + ". Details: ", 0), 0u) << note;
  // Met: nothing said.
  go.novelty = Novelty::kMix;
  auto mix = MakeGallery(in, params, req, {}, go, &note, &said);
  ASSERT_TRUE(mix.ok()) << mix.status().message();
  if (mix->front().score.novelty == Novelty::kMix && mix->front().score.warnings.empty()) {
    EXPECT_TRUE(said.empty());
    EXPECT_EQ(note, "");
  }
}

// Issue 33, "Must show": `make run`'s demo prints the `mix` level's
// variation: scripts/run.sh varies crimp ladder + slab dance with
// `--preset setter --novelty mix`, and that gallery's best (the CLI's search
// radius) is a mix of its inputs and new moves without a warning.
TEST(NoveltyTest, MakeRunsDemoPrintsTheMixLevel) {
  const Result<std::string> run = ReadFile(std::string(SB_SOURCE_DIR) + "/scripts/run.sh");
  ASSERT_TRUE(run.ok()) << run.status().message();
  EXPECT_NE(run->find("vary --preset setter --novelty mix data/examples/crimp-ladder.crdl "
                      "data/examples/slab-dance.crdl"),
            std::string::npos);
  if (!CandidateScorer::Make({}).ok()) GTEST_SKIP() << "grammar or model missing";
  std::vector<chaos::InputRoute> in;
  for (const char* f : {"crimp-ladder", "slab-dance"}) {
    auto r = ReadCrdlFile(std::string(SB_SOURCE_DIR) + "/data/examples/" + f + ".crdl");
    ASSERT_TRUE(r.ok()) << r.status().message();
    in.push_back({r->Name("x"), *r});
  }
  SettingRequest req;
  chaos::VaryParams params;
  ApplySetterPreset(&params, &req);
  GalleryOptions go;
  go.novelty = Novelty::kMix;
  auto choice = ChooseFromGallery(in, &params, &req, {}, go);
  ASSERT_TRUE(choice.ok()) << choice.status().message();
  const Candidate& best = choice->candidates.front();
  EXPECT_FALSE(best.score.rejected);
  EXPECT_EQ(best.score.novelty, Novelty::kMix)
      << best.score.new_moves << " of " << best.score.moves;
  EXPECT_TRUE(best.score.warnings.empty());
  EXPECT_EQ(choice->note, "");
}

}  // namespace
}  // namespace sb::app
