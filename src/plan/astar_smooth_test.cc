// Climbing feature vectors, readable moves, A* plan smoothing and the
// corpus evaluation on the bundled examples.
#include "plan/astar_smooth.h"

#include <gtest/gtest.h>

#include <cmath>

#include "graph/search.h"
#include "plan/climb_tokens.h"
#include "plan/smoothing_eval.h"

namespace sb::plan {
namespace {

std::vector<Route> Examples() {
  std::vector<Route> out;
  for (const char* f : {"crimp-ladder", "slab-dance", "roof-jugs", "sloper-arete", "pinch-prow",
                        "campus-rail", "pocket-traverse", "undercling-flake"}) {
    auto r = ReadCrdlFile(std::string(SB_SOURCE_DIR) + "/data/examples/" + f + ".crdl");
    EXPECT_TRUE(r.ok()) << r.status().message();
    out.push_back(*r);
  }
  return out;
}

language::MoveLanguage Lang() {
  auto l = language::MoveLanguage::LoadDefault();
  EXPECT_TRUE(l.ok());
  return std::move(l).value();
}

TEST(ClimbTokens, FeaturesOfAMove) {
  auto lang = Lang();
  auto t = ClimbToken(Hand::kRight, lang.Read("big move to small sloping crimp").features);
  ASSERT_TRUE(t);
  EXPECT_EQ(graph::FormatToken(*t), "R|move|big|crimp|small|sloping|no|yes|no");
  EXPECT_EQ(ReadableClimbMove(*t, lang), "R big move to small sloping crimp");
  auto m = ClimbToken(Hand::kLeft, lang.Read("match").features);
  ASSERT_TRUE(m);
  EXPECT_EQ(ReadableClimbMove(*m, lang), "L match");
  EXPECT_FALSE(ClimbToken(Hand::kLeft, lang.Read("have fun!").features));
  EXPECT_EQ(ClimbFeatureNames()[3], "hold");
}

// A feature vector written back as a move reads back to the same vector
// (every move of the examples).
TEST(ClimbTokens, ReadableMovesReadBack) {
  auto lang = Lang();
  int n = 0;
  for (const Route& r : Examples()) {
    for (const Move& m : r.moves) {
      auto t = ClimbToken(m.hand, lang.Read(m.text).features);
      if (!t) continue;
      const std::string text = ReadableClimbMove(*t, lang);
      auto back = ClimbToken(m.hand, lang.Read(text.substr(2)).features);
      ASSERT_TRUE(back) << text;
      // Size words of the same class may differ ("long" reads as big).
      EXPECT_EQ(graph::FormatToken(*back), graph::FormatToken(*t)) << m.text << " -> " << text;
      ++n;
    }
  }
  EXPECT_GT(n, 50);
}

TEST(AStarSmooth, SuggestionsFollowTheGraph) {
  ASSERT_FALSE(DefaultGraphPath().empty()) << "data/models/default.sbg missing";
  std::vector<chaos::InputRoute> in;
  auto ex = Examples();
  in.push_back({"a", ex[0]});
  in.push_back({"b", ex[2]});
  auto v = chaos::Vary(in, *chaos::VaryParams::Preset("more"));
  ASSERT_TRUE(v.ok());
  RoutePlan plan{*v, {}, ""};
  ASSERT_TRUE(SmoothAStar("default", &plan).ok());
  EXPECT_EQ(plan.smoothing_model, "default");
  auto g = graph::LoadGraph(DefaultGraphPath());
  ASSERT_TRUE(g.ok());
  auto lang = Lang();
  auto bs = InterpolateBoundaries(*g, plan.variation, lang);
  ASSERT_TRUE(bs.ok()) << bs.status().message();
  ASSERT_FALSE(bs->empty());
  size_t with_moves = 0;
  for (const BoundaryInterpolation& b : *bs) {
    if (!b.searched || b.outcome != graph::Outcome::kFound) continue;
    EXPECT_LE(static_cast<int>(b.inserted.size()), kDefaultAStarInsert);
    EXPECT_LE(b.cost, b.direct_cost + 1e-9);  // A* is never worse than the direct step
    // The cost is the sum of the path's transitions.
    auto from = g->Encode(*ClimbToken(plan.variation.moves[b.after].hand,
                                      lang.Read(plan.variation.moves[b.after].text).features),
                          "from");
    ASSERT_TRUE(from.ok());
    std::vector<int32_t> prev = *from;
    double cost = 0;
    for (const auto& t : b.inserted) {
      auto s = g->Encode(t, "inserted");
      ASSERT_TRUE(s.ok());
      cost += graph::TransitionCost(*g, prev, *s);
      prev = *s;
    }
    const auto& after = plan.variation.moves[b.after + 1];
    cost += graph::TransitionCost(
        *g, prev, *g->Encode(*ClimbToken(after.hand, lang.Read(after.text).features), "to"));
    EXPECT_NEAR(cost, b.cost, 1e-9);
    if (!b.inserted.empty()) ++with_moves;
  }
  EXPECT_EQ(plan.smoothing.size(), with_moves);
  for (const Suggestion& s : plan.smoothing) {
    const BoundaryInterpolation* b = nullptr;
    for (const auto& x : *bs)
      if (x.after == s.after) b = &x;
    ASSERT_NE(b, nullptr);
    EXPECT_NEAR(s.bits_after * std::log(2.0), b->cost, 1e-9);
    EXPECT_EQ(s.moves.size(), b->inserted.size());
    for (const InsertedMove& m : s.moves) {
      EXPECT_TRUE(m.hand == "L" || m.hand == "R");
      EXPECT_EQ(m.description.substr(0, 2), m.hand + " ");
    }
  }
}

TEST(AStarSmooth, RefusesGraphsOfOtherTokens) {
  auto g = graph::GraphModel::Train({{{"a", "b"}, {"c", "d"}}}, 2, {});
  ASSERT_TRUE(g.ok());
  std::vector<chaos::InputRoute> in{{"a", Examples()[0]}};
  auto v = chaos::Vary(in, chaos::VaryParams());
  auto lang = Lang();
  auto r = InterpolateBoundaries(*g, *v, lang);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.status().message().find("not a graph of climbing moves"), std::string::npos);
}

// The evaluation on the examples alone (4 training, 4 judge routes):
// deterministic without times, and its counts add up.
TEST(SmoothingEval, CountsAddUpAndOutputIsDeterministic) {
  auto lang = Lang();
  EvalOptions o;
  o.timing = false;
  auto a = EvaluateSmoothing(Examples(), lang, o);
  ASSERT_TRUE(a.ok()) << a.status().message();
  auto b = EvaluateSmoothing(Examples(), lang, o);
  ASSERT_TRUE(b.ok());
  EXPECT_EQ(FormatEvalReport(*a, false), FormatEvalReport(*b, false));
  EXPECT_EQ(a->training_routes, 4);
  EXPECT_EQ(a->heldout_routes, 4);
  ASSERT_EQ(a->methods.size(), 3u);
  for (const MethodReport& m : a->methods) {
    EXPECT_EQ(m.boundaries, a->boundaries);
    EXPECT_EQ(m.found + m.no_path + m.gave_up, m.boundaries) << m.name;
    EXPECT_EQ(static_cast<int>(m.lengths.size()), m.found);
    int sum = 0;
    for (int l : m.lengths) sum += l;
    EXPECT_EQ(sum, m.moves);
    EXPECT_LE(m.novel_moves, m.moves);
  }
  // The VOMM only inserts symbols it has seen; A* is never costlier than greedy.
  EXPECT_EQ(a->methods[2].novel_symbols, 0);
  EXPECT_EQ(a->methods[2].found, a->methods[2].boundaries);
  EvalOptions bad;
  bad.variations = 0;
  EXPECT_FALSE(EvaluateSmoothing(Examples(), lang, bad).ok());
}

}  // namespace
}  // namespace sb::plan
