// Command-line tests of `strangebeta study` (analyze, simulate, instrument).
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "cli/cli_test_util.h"
#include "cli/commands.h"
#include "studies/analysis.h"
#include "studies/simulate.h"

namespace sb::cli {
namespace {

class StudyCli : public CliFixture {
 protected:
  std::string Slurp(const std::string& name) const {
    std::ifstream in(dir_ / name);
    std::stringstream ss;
    ss << in.rdbuf();
    return ss.str();
  }
  int Run(const std::vector<std::string>& args) { return Capture(RunStudy, args); }
};

TEST_F(StudyCli, SimulateThenAnalyzeJsonIsCompleteAndByteIdentical) {
  ASSERT_EQ(Run({"simulate", "--routes", "4", "--participants", "44", "--instrument", "brc",
                 "--seed", "7", "-o", P("r.csv")}),
            0)
      << err_;
  ASSERT_EQ(Run({"analyze", "--instrument", "brc", "--responses", P("r.csv"), "--censor",
                 "--format", "json", "-o", P("a1.json"), "--boxplot", P("box.svg")}),
            0)
      << err_;
  ASSERT_EQ(Run({"analyze", "--instrument", "brc", "--responses", P("r.csv"), "--censor",
                 "--format", "json"}),
            0);
  EXPECT_EQ(out_, Slurp("a1.json"));
  auto j = nlohmann::json::parse(out_);
  EXPECT_EQ(j["rows"], 176);
  EXPECT_EQ(j["routes"].size(), 4u);
  EXPECT_EQ(j["pairs"].size(), 6u);
  EXPECT_EQ(j["censoring"], "rule");
  EXPECT_TRUE(j["kendall_w"]["w"].is_number());
  EXPECT_EQ(j["correlations"].size(), 3u);
  // The CLI prints exactly what the library computes (the web pages will too).
  studies::SimulationParams p;
  p.seed = 7;
  auto table = studies::Simulate(studies::BrcInstrument(), p);
  auto lib = studies::Analyze(studies::BrcInstrument(), table.value(), {{}, true});
  EXPECT_EQ(out_, studies::AnalysisToJson(lib.value()));
  EXPECT_EQ(Slurp("box.svg").rfind("<?xml", 0), 0u);
  ASSERT_EQ(Run({"analyze", "--responses", P("r.csv"), "--drop", "q1,q9"}), 0) << err_;
  EXPECT_NE(out_.find("owner: dropped q1,q9"), std::string::npos) << out_;
}

TEST_F(StudyCli, InstrumentFilesWorkAndBadOnesExitTwoWithFileLine) {
  Write("i.json", R"({"name": "Mini", "scale": [1, 3], "items": [
      {"id": "fun", "text": "Fun", "negative": false},
      {"id": "awk", "text": "Awkward", "negative": true}]})");
  Write("r.csv", "participant,route,fun,awk\na,1,3,1\nb,1,2,2\na,2,1,3\nb,2,2,1\n");
  ASSERT_EQ(Run({"analyze", "--instrument", P("i.json"), "--responses", P("r.csv")}), 0) << err_;
  EXPECT_NE(out_.find("instrument: Mini, scale [1, 3]"), std::string::npos);
  ASSERT_EQ(Run({"instrument", P("i.json")}), 0);
  EXPECT_NE(out_.find("\"awk\""), std::string::npos);

  Write("bad.json", "{\"name\": \"x\",\n \"scale\": [1, 3],\n \"items\": [,]}");
  EXPECT_EQ(Run({"analyze", "--instrument", P("bad.json"), "--responses", P("r.csv")}), 2);
  EXPECT_NE(err_.find(P("bad.json") + ":3:"), std::string::npos) << err_;
  Write("bad2.json", R"({"name": "x", "scale": [1, 3], "items": [{"id": "a"}]})");
  EXPECT_EQ(Run({"instrument", P("bad2.json")}), 2);
  EXPECT_NE(err_.find(P("bad2.json") + ": items[0].text: missing or not a string"),
            std::string::npos)
      << err_;
  EXPECT_EQ(Run({"instrument", P("missing.json")}), 2);
}

TEST_F(StudyCli, MalformedResponsesExitTwoNamingFileAndLine) {
  Write("r.csv", "participant,route,q1,q2,q3,q4,q5\na,1,1,2,3,4,5\nb,1,1,2,9,4,5\n");
  EXPECT_EQ(Run({"analyze", "--instrument", "pilot", "--responses", P("r.csv")}), 2);
  EXPECT_EQ(err_, "strangebeta study: " + P("r.csv") +
                      ":3: item q3: answer 9 outside the scale [1, 5]\n");
  Write("stuffed.csv",
        "participant,route,q1,q2,q3,q4,q5\na,1,1,2,3,4,5\nb,1,1,2,3,4,5\na,1,5,5,5,5,5\n");
  EXPECT_EQ(Run({"analyze", "--instrument", "pilot", "--responses", P("stuffed.csv")}), 2);
  EXPECT_EQ(err_, "strangebeta study: " + P("stuffed.csv") +
                      ":4: participant \"a\" answered route \"1\" twice (first on line 2)\n");
  EXPECT_EQ(Run({"analyze", "--instrument", "pilot", "--responses", P("nope.csv")}), 2);
  Write("ok.csv", "participant,route,q1,q2,q3,q4,q5\na,1,1,2,3,4,5\n");
  EXPECT_EQ(Run({"analyze", "--instrument", "pilot", "--responses", P("ok.csv"), "--drop", "q7"}),
            2);
  EXPECT_NE(err_.find("drop: \"q7\" is not an item"), std::string::npos) << err_;
  EXPECT_EQ(Run({"analyze", "--instrument", "pilot", "--responses", P("ok.csv"), "--drop", "q1",
                 "--censor"}),
            2);
  EXPECT_EQ(Run({"analyze", "--responses", P("ok.csv"), "--format", "xml"}), 2);
  EXPECT_EQ(Run({"simulate", "--routes", "0"}), 2);
  EXPECT_NE(err_.find("--routes: need 1-50"), std::string::npos) << err_;
  EXPECT_EQ(Run({"simulate", "--quality", "1,x"}), 2);
}

}  // namespace
}  // namespace sb::cli
