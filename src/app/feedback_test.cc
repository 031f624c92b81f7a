#include "app/feedback.h"

#include <gtest/gtest.h>

#include "app/limits.h"

namespace sb::app {
namespace {

TEST(FeedbackTest, ClassifiesEveryLineAndLocatesTheError) {
  EditorFeedback f =
      ReadForEditor("name: Test\nA free line\n---\nR big jug (crux)\n# note\n\nX oops\n",
                    RouteLimits{});
  EXPECT_FALSE(f.ok);
  ASSERT_TRUE(f.error.has_value());
  EXPECT_EQ(f.error->line, 7);
  EXPECT_EQ(f.error->column, 1);
  EXPECT_EQ(f.error_reason, "expected hand L or R, got \"X\"");
  ASSERT_EQ(f.lines.size(), 7u);
  EXPECT_EQ(f.lines[0].kind, "meta");
  EXPECT_EQ(f.lines[1].kind, "description");
  EXPECT_EQ(f.lines[2].kind, "separator");
  EXPECT_EQ(f.lines[3].kind, "move");
  EXPECT_EQ(f.lines[3].hand, "R");
  EXPECT_EQ(f.lines[3].move, "big jug");
  EXPECT_TRUE(f.lines[3].crux);
  EXPECT_EQ(f.lines[4].kind, "comment");
  EXPECT_EQ(f.lines[5].kind, "blank");
  EXPECT_EQ(f.lines[6].kind, "error");
  EXPECT_EQ(f.lines[6].error, f.error_reason);
  EXPECT_EQ(f.moves, 1);
  if (f.language) {
    EXPECT_TRUE(f.lines[3].parsed);
    EXPECT_FALSE(f.lines[3].reading.empty());
  }
}

TEST(FeedbackTest, AgreesWithTheParserOnMetadata) {
  // "a:b" is description for the parser, so for the editor too.
  EditorFeedback f = ReadForEditor("a:b\nkey: v\n---\nR x\n", RouteLimits{});
  EXPECT_TRUE(f.ok);
  EXPECT_EQ(f.lines[0].kind, "description");
  EXPECT_EQ(f.lines[1].kind, "meta");
}

TEST(FeedbackTest, NeverFailsOnOddBytes) {
  for (std::string s :
       {std::string(), std::string("\xEF\xBB\xBF---\nL x\r\n"),
        std::string("\xff\xfe\n---\nR \xc3\n"), std::string(1, '\0'), std::string("---"),
        std::string("---\nR a\xED\xA0\x80\n")}) {
    EditorFeedback f = ReadForEditor(s, RouteLimits{});
    EXPECT_TRUE(f.ok || f.error.has_value()) << s;
  }
  EditorFeedback bad = ReadForEditor("---\nR a\xED\xA0\x80\n", RouteLimits{});
  ASSERT_TRUE(bad.error.has_value());
  EXPECT_EQ(bad.error->line, 2);
  EXPECT_EQ(bad.lines[1].kind, "error");
}

TEST(FeedbackTest, MoveReadings) {
  Result<Route> r = ParseCrdl("---\nR big jug\nL zzzz qqqq\n", "r");
  ASSERT_TRUE(r.ok());
  std::vector<std::string> readings = MoveReadings(*r);
  if (!LanguageAvailable()) GTEST_SKIP() << "no grammar";
  ASSERT_EQ(readings.size(), 2u);
  EXPECT_FALSE(readings[0].empty());
  EXPECT_TRUE(readings[1].empty());
}

TEST(EditorFeedbackLimits, TextOverTheLimitsIsRefusedBeforeAnyWork) {
  std::string lines = "name: Long\n---\n";
  while (lines.size() <= kMaxEditorBytes) lines += "R jug\n";
  EditorFeedback f = ReadForEditor(lines, RouteLimits{});
  EXPECT_FALSE(f.ok);
  EXPECT_TRUE(f.lines.empty());
  EXPECT_NE(f.error_reason.find("too long for live feedback"), std::string::npos);
  std::string many(kMaxEditorLines, '\n');
  EXPECT_TRUE(ReadForEditor(many, RouteLimits{}).lines.empty());
  const int max_moves = RouteLimits{}.max_moves;
  std::string fits = "name: Fits\n---\n";
  for (int i = 0; i < max_moves; ++i) fits += "R jug\n";
  EditorFeedback g = ReadForEditor(fits, RouteLimits{});
  EXPECT_TRUE(g.ok) << g.error_reason;
  EXPECT_EQ(g.moves, max_moves);
  // One move more is read (the lines are shown) but refused as the API
  // refuses it, naming the field.
  EditorFeedback over = ReadForEditor(fits + "L crimp\n", RouteLimits{});
  EXPECT_FALSE(over.ok);
  EXPECT_FALSE(over.lines.empty());
  EXPECT_NE(over.error_reason.find("moves: at most"), std::string::npos) << over.error_reason;
}

TEST(RouteLimitsTest, EveryFieldIsCheckedAndNamed) {
  RouteLimits lim;
  auto reason = [&](const std::string& crdl) {
    Result<Route> r = ParseCrdl(crdl, "t.crdl");
    EXPECT_TRUE(r.ok()) << r.status().message();
    return r.ok() ? CheckRouteLimits(*r, lim, "t.crdl").message() : std::string();
  };
  EXPECT_EQ(reason("name: ok\n---\nR jug\n"), "");
  EXPECT_NE(reason("name: " + std::string(201, 'n') + "\n---\nR jug\n").find("name: at most 200"),
            std::string::npos);
  // Characters, not bytes: 200 two-byte letters fit.
  std::string umlauts;
  for (int i = 0; i < 200; ++i) umlauts += "\xc3\xa4";
  EXPECT_EQ(reason("name: " + umlauts + "\n---\nR jug\n"), "");
  EXPECT_NE(reason("name: x\nwall: " + std::string(201, 'w') + "\n---\nR jug\n")
                .find("wall: at most 200"),
            std::string::npos);
  EXPECT_NE(reason("name: x\n" + std::string(4001, 'd') + "\n---\nR jug\n")
                .find("description: at most 4000"),
            std::string::npos);
  std::string move_err = reason("name: x\n---\nR jug\nL " + std::string(201, 'm') + "\n");
  EXPECT_NE(move_err.find("t.crdl:4"), std::string::npos) << move_err;
  EXPECT_NE(move_err.find("move 2: at most 200"), std::string::npos) << move_err;
  std::string meta = "name: x\n";
  for (int i = 0; i < 50; ++i) meta += "k" + std::to_string(i) + ": v\n";
  EXPECT_NE(reason(meta + "---\nR jug\n").find("metadata: at most 50"), std::string::npos);
}

}  // namespace
}  // namespace sb::app

namespace sb::app {
namespace {

TEST(DidYouMeanTest, SuggestsTheClosestVocabularyWord) {
  const std::vector<std::string> vocab = {"crimp", "sidepull", "jug", "sloper", "pinch"};
  EXPECT_EQ(DidYouMean("crmip", vocab), "crimp");  // two swaps away at most
  EXPECT_EQ(DidYouMean("slpoer", vocab), "sloper");
  EXPECT_EQ(DidYouMean("crimp", vocab), "");       // known words need nothing
  EXPECT_EQ(DidYouMean("zanzibar", vocab), "");    // nothing close
  EXPECT_EQ(DidYouMean("ju", vocab), "");          // too short to guess
}

TEST(DidYouMeanTest, SkipsCommonEnglishWords) {
  const std::vector<std::string> vocab = {"toe", "hand", "wish"};
  EXPECT_EQ(DidYouMean("the", vocab), "");   // one letter from "toe"
  EXPECT_EQ(DidYouMean("and", vocab), "");   // one letter from "hand"
  EXPECT_EQ(DidYouMean("with", vocab), "");  // one letter from "wish"
  EXPECT_EQ(DidYouMean("tho", vocab), "toe");  // not a common word: still suggested
}

TEST(EditorStyleTest, TheEditorShowsTheStyleReading) {
  if (!LanguageAvailable()) GTEST_SKIP() << "no grammar";
  EditorFeedback f = ReadForEditor("name: t\n---\nR cross to good sidepull\nL xyzzy\n",
                                   RouteLimits{});
  ASSERT_EQ(f.lines.size(), 4u);
  EXPECT_EQ(f.lines[2].style, "cross, sidepull");
  EXPECT_EQ(f.lines[3].style, "unparsed");
}

TEST(DidYouMeanTest, TheEditorDoesNotCorrectCommonWords) {
  if (!LanguageAvailable()) GTEST_SKIP() << "no grammar";
  EditorFeedback f = ReadForEditor("name: t\n---\nR reach the crack and match the jug\n",
                                   RouteLimits{});
  ASSERT_EQ(f.lines.size(), 3u);
  EXPECT_TRUE(f.lines[2].did_you_mean.empty());
}

TEST(DidYouMeanTest, TheEditorFlagsAMisspeltHold) {
  if (!LanguageAvailable()) GTEST_SKIP() << "no grammar";
  EditorFeedback f = ReadForEditor("name: t\n---\nR crmip\n", RouteLimits{});
  ASSERT_EQ(f.lines.size(), 3u);
  ASSERT_EQ(f.lines[2].did_you_mean.size(), 1u);
  EXPECT_EQ(f.lines[2].did_you_mean[0].first, "crmip");
  EXPECT_EQ(f.lines[2].did_you_mean[0].second, "crimp");
}

}  // namespace
}  // namespace sb::app
