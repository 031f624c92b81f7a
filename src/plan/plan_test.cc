#include "plan/plan.h"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

namespace sb::plan {
namespace {

using nlohmann::json;

json ToJson(const RoutePlan& plan) { return json::parse(RenderJson(plan)); }

RoutePlan MakePlan(const chaos::VaryParams& p) {
  auto a = ParseCrdl("name: Alpha\n---\nR jug\nL match\nR crimp | rail\nL sloper\nR pinch\n", "a");
  auto b = ParseCrdl("---\nL pocket\nR edge\nL gaston\nR undercling\n", "b");
  EXPECT_TRUE(a.ok() && b.ok());
  auto v = chaos::Vary({{"Alpha", *a}, {"b", *b}}, p);
  EXPECT_TRUE(v.ok()) << v.status().message();
  return {*v, {}, ""};
}

TEST(Plan, JsonHasTheDocumentedShape) {
  RoutePlan plan = MakePlan(*chaos::VaryParams::Preset("more"));
  auto j = ToJson(plan);
  ASSERT_TRUE(j.contains("parameters"));
  EXPECT_EQ(j["parameters"]["preset"], "more");
  EXPECT_EQ(j["parameters"]["skip"], 100);
  EXPECT_EQ(j["parameters"]["mask"], "101");
  EXPECT_EQ(j["parameters"]["var_ic"][1], -13.5);
  ASSERT_EQ(j["inputs"].size(), 2u);
  EXPECT_EQ(j["inputs"][0]["name"], "Alpha");
  EXPECT_EQ(j["inputs"][1]["moves"], 4);
  ASSERT_EQ(j["moves"].size(), 9u);
  ASSERT_EQ(j["reference"].size(), 9u);
  ASSERT_EQ(j["variation"][0].size(), 3u);
  for (size_t i = 0; i < 9; ++i) {
    const auto& m = j["moves"][i];
    const auto& src = m["source"];
    int flat = src["route"].get<int>() == 0 ? src["move"].get<int>() : 5 + src["move"].get<int>();
    EXPECT_EQ(m["changed"].get<bool>(), flat != int(i));
    EXPECT_EQ(m["crux"], false);
    EXPECT_TRUE(m["hand"] == "L" || m["hand"] == "R");
  }
  EXPECT_FALSE(j.contains("smoothing"));
}

TEST(Plan, TextPlanShowsChangesProvenanceAndEveryParameter) {
  RoutePlan plan = MakePlan(*chaos::VaryParams::Preset("more"));
  std::string text = RenderText(plan);
  EXPECT_NE(text.find("CHAOTIC ROUTE PLAN"), std::string::npos);
  EXPECT_NE(text.find("Alpha #"), std::string::npos);
  EXPECT_NE(text.find("(match?)"), std::string::npos);
  EXPECT_NE(text.find("--var-ic=-16,-13.5,52"), std::string::npos);
  EXPECT_NE(text.find("skip 100"), std::string::npos);
  EXPECT_NE(text.find("integrator rk4"), std::string::npos);
  // No copy of the inputs: the header line of the inputs is not printed.
  EXPECT_EQ(text.find("name: Alpha"), std::string::npos);
  chaos::VaryParams same;
  same.var_ic = same.ref_ic;  // the variation is the input: every move appears
  std::string md = RenderMarkdown(MakePlan(same));
  EXPECT_NE(md.find("crimp \\| rail"), std::string::npos);  // escaped table cell
}

TEST(Plan, BlanksAreShownForTheSetterToFill) {
  chaos::VaryParams p;
  p.mapping.kind = chaos::MappingKind::kDabby;
  p.var_ic = {10, 10, 30};
  RoutePlan plan = MakePlan(p);
  bool blank = false;
  for (const auto& m : plan.variation.moves) blank |= !m.source.has_value();
  if (!blank) GTEST_SKIP() << "no blank with these parameters";
  EXPECT_NE(RenderText(plan).find("(fill in)"), std::string::npos);
  EXPECT_NE(RenderJson(plan).find("\"source\": null"), std::string::npos);
}

TEST(Plan, RenderingIsDeterministic) {
  RoutePlan a = MakePlan(chaos::VaryParams()), b = MakePlan(chaos::VaryParams());
  for (Format f : {Format::kText, Format::kMarkdown, Format::kJson, Format::kSvg}) {
    EXPECT_EQ(Render(a, f), Render(b, f));
  }
  std::string svg = RenderTrajectorySvg(a);
  EXPECT_EQ(svg.rfind("<?xml", 0), 0u);
  EXPECT_NE(svg.find("<svg"), std::string::npos);
  EXPECT_NE(svg.find("</svg>"), std::string::npos);
}

TEST(Plan, SmoothingSuggestionsAppearInEveryFormat) {
  RoutePlan plan = MakePlan(chaos::VaryParams());
  plan.smoothing_model = "test.model";
  plan.smoothing.push_back({2, {{"L", "jug", "good jug"}}, 10.5, 7.25});
  EXPECT_NE(RenderText(plan).find("insert: L good jug"), std::string::npos);
  EXPECT_NE(RenderText(plan).find("saves 3.25 bits"), std::string::npos);
  EXPECT_NE(RenderText(plan).find("saves 3.25 bits"), std::string::npos);
  auto j = ToJson(plan);
  EXPECT_EQ(j["smoothing"]["suggestions"][0]["after"], 2);
  EXPECT_EQ(j["smoothing"]["suggestions"][0]["bits_saved"], 3.25);
  EXPECT_NE(RenderMarkdown(plan).find("insert: good jug"), std::string::npos);
}

TEST(Plan, RenderedJsonIsValidWhateverTheText) {
  auto a = ParseCrdl("---\nR say \"hi\" \\ back\tslash\nL match\nR \u00e9 crimp\n", "q");
  ASSERT_TRUE(a.ok()) << a.status().message();
  auto v = chaos::Vary({{"quote \"name\"", *a}}, *chaos::VaryParams::Preset("more"));
  ASSERT_TRUE(v.ok());
  RoutePlan plan{*v, {}, ""};
  json j = ToJson(plan);
  EXPECT_EQ(j["inputs"][0]["name"], "quote \"name\"");
  EXPECT_EQ(json::parse(RenderMovesJson(plan)), j["moves"]);
  // Text that is not UTF-8 (a model path, a name from an old database) is
  // replaced, never an exception.
  plan.variation.inputs[0].name = "bad \xFF name";
  plan.variation.moves[0].text = "\xC0\xAF";
  plan.smoothing_model = "/models/\xFE.sbm";
  plan.smoothing.push_back({0, {{"L", "jug", "jug"}}, 3, 2});
  std::string text;
  ASSERT_NO_THROW(text = RenderJson(plan));
  json k = json::parse(text);
  EXPECT_EQ(k["inputs"][0]["name"], "bad \xEF\xBF\xBD name");
  EXPECT_EQ(k["smoothing"]["suggestions"][0]["bits_saved"], 1);
}

TEST(Plan, CruxesAreCarriedAndMarked) {
  auto a = ParseCrdl("---\nR jug\nL small crimp (crux)\nR sloper\n", "c");
  ASSERT_TRUE(a.ok());
  chaos::VaryParams same;
  same.var_ic = same.ref_ic;  // the variation is the input
  auto v = chaos::Vary({{"c", *a}}, same);
  ASSERT_TRUE(v.ok());
  ASSERT_TRUE(v->moves[1].crux);
  RoutePlan plan{*v, {}, ""};
  json j = ToJson(plan);
  EXPECT_EQ(j["moves"][0]["crux"], false);
  EXPECT_EQ(j["moves"][1]["crux"], true);
  EXPECT_EQ(j["moves"][1]["text"], "small crimp");
  EXPECT_NE(RenderText(plan).find("small crimp (crux)"), std::string::npos);
  EXPECT_NE(RenderMarkdown(plan).find("small crimp (crux)"), std::string::npos);
  EXPECT_EQ(RenderText(plan).find("jug (crux)"), std::string::npos);
}

TEST(Plan, SmoothingSurvivesAJsonRoundTrip) {
  RoutePlan plan = MakePlan(chaos::VaryParams());
  plan.smoothing_model = "gym.sbm";
  plan.smoothing.push_back({1, {{"R", "jug", "jug"}, {"L", "crimp", "crimp"}}, 12.5, 9.0});
  RoutePlan back = MakePlan(chaos::VaryParams());
  ASSERT_TRUE(SmoothingFromJson(RenderJson(plan), &back));
  EXPECT_EQ(RenderText(back), RenderText(plan));
  EXPECT_EQ(RenderJson(back), RenderJson(plan));
  RoutePlan untouched = MakePlan(chaos::VaryParams());
  EXPECT_FALSE(SmoothingFromJson(RenderJson(untouched), &untouched));  // no "smoothing" member
  EXPECT_FALSE(SmoothingFromJson(R"({"smoothing": {"model": 3}})", &untouched));
  EXPECT_FALSE(SmoothingFromJson("not json", &untouched));
  EXPECT_TRUE(untouched.smoothing_model.empty());
}

TEST(Plan, FormatParsing) {
  EXPECT_EQ(*ParseFormat("md"), Format::kMarkdown);
  EXPECT_FALSE(ParseFormat("pdf").ok());
}

}  // namespace
}  // namespace sb::plan
