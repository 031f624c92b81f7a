// Command-line tests of `strangebeta parse` and `strangebeta symbols`: a small
// Phoenix grammar written here (with a macro and an #include), the exact
// --phoenix output, JSON, the four symbol columns, the default grammar,
// grammar errors and help; and, when ../shared is present, Phoenix
// compatibility on a prefix of the public reference parses.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "base/files.h"
#include "cli/cli_test_util.h"
#include "cli/commands.h"

namespace sb::cli {
namespace {

// Symbolizer-compatible net names (src/language/symbols.h). [HoldTypeT]
// uses the macro NUM; the hold nets come from an #include'd file.
const char kGra[] =
    "# A small move grammar for the CLI tests.\n"
    "[Move]\n"
    "\t([Action] [Hold])\n"
    "\t([Hold] [Action])\n"
    "\t([Hold])\n"
    "\t([Match])\n"
    ";\n"
    "[Match]\n"
    "\t(match)\n"
    ";\n"
    "[Action]\n"
    "\t([ActionVerb])\n"
    ";\n"
    "[ActionVerb]\n"
    "\t([ActionVerbBig])\n"
    "\t([ActionVerbSmall])\n"
    ";\n"
    "[ActionVerbBig]\n"
    "\t(dyno)\n"
    "\t(big move)\n"
    ";\n"
    "[ActionVerbSmall]\n"
    "\t(reach)\n"
    "\t(move)\n"
    ";\n"
    "#include holds.gra\n";

const char kHolds[] =
    "[Hold]\n"
    "\t(*[HoldSize] [HoldType])\n"
    ";\n"
    "[HoldSize]\n"
    "\t([HoldSizeBig])\n"
    "\t([HoldSizeSmall])\n"
    ";\n"
    "[HoldSizeBig]\n"
    "\t(big)\n"
    ";\n"
    "[HoldSizeSmall]\n"
    "\t(small)\n"
    ";\n"
    "[HoldType]\n"
    "\t([HoldTypeT])\n"
    ";\n"
    "[HoldTypeT]\n"
    "\t(jug)\n"
    "\t(crimp)\n"
    "\t(NUM finger pocket)\n"
    "NUM\n"
    "\t(two)\n"
    "\t(three)\n"
    ";\n";

const char kFrames[] = "# one frame\nFrame: IsMove\nElements:\n\t[Move]\n;\n";

// Input lines and exactly what Phoenix prints for each of them.
const char kMovesIn[] =
    "dyno to big jug\n"
    "reach the two finger pocket\n"
    "jug big move crimp\n"
    "hello world\n"
    "R Big Jug\n"
    "match\n";

const char kPhoenixOut[] =
    ";;; dyno to big jug\n"
    "PARSE_0:\n"
    "IsMove:[Move].[Action].[ActionVerb].[ActionVerbBig].dyno [Hold].[HoldSize].[HoldSizeBig].big "
    "[HoldType].[HoldTypeT].jug \n"
    "END_PARSE\n"
    "\n"
    ";;; reach the two finger pocket\n"
    "PARSE_0:\n"
    "IsMove:[Move].[Action].[ActionVerb].[ActionVerbSmall].reach "
    "[Hold].[HoldType].[HoldTypeT].two finger pocket \n"
    "END_PARSE\n"
    "\n"
    ";;; jug big move crimp\n"
    "PARSE_0:\n"
    "IsMove:[Move].[Hold].[HoldType].[HoldTypeT].jug [Action].[ActionVerb].[ActionVerbBig].big "
    "move \n"
    "IsMove:[Move].[Hold].[HoldType].[HoldTypeT].crimp \n"
    "END_PARSE\n"
    "PARSE_1:\n"
    "IsMove:[Move].[Hold].[HoldType].[HoldTypeT].jug \n"
    "IsMove:[Move].[Action].[ActionVerb].[ActionVerbBig].big move "
    "[Hold].[HoldType].[HoldTypeT].crimp \n"
    "END_PARSE\n"
    "\n"
    ";;; hello world\n"
    "No parse\n"
    ";;; R Big Jug\n"
    "No parse\n"
    ";;; match\n"
    "PARSE_0:\n"
    "IsMove:[Move].[Match].match \n"
    "END_PARSE\n"
    "\n";

std::vector<std::string> Lines(const std::string& s) {
  std::vector<std::string> out;
  std::istringstream in(s);
  for (std::string line; std::getline(in, line);) out.push_back(line);
  return out;
}

std::vector<std::string> SplitTabs(const std::string& s) {
  std::vector<std::string> out;
  size_t b = 0;
  for (;;) {
    size_t e = s.find('\t', b);
    out.push_back(s.substr(b, e == std::string::npos ? std::string::npos : e - b));
    if (e == std::string::npos) break;
    b = e + 1;
  }
  return out;
}

class LanguageCli : public CliFixture {
 protected:
  void SetUp() override {
    CliFixture::SetUp();
    Write("moves.gra", kGra);
    Write("holds.gra", kHolds);
    Write("frames", kFrames);
    Write("moves.txt", kMovesIn);
  }

  // Runs `fn(args)` with `stdin_text` as standard input (std::cin), capturing
  // stdout into out_ and stderr into err_.
  int Run(CliCommand fn, const std::vector<std::string>& args, const std::string& stdin_text = "") {
    return Capture(fn, args, stdin_text);
  }
  int Parse(const std::vector<std::string>& args, const std::string& in = "") {
    return Run(&RunParse, args, in);
  }
  int Symbols(const std::vector<std::string>& args, const std::string& in = "") {
    return Run(&RunSymbols, args, in);
  }
  std::vector<std::string> Grammar() const {
    return {"--grammar", P("moves.gra"), "--frames", P("frames")};
  }
  std::vector<std::string> With(std::vector<std::string> a,
                                const std::vector<std::string>& more) const {
    a.insert(a.end(), more.begin(), more.end());
    return a;
  }
};

TEST_F(LanguageCli, PhoenixOutputIsExactFromStdinAndFromAFile) {
  ASSERT_EQ(Parse(With(Grammar(), {"--phoenix"}), kMovesIn), 0) << err_;
  EXPECT_EQ(out_, kPhoenixOut);
  EXPECT_EQ(err_, "");
  ASSERT_EQ(Parse(With(Grammar(), {"--phoenix", "--input", P("moves.txt")})), 0) << err_;
  EXPECT_EQ(out_, kPhoenixOut);
  // CRLF line ends read like LF.
  std::string crlf;
  for (const std::string& l : Lines(kMovesIn)) crlf += l + "\r\n";
  ASSERT_EQ(Parse(With(Grammar(), {"--phoenix"}), crlf), 0) << err_;
  EXPECT_EQ(out_, kPhoenixOut);
  // The frames file defaults to 'frames' beside the grammar.
  ASSERT_EQ(Parse({"--phoenix", "--grammar", P("moves.gra")}, kMovesIn), 0) << err_;
  EXPECT_EQ(out_, kPhoenixOut);
}

TEST_F(LanguageCli, NonMovesSayNoParse) {
  const std::string in = "hello world\nbig\n\nsmall\n";
  ASSERT_EQ(Parse(With(Grammar(), {"--phoenix"}), in), 0) << err_;
  EXPECT_EQ(out_,
            ";;; hello world\nNo parse\n;;; big\nNo parse\n;;; \nNo parse\n;;; small\nNo parse\n");
}

TEST_F(LanguageCli, FoldedModeIgnoresCaseAndPunctuation) {
  // Without --phoenix "R Big Jug!" reads as "big jug"; with it, nothing is known.
  ASSERT_EQ(Parse(With(Grammar(), {"--format", "json"}), "R Big Jug!\n"), 0) << err_;
  auto j = nlohmann::json::parse(out_);
  EXPECT_EQ(j["words"], nlohmann::json({"big", "jug"}));
  ASSERT_EQ(j["parses"].size(), 1u);
}

TEST_F(LanguageCli, JsonHasFramesSlotsNetsAndWords) {
  ASSERT_EQ(Parse(With(Grammar(), {"--format", "json"}), kMovesIn), 0) << err_;
  std::vector<std::string> lines = Lines(out_);
  ASSERT_EQ(lines.size(), 6u) << out_;
  std::vector<nlohmann::json> js;
  for (const std::string& l : lines) js.push_back(nlohmann::json::parse(l));

  const auto& a = js[0];
  EXPECT_EQ(a["text"], "dyno to big jug");
  EXPECT_EQ(a["words"], nlohmann::json({"dyno", "big", "jug"}));  // "to" is out of vocabulary
  EXPECT_EQ(a["covered"], 3);
  ASSERT_EQ(a["parses"].size(), 1u);
  ASSERT_EQ(a["parses"][0]["slots"].size(), 1u);
  const auto& slot = a["parses"][0]["slots"][0];
  EXPECT_EQ(slot["frame"], "IsMove");
  EXPECT_EQ(slot["begin"], 0);
  EXPECT_EQ(slot["end"], 3);
  EXPECT_EQ(slot["words"], nlohmann::json({"dyno", "big", "jug"}));
  EXPECT_EQ(slot["tree"]["net"], "Move");
  ASSERT_EQ(slot["tree"]["children"].size(), 2u);
  EXPECT_EQ(slot["tree"]["children"][0]["net"], "Action");
  EXPECT_EQ(slot["tree"]["children"][1]["net"], "Hold");
  // Macros never show: "two finger pocket" are three word leaves of [HoldTypeT].
  const auto& pocket = js[1]["parses"][0]["slots"][0]["tree"]["children"][1];
  EXPECT_EQ(pocket["net"], "Hold");
  EXPECT_EQ(pocket["children"][0]["net"], "HoldType");
  EXPECT_EQ(pocket["children"][0]["children"][0],
            nlohmann::json::parse(R"({"net":"HoldTypeT","children":["two","finger","pocket"]})"));
  // The tie: two parses of two slots each.
  ASSERT_EQ(js[2]["parses"].size(), 2u);
  EXPECT_EQ(js[2]["parses"][0]["slots"].size(), 2u);
  EXPECT_EQ(js[2]["parses"][1]["slots"][1]["words"], nlohmann::json({"big", "move", "crimp"}));
  // Non-moves: no parses.
  EXPECT_EQ(js[3]["parses"].size(), 0u);
  EXPECT_EQ(js[3]["covered"], 0);
  // Folded mode lower-cases: "R Big Jug" parses here.
  EXPECT_EQ(js[4]["parses"].size(), 1u);
  EXPECT_EQ(js[5]["parses"][0]["slots"][0]["tree"]["children"][0]["net"], "Match");
}

TEST_F(LanguageCli, ReadableOutputShowsReadingsAndTheSymbol) {
  ASSERT_EQ(Parse(Grammar(), "dyno to big jug\nhello world\njug big move crimp\n"), 0) << err_;
  EXPECT_NE(out_.find("dyno to big jug"), std::string::npos) << out_;
  EXPECT_NE(out_.find("    symbol: jug \u00b7 big \u00b7 big-move \u00b7 good-hold\n"),
            std::string::npos)
      << out_;
  EXPECT_NE(out_.find("no parse"), std::string::npos) << out_;
  EXPECT_NE(out_.find("reading 2"), std::string::npos) << out_;  // the tie
  // Both slots of the first reading combine into one hybrid symbol.
  EXPECT_NE(out_.find("    symbol: crimp-jug \u00b7 big-move\n"), std::string::npos) << out_;
}

TEST_F(LanguageCli, SymbolsPrintFourColumnsAndNoParse) {
  ASSERT_EQ(Symbols(With(Grammar(), {"--phoenix"}), kMovesIn), 0) << err_;
  std::vector<std::string> lines = Lines(out_);
  ASSERT_EQ(lines.size(), 6u) << out_;
  std::vector<std::vector<std::string>> cols;
  for (const std::string& l : lines) {
    cols.push_back(SplitTabs(l));
    ASSERT_EQ(cols.back().size(), 4u) << l;
  }
  const std::string jug = "[HoldType].[HoldTypeT].jug";
  const std::string big = "[HoldSize].[HoldSizeBig].big";
  EXPECT_EQ(cols[0], (std::vector<std::string>{jug, jug + ":" + big + ":", jug + ":BIG+GOOD",
                                               jug + ":" + big + "::BIG+GOOD"}));
  const std::string pocket = "[HoldType].[HoldTypeT].two";  // first word of a multi-word type
  EXPECT_EQ(cols[1], (std::vector<std::string>{pocket, pocket + "::", pocket, pocket + "::"}));
  // Hybrid of both slots of PARSE_0, types sorted; "big move" is a big move.
  const std::string cj = "[HoldType].[HoldTypeT].crimp.[HoldType].[HoldTypeT].jug";
  EXPECT_EQ(cols[2], (std::vector<std::string>{cj, cj + "::", cj + ":BIG", cj + ":::BIG"}));
  for (int i : {3, 4}) {
    EXPECT_EQ(cols[i], (std::vector<std::string>(4, "NO_PARSE"))) << lines[i];
  }
  const std::string m = "[HoldType].[Match]";
  EXPECT_EQ(cols[5], (std::vector<std::string>{m, m + "::", m, m + "::"}));

  // Folded mode (default) reads "R Big Jug"; a file input gives the same as stdin.
  ASSERT_EQ(Symbols(With(Grammar(), {"--input", P("moves.txt")})), 0) << err_;
  std::vector<std::string> folded = Lines(out_);
  ASSERT_EQ(folded.size(), 6u);
  EXPECT_EQ(folded[3], "NO_PARSE\tNO_PARSE\tNO_PARSE\tNO_PARSE");
  EXPECT_EQ(SplitTabs(folded[4])[1], jug + ":" + big + ":");
}

TEST_F(LanguageCli, SymbolsReadableForm) {
  ASSERT_EQ(Symbols(With(Grammar(), {"--format", "readable"}),
                    "dyno to big jug\nhello\njug big move crimp\nmatch\n"),
            0)
      << err_;
  EXPECT_EQ(out_,
            "jug \u00b7 big \u00b7 big-move \u00b7 good-hold\n"
            "no parse\n"
            "crimp-jug \u00b7 big-move\n"
            "match\n");
}

TEST_F(LanguageCli, DefaultGrammarReadsEverydayMoves) {
  // No --grammar: the project's grammar (data/grammar), folded tokenization.
  ASSERT_EQ(Symbols({"--format", "readable"}, "R big crimp\nL small sloper\nthe end of the day\n"),
            0)
      << err_;
  std::vector<std::string> lines = Lines(out_);
  ASSERT_EQ(lines.size(), 3u) << out_;
  EXPECT_EQ(lines[0].rfind("crimp \u00b7 big", 0), 0u) << lines[0];
  EXPECT_EQ(lines[1].rfind("sloper \u00b7 small", 0), 0u) << lines[1];
  EXPECT_EQ(lines[2], "no parse");

  ASSERT_EQ(Symbols({}, "R big crimp\n"), 0) << err_;
  std::vector<std::string> cols = SplitTabs(Lines(out_).at(0));
  ASSERT_EQ(cols.size(), 4u);
  EXPECT_EQ(cols[0], "[HoldType].[Crimp]");
  EXPECT_NE(cols[0], "NO_PARSE");
  EXPECT_NE(cols[1].find("[HoldSize]"), std::string::npos) << cols[1];

  ASSERT_EQ(Parse({"--format", "json"}, "R big crimp\n"), 0) << err_;
  auto j = nlohmann::json::parse(out_);
  ASSERT_GE(j["parses"].size(), 1u);
  EXPECT_EQ(j["parses"][0]["slots"][0]["frame"], "IsMove");
  ASSERT_EQ(Parse({"--phoenix"}, "R big crimp\n"), 0) << err_;
  EXPECT_EQ(out_.rfind(";;; R big crimp\nPARSE_0:\nIsMove:[Move].", 0), 0u) << out_;
}

TEST_F(LanguageCli, GrammarErrorsExitTwoWithFileAndLine) {
  Write("undef.gra", "# comment\n[Move]\n\t([Hold])\n\t([Nope] jug)\n;\n[Hold]\n\t(jug)\n;\n");
  for (auto fn : {&RunParse, &RunSymbols}) {
    EXPECT_EQ(Run(fn, {"--grammar", P("undef.gra"), "--frames", P("frames")}, "jug\n"), 2);
    EXPECT_NE(err_.find(P("undef.gra") + ":4:"), std::string::npos) << err_;
    EXPECT_NE(err_.find("undefined net [Nope]"), std::string::npos) << err_;
    EXPECT_EQ(out_, "");
  }
  Write("paren.gra", "[Move]\n\t(jug\n;\n");
  for (auto fn : {&RunParse, &RunSymbols}) {
    EXPECT_EQ(Run(fn, {"--grammar", P("paren.gra"), "--frames", P("frames")}, "jug\n"), 2);
    EXPECT_NE(err_.find(P("paren.gra") + ":2:"), std::string::npos) << err_;
    EXPECT_EQ(out_, "");
  }
  Write("stray.gra", "[Move]\n\t(jug))\n;\n");
  EXPECT_EQ(Parse({"--grammar", P("stray.gra"), "--frames", P("frames")}, "jug\n"), 2);
  EXPECT_NE(err_.find(P("stray.gra") + ":2:"), std::string::npos) << err_;
  // An error inside an #include'd file names that file.
  Write("holds.gra", "[Hold]\n\t(*[HoldSize] [HoldType]\n;\n");
  EXPECT_EQ(Parse(Grammar(), "jug\n"), 2);
  EXPECT_NE(err_.find(P("holds.gra") + ":2:"), std::string::npos) << err_;
  // A frame naming an undefined net names the frames file.
  Write("frames2", "Frame: IsMove\n\t[Move]\n\t[Missing]\n;\n");
  Write("holds.gra", kHolds);
  EXPECT_EQ(Symbols({"--grammar", P("moves.gra"), "--frames", P("frames2")}, "jug\n"), 2);
  EXPECT_NE(err_.find(P("frames2") + ":3:"), std::string::npos) << err_;
  // Missing files.
  EXPECT_EQ(Parse({"--grammar", P("none.gra"), "--frames", P("frames")}, "jug\n"), 2);
  EXPECT_NE(err_.find("none.gra"), std::string::npos) << err_;
  EXPECT_EQ(Parse(With(Grammar(), {"--input", P("none.txt")})), 2);
  EXPECT_NE(err_.find("none.txt"), std::string::npos) << err_;
  EXPECT_EQ(Symbols(With(Grammar(), {"--input", P("none.txt")})), 2);
}

TEST_F(LanguageCli, BadOptionsAreUsageErrors) {
  EXPECT_EQ(Parse(With(Grammar(), {"--format", "xml"})), 2);
  EXPECT_EQ(Parse(With(Grammar(), {"--no-such-option"})), 2);
  EXPECT_EQ(Symbols(With(Grammar(), {"--format", "json"})), 2);
  EXPECT_EQ(Symbols(With(Grammar(), {"extra-positional"})), 2);
}

TEST_F(LanguageCli, HelpListsEveryOption) {
  ASSERT_EQ(Parse({"--help"}), 0);
  for (const char* opt : {"--grammar", "--frames", "--input", "--phoenix", "--format"}) {
    EXPECT_NE(out_.find(opt), std::string::npos) << "parse " << opt << "\n" << out_;
  }
  ASSERT_EQ(Symbols({"--help"}), 0);
  for (const char* opt : {"--grammar", "--frames", "--input", "--phoenix", "--format"}) {
    EXPECT_NE(out_.find(opt), std::string::npos) << "symbols " << opt << "\n" << out_;
  }
}

TEST_F(LanguageCli, OutputIsDeterministic) {
  std::string in;
  for (int i = 0; i < 50; ++i) in += kMovesIn;
  ASSERT_EQ(Parse(With(Grammar(), {"--phoenix"}), in), 0);
  const std::string first = out_;
  ASSERT_EQ(Parse(With(Grammar(), {"--phoenix"}), in), 0);
  EXPECT_EQ(out_, first);
  std::string expected;
  for (int i = 0; i < 50; ++i) expected += kPhoenixOut;
  EXPECT_EQ(first, expected);  // also across the 64 KiB output flushes
}

// The original grammar over the first 200 public moves (even route ids) must
// print exactly what Phoenix printed (../shared/peer/phoenix_parses.public.txt).
TEST_F(LanguageCli, PhoenixCompatibleOnThePublicCorpusPrefix) {
  const std::string shared = sb::FindSharedDir(SB_SHARED_DIR);
  if (shared.empty()) GTEST_SKIP() << "../shared not found (set SB_SHARED)";
  const std::string psv = shared + "/corpus/moves_sanitized.psv";
  const std::string ref_path = shared + "/peer/phoenix_parses.public.txt";
  const std::string gra = shared + "/peer/climbing.gra";
  if (!std::filesystem::exists(psv) || !std::filesystem::exists(ref_path) ||
      !std::filesystem::exists(gra)) {
    GTEST_SKIP() << "corpus or peer files missing under " << shared;
  }
  constexpr int kMoves = 200;
  std::ifstream in(psv);
  std::string moves;
  int n = 0;
  for (std::string line; n < kMoves && std::getline(in, line);) {
    // user|route|move|hand|crux|text (the text may itself hold '|').
    size_t p = 0;
    std::vector<size_t> bars;
    for (int f = 0; f < 5; ++f) {
      p = line.find('|', p);
      ASSERT_NE(p, std::string::npos) << line;
      bars.push_back(p++);
    }
    const long route = std::stol(line.substr(bars[0] + 1, bars[1] - bars[0] - 1));
    if (route % 2 != 0) continue;
    moves += line.substr(bars[4] + 1) + "\n";
    ++n;
  }
  ASSERT_EQ(n, kMoves);
  Write("corpus_moves.txt", moves);
  ASSERT_EQ(Parse({"--phoenix", "--grammar", gra, "--frames", shared + "/peer/frames", "--input",
                   P("corpus_moves.txt")}),
            0)
      << err_;
  std::ifstream rin(ref_path);
  std::stringstream ss;
  ss << rin.rdbuf();
  const std::string ref = ss.str();
  // The prefix of the reference up to the (kMoves+1)-th ";;; " block.
  size_t pos = 0;
  int blocks = 0;
  for (;;) {
    if (ref.compare(pos, 4, ";;; ") == 0 && ++blocks == kMoves + 1) break;
    pos = ref.find('\n', pos);
    if (pos == std::string::npos) break;
    ++pos;
  }
  ASSERT_EQ(blocks, kMoves + 1);
  const std::string want = ref.substr(0, pos);
  if (out_ != want) {
    // Report the first differing line.
    std::vector<std::string> a = Lines(out_), b = Lines(want);
    size_t i = 0;
    while (i < a.size() && i < b.size() && a[i] == b[i]) ++i;
    FAIL() << "first difference at output line " << i + 1
           << ":\n  got:  " << (i < a.size() ? a[i] : "<end>")
           << "\n  want: " << (i < b.size() ? b[i] : "<end>");
  }
}

}  // namespace
}  // namespace sb::cli
