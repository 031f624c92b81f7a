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

TEST(Variation, CruxFlagsComeFromTheSourceMove) {
  auto a = MakeRoute("a", "---\nR a0\nL a1 (crux)\nR a2\nL match\n");
  auto moves = PrepareMoves({a});
  EXPECT_FALSE(moves[0].crux);
  EXPECT_TRUE(moves[1].crux);
  VaryParams p = *VaryParams::Preset("more");
  auto v = Vary({a}, p);
  ASSERT_TRUE(v.ok());
  for (const VariedMove& m : v->moves) {
    ASSERT_TRUE(m.source.has_value());
    EXPECT_EQ(m.crux, m.source->move == 1) << m.text;
  }
}

TEST(VaryParamsCodec, JsonRoundTrip) {
  VaryParams p = *VaryParams::Preset("more");
  p.system = System::Rossler(0.1, 0.3, 6);
  p.integrator = IntegratorKind::kRkf45;
  p.mapping.kind = MappingKind::kDabby;
  p.mapping.dabby_direction = DabbyDirection::kBelow;
  p.mapping.max_repeat = 2;
  p.mapping.mask = kMaskY;
  auto back = ParamsFromJson(ParamsToJson(p));
  ASSERT_TRUE(back.ok()) << back.status().message();
  EXPECT_EQ(ParamsToJson(*back), ParamsToJson(p));
  EXPECT_EQ(ParamsToJson(VaryParams()),
            R"({"dabby_direction":"above","integrator":"rk4","mapping":"euclidean","mask":"101",)"
            R"("max_repeat":0,"params":[16.0,45.0,4.0],"preset":"default","ref_ic":[-13.0,-12.0,)"
            R"(52.0],"skip":0,"step":0.015,"system":"lorenz","var_ic":[-16.0,-12.0,52.0]})");
}

TEST(VaryParamsCodec, JsonErrorsNameTheField) {
  EXPECT_EQ(ParamsFromJson(R"({"step":"x"})").status().message(), "step: expected a number");
  EXPECT_EQ(ParamsFromJson(R"({"var_ic":[1,2]})").status().message(),
            "var_ic: expected an array of 3 numbers");
  EXPECT_EQ(ParamsFromJson(R"({"mask":"000"})").status().message(),
            "mask: mask \"000\" selects no dimension");
  EXPECT_EQ(ParamsFromJson(R"({"skip":-1})").status().message(),
            "skip: must be between 0 and 10000000");
  EXPECT_EQ(ParamsFromJson(R"({"skip":18446744073709551615})").status().message(),
            "skip: must be between 0 and 10000000");
  EXPECT_FALSE(ParamsFromJson(R"({"skip":10000001})").ok());
  EXPECT_TRUE(ParamsFromJson(R"({"skip":10000000})").ok());
  EXPECT_FALSE(ParamsFromJson(R"({"preset":"wild"})").ok());
  EXPECT_EQ(ParamsFromJson("[]").status().message(), "parameters: expected an object");
  EXPECT_EQ(ParamsFromJson("{").status().message(), "parameters: malformed JSON");
  auto sys = ParamsFromJson(R"({"system":"rossler","routes":[1,2]})");  // other fields ignored
  ASSERT_TRUE(sys.ok());
  EXPECT_EQ(sys->system.params[2], 5.7);
  auto tri = ParamsFromJson(R"({"var_ic":"-15, -12, 52"})");
  ASSERT_TRUE(tri.ok());
  EXPECT_EQ(tri->var_ic[0], -15);
}

TEST(VaryParamsCodec, SiteColumnsRoundTripAndAreValidated) {
  std::map<std::string, std::string> c = {{"nna", "B"},          {"dim_mask", "011"},
                                          {"max_repeat", "1"},   {"transient", "100"},
                                          {"rx", "-13.0"},       {"ry", "-12"},
                                          {"rz", "52"},          {"vx", "-16.5"},
                                          {"vy", ""},            {"vz", "52"}};
  SourceLocation at{"routes.csv", 7, 0};
  std::vector<std::string> notes;
  auto p = ParamsFromSiteColumns(c, at, &notes);
  ASSERT_TRUE(p.ok()) << p.status().message();
  EXPECT_EQ(p->integrator, IntegratorKind::kRkf45);
  EXPECT_EQ(p->mapping.mask, kMaskY | kMaskZ);
  EXPECT_EQ(p->skip, 100);
  EXPECT_EQ(p->var_ic, (State{-16.5, -12, 52}));  // vy empty: the default
  auto back = ParamsFromSiteColumns(SiteColumnsFromParams(*p), at, nullptr);
  ASSERT_TRUE(back.ok());
  EXPECT_EQ(ParamsToJson(*back), ParamsToJson(*p));
  c["dim_mask"] = "000";
  ASSERT_TRUE(ParamsFromSiteColumns(c, at, &notes).ok());
  EXPECT_EQ(notes.size(), 1u);
  c["dim_mask"] = "101";
  for (const char* bad : {"nan", "inf", "1e400", "x"}) {
    c["rx"] = bad;
    auto r = ParamsFromSiteColumns(c, at, nullptr);
    ASSERT_FALSE(r.ok()) << bad;
    EXPECT_EQ(r.status().message().rfind("routes.csv:7: rx: not a finite number", 0), 0u);
  }
  c["rx"] = "-13";
  c["transient"] = "99999999";
  EXPECT_FALSE(ParamsFromSiteColumns(c, at, nullptr).ok());
}

}  // namespace
}  // namespace sb::chaos
