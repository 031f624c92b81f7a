// Command-line tests of `strangebeta vary` and `strangebeta check`.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "cli/cli_test_util.h"
#include "cli/commands.h"

namespace sb::cli {
namespace {

std::string Slurp(const std::string& path) {
  std::ifstream in(path);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

class VaryCli : public CliFixture {
 protected:
  void SetUp() override {
    CliFixture::SetUp();
    Write("a.crdl", "name: Alpha\ngrade: V3\n---\nR jug\nL match\nR crimp\nL sloper\nR pinch\n");
    Write("b.crdl", "---\nL pocket\nR edge\nL gaston\nR undercling\nL match\n");
    Write("bad.crdl", "name: Bad\n---\nR jug\nL crimp\nQ sloper\n");
  }
  int Run(const std::vector<std::string>& args, std::string* err = nullptr) {
    int rc = Capture(RunVary, args);
    if (err) *err = err_;
    return rc;
  }
};

TEST_F(VaryCli, JsonOutputFollowsTheSchemaAndIsByteIdentical) {
  ASSERT_EQ(Run({P("a.crdl"), P("b.crdl"), "--format", "json", "-o", P("v1.json")}), 0);
  ASSERT_EQ(Run({P("a.crdl"), P("b.crdl"), "--format", "json", "-o", P("v2.json")}), 0);
  std::string a = Slurp(P("v1.json")), b = Slurp(P("v2.json"));
  EXPECT_EQ(a, b);
  auto j = nlohmann::json::parse(a);
  EXPECT_EQ(j["inputs"][0]["name"], "Alpha");
  EXPECT_EQ(j["inputs"][1]["name"], "b");  // file stem when the route has no name
  EXPECT_EQ(j["moves"].size(), 10u);
  EXPECT_EQ(j["parameters"]["integrator"], "rk4");
  EXPECT_EQ(j["parameters"]["ref_ic"], nlohmann::json({-13, -12, 52}));
}

TEST_F(VaryCli, ExplicitOptionsOverrideThePreset) {
  ASSERT_EQ(Run({P("a.crdl"), "--preset", "more", "--skip", "7", "--format", "json"}), 0);
  auto j = nlohmann::json::parse(out_);
  EXPECT_EQ(j["parameters"]["preset"], "more");
  EXPECT_EQ(j["parameters"]["skip"], 7);
  EXPECT_EQ(j["parameters"]["var_ic"], nlohmann::json({-16, -13.5, 52}));
  ASSERT_EQ(Run({P("a.crdl"), "--system", "rossler", "--var-ic", "-1,2,3", "--integrator",
                 "rkf45", "--mask", "111", "--max-repeat", "1", "--format", "json"}),
            0);
  j = nlohmann::json::parse(out_);
  EXPECT_EQ(j["parameters"]["params"], nlohmann::json({0.2, 0.2, 5.7}));
  EXPECT_EQ(j["parameters"]["var_ic"], nlohmann::json({-1, 2, 3}));
  EXPECT_EQ(j["parameters"]["mask"], "111");
}

TEST_F(VaryCli, BadRouteIsReportedWithFileLineColumnAndNothingWritten) {
  std::string err;
  EXPECT_EQ(Run({P("a.crdl"), P("bad.crdl"), "-o", P("out.txt")}, &err), 2);
  EXPECT_NE(err.find(P("bad.crdl") + ":5:1: expected hand L or R, got \"Q\""), std::string::npos)
      << err;
  EXPECT_FALSE(std::filesystem::exists(P("out.txt")));
  EXPECT_EQ(Run({P("missing.crdl")}, &err), 2);
  EXPECT_NE(err.find("missing.crdl: no such file"), std::string::npos) << err;
}

TEST_F(VaryCli, BadOptionsAreUsageErrors) {
  std::string err;
  EXPECT_EQ(Run({P("a.crdl"), "--mask", "000"}, &err), 2);
  EXPECT_NE(err.find("--mask"), std::string::npos);
  EXPECT_EQ(Run({P("a.crdl"), "--format", "pdf"}, &err), 2);
  EXPECT_EQ(Run({P("a.crdl"), "--preset", "wild"}, &err), 2);
  EXPECT_EQ(Run({P("a.crdl"), "--step", "-1"}, &err), 2);
  EXPECT_EQ(Run({P("a.crdl"), "--var-ic", "1,2"}, &err), 2);
  EXPECT_NE(err.find("--var-ic: expected three numbers"), std::string::npos) << err;
  EXPECT_EQ(Run({P("a.crdl"), "--no-such-option"}, &err), 2);
  EXPECT_EQ(Run({}, &err), 2);
}

TEST_F(VaryCli, HelpDocumentsEveryOption) {
  ASSERT_EQ(Run({"--help"}), 0);
  for (const char* opt : {"--preset", "--system", "--params", "--integrator", "--step", "--ref-ic",
                          "--var-ic", "--skip", "--mapping", "--mask", "--dabby-direction",
                          "--max-repeat", "--format", "--output", "--smooth"}) {
    EXPECT_NE(out_.find(opt), std::string::npos) << opt;
  }
}

TEST_F(VaryCli, TextSvgAndMarkdownFormats) {
  ASSERT_EQ(Run({P("a.crdl"), P("b.crdl")}), 0);
  EXPECT_NE(out_.find("CHAOTIC ROUTE PLAN"), std::string::npos);
  ASSERT_EQ(Run({P("a.crdl"), "--format", "svg"}), 0);
  EXPECT_NE(out_.find("<svg"), std::string::npos);
  ASSERT_EQ(Run({P("a.crdl"), "--format", "markdown"}), 0);
  EXPECT_EQ(out_.rfind("# Chaotic route plan", 0), 0u);
}

TEST_F(VaryCli, CheckReportsEachFile) {
  ::testing::internal::CaptureStderr();
  ::testing::internal::CaptureStdout();
  int rc = RunCheck({P("a.crdl"), P("bad.crdl")});
  std::string err = ::testing::internal::GetCapturedStderr();
  std::string out = ::testing::internal::GetCapturedStdout();
  EXPECT_EQ(rc, 2);
  EXPECT_NE(out.find("\"Alpha\", 5 moves"), std::string::npos);
  EXPECT_NE(err.find(":5:1:"), std::string::npos);
}

TEST(ExampleRoutes, AllParseAndSomeUseMatch) {
  int files = 0, with_match = 0;
  for (const auto& e : std::filesystem::directory_iterator(SB_SOURCE_DIR "/data/examples")) {
    if (e.path().extension() != ".crdl") continue;
    ++files;
    std::string text = Slurp(e.path().string());
    ::testing::internal::CaptureStdout();
    int rc = RunCheck({e.path().string()});
    ::testing::internal::GetCapturedStdout();
    EXPECT_EQ(rc, 0) << e.path();
    with_match += text.find("match\n") != std::string::npos;
  }
  EXPECT_GE(files, 10);
  EXPECT_LE(files, 20);
  EXPECT_GE(with_match, 3);
}

}  // namespace
}  // namespace sb::cli
