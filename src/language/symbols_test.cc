#include "language/symbols.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <string>
#include <thread>
#include <vector>

namespace sb::language {
namespace {

// A grammar shaped like the paper's (same net names), written for the tests.
const char kGra[] =
    "[Move]\n"
    "\t([Action] [Hold])\n"
    "\t([Hold] [Action])\n"
    "\t([Hold])\n"
    "\t([Match])\n"
    ";\n"
    "[Match]\n\t(match)\n;\n"
    "[Hold]\n"
    "\t([HoldSize] [HoldShape] [HoldType])\n"
    "\t([HoldShape] [HoldType])\n"
    "\t([HoldSize] [HoldType])\n"
    "\t([HoldType])\n"
    ";\n"
    "[HoldSize]\n\t([HoldSizeBig])\n\t([HoldSizeSmall])\n;\n"
    "[HoldSizeBig]\n\t([HoldSizeBigT])\n;\n"
    "[HoldSizeBigT]\n\t(big)\n\t(positive)\n;\n"
    "[HoldSizeSmall]\n\t([HoldSizeSmallT])\n;\n"
    "[HoldSizeSmallT]\n\t(small)\n;\n"
    "[HoldShape]\n\t([HoldShapeGood])\n\t([HoldShapeBad])\n;\n"
    "[HoldShapeGood]\n\t([HoldShapeGoodT])\n;\n"
    "[HoldShapeGoodT]\n\t(right angle)\n\t(bulbous)\n;\n"
    "[HoldShapeBad]\n\t(sloping)\n\t(flat)\n;\n"
    "[HoldType]\n\t([HoldTypeT])\n\t([SidePull])\n\t([GenericHold])\n\t([Mantle])\n;\n"
    "[HoldTypeT]\n\t(crimp)\n\t(rail)\n\t(jug)\n\t(thumb catch)\n;\n"
    "[SidePull]\n\t(sidepull)\n;\n"
    "[GenericHold]\n\t(hold)\n\t(start)\n;\n"
    "[Mantle]\n\t(top)\n\t(finish)\n;\n"
    "[Action]\n\t([ActionSize] [ActionVerb])\n\t([ActionVerb])\n;\n"
    "[ActionSize]\n\t([ActionSizeBig])\n;\n"
    "[ActionSizeBig]\n\t(huge)\n;\n"
    "[ActionVerb]\n\t([ActionVerbBig])\n\t([ActionVerbSmall])\n;\n"
    "[ActionVerbBig]\n\t(dyno)\n;\n"
    "[ActionVerbSmall]\n\t([ActionVerbSmallT])\n\t([Cross])\n;\n"
    "[ActionVerbSmallT]\n\t(right)\n\t(move)\n;\n"
    "[Cross]\n\t(cross)\n;\n";

MoveLanguage Lang() {
  auto g = Grammar::FromText(kGra, "t.gra", "Frame: IsMove\n\t[Move]\n;\n", "t.frames");
  EXPECT_TRUE(g.ok()) << g.status().message();
  return MoveLanguage(g.value(), Tokenization::kPhoenix);
}

TEST(SymbolsTest, PaperHybridExample) {
  // Section 10.1: two IsMove slots combine into "right-right-angle-crimp-rail".
  MoveLanguage lang = Lang();
  MoveReading r = lang.Read("R moving right to a right angle crimp rail");
  ASSERT_EQ(r.parse.parses.size(), 1u);
  ASSERT_EQ(r.parse.parses[0].slots.size(), 2u);
  EXPECT_EQ(r.symbols.k[0], "[HoldType].[HoldTypeT].crimp.[HoldType].[HoldTypeT].rail");
  EXPECT_EQ(r.symbols.k[1],
            "[HoldType].[HoldTypeT].crimp.[HoldType].[HoldTypeT].rail::"
            "[HoldShape].[HoldShapeGood].[HoldShapeGoodT].right");
  EXPECT_EQ(r.symbols.k[2], "[HoldType].[HoldTypeT].crimp.[HoldType].[HoldTypeT].rail:GOOD");
  EXPECT_EQ(r.symbols.k[3], r.symbols.k[1] + ":GOOD");
  EXPECT_EQ(DescribeSymbol(r.symbols.k[3]), "crimp-rail \u00b7 right \u00b7 good-hold");
}

TEST(SymbolsTest, SizeShapeAndGoodness) {
  MoveLanguage lang = Lang();
  // small (-1) + sloping (-1): not good; size and shape both shown.
  Symbols s = lang.SymbolsOf("small sloping crimp");
  EXPECT_EQ(s.k[1],
            "[HoldType].[HoldTypeT].crimp:[HoldSize].[HoldSizeSmall].[HoldSizeSmallT].small:"
            "[HoldShape].[HoldShapeBad].sloping");
  EXPECT_EQ(s.k[2], "[HoldType].[HoldTypeT].crimp");
  // big (+1) + flat (-1) = 0: not good.
  EXPECT_EQ(lang.SymbolsOf("big flat jug").k[2], "[HoldType].[HoldTypeT].jug");
  // positive (+1): good.
  EXPECT_EQ(lang.SymbolsOf("positive jug").k[2], "[HoldType].[HoldTypeT].jug:GOOD");
  // multi-word types show their first word.
  EXPECT_EQ(lang.SymbolsOf("thumb catch").k[0], "[HoldType].[HoldTypeT].thumb");
}

TEST(SymbolsTest, FlagsInOrder) {
  MoveLanguage lang = Lang();
  EXPECT_EQ(lang.SymbolsOf("cross jug").k[3], "[HoldType].[HoldTypeT].jug:::CROSS");
  EXPECT_EQ(lang.SymbolsOf("dyno jug").k[2], "[HoldType].[HoldTypeT].jug:BIG");
  EXPECT_EQ(lang.SymbolsOf("huge move big jug").k[2], "[HoldType].[HoldTypeT].jug:BIG+GOOD");
  EXPECT_EQ(lang.SymbolsOf("cross jug dyno bulbous sidepull").k[2],
            "[HoldType].[HoldTypeT].jug.[HoldType].[SidePull]:CROSS+BIG+GOOD");
  EXPECT_EQ(DescribeSymbol("[HoldType].[HoldTypeT].jug.[HoldType].[SidePull]:CROSS+BIG+GOOD"),
            "jug-sidepull \u00b7 cross \u00b7 big-move \u00b7 good-hold");
}

TEST(SymbolsTest, HoldTypesSortedDedupedGenericAndMatchDropped) {
  MoveLanguage lang = Lang();
  // Sorted, not in text order; sidepull after HoldTypeT entries.
  EXPECT_EQ(lang.SymbolsOf("sidepull rail crimp").k[0],
            "[HoldType].[HoldTypeT].crimp.[HoldType].[HoldTypeT].rail.[HoldType].[SidePull]");
  EXPECT_EQ(lang.SymbolsOf("jug jug").k[0], "[HoldType].[HoldTypeT].jug");
  // Generic "hold" goes when a specific type is present; alone it shows once.
  EXPECT_EQ(lang.SymbolsOf("hold jug").k[0], "[HoldType].[HoldTypeT].jug");
  EXPECT_EQ(lang.SymbolsOf("start hold").k[0], "[HoldType].[GenericHold]");
  // Different words of one non-T type stay distinct (as the original did).
  EXPECT_EQ(lang.SymbolsOf("finish top").k[0], "[HoldType].[Mantle].[HoldType].[Mantle]");
  // The match move is its own type, only when nothing else is named.
  EXPECT_EQ(lang.SymbolsOf("match").k[0], "[HoldType].[Match]");
  EXPECT_EQ(lang.SymbolsOf("match jug").k[0], "[HoldType].[HoldTypeT].jug");
  EXPECT_EQ(lang.SymbolsOf("match hold").k[0], "[HoldType].[GenericHold]");
  Symbols none = lang.SymbolsOf("asdf");
  for (const std::string& k : none.k) EXPECT_EQ(k, "NO_PARSE");
  EXPECT_EQ(DescribeSymbol("NO_PARSE"), "no parse");
}

TEST(SymbolsTest, ExplainAndDescribe) {
  MoveLanguage lang = Lang();
  EXPECT_EQ(lang.Explain("asdf"), "no parse");
  std::string e = lang.Explain("dyno to big jug");
  EXPECT_NE(e.find("jug \u00b7 big \u00b7 big-move \u00b7 good-hold"), std::string::npos) << e;
  EXPECT_NE(e.find("Action 'dyno'"), std::string::npos) << e;
  EXPECT_EQ(DescribeSymbol("[HoldType].[Match]::"), "match");
  EXPECT_EQ(DescribeSymbol("[HoldType].[GenericHold]"), "hold");
  EXPECT_EQ(DescribeSymbol("weird:a:b:c:d:e"), "weird:a:b:c:d:e");
}

TEST(SymbolsTest, DefaultGrammarIsFound) {
  std::string dir = DefaultGrammarDir();
  ASSERT_FALSE(dir.empty());
  auto lang = MoveLanguage::LoadDefault();
  ASSERT_TRUE(lang.ok()) << lang.status().message();
  ::setenv("SB_DATA_DIR", "/nonexistent-dir", 1);
  EXPECT_FALSE(DefaultGrammarDir().empty());  // falls back to the source tree
  ::unsetenv("SB_DATA_DIR");
}

// Issue 33: the bundled grammar is compiled once per process and shared by
// every MoveLanguage LoadDefault makes (each with its own parser), from any
// thread, reading moves exactly as a grammar loaded on its own does.
TEST(SymbolsTest, LoadDefaultSharesOneGrammarAcrossThreads) {
  auto a = MoveLanguage::LoadDefault();
  ASSERT_TRUE(a.ok()) << a.status().message();
  auto fresh = MoveLanguage::LoadDir(DefaultGrammarDir());
  ASSERT_TRUE(fresh.ok()) << fresh.status().message();
  EXPECT_NE(&a->grammar(), &fresh->grammar());
  const std::vector<std::string> moves = {"dyno to big sloping edge", "L crimp sidepull",
                                          "match", "heel hook the jug"};
  std::vector<std::string> want;
  for (const std::string& m : moves) want.push_back(fresh->SymbolsOf(m).k[3]);
  std::vector<const Grammar*> seen(4, nullptr);
  std::vector<int> same(4, 0);
  std::vector<std::thread> threads;
  for (int t = 0; t < 4; ++t) {
    threads.emplace_back([&, t] {
      auto l = MoveLanguage::LoadDefault();
      if (!l.ok()) return;
      seen[t] = &l->grammar();
      for (size_t i = 0; i < moves.size(); ++i) same[t] += l->SymbolsOf(moves[i]).k[3] == want[i];
    });
  }
  for (std::thread& th : threads) th.join();
  for (int t = 0; t < 4; ++t) {
    EXPECT_EQ(seen[t], &a->grammar()) << t;
    EXPECT_EQ(same[t], static_cast<int>(moves.size())) << t;
  }
}

// The project's grammar: moves as climbers write them.
TEST(OwnGrammarTest, ReadsMoves) {
  auto lang = MoveLanguage::LoadDefault();
  ASSERT_TRUE(lang.ok()) << lang.status().message();
  struct Case {
    const char* text;
    const char* readable;  // DescribeSymbol(k4)
  };
  const Case cases[] = {
      {"Dyno to a HUGE jug!", "jug \u00b7 huge \u00b7 big-move \u00b7 good-hold"},
      {"moving right to a right angle crimp rail", "crimp-rail \u00b7 right"},
      {"small sloping crimp-rail, big move",
       "crimp-rail \u00b7 small \u00b7 sloping \u00b7 big-move"},
      {"cross over to a two finger pocket", "pocket \u00b7 two \u00b7 cross"},
      {"match", "match"},
      {"bump right", "next-hold"},
      {"heel hook the ledge", "foot-hook-ledge"},
      {"left hand gaston", "gaston"},
      {"lock off to tiny crimper", "crimp \u00b7 tiny"},
      {"top out", "mantle"},
      {"throw onto triangle", "volume \u00b7 big-move"},
      {"deadpoint to slopr", "sloper \u00b7 big-move"},
  };
  for (const Case& c : cases) {
    MoveReading r = lang->Read(c.text);
    EXPECT_EQ(DescribeSymbol(r.symbols.k[3]), c.readable) << c.text;
  }
}

// Text that is not a move must not parse.
TEST(OwnGrammarTest, NonMovesDoNotParse) {
  auto lang = MoveLanguage::LoadDefault();
  ASSERT_TRUE(lang.ok()) << lang.status().message();
  const char* non_moves[] = {
      "",
      "asdf",
      "a",
      "1",
      "14",
      "crux",
      "fix",
      "the weather is nice today",
      "see the description above",
      "route set by bob in 2010",
      "have fun!",
      "this is a hard one",
      "good luck",
      "thanks for climbing",
      "left",
      "up",
      "very nice route overall",
      "lorem ipsum dolor sit amet",
      "call me at 555 1234",
      "http://example.com",
  };
  for (const char* t : non_moves) {
    MoveReading r = lang->Read(t);
    EXPECT_FALSE(r.parse.ok()) << "'" << t << "' parsed as " << r.symbols.k[3];
  }
}

TEST(SymbolsTest, ProjectStyleNamesEachHoldTypeOnce) {
  // "finish on top": two [Mantle] words. The original symbolizer printed
  // mantle twice (kept with the Phoenix tokenization); the project's once.
  auto g = Grammar::FromText(kGra, "t.gra", "Frame: IsMove\n\t[Move]\n;\n", "t.frames");
  ASSERT_TRUE(g.ok());
  MoveLanguage original(g.value(), Tokenization::kPhoenix);
  MoveLanguage project(g.value(), Tokenization::kFolded);
  EXPECT_EQ(original.Read("finish top").symbols.k[0], "[HoldType].[Mantle].[HoldType].[Mantle]");
  EXPECT_EQ(project.Read("finish top").symbols.k[0], "[HoldType].[Mantle]");
  // Distinct [HoldTypeT] words stay two types in both.
  EXPECT_EQ(project.Read("crimp rail").symbols.k[0],
            "[HoldType].[HoldTypeT].crimp.[HoldType].[HoldTypeT].rail");
  auto own = MoveLanguage::LoadDefault();
  ASSERT_TRUE(own.ok());
  EXPECT_EQ(own->Read("finish on top").symbols.k[0], "[HoldType].[Mantle]");
  EXPECT_EQ(own->Read("foot on foothold, hand on foot pad sloper")
                .symbols.k[0]
                .find("[HoldType].[FootHold].[HoldType].[FootHold]"),
            std::string::npos);
}

TEST(SymbolsTest, VerbClassAndMoveSize) {
  auto lang = MoveLanguage::LoadDefault();
  ASSERT_TRUE(lang.ok());
  MoveFeatures a = lang->Read("big dyno to a jug").features;
  EXPECT_EQ(a.verb, "dyno");
  EXPECT_EQ(a.move_size, "big");
  MoveFeatures b = lang->Read("small move to sloping crimp").features;
  EXPECT_EQ(b.verb, "move");
  EXPECT_EQ(b.move_size, "small");
  MoveFeatures c = lang->Read("cross to pinch").features;
  EXPECT_EQ(c.verb, "cross");
  EXPECT_TRUE(c.cross);
  MoveFeatures d = lang->Read("slopey ledge").features;
  EXPECT_EQ(d.verb, "");
  EXPECT_EQ(d.move_size, "");
}

TEST(SymbolsTest, MoveTextReadsBackToTheSameSymbol) {
  auto lang = MoveLanguage::LoadDefault();
  ASSERT_TRUE(lang.ok());
  EXPECT_EQ(SymbolToMoveText("NO_PARSE"), "");
  EXPECT_EQ(SymbolToMoveText("[HoldType].[Crimp].[HoldType].[Rail]::[HoldShape].[HoldShapeBad]."
                             "sloping:BIG"),
            "big move to sloping crimp rail");
  EXPECT_EQ(SymbolToMoveText("[HoldType].[Match]"), "match");
  EXPECT_EQ(lang->HoldPhrase("foot-hook"), "heel hook");
  EXPECT_EQ(lang->HoldPhrase("no-such-type"), "no such type");
  const char* moves[] = {"big dyno to a small sloping crimp",
                         "cross to pinch",
                         "heel hook",
                         "L match",
                         "slopey ledge",
                         "huge move to good jug",
                         "thumb catch sidepull",
                         "finish on top",
                         "undercling flake"};
  for (const char* m : moves) {
    const Symbols s = lang->Read(m).symbols;
    ASSERT_NE(s.k[3], "NO_PARSE") << m;
    for (int k : {0, 2}) {  // hold types, and with the flags
      const std::string text = lang->MoveText(s.k[k]);
      EXPECT_EQ(lang->Read(text).symbols.k[k], s.k[k]) << m << " -> '" << text << "'";
    }
  }
}

}  // namespace
}  // namespace sb::language
