#include "chaos/variation.h"

#include <gtest/gtest.h>

namespace sb::chaos {
namespace {

InputRoute MakeRoute(const std::string& name, const std::string& crdl) {
  auto r = ParseCrdl(crdl, name);
  EXPECT_TRUE(r.ok()) << r.status().message();
  return {name, *r};
}

TEST(Variation, Presets) {
  auto d = VaryParams::Preset("default");
  ASSERT_TRUE(d.ok());
  EXPECT_EQ(d->ref_ic, (State{-13, -12, 52}));
  EXPECT_EQ(d->var_ic, (State{-16, -12, 52}));
  EXPECT_EQ(d->skip, 0);
  EXPECT_EQ(d->step, 0.015);
  EXPECT_EQ(d->system.params, (std::array<double, 3>{16, 45, 4}));
  EXPECT_EQ(d->integrator, IntegratorKind::kRk4);
  EXPECT_EQ(d->mapping.mask, kMaskX | kMaskZ);
  auto m = VaryParams::Preset("more");
  ASSERT_TRUE(m.ok());
  EXPECT_EQ(m->var_ic, (State{-16, -13.5, 52}));
  EXPECT_EQ(m->skip, 100);
  EXPECT_FALSE(VaryParams::Preset("wild").ok());
}

TEST(Variation, MatchTakesPreviousMoveOfOtherHand) {
  auto in = MakeRoute("a", "---\nR match\nR slopey ledge\nL match\nL crimp\nR Match\n");
  auto moves = PrepareMoves({in});
  ASSERT_EQ(moves.size(), 5u);
  EXPECT_EQ(moves[0].text, "match");  // leading match: kept
  EXPECT_TRUE(moves[0].notes.empty());
  EXPECT_EQ(moves[2].text, "slopey ledge");
  EXPECT_EQ(moves[2].hand, Hand::kLeft);
  EXPECT_EQ(moves[2].notes, std::vector<std::string>{"(match?)"});
  EXPECT_EQ(moves[4].text, "crimp");
  EXPECT_EQ(moves[4].hand, Hand::kRight);
}

TEST(Variation, MatchDoesNotReachIntoAnotherRoute) {
  auto a = MakeRoute("a", "---\nL jug\n");
  auto b = MakeRoute("b", "---\nR match\n");
  auto moves = PrepareMoves({a, b});
  EXPECT_EQ(moves[1].text, "match");
  EXPECT_EQ(*moves[1].source, (SourceRef{1, 0}));
}

TEST(Variation, IdenticalIcsGiveTheInput) {
  auto in = MakeRoute("a", "---\nR a\nL b\nR c\nL d\nR e\nL f\n");
  VaryParams p;
  p.var_ic = p.ref_ic;
  auto v = Vary({in}, p);
  ASSERT_TRUE(v.ok());
  for (size_t j = 0; j < v->moves.size(); ++j) {
    EXPECT_FALSE(v->moves[j].changed);
    EXPECT_EQ(v->moves[j].source->move, int(j));
  }
}

TEST(Variation, ProvenanceAndChangedAreConsistent) {
  auto a = MakeRoute("a", "---\nR a0\nL a1\nR a2\nL a3\nR a4\n");
  auto b = MakeRoute("b", "---\nR b0\nL b1\nR b2\nL b3\nR b4\nL b5\n");
  auto v = Vary({a, b}, *VaryParams::Preset("more"));
  ASSERT_TRUE(v.ok());
  ASSERT_EQ(v->moves.size(), 11u);
  ASSERT_EQ(v->reference.size(), 11u);
  int changed = 0;
  for (size_t j = 0; j < 11; ++j) {
    int k = v->mapping[j];
    ASSERT_GE(k, 0);
    const auto& src = *v->moves[j].source;
    int flat = src.route == 0 ? src.move : 5 + src.move;
    EXPECT_EQ(flat, k);
    EXPECT_EQ(v->moves[j].changed, k != int(j));
    EXPECT_EQ(v->moves[j].text, (src.route == 0 ? "a" : "b") + std::to_string(src.move));
    changed += v->moves[j].changed;
  }
  EXPECT_GT(changed, 0);
}

TEST(Variation, DeterministicAndValidated) {
  auto a = MakeRoute("a", "---\nR a0\nL a1\nR a2\n");
  auto v1 = Vary({a}, VaryParams());
  auto v2 = Vary({a}, VaryParams());
  ASSERT_TRUE(v1.ok() && v2.ok());
  EXPECT_EQ(v1->variation, v2->variation);
  VaryParams bad;
  bad.step = -1;
  EXPECT_FALSE(Vary({a}, bad).ok());
  bad = VaryParams();
  bad.step = 10;  // diverges
  auto d = Vary({a}, bad);
  EXPECT_FALSE(d.ok());
}

TEST(Variation, DabbyBlanks) {
  auto a = MakeRoute("a", "---\nR a0\nL a1\nR a2\nL a3\nR a4\nL a5\nR a6\nL a7\n");
  VaryParams p;
  p.mapping.kind = MappingKind::kDabby;
  p.var_ic = {10, 10, 30};
  auto v = Vary({a}, p);
  ASSERT_TRUE(v.ok());
  for (size_t j = 0; j < v->moves.size(); ++j) {
    if (v->mapping[j] < 0) {
      EXPECT_FALSE(v->moves[j].source.has_value());
      EXPECT_TRUE(v->moves[j].text.empty());
    } else {
      EXPECT_GE(v->reference[v->mapping[j]][0], v->variation[j][0]);
    }
  }
}

}  // namespace
}  // namespace sb::chaos
