// Command-line tests of `strangebeta graph`: train on token files (errors
// name file:line:col), interpolate (text and JSON, the cost summed over
// every transition), damaged graph files, climbing routes.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "cli/cli_test_util.h"
#include "cli/commands.h"
#include "graph/graph.h"
#include "graph/search.h"

namespace sb::cli {
namespace {

class GraphCli : public CliFixture {
 protected:
  int Run(const std::vector<std::string>& args) { return Capture(RunGraph, args); }
};

// A melody as pitch|duration tokens, one phrase a line.
const char kMelody[] =
    "C4|q D4|q E4|q F4|q G4|h E4|q C4|q\n"
    "G4|q F4|q E4|q D4|q C4|h D4|q E4|q\n"
    "E4|q F4|q G4|h A4|q G4|q F4|q E4|h\n"
    "C4|h E4|q G4|q C5|h B4|q A4|q G4|h\n";

TEST_F(GraphCli, TrainAndInterpolateAMelody) {
  Write("melody.tok", kMelody);
  ASSERT_EQ(Run({"train", "--out", P("m.sbg"), "--influence", "learn", P("melody.tok")}), 0)
      << err_;
  ASSERT_EQ(Run({"interpolate", "--graph", P("m.sbg"), "--from", "C4|q", "--to", "C5|h", "--format",
                 "json"}),
            0)
      << err_;
  const auto j = nlohmann::json::parse(out_);
  ASSERT_TRUE(j["found"].get<bool>());
  const auto inserted = j["inserted"].get<std::vector<std::string>>();
  // The cost is every transition's weight from --from through the inserted
  // states to --to.
  auto g = graph::LoadGraph(P("m.sbg"));
  ASSERT_TRUE(g.ok());
  std::vector<std::string> path = {"C4|q"};
  path.insert(path.end(), inserted.begin(), inserted.end());
  path.push_back("C5|h");
  double cost = 0;
  for (size_t i = 0; i + 1 < path.size(); ++i) {
    auto a = g->Encode(*graph::ParseToken(path[i], 2, "a"), "a");
    auto b = g->Encode(*graph::ParseToken(path[i + 1], 2, "b"), "b");
    cost += graph::TransitionCost(*g, *a, *b);
  }
  EXPECT_NEAR(j["cost"].get<double>(), cost, 1e-12);
  EXPECT_GT(j["expanded"].get<uint64_t>(), 0u);
  // Greedy is never cheaper; the text format lists the same states.
  ASSERT_EQ(Run({"interpolate", "--graph", P("m.sbg"), "--from", "C4|q", "--to", "C5|h", "--greedy",
                 "--format", "json"}),
            0);
  EXPECT_GE(nlohmann::json::parse(out_)["cost"].get<double>(), cost - 1e-12);
  ASSERT_EQ(Run({"interpolate", "--graph", P("m.sbg"), "--from", "C4|q", "--to", "C5|h"}), 0);
  for (const auto& s : inserted) EXPECT_NE(out_.find(s), std::string::npos) << out_;
  // No path within the length: exit 1 and the reason.
  EXPECT_EQ(Run({"interpolate", "--graph", P("m.sbg"), "--from", "C4|q", "--to", "C5|h",
                 "--max-length", "0"}),
            1);
  EXPECT_NE(out_.find("no interpolation"), std::string::npos) << out_;
  ASSERT_EQ(Run({"info", "--graph", P("m.sbg")}), 0);
  EXPECT_NE(out_.find("features 2"), std::string::npos) << out_;
}

TEST_F(GraphCli, InputErrorsNameTheirPlace) {
  Write("bad.tok", "a|b c|d\ne|f g\n");
  EXPECT_EQ(Run({"train", "--out", P("g.sbg"), P("bad.tok")}), 2);
  EXPECT_NE(err_.find(P("bad.tok") + ":2:5:"), std::string::npos) << err_;
  EXPECT_FALSE(std::filesystem::exists(P("g.sbg")));
  Write("ok.tok", "a|b c|d\n");
  Write("infl.txt", "2 1\n3 1\n");
  EXPECT_EQ(Run({"train", "--out", P("g.sbg"), "--influence", P("infl.txt"), P("ok.tok")}), 2);
  EXPECT_NE(err_.find(P("infl.txt") + ":2:"), std::string::npos) << err_;
  ASSERT_EQ(Run({"train", "--out", P("g.sbg"), P("ok.tok")}), 0) << err_;
  EXPECT_EQ(Run({"interpolate", "--graph", P("g.sbg"), "--from", "a|x", "--to", "c|d"}), 2);
  EXPECT_NE(err_.find("value 'x' of feature 2 never occurs"), std::string::npos) << err_;
  EXPECT_EQ(Run({"interpolate", "--graph", P("g.sbg"), "--from", "a|b", "--to", "c|d",
                 "--memory-mb", "0"}),
            2);
  EXPECT_EQ(Run({"interpolate", "--graph", P("g.sbg"), "--from", "a|b", "--to", "c|d",
                 "--max-length", "1001"}),
            2);
  // A damaged graph file.
  std::string bytes;
  {
    std::ifstream in(P("g.sbg"), std::ios::binary);
    std::stringstream ss;
    ss << in.rdbuf();
    bytes = ss.str();
  }
  Write("cut.sbg", bytes.substr(0, bytes.size() / 2));
  EXPECT_EQ(Run({"info", "--graph", P("cut.sbg")}), 2);
  EXPECT_NE(err_.find("truncated"), std::string::npos) << err_;
  EXPECT_EQ(Run({"nonsense"}), 2);
  EXPECT_EQ(Run({"--help"}), 0);
  for (const char* sub : {"train", "interpolate", "info", "tokens", "evaluate"}) {
    EXPECT_NE(out_.find(sub), std::string::npos) << sub;
  }
}

TEST_F(GraphCli, ClimbingRoutes) {
  const std::string ex = std::string(SB_SOURCE_DIR) + "/data/examples/";
  ASSERT_EQ(Run({"train", "--out", P("c.sbg"), "--influence", "learn", "--routes",
                 ex + "crimp-ladder.crdl", ex + "roof-jugs.crdl", ex + "slab-dance.crdl"}),
            0)
      << err_;
  auto g = graph::LoadGraph(P("c.sbg"));
  ASSERT_TRUE(g.ok());
  EXPECT_EQ(g->num_features(), 9);
  EXPECT_EQ(g->metadata().at("tokens"), "climbing");
  ASSERT_EQ(Run({"tokens", "--routes", ex + "crimp-ladder.crdl"}), 0);
  EXPECT_EQ(out_.substr(0, out_.find(' ')), "R|none|none|crimp|small|none|no|no|no");
  ASSERT_EQ(Run({"tokens", "--readable", "--routes", ex + "crimp-ladder.crdl"}), 0);
  EXPECT_EQ(out_.substr(0, out_.find('\n')), "R small crimp");
}

}  // namespace
}  // namespace sb::cli
