// `strangebeta ratings` with abilities that drift (issue 35): a static fit
// (drift off, or auto within a season) is byte-identical to main's binary
// before drift existed; auto turns drift on past a season and records its
// settings; predict uses the latest ability, from the ticks or a saved fit;
// skewed intervals.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "base/files.h"
#include "base/hash.h"
#include "cli/commands.h"
#include "cli/ratings_cli_test_util.h"

namespace sb::cli {
namespace {

using RatingsDriftCli = RatingsCliFixture;

// The digests are FNV-1a 64 of main's `strangebeta ratings fit` output
// (commit abe9d84, before drift) on `ratings synth --climbers 60 --routes 50
// --ticks-per-route 8 --seed 7`: JSON, text, and JSON with --model session.
TEST_F(RatingsDriftCli, DriftOffIsByteIdenticalToMainBeforeDrift) {
  ASSERT_EQ(Ratings({"synth", "--climbers", "60", "--routes", "50", "--ticks-per-route", "8",
                     "--seed", "7", "--out", P("gym")}),
            0)
      << err_;
  const std::string t = P("gym/TICKS.csv"), r = P("gym/ROUTES.csv");
  ASSERT_EQ(Ratings({"fit", "--ticks", t, "--routes", r, "--format", "json", "--drift", "off"}), 0)
      << err_;
  EXPECT_EQ(Fnv1a64(out_), 0xdf4cbedd37667b30ull) << out_.substr(0, 400);
  ASSERT_EQ(Ratings({"fit", "--ticks", t, "--routes", r, "--drift", "off"}), 0) << err_;
  EXPECT_EQ(Fnv1a64(out_), 0xb873ed90640bd052ull);
  ASSERT_EQ(Ratings({"fit", "--ticks", t, "--routes", r, "--format", "json", "--model", "session",
                     "--drift", "off"}),
            0)
      << err_;
  EXPECT_EQ(Fnv1a64(out_), 0xd35ccf3f283b5e1eull);
  // The synthetic gym spans 2026: auto drifts, and says so.
  ASSERT_EQ(Ratings({"fit", "--ticks", t, "--routes", r, "--format", "json"}), 0) << err_;
  const auto j = nlohmann::json::parse(out_);
  EXPECT_EQ(j["drift"], true);
  EXPECT_EQ(j["drift_mode"], "auto");
  EXPECT_EQ(j["season_days"], 120);
  EXPECT_EQ(j["node_days"], 7);
  EXPECT_EQ(j["drift_sd_estimated"], true);
  EXPECT_GT(j["drift_sd"].get<double>(), 0.0);
  EXPECT_LT(j["first_date"].get<std::string>(), j["last_date"].get<std::string>());
  ASSERT_EQ(j["climbers"].size(), 57u);  // the climbers with ticks
  EXPECT_TRUE(j["climbers"][0].contains("as_of"));
  EXPECT_TRUE(j["climbers"][0].contains("sd"));
}

TEST_F(RatingsDriftCli, AutoWithinASeasonIsStaticAndPredictUsesTheLatestAbility) {
  // 100 days: within a season, auto is off (the same bytes as off).
  ASSERT_TRUE(WriteFileAtomic(P("T.csv"),
                              "climber,route,date,outcome,attempts,felt_grade\n"
                              "ann,A,2026-01-01,attempt,3,\n"
                              "ann,B,2026-01-02,flash,,\n"
                              "bob,A,2026-02-01,send,2,\n"
                              "bob,B,2026-02-01,flash,,\n"
                              "ann,A,2026-04-11,flash,,\n")
                  .ok());
  ASSERT_TRUE(WriteFileAtomic(P("R.csv"), "route,grade\nA,V5\nB,V2\n").ok());
  ASSERT_TRUE(WriteFileAtomic(P("PAIRS.csv"), "climber,route\nann,A\nbob,A\nzed,B\n").ok());
  ASSERT_EQ(Ratings({"fit", "--ticks", P("T.csv"), "--routes", P("R.csv"), "--format", "json"}), 0);
  const std::string auto_out = out_;
  ASSERT_EQ(Ratings({"fit", "--ticks", P("T.csv"), "--routes", P("R.csv"), "--format", "json",
                     "--drift", "off"}),
            0);
  EXPECT_EQ(out_, auto_out);
  EXPECT_EQ(nlohmann::json::parse(out_)["drift"], false);
  // Drift on: ann failed A in January and flashed it in April; her latest
  // ability is above her static one.
  ASSERT_EQ(Ratings({"fit", "--ticks", P("T.csv"), "--routes", P("R.csv"), "--format", "json",
                     "--drift", "on", "--drift-sd", "2", "-o", P("FIT.json")}),
            0)
      << err_;
  const auto on = nlohmann::json::parse(*ReadFile(P("FIT.json")));
  const auto off = nlohmann::json::parse(auto_out);
  EXPECT_EQ(on["drift_sd"], 2.0);
  EXPECT_EQ(on["drift_sd_estimated"], false);
  EXPECT_EQ(on["climbers"][0]["as_of"], "2026-04-09");  // the week of 11 April from 1 January
  EXPECT_GT(on["climbers"][0]["ability"].get<double>(), off["climbers"][0]["ability"].get<double>());
  // Predictions from the ticks and from the saved fit agree.
  ASSERT_EQ(Ratings({"predict", "--ticks", P("T.csv"), "--routes", P("R.csv"), "--pairs",
                     P("PAIRS.csv"), "--drift", "on", "--drift-sd", "2"}),
            0)
      << err_;
  const std::string from_ticks = out_;
  ASSERT_EQ(Ratings({"predict", "--fit", P("FIT.json"), "--pairs", P("PAIRS.csv")}), 0) << err_;
  EXPECT_EQ(out_, from_ticks);
  // Bad settings name the option.
  EXPECT_EQ(Ratings({"fit", "--ticks", P("T.csv"), "--drift", "yes"}), 2);
  EXPECT_NE(err_.find("--drift: expected on, off or auto, got 'yes'"), std::string::npos) << err_;
  EXPECT_EQ(Ratings({"fit", "--ticks", P("T.csv"), "--interval-shape", "round"}), 2);
  EXPECT_NE(err_.find("--interval-shape: expected symmetric or skewed"), std::string::npos);
}

TEST_F(RatingsDriftCli, SkewedIntervalsReachUpForARouteNobodySent) {
  std::string ticks = "climber,route,date,outcome,attempts,felt_grade\n";
  for (int c = 0; c < 8; ++c) {
    const std::string name = "c" + std::to_string(c);
    ticks += name + ",Easy,2026-03-01,flash,,\n" + name + ",Mid,2026-03-01," +
             (c % 2 ? "flash,," : "attempt,2,") + "\n" + name + ",Roof,2026-03-02,attempt,4,\n";
  }
  ASSERT_TRUE(WriteFileAtomic(P("T.csv"), ticks).ok());
  ASSERT_TRUE(WriteFileAtomic(P("R.csv"), "route,grade\nEasy,V1\nMid,V3\nRoof,\n").ok());
  ASSERT_EQ(Ratings({"fit", "--ticks", P("T.csv"), "--routes", P("R.csv"), "--format", "json",
                     "--interval-shape", "skewed"}),
            0)
      << err_;
  const auto j = nlohmann::json::parse(out_);
  const auto& roof = j["routes"][2];
  ASSERT_EQ(roof["route"], "Roof");
  const double v = roof["value"], lo = roof["lo"], hi = roof["hi"];
  EXPECT_GT(hi - v, 1.2 * (v - lo)) << lo << " " << v << " " << hi;
}

}  // namespace
}  // namespace sb::cli
