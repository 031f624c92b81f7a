#include "language/grammar.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <map>

#include "language/parser.h"

namespace sb::language {
namespace {

const char kFrames[] = "Frame: F\nElements:\n\t[Top]\n;\n";

Result<std::shared_ptr<const Grammar>> Load(const std::string& gra,
                                            const std::string& frames = kFrames) {
  return Grammar::FromText(gra, "t.gra", frames, "t.frames");
}

// The error message of loading `gra`, or "" when it loads.
std::string Error(const std::string& gra, const std::string& frames = kFrames) {
  auto r = Load(gra, frames);
  return r.ok() ? std::string() : r.status().message();
}

std::string Phoenix(const std::shared_ptr<const Grammar>& g, const std::string& text) {
  Parser p(g);
  std::string out;
  p.AppendPhoenix(text, &out);
  return out;
}

TEST(GrammarTest, NetsRulesWordsAndCalls) {
  auto g = Load(
      "# a comment line\n"
      "[Top]\n"
      "\t([Sub] b)   # trailing comment\n"
      "\t(c)\n"
      ";\n"
      "[Sub]\n"
      "\t(a)\n"
      ";\n");
  ASSERT_TRUE(g.ok()) << g.status().message();
  const Grammar& gr = **g;
  ASSERT_EQ(gr.NetIndex("Top"), 0);
  ASSERT_EQ(gr.NetIndex("Sub"), 1);
  EXPECT_EQ(gr.NetIndex("Nope"), -1);
  EXPECT_EQ(gr.nets()[0].rules.size(), 2u);
  EXPECT_GE(gr.WordId("a"), 0);
  EXPECT_GE(gr.WordId("b"), 0);
  EXPECT_EQ(gr.WordId("comment"), -1);  // comments are not vocabulary
  ASSERT_EQ(gr.frames().size(), 1u);
  EXPECT_EQ(gr.frames()[0].name, "F");
  EXPECT_EQ(Phoenix(*g, "a b"), ";;; a b\nPARSE_0:\nF:[Top].[Sub].a b \nEND_PARSE\n\n");
}

TEST(GrammarTest, OptionalRepeatAndZeroOrMore) {
  auto g = Load(
      "[Top]\n"
      "\t(*x y +z +*w)\n"
      ";\n");
  ASSERT_TRUE(g.ok()) << g.status().message();
  const RuleElem* e = g.value()->nets()[0].rules[0].elems.data();
  EXPECT_TRUE(e[0].optional && !e[0].repeat);
  EXPECT_TRUE(!e[1].optional && !e[1].repeat);
  EXPECT_TRUE(!e[2].optional && e[2].repeat);
  EXPECT_TRUE(e[3].optional && e[3].repeat);
  auto slot = [&](const std::string& text) {
    Parser p(*g);
    ParseResult r = p.Parse(text);
    if (!r.ok() || r.parses[0].slots.size() != 1) return std::string("none");
    return PhoenixSlotString(r.parses[0].slots[0].tree);
  };
  EXPECT_EQ(slot("y z"), "[Top].y z ");
  EXPECT_EQ(slot("x y z z z"), "[Top].x y z z z ");
  EXPECT_EQ(slot("y z w w"), "[Top].y z w w ");
  EXPECT_EQ(slot("x y"), "none");  // + needs one z
}

TEST(GrammarTest, MacrosAreLocalAndPrintedInline) {
  auto g = Load(
      "[Top]\n"
      "\t(SIZE [Thing])\n"
      "SIZE\n"
      "\t(big)\n"
      "\t(very SIZE2)\n"
      "SIZE2\n"
      "\t(big)\n"
      ";\n"
      "[Thing]\n"
      "\t(jug)\n"
      "SIZE\n"
      "\t(other)\n"
      ";\n");
  ASSERT_TRUE(g.ok()) << g.status().message();
  EXPECT_EQ(Phoenix(*g, "very big jug"),
            ";;; very big jug\nPARSE_0:\nF:[Top].very big [Thing].jug \nEND_PARSE\n\n");
  // [Thing]'s own SIZE macro is a different one.
  EXPECT_EQ(Phoenix(*g, "other jug"), ";;; other jug\nNo parse\n")
      << "'other' belongs to [Thing].SIZE only, and [Thing] is not a slot net";
}

TEST(GrammarTest, IncludeReadsAnotherFile) {
  namespace fs = std::filesystem;
  fs::path dir = fs::temp_directory_path() / ("sb_lang_inc_" + std::to_string(::getpid()));
  fs::create_directories(dir / "sub");
  std::ofstream(dir / "main.gra") << "[Top]\n\t([Inc])\n;\n#include sub/inc.gra\n";
  std::ofstream(dir / "sub" / "inc.gra") << "[Inc]\n\t(hello)\n;\n";
  std::ofstream(dir / "frames") << kFrames;
  auto g = Grammar::Load((dir / "main.gra").string(), (dir / "frames").string());
  ASSERT_TRUE(g.ok()) << g.status().message();
  EXPECT_GE(g.value()->WordId("hello"), 0);
  std::ofstream(dir / "bad.gra") << "[Top]\n\t(a)\n;\n#include missing.gra\n";
  auto bad = Grammar::Load((dir / "bad.gra").string(), (dir / "frames").string());
  ASSERT_FALSE(bad.ok());
  EXPECT_NE(bad.status().message().find("bad.gra:4:1: cannot #include missing.gra"),
            std::string::npos)
      << bad.status().message();
  std::ofstream(dir / "err.gra") << "[Inc2]\n\t(x\n;\n";
  std::ofstream(dir / "top2.gra") << "[Top]\n\t([Inc2])\n;\n#include err.gra\n";
  auto err = Grammar::Load((dir / "top2.gra").string(), (dir / "frames").string());
  ASSERT_FALSE(err.ok());
  EXPECT_NE(err.status().message().find("err.gra:2:2: unbalanced parenthesis"), std::string::npos)
      << err.status().message();
  auto missing = Grammar::Load((dir / "nope.gra").string(), (dir / "frames").string());
  EXPECT_EQ(missing.status().code(), Status::Code::kNotFound);
  fs::remove_all(dir);
}

TEST(GrammarTest, FramesFileForms) {
  const std::string gra = "[A]\n\t(a)\n;\n[B]\n\t(b)\n;\n";
  auto g = Load(gra, "# frames\nFRAME: One\nNETS:\n\t[A]\n\t[B]\n;\nFrame: Two\n\t[B]\n;\n");
  ASSERT_TRUE(g.ok()) << g.status().message();
  ASSERT_EQ(g.value()->frames().size(), 2u);
  EXPECT_EQ(g.value()->frames()[1].name, "Two");
  ASSERT_EQ(g.value()->slot_nets().size(), 3u);  // [B] fills slots of both frames
  EXPECT_EQ(Phoenix(*g, "a"), ";;; a\nPARSE_0:\nOne:[A].a \nEND_PARSE\n\n");
}

TEST(GrammarTest, ErrorsNameFileLineAndColumn) {
  std::map<std::string, std::string> cases = {
      {"[Top]\n\t([Nope])\n;\n", "t.gra:2:3: undefined net [Nope]"},
      {"[Top]\n\t(MAC)\n;\n", "t.gra:2:3: undefined macro MAC in [Top]"},
      {"[Top]\n\t(a b\n;\n", "t.gra:2:2: unbalanced parenthesis: rule has no ')'"},
      {"[Top]\n\t(a (b))\n;\n", "t.gra:2:5: unbalanced parenthesis: nested '('"},
      {"[Top]\n\t(a)\n\t)\n;\n", "t.gra:3:2: unbalanced parenthesis: ')' without '('"},
      {"(a)\n", "t.gra:1:1: rule outside a net"},
      {"[Top]\n\t(a)\n", "t.gra:2:1: net [Top] is not closed with ';' at end of file"},
      {"[Top]\n\t(a)\n[B]\n\t(b)\n;\n", "t.gra:3:1: net [Top] is not closed with ';' before [B]"},
      {"[Top]\n\t(a)\n;\n[Top]\n\t(b)\n;\n", "t.gra:4:1: net [Top] already defined at t.gra:1"},
      {"[Top]\n;\n", "t.gra:2:1: [Top] has no rules"},
      {"[Top]\n\t()\n;\n", "t.gra:2:2: empty rule '()'"},
      {"[Top]\n\t(*)\n;\n", "t.gra:2:3: operator without a token"},
      {"[Top]\n\t([A] x)\n;\n[A]\n\t([Top] y)\n;\n",
       "left recursion the parser cannot handle: [Top] -> [A] -> [Top]"},
      {"[Top]\n\t(*a [Top] b)\n;\n",
       "t.gra:1:1: left recursion the parser cannot handle: [Top] -> [Top]"},
      {";\n", "t.gra:1:1: ';' outside a net"},
      {"[Top]\n\t(a)\nfoo bar\n;\n", "t.gra:3:1: unexpected text 'foo bar'"},
      {"[Top\n", "t.gra:1:1: net name without ']'"},
      {"[Top]\n\t([A b)\n;\n", "t.gra:2:3: bad net call '[A'"},
  };
  for (const auto& [gra, want] : cases) {
    std::string got = Error(gra);
    EXPECT_NE(got.find(want), std::string::npos) << "grammar:\n"
                                                 << gra << "got:  " << got << "\nwant: " << want;
  }
  // Right recursion is fine.
  EXPECT_EQ(Error("[Top]\n\t(not [Top])\n\t(big)\n;\n"), "");
}

TEST(GrammarTest, FrameErrors) {
  const std::string gra = "[Top]\n\t(a)\n;\n";
  std::map<std::string, std::string> cases = {
      {"Frame: F\n\t[Nope]\n;\n", "t.frames:2:2: frame F names undefined net [Nope]"},
      {"Frame: F\n;\n", "t.frames:2:1: frame F has no nets"},
      {"Frame: F\n\t[Top]\n", "t.frames:2:1: frame F is not closed with ';' at end of file"},
      {"[Top]\n", "t.frames:1:1: net outside a frame"},
      {"", "t.frames:1:1: no frames defined"},
      {"Frame: F\n\t[Top]\nFrame: G\n", "t.frames:3:1: frame F is not closed with ';'"},
      {"Frame: F\n\t[Top]\n;\nFrame: F\n\t[Top]\n;\n", "t.frames:4:1: frame F defined twice"},
      {"Frame:\n", "t.frames:1:1: frame without a name"},
      {"Frame: F\n\twhat\n;\n", "t.frames:2:2: unexpected text 'what'"},
  };
  for (const auto& [frames, want] : cases) {
    std::string got = Error(gra, frames);
    EXPECT_NE(got.find(want), std::string::npos) << "frames:\n"
                                                 << frames << "got:  " << got << "\nwant: " << want;
  }
}

TEST(GrammarTest, ShippedGrammarLoads) {
  std::string dir = std::string(SB_SOURCE_DIR) + "/data/grammar";
  auto g = Grammar::Load(dir + "/climbing.gra", dir + "/frames");
  ASSERT_TRUE(g.ok()) << g.status().message();
  EXPECT_GE(g.value()->NetIndex("Move"), 0);
  // Function words stay out of the vocabulary so they never break a phrase.
  for (const char* w : {"to", "on", "the", "a", "and", "with", "into", "onto", "of", "for"}) {
    EXPECT_EQ(g.value()->WordId(w), -1) << w;
  }
}

}  // namespace
}  // namespace sb::language

namespace sb::language {
namespace {

// [N0] calls [N1] calls ... [N(n-1)], each net also matching its own word.
std::string Chain(int n) {
  std::string gra;
  for (int i = 0; i < n; ++i) {
    gra += "[" + std::string(i == 0 ? "Top" : "N" + std::to_string(i)) + "]\n";
    if (i + 1 < n) gra += "\t([N" + std::to_string(i + 1) + "])\n";
    gra += "\t(w" + std::to_string(i) + ")\n;\n";
  }
  return gra;
}

TEST(GrammarLimitsTest, LongChainsLoadInOnePassAndParse) {
  // FIRST sets by one pass over the left-call DAG: a 1,500-net chain with
  // 1,500 words used to need 1,500 fixpoint rounds over every net and word.
  auto g = Load(Chain(1500));
  ASSERT_TRUE(g.ok()) << g.status().message();
  const Grammar& gr = **g;
  EXPECT_TRUE(gr.CanStartWith(0, gr.WordId("w1499")));
  EXPECT_TRUE(gr.CanStartWith(1498, gr.WordId("w1499")));
  EXPECT_FALSE(gr.CanStartWith(1499, gr.WordId("w0")));
  EXPECT_GT(gr.max_parse_depth(), 3000);
  EXPECT_LE(gr.max_parse_depth(), kMaxParseDepth);
  std::string out = Phoenix(*g, "w1499");
  EXPECT_EQ(out.find(";;; w1499\nPARSE_0:\nF:[Top].[N1].[N2]."), 0u) << out.substr(0, 200);
  EXPECT_NE(out.find("[N1499].w1499 \nEND_PARSE"), std::string::npos);
}

TEST(GrammarLimitsTest, TooDeepNestingIsAnErrorNotAStackOverflow) {
  // 10,000 nets deep overflowed the parser's stack; now the load refuses it.
  std::string err = Error(Chain(10000));
  EXPECT_EQ(err.find("t.gra:1:1: nets nest too deep: a line of 64 words can take the parser "), 0u)
      << err;
  EXPECT_NE(err.find("(limit 4096): [Top] -> [N1] -> [N2]"), std::string::npos) << err;
  EXPECT_NE(err.find("-> [N9999]"), std::string::npos) << err;
  // Right recursion counts every word a line can feed it: a net that
  // re-enters itself after each word, through 40 nets, is too deep for
  // 64 words (40 x 64 x 2 frames) although its static chain is short.
  std::string gra = "[Top]\n\t(w *[N1])\n;\n";
  for (int i = 1; i < 40; ++i) {
    gra += "[N" + std::to_string(i) + "]\n\t([" +
           (i + 1 < 40 ? "N" + std::to_string(i + 1) : "Top") + "])\n;\n";
  }
  err = Error(gra);
  EXPECT_NE(err.find("nets nest too deep"), std::string::npos) << err;
  // The same loop through 10 nets is fine.
  gra = "[Top]\n\t(w *[N1])\n;\n";
  for (int i = 1; i < 10; ++i) {
    gra += "[N" + std::to_string(i) + "]\n\t([" +
           (i + 1 < 10 ? "N" + std::to_string(i + 1) : "Top") + "])\n;\n";
  }
  EXPECT_EQ(Error(gra), "");
}

TEST(GrammarLimitsTest, RecursionCheckIsIterative) {
  // A left-recursive cycle through 9,000 nets (the recursive check
  // overflowed at 30,000): found without recursion, reported from its
  // lowest net.
  std::string gra;
  for (int i = 0; i < 9000; ++i) {
    gra += "[" + std::string(i == 0 ? "Top" : "N" + std::to_string(i)) + "]\n\t([" +
           (i + 1 < 9000 ? "N" + std::to_string(i + 1) : "Top") + "] x)\n;\n";
  }
  std::string err = Error(gra);
  EXPECT_EQ(err.find("t.gra:1:1: left recursion the parser cannot handle: [Top] -> [N1] -> "), 0u)
      << err.substr(0, 300);
  EXPECT_NE(err.find("[N8999] -> [Top]"), std::string::npos) << err.substr(0, 300);
}

TEST(GrammarLimitsTest, CountsAndSizesAreLimited) {
  // Nets.
  std::string many;
  for (size_t i = 0; i <= kMaxNets; ++i) many += "[N" + std::to_string(i) + "]\n\t(a)\n;\n";
  EXPECT_EQ(Error(many).find("t.gra:" + std::to_string(3 * kMaxNets + 1) +
                             ":1: more than 10000 nets and macros (limit)"),
            0u)
      << Error(many);
  // Elements per rule.
  std::string rule = "[Top]\n\t(";
  for (size_t i = 0; i <= kMaxRuleElements; ++i) rule += "a ";
  rule += ")\n;\n";
  EXPECT_NE(Error(rule).find("t.gra:2:131: rule has more than 64 elements (limit)"),
            std::string::npos)
      << Error(rule);
  // Bytes, includes counted each time they are read: a file including
  // itself twice per level would read 2^16 copies.
  auto self = [](const std::string&,
                 const std::string&) -> Result<std::pair<std::string, std::string>> {
    return std::make_pair(std::string(300000, '#') + "\n#include self\n#include self\n",
                          std::string("self"));
  };
  auto r =
      Grammar::FromText("#include self\n[Top]\n\t(a)\n;\n", "t.gra", kFrames, "t.frames", self);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.status().message().find("larger than 4194304 bytes (limit)"), std::string::npos)
      << r.status().message();
  // Include depth.
  auto deep = [](const std::string&,
                 const std::string&) -> Result<std::pair<std::string, std::string>> {
    return std::make_pair(std::string("#include again\n"), std::string("again"));
  };
  r = Grammar::FromText("#include again\n", "t.gra", kFrames, "t.frames", deep);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.status().message(), "again:1:1: #include nested more than 16 deep (limit)");
  // Slot nets.
  std::string nets, frames = "Frame: F\n";
  for (size_t i = 0; i <= kMaxSlotNets; ++i) {
    nets += "[" + std::string(i == 0 ? "Top" : "N" + std::to_string(i)) + "]\n\t(a)\n;\n";
    frames += "\t[" + std::string(i == 0 ? "Top" : "N" + std::to_string(i)) + "]\n";
  }
  frames += ";\n";
  EXPECT_EQ(Error(nets, frames), "t.frames:1:1: frames list 257 slots, more than 256 (limit)");
}

TEST(GrammarLimitsTest, EndlessFilesAreRefusedWhileReading) {
  auto r = Grammar::Load("/dev/zero", "/dev/zero");
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.status().message(), "/dev/zero:1:1: grammar file larger than 4194304 bytes (limit)");
}

}  // namespace
}  // namespace sb::language
