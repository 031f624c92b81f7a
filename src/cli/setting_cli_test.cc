// Command-line tests of `strangebeta search` and `strangebeta difficulty`
// (issue 13), and of the reusable setter options.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "base/files.h"
#include "cli/commands.h"
#include "cli/setting_options.h"

namespace sb::cli {
namespace {

class SettingCli : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::path(::testing::TempDir()) /
           ("sb_setting_cli_" +
            std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()) + "_" +
            std::to_string(::getpid()));
    std::filesystem::remove_all(dir_);
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  std::string Example(const std::string& name) const {
    return std::string(SB_SOURCE_DIR) + "/data/examples/" + name + ".crdl";
  }
  std::vector<std::string> Three() const {
    return {Example("edge-crack"), Example("pocket-traverse"), Example("slab-dance")};
  }
  int Run(int (*cmd)(const std::vector<std::string>&), std::vector<std::string> args,
          std::string* err = nullptr) {
    ::testing::internal::CaptureStderr();
    ::testing::internal::CaptureStdout();
    int rc = cmd(args);
    std::string e = ::testing::internal::GetCapturedStderr();
    out_ = ::testing::internal::GetCapturedStdout();
    if (err) *err = e;
    return rc;
  }
  std::filesystem::path dir_;
  std::string out_;
};

TEST_F(SettingCli, SearchReportsTheIcConstraintsAndWarningsDeterministically) {
  std::vector<std::string> args = Three();
  for (const char* a : {"--keep-start", "--keep-finish", "--crux-window", "0.5,0.9",
                        "--alternate-hands", "--max-repeat", "2", "--format", "json"}) {
    args.push_back(a);
  }
  ASSERT_EQ(Run(RunSearch, args), 0);
  std::string first = out_;
  ASSERT_EQ(Run(RunSearch, args), 0);
  EXPECT_EQ(out_, first);
  auto j = nlohmann::json::parse(first);
  const auto& s = j["search"];
  EXPECT_EQ(s["requested_ic"], nlohmann::json({-16.0, -12.0, 52.0}));
  EXPECT_GT(s["distance"].get<double>(), 0.0);
  ASSERT_EQ(s["constraints"].size(), 5u);
  for (const auto& c : s["constraints"]) EXPECT_TRUE(c["held"].get<bool>()) << c.dump();
  EXPECT_EQ(s["constraints"][0]["name"], "keep-start");
  // The plan is vary's at the IC used (modulo the noted hand swaps).
  const auto& moves = j["plan"]["moves"];
  ASSERT_EQ(moves.size(), 30u);
  int swapped = 0;
  for (size_t m = 0; m < moves.size(); ++m) {
    if (moves[m].dump().find("(hand swapped)") != std::string::npos) ++swapped;
    if (m > 0) {
      EXPECT_NE(moves[m]["hand"], moves[m - 1]["hand"]);
    }
  }
  EXPECT_EQ(swapped, s["hands_swapped"].get<int>());
  EXPECT_EQ(j["move_facts"].size(), 30u);
  EXPECT_TRUE(j["summary"].contains("text_changed"));
  EXPECT_TRUE(j["warnings"].is_array());
}

TEST_F(SettingCli, SearchWithoutConstraintsIsVary) {
  std::vector<std::string> args = Three();
  args.push_back("--format");
  args.push_back("json");
  ASSERT_EQ(Run(RunSearch, args), 0);
  auto j = nlohmann::json::parse(out_);
  EXPECT_TRUE(j["search"].is_null());
  std::vector<std::string> vargs = Three();
  for (const char* a : {"--format", "json"}) vargs.push_back(a);
  ASSERT_EQ(Run(RunVary, vargs), 0);
  auto v = nlohmann::json::parse(out_);
  EXPECT_EQ(j["plan"]["moves"], v["moves"]);
}

TEST_F(SettingCli, TextPlanCarriesTheReport) {
  std::vector<std::string> args = Three();
  for (const char* a : {"--keep-start", "--keep-finish"}) args.push_back(a);
  ASSERT_EQ(Run(RunSearch, args), 0);
  EXPECT_EQ(out_.rfind("# search: IC ", 0), 0u) << out_;
  EXPECT_NE(out_.find("#   keep-start: held"), std::string::npos);
  EXPECT_NE(out_.find("# summary: changed "), std::string::npos);
  EXPECT_NE(out_.find("CHAOTIC ROUTE PLAN"), std::string::npos);
}

TEST_F(SettingCli, BadOptionsAndUnmetConstraintsExitTwoWithTheName) {
  std::string err;
  std::vector<std::string> args = Three();
  args.push_back("--crux-window");
  args.push_back("0.9,0.5");
  EXPECT_EQ(Run(RunSearch, args, &err), 2);
  EXPECT_NE(err.find("--crux-window"), std::string::npos) << err;
  args = Three();
  args.push_back("--match");
  args.push_back("both");
  EXPECT_EQ(Run(RunSearch, args, &err), 2);
  EXPECT_NE(err.find("--match"), std::string::npos) << err;
  args = Three();
  args.push_back("--search-radius");
  args.push_back("100000");
  EXPECT_EQ(Run(RunSearch, args, &err), 2);
  EXPECT_NE(err.find("--search-radius"), std::string::npos) << err;
  args = Three();
  for (const char* a : {"--crux-window", "0,0.01", "--search-radius", "5"}) args.push_back(a);
  EXPECT_EQ(Run(RunSearch, args, &err), 2);
  EXPECT_NE(err.find("crux-window could not be met"), std::string::npos) << err;
}

TEST_F(SettingCli, MatchGrammarReadsMatchMovesThatTheTextRuleLeaves) {
  std::ofstream(dir_ / "m.crdl") << "name: M\n---\nR sloper\nL match on sloper\nR crimp\n"
                                    "L pinch\nR match\n";
  std::string route = (dir_ / "m.crdl").string();
  ASSERT_EQ(Run(RunSearch, {route, "--var-ic", "-13,-12,52", "--format", "json"}), 0);
  auto text_rule = nlohmann::json::parse(out_);
  ASSERT_EQ(
      Run(RunSearch, {route, "--var-ic", "-13,-12,52", "--match", "grammar", "--format", "json"}),
      0);
  auto grammar = nlohmann::json::parse(out_);
  // At the reference IC the mapping is the identity: move 2 is itself.
  EXPECT_EQ(text_rule["plan"]["moves"][1]["text"], "match on sloper");
  EXPECT_EQ(grammar["plan"]["moves"][1]["text"], "sloper");
  EXPECT_NE(grammar["plan"]["moves"][1].dump().find("(match?)"), std::string::npos);
  EXPECT_EQ(text_rule["plan"]["moves"][4]["text"], "pinch");  // "match" under both rules
  EXPECT_EQ(grammar["plan"]["moves"][4]["text"], "pinch");
}

TEST_F(SettingCli, ResolveSettingOptionsFillsTheRequest) {
  SettingOptions o;
  o.keep_start = true;
  o.crux_window = "0.25,0.75";
  o.match = "grammar";
  o.search_plane = "cube";
  o.search_radius = 20;
  auto r = ResolveSettingOptions(o);
  ASSERT_TRUE(r.ok()) << r.status().message();
  EXPECT_TRUE(r->constraints.keep_start);
  EXPECT_DOUBLE_EQ(r->constraints.crux_window->end, 0.75);
  EXPECT_EQ(r->match, difficulty::MatchRule::kGrammar);
  EXPECT_EQ(r->grid.plane, chaos::SearchPlane::kCube);
  o.search_plane = "zz";
  EXPECT_NE(ResolveSettingOptions(o).status().message().find("--search-plane"), std::string::npos);
}

TEST_F(SettingCli, DifficultyShowListsEveryMove) {
  ASSERT_EQ(Run(RunDifficulty, {"show", Example("crimp-ladder"), "--format", "json"}), 0);
  auto j = nlohmann::json::parse(out_);
  ASSERT_EQ(j["moves"].size(), 11u);
  size_t hardest = j["hardest"].get<size_t>();
  for (const auto& m : j["moves"]) {
    double d = m["difficulty"].get<double>();
    EXPECT_TRUE(d > 0 && d < 1);
    EXPECT_LE(d, j["moves"][hardest]["difficulty"].get<double>());
  }
  ASSERT_EQ(Run(RunDifficulty, {"show", Example("crimp-ladder")}), 0);
  EXPECT_NE(out_.find("hardest by the estimate: move "), std::string::npos);
}

TEST_F(SettingCli, DifficultyErrorsExitTwo) {
  std::string err;
  EXPECT_EQ(Run(RunDifficulty, {"show", (dir_ / "missing.crdl").string()}, &err), 2);
  std::ofstream(dir_ / "bad.sbd") << "strangebeta difficulty model\nversion 1\n";
  EXPECT_EQ(Run(RunDifficulty,
                {"show", Example("crimp-ladder"), "--model", (dir_ / "bad.sbd").string()}, &err),
            2);
  EXPECT_NE(err.find("bad.sbd:"), std::string::npos) << err;
  EXPECT_EQ(Run(RunDifficulty, {"evaluate", "--corpus", (dir_ / "none").string()}, &err), 2);
  EXPECT_EQ(Run(RunDifficulty, {"evaluate"}, &err), 2);
}

TEST_F(SettingCli, DifficultyEvaluateAndTrainOnTheCorpus) {
  std::string shared = FindSharedDir(SB_SHARED_DIR);
  if (shared.empty()) GTEST_SKIP() << "../shared not found (set SB_SHARED); corpus test skipped";
  ASSERT_EQ(Run(RunDifficulty,
                {"evaluate", "--corpus", shared + "/corpus", "--folds", "5", "--format", "json"}),
            0);
  auto j = nlohmann::json::parse(out_);
  for (const char* k : {"auc", "top1"}) {
    EXPECT_TRUE(j[k].is_number());
    EXPECT_TRUE(j["baselines"]["position"][k].is_number());
    EXPECT_TRUE(j["baselines"]["chance"][k].is_number());
  }
  EXPECT_EQ(j["folds"], 5);
  std::string err;
  EXPECT_EQ(Run(RunDifficulty, {"evaluate", "--corpus", shared + "/corpus", "--folds", "1"}, &err),
            2);
  EXPECT_NE(err.find("--folds"), std::string::npos) << err;
  std::string model = (dir_ / "d.sbd").string();
  ASSERT_EQ(Run(RunDifficulty, {"train", "--corpus", shared + "/corpus", "--out", model}), 0);
  ASSERT_EQ(Run(RunDifficulty, {"show", Example("crimp-ladder"), "--model", model}), 0);
}

}  // namespace
}  // namespace sb::cli
