// Command-line tests of `strangebeta grade`: conversions, exit codes and
// messages for bad input, estimates with the bundled and a trained
// estimator, and train/evaluate on a small export written here.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "base/files.h"
#include "cli/cli_test_util.h"
#include "cli/commands.h"

namespace sb::cli {
namespace {

class GradeCli : public CliFixture {
 protected:
  int Grade(const std::vector<std::string>& args) { return Capture(RunGrade, args); }
  static std::string Example(const std::string& name) {
    return std::string(SB_SOURCE_DIR) + "/data/examples/" + name;
  }
  // A small site export: 16 boulders and 8 sport routes, each of two grades
  // whose moves differ (an unknown word "xN" makes every route's text unique,
  // so each is its own group).
  void WriteExport() {
    std::string routes = "route_id,name,grade,type\n", moves = "route_id,seq_no,hand,move\n";
    for (int i = 1; i <= 24; ++i) {
      const bool boulder = i <= 16, hard = i % 2 == 0;
      routes += std::to_string(i) + ",r" + std::to_string(i) + "," +
                (boulder ? (hard ? "V6" : "V1") : (hard ? "5.12a" : "5.9")) + "," +
                (boulder ? "Bouldering" : "Sport") + "\n";
      for (int m = 1; m <= 5; ++m) {
        moves += std::to_string(i) + "," + std::to_string(m) + "," + (m % 2 ? "L" : "R") + "," +
                 (hard ? "dyno to small sloper" : "big jug") + " x" + std::to_string(i) + "\n";
      }
    }
    Write("public_routes.csv", routes);
    Write("public_moves.csv", moves);
  }
};

TEST_F(GradeCli, ConvertPrintsOneScaleOrAll) {
  ASSERT_EQ(Grade({"convert", "V4", "--to", "font"}), 0) << err_;
  EXPECT_EQ(out_, "6B/6B+\n");
  ASSERT_EQ(Grade({"convert", "5.10a", "--to", "french"}), 0);
  EXPECT_EQ(out_, "6a\n");
  ASSERT_EQ(Grade({"convert", "10", "--discipline", "roped", "--to", "yds"}), 0);
  EXPECT_EQ(out_, "5.10\n");
  ASSERT_EQ(Grade({"convert", "7+", "--from", "uiaa", "--to", "yds"}), 0);
  EXPECT_EQ(out_, "5.10d\n");
  ASSERT_EQ(Grade({"convert", "V4"}), 0);
  EXPECT_EQ(out_,
            "V4 (scale v, bouldering)\n"
            "yds     5.12a      (across disciplines: a rough translation)\n"
            "v       V4\n"
            "font    6B/6B+\n"
            "french  7a+        (across disciplines: a rough translation)\n"
            "uiaa    VIII+      (across disciplines: a rough translation)\n");
}

TEST_F(GradeCli, BadInputExitsTwoNamingTheField) {
  EXPECT_EQ(Grade({"convert", "Vmack"}), 2);
  EXPECT_NE(err_.find("GRADE: 'Vmack': not a V grade"), std::string::npos) << err_;
  EXPECT_EQ(out_, "");
  EXPECT_EQ(Grade({"convert", "4"}), 2);
  EXPECT_NE(err_.find("needs the discipline"), std::string::npos) << err_;
  EXPECT_EQ(Grade({"convert", "V4", "--to", "british"}), 2);
  EXPECT_NE(err_.find("--to: expected yds, v, font, french or uiaa"), std::string::npos) << err_;
  EXPECT_EQ(Grade({"convert", "4", "--discipline", "aid"}), 2);
  EXPECT_NE(err_.find("--discipline: expected roped or bouldering"), std::string::npos) << err_;
  EXPECT_EQ(Grade({"estimate", P("missing.crdl")}), 2);
  Write("bad.crdl", "name: Bad\ngrade: Vmack\n---\nR jug\n");
  EXPECT_EQ(Grade({"estimate", P("bad.crdl")}), 2);
  EXPECT_NE(err_.find(P("bad.crdl") + ": grade: 'Vmack'"), std::string::npos) << err_;
  Write("plain.crdl", "name: Plain\n---\nR jug\n");
  EXPECT_EQ(Grade({"estimate", P("plain.crdl")}), 2);
  EXPECT_NE(err_.find("give --discipline"), std::string::npos) << err_;
  EXPECT_EQ(Grade({"estimate", "--model", P("nope.sbg"), Example("roof-jugs.crdl")}), 2);
  Write("junk.sbg", "junk\n");
  EXPECT_EQ(Grade({"estimate", "--model", P("junk.sbg"), Example("roof-jugs.crdl")}), 2);
  EXPECT_NE(err_.find("not a valid grade estimator file"), std::string::npos) << err_;
  EXPECT_EQ(Grade({"evaluate", "--corpus", P("nowhere")}), 2);
  EXPECT_EQ(Grade({"evaluate", "--corpus", P("nowhere"), "--folds", "1"}), 2);
  EXPECT_NE(err_.find("--folds: expected 2..50"), std::string::npos) << err_;
  EXPECT_EQ(Grade({"evaluate", "--corpus", P("nowhere"), "--difficulty", "maybe"}), 2);
  EXPECT_NE(err_.find("--difficulty: expected on or off, got 'maybe'"), std::string::npos) << err_;
  EXPECT_EQ(Grade({"frobnicate"}), 2);
}

TEST_F(GradeCli, EstimatesWithTheBundledEstimator) {
  ASSERT_EQ(Grade({"estimate", Example("crimp-ladder.crdl"), Example("roof-jugs.crdl")}), 0)
      << err_;
  EXPECT_NE(out_.find("crimp-ladder.crdl: Crimp Ladder (roped): estimate 5."), std::string::npos)
      << out_;
  EXPECT_NE(out_.find("; setter's grade 5.11a\n"), std::string::npos) << out_;
  EXPECT_NE(out_.find("roof-jugs.crdl: Roof Jugs (bouldering): estimate V"), std::string::npos);
  ASSERT_EQ(
      Grade({"estimate", "--scale", "font", "--format", "json", Example("dyno-problem.crdl")}), 0)
      << err_;
  auto j = nlohmann::json::parse(out_);
  ASSERT_EQ(j.size(), 1u);
  EXPECT_EQ(j[0]["discipline"], "bouldering");
  EXPECT_EQ(j[0]["scale"], "font");
  EXPECT_EQ(j[0]["grade"], "V4");
  double sum = 0;
  for (const auto& p : j[0]["probabilities"]) sum += p["p"].get<double>();
  EXPECT_NEAR(sum, 1.0, 1e-12);
  // A route without a type or grade, with --discipline.
  Write("plain.crdl", "name: Plain\n---\nR jug\nL crimp\n");
  ASSERT_EQ(Grade({"estimate", "--discipline", "roped", P("plain.crdl")}), 0) << err_;
  EXPECT_EQ(out_.find("setter's grade"), std::string::npos);
}

TEST_F(GradeCli, TrainEvaluateAndEstimateOnAnExport) {
  WriteExport();
  ASSERT_EQ(Grade({"train", "--corpus", dir_.string(), "--out", P("m.sbg")}), 0) << err_;
  EXPECT_NE(err_.find("wrote " + P("m.sbg") + " (24 labelled routes)"), std::string::npos) << err_;
  Write("hard.crdl",
        "name: Hard\ntype: Bouldering\n---\nR dyno to small sloper\nL dyno to small sloper\n");
  Write("easy.crdl", "name: Easy\ngrade: V0\n---\nR big jug\nL big jug\n");
  ASSERT_EQ(Grade({"estimate", "--model", P("m.sbg"), P("hard.crdl"), P("easy.crdl")}), 0) << err_;
  EXPECT_NE(out_.find("Hard (bouldering): estimate V6"), std::string::npos) << out_;
  EXPECT_NE(out_.find("Easy (bouldering): estimate V1"), std::string::npos) << out_;
  ASSERT_EQ(Grade({"evaluate", "--corpus", dir_.string(), "--folds", "2", "--format", "json"}), 0)
      << err_;
  auto j = nlohmann::json::parse(out_);
  EXPECT_EQ(j["folds"], 2);
  EXPECT_EQ(j["bouldering"]["n"], 16);
  EXPECT_EQ(j["roped"]["n"], 8);
  for (const char* d : {"roped", "bouldering"}) {
    for (const char* p : {"model", "majority", "median"}) {
      for (const char* f : {"exact", "within_one", "mae"}) EXPECT_TRUE(j[d][p][f].is_number());
    }
    EXPECT_EQ(j[d]["model"]["exact"], 1.0) << d;  // the moves tell the grade here
  }
  std::string first = out_;
  ASSERT_EQ(Grade({"evaluate", "--corpus", dir_.string(), "--folds", "2", "--format", "json"}), 0);
  EXPECT_EQ(out_, first);
  ASSERT_EQ(Grade({"evaluate", "--corpus", dir_.string(), "--folds", "2"}), 0);
  EXPECT_NE(out_.find("bouldering      16  majority"), std::string::npos) << out_;
}

}  // namespace
}  // namespace sb::cli
