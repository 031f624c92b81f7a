// Command-line tests of `strangebeta ratings`: fit (JSON shape, text,
// bad rows located file:line with exit 2 and nothing fitted, --skip-bad),
// synth (three files, deterministic) and eval.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "base/files.h"
#include "cli/commands.h"

namespace sb::cli {
namespace {

class RatingsCli : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() /
           ("sb_ratings_cli_" + std::to_string(getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }

  int Ratings(const std::vector<std::string>& args) {
    ::testing::internal::CaptureStderr();
    ::testing::internal::CaptureStdout();
    int rc = RunRatings(args);
    err_ = ::testing::internal::GetCapturedStderr();
    out_ = ::testing::internal::GetCapturedStdout();
    return rc;
  }
  std::string P(const std::string& name) const { return (dir_ / name).string(); }
  void Write(const std::string& name, const std::string& text) {
    ASSERT_TRUE(WriteFileAtomic(P(name), text).ok());
  }
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

  std::filesystem::path dir_;
  std::string out_, err_;
};

TEST_F(RatingsCli, JsonShape) {
  WriteGym();
  ASSERT_EQ(
      Ratings({"fit", "--ticks", P("TICKS.csv"), "--routes", P("ROUTES.csv"), "--format", "json"}),
      0)
      << err_;
  const auto j = nlohmann::json::parse(out_);
  ASSERT_EQ(j.size(), 2u);
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

}  // namespace
}  // namespace sb::cli
