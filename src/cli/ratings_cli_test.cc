// Command-line tests of `strangebeta ratings`: fit (JSON shape, text,
// bad rows located file:line with exit 2 and nothing fitted, --skip-bad),
// synth (three files, deterministic) and eval.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "base/files.h"
#include "cli/commands.h"
#include "cli/ratings_cli_test_util.h"

namespace sb::cli {
namespace {

class RatingsCli : public RatingsCliFixture {
 protected:
  void WriteGym(const std::string& bad_rows = "") {
    Write("TICKS.csv",
          "climber,route,date,outcome,attempts,felt_grade\n"
          "ann,Blue Roof,2026-03-01,flash,,V3\n"
          "bob,Blue Roof,2026-03-01,send,4,\n"
          "bob,Crimp Line,2026-03-02,attempt,,\n"
          "cat,Crimp Line,2026-03-02,send,3,V5\n"
          "ann,Crimp Line,2026-03-03,attempt,2,\n" +
              bad_rows);
    Write("ROUTES.csv", "route,grade\nCrimp Line,V4\nBlue Roof,6B+\nNew Slab,V1\n");
  }
};

TEST_F(RatingsCli, JsonShape) {
  WriteGym();
  ASSERT_EQ(
      Ratings({"fit", "--ticks", P("TICKS.csv"), "--routes", P("ROUTES.csv"), "--format", "json"}),
      0)
      << err_;
  const auto j = nlohmann::json::parse(out_);
  ASSERT_EQ(j.size(), 14u);
  // What a saved fit needs to predict (ratings predict --fit).
  EXPECT_EQ(j["discipline"], "bouldering");
  EXPECT_EQ(j["scale"], "v");
  EXPECT_EQ(j["model"], "tries");
  EXPECT_DOUBLE_EQ(j["k"].get<double>(), std::log(3.0));
  EXPECT_DOUBLE_EQ(j["prior_mean"].get<double>(), (4.0 + 4.25 + 1.0) / 3);  // V4, 6B+, V1
  EXPECT_DOUBLE_EQ(j["climber_sd"].get<double>(), 3.0);
  EXPECT_DOUBLE_EQ(j["setter_sd"].get<double>(), 1.0);
  EXPECT_DOUBLE_EQ(j["open_route_sd"].get<double>(), 3.0);
  EXPECT_DOUBLE_EQ(j["felt_sd"].get<double>(), 1.5);
  EXPECT_DOUBLE_EQ(j["session_offset"].get<double>(), 0.0);
  EXPECT_DOUBLE_EQ(j["session_tries"].get<double>(), (1 + 4 + 3 + 2) / 4.0);
  EXPECT_EQ(j["drift"], false);
  ASSERT_EQ(j["routes"].size(), 3u);
  ASSERT_EQ(j["climbers"].size(), 3u);
  const auto& r0 = j["routes"][0];
  EXPECT_EQ(r0.size(), 6u);
  EXPECT_EQ(r0["route"], "Crimp Line");
  EXPECT_EQ(r0["n"], 3);
  EXPECT_LT(r0["lo"].get<double>(), r0["value"].get<double>());
  EXPECT_GT(r0["hi"].get<double>(), r0["value"].get<double>());
  // Crimp Line: two failures and one send in three: harder than its V4.
  EXPECT_GT(r0["value"].get<double>(), 4.0);
  EXPECT_EQ(r0["grade"].get<std::string>()[0], 'V');
  // Blue Roof keeps its setter's scale (Font).
  EXPECT_NE(j["routes"][1]["grade"].get<std::string>().find_first_of("ABC"), std::string::npos);
  EXPECT_EQ(j["routes"][2]["n"], 0);
  EXPECT_DOUBLE_EQ(j["routes"][2]["value"].get<double>(), 1.0);  // only the setter's grade
  const auto& c0 = j["climbers"][0];
  EXPECT_EQ(c0.size(), 5u);
  EXPECT_EQ(c0["climber"], "ann");
  EXPECT_EQ(c0["n"], 2);
  EXPECT_TRUE(c0.contains("ability") && c0.contains("lo") && c0.contains("hi"));
  // Deterministic: byte-identical output.
  const std::string first = out_;
  ASSERT_EQ(
      Ratings({"fit", "--ticks", P("TICKS.csv"), "--routes", P("ROUTES.csv"), "--format", "json"}),
      0);
  EXPECT_EQ(out_, first);
}

TEST_F(RatingsCli, TextNamesRoutesAndIntervals) {
  WriteGym();
  ASSERT_EQ(Ratings({"fit", "--ticks", P("TICKS.csv"), "--routes", P("ROUTES.csv")}), 0) << err_;
  EXPECT_NE(out_.find("3 routes, 3 climbers, 5 ticks; bouldering"), std::string::npos) << out_;
  EXPECT_NE(out_.find("Crimp Line"), std::string::npos);
  EXPECT_NE(out_.find("exact Laplace"), std::string::npos);
}

TEST_F(RatingsCli, BadRowsStopTheFitUnlessSkipped) {
  WriteGym("dan,Blue Roof,2026-03-04,onsight,,\ndan,Blue Roof,yesterday,flash,,\n");
  EXPECT_EQ(
      Ratings({"fit", "--ticks", P("TICKS.csv"), "--routes", P("ROUTES.csv"), "--format", "json"}),
      2);
  EXPECT_EQ(out_, "");  // nothing fitted
  EXPECT_NE(err_.find(P("TICKS.csv") + ":7: outcome: expected flash, send or attempt, got "
                                       "'onsight'"),
            std::string::npos)
      << err_;
  EXPECT_NE(err_.find(P("TICKS.csv") + ":8: date: expected YYYY-MM-DD"), std::string::npos);
  EXPECT_NE(err_.find("2 bad row(s); nothing fitted"), std::string::npos);

  ASSERT_EQ(Ratings({"fit", "--ticks", P("TICKS.csv"), "--routes", P("ROUTES.csv"), "--format",
                     "json", "--skip-bad"}),
            0)
      << err_;
  EXPECT_NE(err_.find(":7: outcome: expected flash, send or attempt, got 'onsight' (skipped)"),
            std::string::npos)
      << err_;
  const auto j = nlohmann::json::parse(out_);
  EXPECT_EQ(j["climbers"].size(), 3u);  // dan's rows were all bad
}

TEST_F(RatingsCli, UsageAndFileErrors) {
  EXPECT_EQ(Ratings({"fit", "--ticks", P("missing.csv")}), 2);
  EXPECT_NE(err_.find("missing.csv"), std::string::npos);
  WriteGym();
  EXPECT_EQ(Ratings({"fit", "--ticks", P("TICKS.csv"), "--format", "xml"}), 2);
  EXPECT_NE(err_.find("--format: expected text or json"), std::string::npos);
  Write("BAD.csv", "climber,route,when\n");
  EXPECT_EQ(Ratings({"fit", "--ticks", P("BAD.csv")}), 2);
  EXPECT_NE(err_.find(P("BAD.csv") + ":1: missing column 'date'"), std::string::npos) << err_;
}

TEST_F(RatingsCli, SynthWritesAGymThatFits) {
  ASSERT_EQ(Ratings({"synth", "--climbers", "40", "--routes", "30", "--ticks-per-route", "5",
                     "--seed", "3", "--out", P("gym")}),
            0)
      << err_;
  for (const char* f : {"TICKS.csv", "ROUTES.csv", "TRUTH.csv"}) {
    EXPECT_TRUE(std::filesystem::exists(dir_ / "gym" / f)) << f;
  }
  const std::string ticks = *ReadFile(P("gym/TICKS.csv"));
  EXPECT_EQ(std::count(ticks.begin(), ticks.end(), '\n'), 151);
  ASSERT_EQ(Ratings({"synth", "--climbers", "40", "--routes", "30", "--ticks-per-route", "5",
                     "--seed", "3", "--out", P("gym2")}),
            0);
  EXPECT_EQ(*ReadFile(P("gym2/TICKS.csv")), ticks);
  ASSERT_EQ(Ratings({"fit", "--ticks", P("gym/TICKS.csv"), "--routes", P("gym/ROUTES.csv"),
                     "--format", "json"}),
            0)
      << err_;
  EXPECT_EQ(nlohmann::json::parse(out_)["routes"].size(), 30u);
  EXPECT_EQ(Ratings({"synth", "--routes", "0", "--out", P("gym3")}), 2);
}

TEST_F(RatingsCli, EvalPrintsTheFigures) {
  ASSERT_EQ(Ratings({"eval", "--climbers", "60", "--routes", "50", "--ticks-per-route", "8,2",
                     "--format", "json"}),
            0)
      << err_;
  const auto j = nlohmann::json::parse(out_);
  ASSERT_EQ(j["results"].size(), 2u);
  EXPECT_EQ(j["results"][0]["ticks_per_route"], 8);
  EXPECT_GT(j["results"][0]["spearman"].get<double>(), j["results"][1]["spearman"].get<double>());
  EXPECT_EQ(Ratings({"eval", "--ticks-per-route", "20,x"}), 2);
}

TEST_F(RatingsCli, DuplicatesAndZeroTriesAreNoted) {
  WriteGym("cat,Crimp Line,2026-03-02,send,3,V5\ndan,New Slab,2026-03-05,attempt,0,\n");
  ASSERT_EQ(
      Ratings({"fit", "--ticks", P("TICKS.csv"), "--routes", P("ROUTES.csv"), "--format", "json"}),
      0)
      << err_;
  EXPECT_NE(err_.find("note: " + P("TICKS.csv") +
                      ":7: duplicate of line 5 (counted again; --dedupe counts it once)"),
            std::string::npos)
      << err_;
  EXPECT_NE(err_.find("note: " + P("TICKS.csv") +
                      ":8: attempts: 0 tries: a session with no try (no games)"),
            std::string::npos)
      << err_;
  EXPECT_NE(err_.find("note: 1 exact duplicate row(s) (counted again; --dedupe), 1 row(s) of 0 "
                      "tries (no games)"),
            std::string::npos)
      << err_;
  auto j = nlohmann::json::parse(out_);
  EXPECT_EQ(j["routes"][0]["n"], 4);  // Crimp Line: the duplicate counted
  ASSERT_EQ(j["climbers"].size(), 4u);
  EXPECT_EQ(j["climbers"][3]["climber"], "dan");
  EXPECT_EQ(j["climbers"][3]["n"], 0);
  ASSERT_EQ(Ratings({"fit", "--ticks", P("TICKS.csv"), "--routes", P("ROUTES.csv"), "--format",
                     "json", "--dedupe"}),
            0)
      << err_;
  EXPECT_NE(err_.find(":7: duplicate of line 5 (counted once: --dedupe)"), std::string::npos)
      << err_;
  j = nlohmann::json::parse(out_);
  EXPECT_EQ(j["routes"][0]["n"], 3);
}

TEST_F(RatingsCli, PredictFromTicksOrASavedFit) {
  WriteGym();
  Write("PAIRS.csv", "climber,route\nann,Crimp Line\ncat,Blue Roof\nzed,New Slab\nann,Nowhere\n");
  for (const std::string model : {"tries", "session"}) {
    SCOPED_TRACE(model);
    ASSERT_EQ(Ratings({"predict", "--ticks", P("TICKS.csv"), "--routes", P("ROUTES.csv"), "--pairs",
                       P("PAIRS.csv"), "--model", model}),
              0)
        << err_;
    const std::string csv = out_;
    EXPECT_EQ(csv.rfind("climber,route,p_flash,p_send\nann,Crimp Line,", 0), 0u) << csv;
    EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 5);
    // The same from the saved fit.
    ASSERT_EQ(Ratings({"fit", "--ticks", P("TICKS.csv"), "--routes", P("ROUTES.csv"), "--format",
                       "json", "--model", model, "-o", P("FIT.json")}),
              0)
        << err_;
    ASSERT_EQ(Ratings({"predict", "--fit", P("FIT.json"), "--routes", P("ROUTES.csv"), "--pairs",
                       P("PAIRS.csv")}),
              0)
        << err_;
    EXPECT_EQ(out_, csv);
    ASSERT_EQ(
        Ratings({"predict", "--fit", P("FIT.json"), "--pairs", P("PAIRS.csv"), "--format", "json"}),
        0)
        << err_;
    const auto j = nlohmann::json::parse(out_);
    EXPECT_EQ(j["model"], model);
    ASSERT_EQ(j["pairs"].size(), 4u);
    for (const auto& p : j["pairs"]) {
      EXPECT_GT(p["p_flash"].get<double>(), 0.0);
      EXPECT_LE(p["p_flash"].get<double>(), p["p_send"].get<double>());
      EXPECT_LT(p["p_send"].get<double>(), 1.0);
    }
    EXPECT_EQ(j["pairs"][2]["climber_seen"], false);  // zed: at the prior
    EXPECT_EQ(j["pairs"][3]["route_seen"], false);    // Nowhere: at the prior
    // ann at a route of the prior mean's difficulty vs zed (the prior) at New Slab (V1).
    const auto fit = nlohmann::json::parse(*ReadFile(P("FIT.json")));
    const double k = fit["k"].get<double>();
    const double a = fit["climbers"][0]["ability"].get<double>();
    EXPECT_NEAR(j["pairs"][3]["p_flash"].get<double>(),
                1 / (1 + std::exp(-k * (a - fit["prior_mean"].get<double>()))), 1e-15);
  }
  // The zones model (session offsets; a gym has no zones) from the ticks.
  ASSERT_EQ(Ratings({"predict", "--ticks", P("TICKS.csv"), "--routes", P("ROUTES.csv"), "--pairs",
                     P("PAIRS.csv"), "--model", "zones", "--format", "json"}),
            0)
      << err_;
  const auto z = nlohmann::json::parse(out_);
  EXPECT_EQ(z["model"], "zones");
  ASSERT_EQ(z["pairs"].size(), 4u);
  for (const auto& p : z["pairs"]) {
    EXPECT_GT(p["p_flash"].get<double>(), 0.0);
    EXPECT_LE(p["p_flash"].get<double>(), p["p_send"].get<double>());
    EXPECT_LT(p["p_send"].get<double>(), 1.0);
  }
  EXPECT_EQ(z["pairs"][2]["climber_seen"], false);
  EXPECT_EQ(z["pairs"][3]["route_seen"], false);
  EXPECT_EQ(Ratings({"predict", "--fit", P("FIT.json"), "--pairs", P("PAIRS.csv"), "--model",
                     "zones"}),
            2);
  EXPECT_NE(err_.find("--model zones: predicts from --ticks only"), std::string::npos) << err_;
  // Errors name the file and field.
  Write("NOPAIRS.csv", "climber,wall\nann,x\n");
  EXPECT_EQ(Ratings({"predict", "--ticks", P("TICKS.csv"), "--pairs", P("NOPAIRS.csv")}), 2);
  EXPECT_NE(err_.find(P("NOPAIRS.csv") + ":1: missing column 'route'"), std::string::npos) << err_;
  Write("EMPTY.csv", "climber,route\nann,\n");
  EXPECT_EQ(Ratings({"predict", "--ticks", P("TICKS.csv"), "--pairs", P("EMPTY.csv")}), 2);
  EXPECT_NE(err_.find(P("EMPTY.csv") + ":2: route: empty"), std::string::npos) << err_;
  EXPECT_EQ(Ratings({"predict", "--pairs", P("PAIRS.csv")}), 2);
  EXPECT_NE(err_.find("--ticks: required"), std::string::npos) << err_;
  Write("BADFIT.json", "{\"routes\":[]}");
  EXPECT_EQ(Ratings({"predict", "--fit", P("BADFIT.json"), "--pairs", P("PAIRS.csv")}), 2);
  EXPECT_NE(err_.find(P("BADFIT.json") + ": k: missing"), std::string::npos) << err_;
  EXPECT_EQ(Ratings({"fit", "--ticks", P("TICKS.csv"), "--model", "whr"}), 2);
  EXPECT_NE(err_.find("--model: expected tries or session, got 'whr'"), std::string::npos);
}

}  // namespace
}  // namespace sb::cli
