// The setter's annotations of a route plan (issues 13, 15, 16): the codec of
// the setter's parameters, and what every renderer shows of the search,
// warnings, profile, grades and smoothing costs.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "chaos/tokens.h"
#include "plan/plan.h"

namespace sb::plan {
namespace {

using nlohmann::json;

RoutePlan Annotated() {
  auto a = ParseCrdl("name: Alpha\n---\nR jug\nL crimp (crux)\nR crimp\nL sloper\nR pinch\n", "a");
  auto b = ParseCrdl("---\nL pocket\nR edge\nL gaston\nR undercling\n", "b");
  EXPECT_TRUE(a.ok() && b.ok());
  auto v = chaos::Vary({{"Alpha", *a}, {"b", *b}}, *chaos::VaryParams::Preset("more"));
  EXPECT_TRUE(v.ok()) << v.status().message();
  RoutePlan p{*v, {}, ""};
  chaos::MoveFacts facts;
  facts.crux = chaos::CruxFlags(v->inputs);
  for (int i = 0; i < 9; ++i) facts.difficulty.push_back(0.1 * (i % 5) + 0.05);
  p.warnings = Warn(p.variation, facts);
  p.profile = Profile(p.variation, facts);
  SearchReport r;
  r.requested_ic = {-16, -12, 52};
  r.used_ic = {-15.9, -12, 52};
  r.offset = {1, 0, 0};
  r.distance = 0.1;
  r.evaluated = 2;
  r.constraints.push_back({chaos::Constraint::kKeepStart, true, "starts with \"jug\""});
  p.search = r;
  p.setter.constraints.keep_start = true;
  PlanGrades g;
  g.inputs = {"5.10a", ""};
  g.discipline = "roped";
  g.scale = "yds";
  g.estimate = "5.10";
  g.low = "5.9";
  g.high = "5.11";
  g.level = 0.8;
  p.grades = g;
  return p;
}

TEST(PlanAnnotations, DefaultParametersAreThePapersExactly) {
  chaos::VaryParams p = *chaos::VaryParams::Preset("more");
  EXPECT_EQ(ParametersJson(p, SetterOptions{}), chaos::ParamsToJson(p));
  auto o = SetterOptionsFromJson(chaos::ParamsToJson(p));
  ASSERT_TRUE(o.ok());
  EXPECT_FALSE(o->Search());
  EXPECT_FALSE(o->match_grammar);
  EXPECT_EQ(o->smooth_method, SmoothingMethod::kVomm);
}

TEST(PlanAnnotations, SetterFieldsRoundTripThroughTheOneCodec) {
  SetterOptions s;
  s.constraints.keep_start = true;
  s.constraints.keep_finish = true;
  s.constraints.crux_window = chaos::CruxWindow{0.25, 0.75};
  s.constraints.alternate_hands = true;
  s.constraints.target_effect = 12;
  s.constraints.target_change = 3.5;
  s.match_grammar = true;
  s.grid.radius = 40;
  s.grid.plane = chaos::SearchPlane::kCube;
  s.smooth_method = SmoothingMethod::kAStar;
  s.drop_inner_finishes = true;
  s.drop_inner_starts = true;
  std::string text = ParametersJson(chaos::VaryParams{}, s);
  json j = json::parse(text);
  EXPECT_EQ(j["keep_start"], true);
  EXPECT_EQ(j["drop_inner_finishes"], true);
  EXPECT_EQ(j["drop_inner_starts"], true);
  EXPECT_EQ(j["crux_window"], json({0.25, 0.75}));
  EXPECT_EQ(j["match"], "grammar");
  EXPECT_EQ(j["smooth_method"], "astar");
  EXPECT_EQ(j["search_plane"], "cube");
  auto back = SetterOptionsFromJson(text);
  ASSERT_TRUE(back.ok()) << back.status().message();
  EXPECT_EQ(ParametersJson(chaos::VaryParams{}, *back), text);
  EXPECT_TRUE(ReproduceOptions(chaos::VaryParams{}, *back).find(
                  "--keep-start --keep-finish --crux-window 0.25,0.75 --alternate-hands "
                  "--drop-inner-finishes --drop-inner-starts --match grammar --target-effect 12 --target-change 3.5") != std::string::npos)
      << ReproduceOptions(chaos::VaryParams{}, *back);
}

TEST(PlanAnnotations, BadSetterFieldsAreNamed) {
  struct Case {
    const char* json;
    const char* field;
  };
  for (const Case& c : {Case{R"({"keep_start": 1})", "keep_start:"},
                        Case{R"({"crux_window": [0.9, 0.1]})", "crux_window:"},
                        Case{R"({"crux_window": [0.1]})", "crux_window:"},
                        Case{R"({"match": "both"})", "match:"},
                        Case{R"({"target_effect": -1})", "target_effect:"},
                        Case{R"({"search_radius": 1.5})", "search_radius:"},
                        Case{R"({"search_plane": "xx"})", "search_plane:"},
                        Case{R"({"smooth_method": "spline"})", "smooth_method:"},
                        Case{"[1]", "parameters:"}}) {
    auto r = SetterOptionsFromJson(c.json);
    ASSERT_FALSE(r.ok()) << c.json;
    EXPECT_EQ(r.status().code(), Status::Code::kInvalidInput);
    EXPECT_EQ(r.status().message().rfind(c.field, 0), 0u) << r.status().message();
  }
}

TEST(PlanAnnotations, JsonCarriesEveryAnnotation) {
  RoutePlan p = Annotated();
  json j = json::parse(RenderJson(p));
  EXPECT_EQ(j["kind"], "routes");
  EXPECT_EQ(j["parameters"]["keep_start"], true);
  EXPECT_EQ(j["inputs"][0]["grade"], "5.10a");
  EXPECT_TRUE(j["inputs"][1]["grade"].is_null());
  EXPECT_EQ(j["grades"]["estimate"], "5.10");
  EXPECT_EQ(j["grades"]["level"], 0.8);
  EXPECT_EQ(j["search"]["evaluated"], 2);
  EXPECT_EQ(j["search"]["constraints"][0]["name"], "keep-start");
  EXPECT_TRUE(j["search"]["constraints"][0]["held"].get<bool>());
  EXPECT_TRUE(j["warnings"].is_array());
  EXPECT_EQ(j["summary"]["moves"], 9);
  EXPECT_TRUE(j["summary"].contains("text_changed"));
  EXPECT_TRUE(j["profile"]["estimated"].get<bool>());
  EXPECT_TRUE(j["profile"]["hardest_stretch"].is_object());
  ASSERT_EQ(j["moves"].size(), 9u);
  int cruxes = 0;
  for (size_t i = 0; i < 9; ++i) {
    EXPECT_TRUE(j["moves"][i]["difficulty"].is_number());
    if (j["moves"][i]["crux"].get<bool>()) ++cruxes;
  }
  EXPECT_EQ(static_cast<size_t>(cruxes), j["profile"]["cruxes"].size());
  // Byte-identical twice.
  EXPECT_EQ(RenderJson(p), RenderJson(Annotated()));
}

TEST(PlanAnnotations, APlainPlanHasNullAnnotations) {
  RoutePlan p = Annotated();
  RoutePlan plain{p.variation, {}, ""};
  json j = json::parse(RenderJson(plain));
  for (const char* k : {"search", "warnings", "summary", "profile", "grades"}) {
    EXPECT_TRUE(j[k].is_null()) << k;
  }
  EXPECT_TRUE(j["moves"][0]["difficulty"].is_null());
}

TEST(PlanAnnotations, TextAndMarkdownShowTheAnnotations) {
  RoutePlan p = Annotated();
  for (const std::string& out : {RenderText(p), RenderMarkdown(p)}) {
    EXPECT_NE(out.find("5.10"), std::string::npos) << out;
    EXPECT_NE(out.find("keep-start"), std::string::npos) << out;
    EXPECT_NE(out.find("held"), std::string::npos) << out;
    EXPECT_NE(out.find("changed"), std::string::npos) << out;
    EXPECT_NE(out.find("--keep-start"), std::string::npos) << out;
    EXPECT_NE(out.find("hardest stretch"), std::string::npos) << out;
  }
}

TEST(PlanAnnotations, PlanNotesListTheAnnotationsForPages) {
  RoutePlan p = Annotated();
  std::vector<std::string> notes = PlanNotes(p);
  ASSERT_FALSE(notes.empty());
  std::string all;
  for (const std::string& n : notes) all += n + "\n";
  EXPECT_NE(all.find("5.10"), std::string::npos) << all;
  EXPECT_NE(all.find("keep-start: held"), std::string::npos) << all;
  EXPECT_NE(all.find("Summary: "), std::string::npos) << all;
  EXPECT_NE(all.find("Hardest stretch: "), std::string::npos) << all;
  EXPECT_TRUE(PlanNotes(RoutePlan{p.variation, {}, ""}).empty());
}

TEST(PlanAnnotations, SuggestionCostsReadRightForBothMethods) {
  Suggestion v;
  v.bits_before = 10;
  v.bits_after = 6.5;
  EXPECT_EQ(v.CostNote(), "saves 3.5 bits");
  Suggestion a;
  a.method = SmoothingMethod::kAStar;
  a.bits_before = 12.125;
  a.bits_after = 9.7;
  EXPECT_EQ(a.CostNote(), "path 9.7 bits, direct 12.13 bits");
  a.direct_seen = false;
  a.bits_before = a.bits_after;
  EXPECT_EQ(a.CostNote(), "path 9.7 bits; the direct transition never occurs in the graph's data");
  RoutePlan p = Annotated();
  p.smoothing_model = "default";
  p.setter.smooth_method = SmoothingMethod::kAStar;
  a.after = 3;
  a.moves.push_back({"L", "L|jug", "L jug"});
  p.smoothing.push_back(a);
  std::string text = RenderText(p);
  EXPECT_EQ(text.find("saves 0 bits"), std::string::npos) << text;
  EXPECT_NE(text.find("never occurs"), std::string::npos) << text;
  json j = json::parse(RenderJson(p));
  EXPECT_EQ(j["smoothing"]["suggestions"][0]["method"], "astar");
  EXPECT_EQ(j["smoothing"]["suggestions"][0]["direct_seen"], false);
  // Stored plans give their suggestions back with the method.
  RoutePlan back{p.variation, {}, ""};
  ASSERT_TRUE(SmoothingFromJson(RenderJson(p), &back));
  ASSERT_EQ(back.smoothing.size(), 1u);
  EXPECT_EQ(back.smoothing[0].method, SmoothingMethod::kAStar);
  EXPECT_FALSE(back.smoothing[0].direct_seen);
}

TEST(PlanAnnotations, TokenPlansNamePositions) {
  auto a = chaos::ParseTokenSequence("E4|q\nD4|q\nC4|h\nD4|q\nE4|q\n", "ode.txt", "ode");
  auto b = chaos::ParseTokenSequence("C4|q\nG4|q\nA4|q\nG4|h\n", "tw.txt", "tw");
  ASSERT_TRUE(a.ok() && b.ok());
  auto v = chaos::Vary({*a, *b}, *chaos::VaryParams::Preset("more"));
  ASSERT_TRUE(v.ok()) << v.status().message();
  RoutePlan p{*v, {}, ""};
  ASSERT_TRUE(p.tokens());
  json j = json::parse(RenderJson(p));
  EXPECT_EQ(j["kind"], "tokens");
  EXPECT_FALSE(j.contains("moves"));
  ASSERT_EQ(j["positions"].size(), 9u);
  EXPECT_TRUE(j["positions"][0].contains("token"));
  EXPECT_EQ(j["inputs"][1]["positions"], 4);
  std::string text = RenderText(p);
  EXPECT_NE(text.find("position"), std::string::npos) << text;
  EXPECT_EQ(text.find(" hand "), std::string::npos) << text;
}

}  // namespace
}  // namespace sb::plan
