#include "language/parser.h"

#include <gtest/gtest.h>

namespace sb::language {
namespace {

std::shared_ptr<const Grammar> Make(const std::string& gra, const std::string& frames) {
  auto g = Grammar::FromText(gra, "t.gra", frames, "t.frames");
  EXPECT_TRUE(g.ok()) << g.status().message();
  return g.ok() ? g.value() : nullptr;
}

const char kMoveFrames[] = "Frame: IsMove\nElements:\n\t[Move]\n;\n";

// A small move grammar in the style of the paper's appendix C.
const char kMoves[] =
    "[Move]\n"
    "\t([Action] [Hold])\n"
    "\t([Hold] [Action])\n"
    "\t([Hold])\n"
    ";\n"
    "[Hold]\n"
    "\t(sloper)\n"
    "\t(hand)\n"
    "\t(heelhook)\n"
    "\t(heel hook)\n"
    ";\n"
    "[Action]\n"
    "\t(right)\n"
    "\t(up)\n"
    "\t(move)\n"
    "\t(big move)\n"
    ";\n";

// The slots of every parse, as "[words][words] | [words]".
std::string Shape(const ParseResult& r) {
  std::string s;
  for (size_t k = 0; k < r.parses.size(); ++k) {
    if (k) s += " | ";
    for (const Slot& slot : r.parses[k].slots) {
      s += "[";
      for (int w = slot.begin; w < slot.end; ++w) {
        if (w > slot.begin) s += " ";
        s += r.words[w];
      }
      s += "]";
    }
  }
  return s.empty() ? "none" : s;
}

TEST(ParserTest, OutOfVocabularyWordsAreIgnored) {
  Parser p(Make(kMoves, kMoveFrames));
  ParseResult r = p.Parse("move   to the   sloper");
  EXPECT_EQ(r.words, (std::vector<std::string>{"move", "sloper"}));
  EXPECT_EQ(Shape(r), "[move sloper]");
  EXPECT_EQ(r.covered, 2);
}

TEST(ParserTest, KnownWordsBetweenSlotsAreSkipped) {
  // "big" alone is no move: it is skipped between the two slots.
  Parser p(Make(kMoves, kMoveFrames));
  EXPECT_EQ(Shape(p.Parse("sloper big hand")), "[sloper][hand]");
  EXPECT_EQ(Shape(p.Parse("up")), "none");
}

TEST(ParserTest, MostWordsWinThenFewestSlots) {
  Parser p(Make(kMoves, kMoveFrames));
  // One slot of two words beats two one-word slots... and more words beat fewer slots.
  EXPECT_EQ(Shape(p.Parse("right sloper")), "[right sloper]");
  EXPECT_EQ(Shape(p.Parse("sloper hand")), "[sloper][hand]");
}

TEST(ParserTest, TiesAreKeptInPhoenixOrder) {
  Parser p(Make(kMoves, kMoveFrames));
  EXPECT_EQ(Shape(p.Parse("heelhook big move to sloper")),
            "[heelhook big move][sloper] | [heelhook][big move sloper]");
  EXPECT_EQ(Shape(p.Parse("sloper for right hand continue up o next sloper")),
            "[sloper right][hand up][sloper] | [sloper][right hand][up sloper] | "
            "[sloper right][hand][up sloper]");
}

TEST(ParserTest, OnATieTheParseEndingFirstWins) {
  // [move heel hook] and [heel hook up] both cover three words in one slot;
  // Phoenix keeps only the one reached first.
  Parser p(Make(kMoves, kMoveFrames));
  EXPECT_EQ(Shape(p.Parse("move heel hook up")), "[move heel hook]");
}

TEST(ParserTest, FewestChildrenThenFirstRuleChoosesTheTree) {
  auto g = Make(
      "[Move]\n"
      "\t([Action] [Hold])\n"
      "\t([Hold])\n"
      ";\n"
      "[Action]\n\t(small)\n;\n"
      "[Hold]\n\t(*[Shape] *small crimp)\n;\n"
      "[Shape]\n\t([Good])\n\t([Bad])\n;\n"
      "[Good]\n\t([GoodT])\n;\n"
      "[GoodT]\n\t(vertical)\n;\n"
      "[Bad]\n\t(vertical)\n;\n",
      kMoveFrames);
  Parser p(g);
  std::string out;
  p.AppendPhoenix("small crimp", &out);
  // ([Hold]) has one child, ([Action] [Hold]) two: the smaller tree wins
  // although its rule comes second.
  EXPECT_EQ(out, ";;; small crimp\nPARSE_0:\nIsMove:[Move].[Hold].small crimp \nEND_PARSE\n\n");
  out.clear();
  // Same number of children: the first rule wins ([Good], although deeper).
  p.AppendPhoenix("vertical crimp", &out);
  EXPECT_EQ(
      out,
      ";;; vertical crimp\nPARSE_0:\nIsMove:[Move].[Hold].[Shape].[Good].[GoodT].vertical crimp \n"
      "END_PARSE\n\n");
}

TEST(ParserTest, FewerFramesBreakTies) {
  auto g =
      Make("[X]\n\t(a)\n\t(b)\n;\n[Y]\n\t(b)\n;\n", "Frame: One\n\t[X]\n;\nFrame: Two\n\t[Y]\n;\n");
  Parser p(g);
  ParseResult r = p.Parse("a b");
  ASSERT_EQ(r.parses.size(), 1u);
  EXPECT_EQ(r.parses[0].slots[1].frame, "One");
}

TEST(ParserTest, PhoenixModeIsCaseSensitiveFoldedModeIsNot) {
  auto g = Make(kMoves, kMoveFrames);
  Parser phoenix(g);
  EXPECT_EQ(Shape(phoenix.Parse("R Move to Sloper")), "none");
  ParserOptions o;
  o.tokenization = Tokenization::kFolded;
  Parser folded(g, o);
  EXPECT_EQ(Shape(folded.Parse("R Move to Sloper!")), "[move sloper]");
  EXPECT_EQ(Shape(folded.Parse("heel-hook, sloper")), "[heel hook][sloper]");
}

TEST(ParserTest, Tokenize) {
  EXPECT_EQ(Tokenize("  a  b\tc ", Tokenization::kPhoenix),
            (std::vector<std::string>{"a", "b", "c"}));
  EXPECT_EQ(Tokenize("Crimp-Jug, (don't) 2f", Tokenization::kFolded),
            (std::vector<std::string>{"crimp", "jug", "dont", "2f"}));
  EXPECT_TRUE(Tokenize("", Tokenization::kFolded).empty());
}

TEST(ParserTest, EmptyAndUnknownLinesDoNotParse) {
  Parser p(Make(kMoves, kMoveFrames));
  std::string out;
  p.AppendPhoenix("", &out);
  p.AppendPhoenix("asdf qwer", &out);
  EXPECT_EQ(out, ";;; \nNo parse\n;;; asdf qwer\nNo parse\n");
}

TEST(ParserTest, PrintersAgree) {
  Parser p(Make(kMoves, kMoveFrames));
  const std::string text = "heelhook big move to sloper";
  ParseResult r = p.Parse(text);
  std::string fast;
  p.AppendPhoenix(text, &fast);
  EXPECT_EQ(FormatPhoenix(text, r), fast);
  EXPECT_EQ(fast,
            ";;; heelhook big move to sloper\n"
            "PARSE_0:\n"
            "IsMove:[Move].[Hold].heelhook [Action].big move \n"
            "IsMove:[Move].[Hold].sloper \n"
            "END_PARSE\n"
            "PARSE_1:\n"
            "IsMove:[Move].[Hold].heelhook \n"
            "IsMove:[Move].[Action].big move [Hold].sloper \n"
            "END_PARSE\n\n");
  std::string json = FormatJson("say \"hi\"", p.Parse("say \"hi\" sloper"));
  EXPECT_EQ(json.find("{\"text\":\"say \\\"hi\\\"\",\"words\":[\"sloper\"]"), 0u) << json;
  EXPECT_NE(json.find("\"tree\":{\"net\":\"Move\",\"children\":[{\"net\":\"Hold\",\"children\":["
                      "\"sloper\"]}]}"),
            std::string::npos)
      << json;
  std::string readable = FormatReadable(text, r);
  EXPECT_NE(readable.find("reading 2"), std::string::npos) << readable;
  EXPECT_NE(FormatReadable("x", p.Parse("x")).find("no parse"), std::string::npos);
}

TEST(ParserTest, ManyTiesAreCapped) {
  // Every "h" can be its own slot or pair with its neighbour: exponentially
  // many ties; the cap keeps it bounded.
  auto g = Make("[M]\n\t(h)\n\t(h h)\n;\n", "Frame: F\n\t[M]\n;\n");
  ParserOptions o;
  o.max_parses = 8;
  Parser p(g, o);
  std::string text;
  for (int i = 0; i < 40; ++i) text += "h ";
  ParseResult r = p.Parse(text);
  EXPECT_EQ(r.covered, 40);
  EXPECT_LE(r.parses.size(), 8u);
  EXPECT_GE(r.parses.size(), 1u);
  EXPECT_EQ(r.parses[0].slots.size(), 20u);
}

}  // namespace
}  // namespace sb::language

namespace sb::language {
namespace {

TEST(ParserTest, RepetitionIsNotExponentialAndLinesAreCapped) {
  // 64 words that split into "h" / "h h" pieces in ~2^43 ways: the walk memo
  // must not enumerate them; words past max_words are ignored.
  auto g = Make("[M]\n\t(+[X])\n;\n[X]\n\t(h)\n\t(h h)\n;\n", "Frame: F\n\t[M]\n;\n");
  Parser p(g);
  std::string text;
  for (int i = 0; i < 5000; ++i) text += "h ";
  ParseResult r = p.Parse(text);
  ASSERT_EQ(r.words.size(), ParserOptions().max_words);
  ASSERT_EQ(r.parses.size(), 1u);
  ASSERT_EQ(r.parses[0].slots.size(), 1u);
  // The fewest-children tree: 32 pieces of "h h".
  EXPECT_EQ(r.parses[0].slots[0].tree.children.size(), 32u);
}

}  // namespace
}  // namespace sb::language

namespace sb::language {
namespace {

TEST(ParserTest, OptionalWordsArePolynomial) {
  // One rule of 64 optional words over a 64-word line: 2^64 ways to choose
  // which elements match; the walk memo explores each (element, word) once.
  std::string rule = "[M]\n\t(";
  for (int i = 0; i < kMaxWordsPerLine; ++i) rule += i % 2 ? "*w " : "*v ";
  rule += ")\n;\n";
  Parser p(Make(rule, "Frame: F\n\t[M]\n;\n"));
  std::string text;
  for (int i = 0; i < kMaxWordsPerLine; ++i) text += "w ";
  ParseResult r = p.Parse(text);
  // Every other element is "w": one slot takes 32 of them, another the rest.
  ASSERT_EQ(r.parses.size(), 1u);
  EXPECT_EQ(r.covered, 64);
  ASSERT_EQ(r.parses[0].slots.size(), 2u);
  EXPECT_EQ(r.parses[0].slots[0].end, 32);
}

TEST(ParserTest, RightRecursionWithOptionalWords) {
  // [L] inside [L], each level with a run of optional words: every level's
  // walk memo is put back after the nested call of the same net returns.
  auto g = Make("[L]\n\t(*a *a *a *a *a *a *a *a *a *a *a *a b *[L])\n;\n", "Frame: F\n\t[L]\n;\n");
  Parser p(g);
  std::string text;
  for (int i = 0; i < 5; ++i) text += "a a a a a a a a a a b ";
  ParseResult r = p.Parse(text);
  ASSERT_EQ(r.parses.size(), 1u);
  EXPECT_EQ(r.covered, 55);
  EXPECT_EQ(r.parses[0].slots.size(), 1u);
}

TEST(ParserTest, MaxWordsIsClampedToTheGrammarLimit) {
  ParserOptions o;
  o.max_words = 1000;
  Parser p(Make(kMoves, kMoveFrames), o);
  EXPECT_EQ(p.options().max_words, static_cast<size_t>(kMaxWordsPerLine));
}

}  // namespace
}  // namespace sb::language

namespace sb::language {
namespace {

TEST(ParserTest, JsonIsValidForAnyBytes) {
  // Found by fuzz_grammar: a stray byte (here 0xb0, a lone continuation
  // byte) went into the JSON string as it was; now it is U+FFFD.
  Parser p(Make(kMoves, kMoveFrames));
  std::string text = "sloper to \xb0he right \xc3\xa9 \xed\xa0\x80 \xf4\x90\x80\x80 \xc0\xaf";
  std::string json = FormatJson(text, p.Parse(text));
  const std::string r = "\xef\xbf\xbd";  // U+FFFD
  EXPECT_EQ(json.find("{\"text\":\"sloper to " + r + "he right \xc3\xa9 " + r + r + r + " " + r +
                      r + r + r + " " + r + r + "\""),
            0u)
      << json;
}

}  // namespace
}  // namespace sb::language
