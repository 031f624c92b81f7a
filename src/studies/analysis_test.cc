// The whole survey analysis against an independent NumPy/SciPy
// re-implementation (scipy_reference.py) on simulated surveys with missing
// answers, ties, small samples and degenerate cases; plus the definitions
// that are easiest to check by hand.
#include "studies/analysis.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <random>

#include "studies/boxplot.h"
#include "studies/simulate.h"
#include "studies/studies_test_util.h"

namespace sb::studies {
namespace {

using testing::Row;

using nlohmann::json;

// Compares every field of the reference `ref` with `mine` (numbers to 1e-9;
// a null in mine, which is how JSON prints NaN and inf, matches a reference
// null, "inf" or "-inf").
void ExpectMatches(const json& mine, const json& ref, const std::string& path) {
  if (ref.is_object()) {
    ASSERT_TRUE(mine.is_object()) << path;
    for (auto it = ref.begin(); it != ref.end(); ++it) {
      if (it.key().rfind("friedman_", 0) == 0) continue;  // checked below
      ASSERT_TRUE(mine.contains(it.key())) << path << "." << it.key();
      ExpectMatches(mine[it.key()], it.value(), path + "." + it.key());
    }
    if (ref.contains("friedman_chi2") && !ref["friedman_chi2"].is_null()) {
      ExpectMatches(mine["chi2"], ref["friedman_chi2"], path + ".chi2 (Friedman)");
      ExpectMatches(mine["p"], ref["friedman_p"], path + ".p (Friedman)");
    }
  } else if (ref.is_array()) {
    ASSERT_TRUE(mine.is_array()) << path;
    ASSERT_EQ(mine.size(), ref.size()) << path;
    for (size_t i = 0; i < ref.size(); ++i) {
      ExpectMatches(mine[i], ref[i], path + "[" + std::to_string(i) + "]");
    }
  } else if (ref.is_number_float() || ref.is_null() || (ref.is_string() && mine.is_null())) {
    if (mine.is_null()) {
      EXPECT_TRUE(ref.is_null() || ref == "inf" || ref == "-inf")
          << path << ": got null, want " << ref;
    } else {
      ASSERT_TRUE(mine.is_number()) << path;
      EXPECT_TRUE(testing::Close(mine.get<double>(), ref)) << path;
    }
  } else if (ref.is_number()) {
    ASSERT_TRUE(mine.is_number()) << path;
    EXPECT_TRUE(testing::Close(mine.get<double>(), ref)) << path;
  } else {
    EXPECT_EQ(mine, ref) << path;
  }
}

struct Survey {
  std::string label;
  Instrument instrument;
  ResponseTable table;
  AnalysisOptions options;
};

Instrument SevenPoint() {
  Instrument in{"seven-point test", 1, 7, {}};
  in.items = {{"flow", "Has good flow", false},
              {"awk", "Climbs awkwardly", true},
              {"again", "Would climb again", false}};
  return in;
}

// A survey where some participants skip routes, leave ranks empty or tie
// them, and answer few items: every code path that drops data.
ResponseTable Ragged(const Instrument& in, uint64_t seed) {
  SimulationParams p;
  p.routes = 5;
  p.participants = 9;
  p.seed = seed;
  p.missing = 0.25;
  ResponseTable t = Simulate(in, p).value();
  std::mt19937_64 g(seed);
  ResponseTable out = t;
  out.rows.clear();
  for (Response r : t.rows) {
    if (g() % 7 == 0) continue;  // participant skipped this route
    if (g() % 5 == 0)
      r.rank.reset();  // no rank given
    else if (g() % 6 == 0)
      r.rank = 1;  // tied ranks
    if (g() % 9 == 0) r.order.reset();
    out.rows.push_back(r);
  }
  return out;
}

std::vector<Survey> Surveys() {
  std::vector<Survey> s;
  SimulationParams brc;
  brc.seed = 11;
  brc.missing = 0.05;
  ResponseTable t = Simulate(BrcInstrument(), brc).value();
  s.push_back({"brc", BrcInstrument(), t, {}});
  s.push_back({"brc censor", BrcInstrument(), t, {{}, true}});
  s.push_back({"brc drop", BrcInstrument(), t, {{"q1", "q9", "q10", "q11"}, false}});
  SimulationParams pilot;
  pilot.routes = 3;
  pilot.participants = 6;
  pilot.seed = 5;
  pilot.missing = 0.1;
  pilot.rank = false;
  s.push_back({"pilot", PilotInstrument(), Simulate(PilotInstrument(), pilot).value(), {{}, true}});
  s.push_back({"ragged", SevenPoint(), Ragged(SevenPoint(), 3), {}});
  s.push_back({"ragged censor", SevenPoint(), Ragged(SevenPoint(), 4), {{}, true}});
  SimulationParams tiny;
  tiny.routes = 2;
  tiny.participants = 2;
  tiny.seed = 2;
  tiny.missing = 0;
  Instrument two{"two items", 0, 1, {{"a", "A", false}, {"b", "B", true}}};
  s.push_back({"tiny", two, Simulate(two, tiny).value(), {}});
  // A wide scale: summed scales without ties, so the exact Wilcoxon p-value.
  Instrument wide{"wide", 0, 100, {{"a", "A", false}, {"b", "B", false}, {"c", "C", true}}};
  SimulationParams w;
  w.routes = 3;
  w.participants = 7;
  w.seed = 8;
  w.missing = 0;
  s.push_back({"wide", wide, Simulate(wide, w).value(), {}});
  return s;
}

TEST(AnalysisVsScipy, SimulatedSurveysWithTiesMissingAnswersAndSmallSamples) {
  if (std::string why = testing::ScipyUnavailable(); !why.empty()) GTEST_SKIP() << why;
  const auto dir = testing::TestDir("analysis");
  json in;
  in["analyses"] = json::array();
  std::vector<json> mine;
  const std::vector<Survey> surveys = Surveys();
  for (size_t i = 0; i < surveys.size(); ++i) {
    const Survey& s = surveys[i];
    const std::string csv = (dir / ("survey" + std::to_string(i) + ".csv")).string();
    std::ofstream(csv) << FormatResponsesCsv(s.table, s.instrument);
    // The analysis runs on the file as read back, like the CLI.
    Result<ResponseTable> parsed = ReadResponsesFile(csv, s.instrument);
    ASSERT_TRUE(parsed.ok()) << parsed.status().message();
    Result<Analysis> a = Analyze(s.instrument, *parsed, s.options);
    ASSERT_TRUE(a.ok()) << s.label << ": " << a.status().message();
    mine.push_back(json::parse(AnalysisToJson(*a)));
    in["analyses"].push_back({{"instrument", json::parse(InstrumentToJson(s.instrument))},
                              {"csv", csv},
                              {"drop", s.options.drop},
                              {"censor", s.options.censor}});
  }
  json out = testing::RunScipy(in, dir);
  ASSERT_FALSE(out.is_null());
  ASSERT_EQ(out["analyses"].size(), surveys.size());
  for (size_t i = 0; i < surveys.size(); ++i) {
    SCOPED_TRACE(surveys[i].label);
    ExpectMatches(mine[i], out["analyses"][i], surveys[i].label);
  }
  // The data really exercise the branches the comparison is meant to cover.
  EXPECT_GT(mine[0]["complete_responses"].get<int>(), 0);
  EXPECT_LT(mine[0]["complete_responses"].get<int>(), mine[0]["rows"].get<int>());
  EXPECT_FALSE(mine[1]["dropped"].empty());
  bool exact = false, asymptotic = false;
  for (const json& m : mine) {
    for (const json& p : m["pairs"]) {
      (p["wilcoxon_method"] == "exact" ? exact : asymptotic) = true;
    }
  }
  EXPECT_TRUE(exact && asymptotic);
}

ResponseTable Table(const std::vector<Response>& rows, bool rank = false) {
  ResponseTable t;
  t.rows = rows;
  t.has_rank = rank;
  return t;
}

TEST(Analysis, NegativeItemsAreInvertedBeforeEverything) {
  Instrument in{"keying", -2, 2, {{"pos", "good", false}, {"neg", "bad", true}}};
  // Agreeing with the negative item (2) is a negative attitude: keyed -2.
  ResponseTable t =
      Table({Row("a", "1", {2, 2}), Row("b", "1", {1, -1}), Row("c", "1", {-2, std::nullopt})});
  Analysis a = Analyze(in, t, {}).value();
  EXPECT_DOUBLE_EQ(a.items[0].mean, (2 + 1 - 2) / 3.0);
  EXPECT_DOUBLE_EQ(a.items[1].mean, (-2 + 1) / 2.0);
  ASSERT_EQ(a.routes.size(), 1u);
  // Sums 2 + -2 = 0, 1 + 1 = 2, -2 (one answer); % positive 50, 100, 0.
  EXPECT_DOUBLE_EQ(a.routes[0].median_sum, 0);
  EXPECT_DOUBLE_EQ(a.routes[0].mean_percent_positive, 50);
  EXPECT_EQ(a.complete, 2);
}

TEST(Analysis, PercentPositiveCountsAnswersAboveTheMidpoint) {
  Instrument in{"even", 1, 4, {{"x", "x", false}, {"y", "y", false}}};  // midpoint 2.5
  ResponseTable t =
      Table({Row("a", "r", {3, 2}), Row("b", "r", {4, 3}), Row("c", "r", {1, std::nullopt})});
  Analysis a = Analyze(in, t, {}).value();
  EXPECT_DOUBLE_EQ(a.routes[0].mean_percent_positive, (50 + 100 + 0) / 3.0);
}

TEST(Analysis, CensoringRuleIteratesWhileAlphaRises) {
  SimulationParams p;
  p.seed = 11;
  ResponseTable t = Simulate(BrcInstrument(), p).value();
  Analysis none = Analyze(BrcInstrument(), t, {}).value();
  Analysis rule = Analyze(BrcInstrument(), t, {{}, true}).value();
  EXPECT_EQ(rule.censoring, "rule");
  ASSERT_FALSE(rule.dropped.empty());
  EXPECT_GT(rule.alpha_censored, none.alpha);
  // No further single deletion raises alpha.
  for (const ItemStats& s : rule.items) {
    if (s.dropped) continue;
    std::vector<std::string> drop = rule.dropped;
    drop.push_back(s.id);
    Analysis more = Analyze(BrcInstrument(), t, {drop, false}).value();
    EXPECT_LE(more.alpha_censored, rule.alpha_censored) << s.id;
  }
  // The owner dropping the same items gets the same alpha.
  Analysis owner = Analyze(BrcInstrument(), t, {rule.dropped, false}).value();
  EXPECT_EQ(owner.alpha_censored, rule.alpha_censored);
  EXPECT_EQ(owner.censoring, "owner");
}

TEST(Analysis, DropErrors) {
  ResponseTable t = Table({Row("a", "1", {1, 2, 3, 4, 5})});
  auto msg = [&](AnalysisOptions o) { return Analyze(PilotInstrument(), t, o).status().message(); };
  EXPECT_EQ(msg({{"q9"}, false}), "drop: \"q9\" is not an item of the instrument");
  EXPECT_EQ(msg({{"q1", "q1"}, false}), "drop: \"q1\" given twice");
  EXPECT_EQ(msg({{"q1", "q2", "q3", "q4", "q5"}, false}),
            "drop: every item dropped; keep at least one");
  EXPECT_EQ(msg({{"q1"}, true}), "drop: choose items to drop or the censoring rule, not both");
  EXPECT_EQ(Analyze(PilotInstrument(), Table({}), {}).status().message(),
            "responses: no response rows");
  EXPECT_EQ(Analyze(PilotInstrument(), Table({Row("a", "1", {1, 2})}), {}).status().message(),
            "responses: participant \"a\" route \"1\": expected 5 answers, got 2");
}

TEST(Analysis, KendallWUsesOnlyParticipantsWhoRankedEveryRoute) {
  Instrument in{"one", 1, 5, {{"x", "x", false}}};
  std::vector<Response> rows;
  auto add = [&](const char* p, const char* r, std::optional<int> rank) {
    Response x = Row(p, r, {3});
    x.rank = rank;
    rows.push_back(x);
  };
  add("a", "1", 1), add("a", "2", 2), add("a", "3", 3);
  add("b", "1", 1), add("b", "2", 2), add("b", "3", 3);
  add("c", "1", 3), add("c", "2", std::nullopt), add("c", "3", 1);  // incomplete ranking
  add("d", "1", 2);                                                 // one route only
  Analysis a = Analyze(in, Table(rows, true), {}).value();
  EXPECT_EQ(a.kendall_w.raters, 2);
  EXPECT_DOUBLE_EQ(a.kendall_w.w, 1.0);  // a and b agree perfectly
  // Pair (1, 3) is ranked by a, b and c.
  ASSERT_EQ(a.pairs.size(), 3u);
  EXPECT_EQ(a.pairs[1].a, "1");
  EXPECT_EQ(a.pairs[1].b, "3");
  EXPECT_EQ(a.pairs[1].kendall_w.raters, 3);
  EXPECT_EQ(a.routes[0].median_rank, 1.5);  // ranks 1, 1, 3, 2
}

TEST(Analysis, JsonAndBoxPlotAreDeterministicAndComplete) {
  SimulationParams p;
  p.seed = 3;
  ResponseTable t = Simulate(BrcInstrument(), p).value();
  Analysis a1 = Analyze(BrcInstrument(), t, {{}, true}).value();
  Analysis a2 = Analyze(BrcInstrument(), t, {{}, true}).value();
  const std::string j1 = AnalysisToJson(a1);
  EXPECT_EQ(j1, AnalysisToJson(a2));
  EXPECT_EQ(BoxPlotSvg(a1), BoxPlotSvg(a2));
  json j = json::parse(j1);
  for (const char* k :
       {"alpha", "alpha_censored", "items", "routes", "pairs", "kendall_w", "correlations"}) {
    EXPECT_TRUE(j.contains(k)) << k;
  }
  for (const char* k : {"id", "alpha_if_deleted", "tau_item_total"}) {
    EXPECT_TRUE(j["items"][0].contains(k)) << k;
  }
  for (const char* k : {"route", "n", "median_sum", "mean_percent_positive"}) {
    EXPECT_TRUE(j["routes"][0].contains(k)) << k;
  }
  for (const char* k : {"a", "b", "wilcoxon_p", "welch_t", "welch_p"}) {
    EXPECT_TRUE(j["pairs"][0].contains(k)) << k;
  }
  EXPECT_TRUE(j["kendall_w"].contains("w") && j["kendall_w"].contains("p"));
  ASSERT_EQ(j["correlations"].size(), 3u);
  EXPECT_EQ(j["correlations"][0]["x"], "order");
  EXPECT_EQ(j["correlations"][1]["x"], "ability");
  for (const char* k : {"x", "y", "tau", "tau_p", "r", "r_p"}) {
    EXPECT_TRUE(j["correlations"][0].contains(k)) << k;
  }
  EXPECT_EQ(j["routes"].size(), 4u);
  EXPECT_EQ(j["pairs"].size(), 6u);
  const std::string svg = BoxPlotSvg(a1);
  EXPECT_EQ(svg.rfind("<?xml", 0), 0u);
  size_t boxes = 0;
  for (size_t pos = 0; (pos = svg.find("fill=\"#9ecae1\"", pos)) != std::string::npos; ++pos) {
    ++boxes;
  }
  EXPECT_EQ(boxes, 4u);
  EXPECT_NE(svg.find(">n = 44<"), std::string::npos);
  EXPECT_NE(AnalysisToText(a1).find("Kendall's W over 44 participants"), std::string::npos);
}

TEST(Analysis, BoxPlotDrawsOutliersBeyondTheWhiskers) {
  Instrument in{"one", 0, 100, {{"x", "x", false}}};
  std::vector<Response> rows;
  for (int v : {50, 51, 52, 53, 54, 100}) rows.push_back(Row(std::to_string(v), "r", {v}));
  Analysis a = Analyze(in, Table(rows), {}).value();
  const std::string svg = BoxPlotSvg(a);
  size_t circles = 0;
  for (size_t pos = 0; (pos = svg.find("<circle", pos)) != std::string::npos; ++pos) ++circles;
  EXPECT_EQ(circles, 1u);  // 100 lies beyond Q3 + 1.5 IQR
}

TEST(Simulate, ShapedLikeTheBrcStudyAndDeterministic) {
  SimulationParams p;
  p.seed = 9;
  ResponseTable a = Simulate(BrcInstrument(), p).value(), b = Simulate(BrcInstrument(), p).value();
  EXPECT_EQ(FormatResponsesCsv(a, BrcInstrument()), FormatResponsesCsv(b, BrcInstrument()));
  EXPECT_EQ(a.rows.size(), 176u);
  EXPECT_TRUE(ValidateResponses(a, BrcInstrument(), "sim").ok());
  p.seed = 10;
  EXPECT_NE(FormatResponsesCsv(Simulate(BrcInstrument(), p).value(), BrcInstrument()),
            FormatResponsesCsv(a, BrcInstrument()));
  p.quality = {1, 2};
  EXPECT_EQ(Simulate(BrcInstrument(), p).status().message(),
            "quality: need one value per route (4)");
  p.quality.clear();
  p.routes = 51;
  EXPECT_FALSE(Simulate(BrcInstrument(), p).ok());
}

}  // namespace
}  // namespace sb::studies
