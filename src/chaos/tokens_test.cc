#include "chaos/tokens.h"

#include <gtest/gtest.h>

#include "chaos/constraints.h"

namespace sb::chaos {
namespace {

TEST(Tokens, OneTokenALineWithCommentsAndBlanks) {
  auto s = ParseTokenSequence("\xEF\xBB\xBF# a melody\r\n  E4|q \r\n\nmatch\r\nC4|h\n", "m.txt",
                              "m");
  ASSERT_TRUE(s.ok()) << s.status().message();
  EXPECT_TRUE(s->tokens);
  EXPECT_EQ(s->name, "m");
  ASSERT_EQ(s->route.moves.size(), 3u);
  EXPECT_EQ(s->route.moves[0].text, "E4|q");
  EXPECT_EQ(s->route.moves[1].text, "match");
  EXPECT_EQ(s->route.moves[2].line, 5);
}

TEST(Tokens, ErrorsAreLocated) {
  auto blank = ParseTokenSequence("E4|q\nE4|q D4|q\n", "m.txt", "m");
  ASSERT_FALSE(blank.ok());
  EXPECT_EQ(blank.status().message().rfind("m.txt:2:5:", 0), 0u) << blank.status().message();
  auto none = ParseTokenSequence("# nothing\n\n", "e.txt", "e");
  ASSERT_FALSE(none.ok());
  EXPECT_EQ(none.status().message().rfind("e.txt:", 0), 0u) << none.status().message();
  auto utf = ParseTokenSequence("ok\n\xff\n", "u.txt", "u");
  ASSERT_FALSE(utf.ok());
  EXPECT_EQ(utf.status().message().rfind("u.txt:2:1:", 0), 0u) << utf.status().message();
  auto big = ParseTokenSequence(std::string(kMaxTokenBytes + 1, 'x') + "\n", "b.txt", "b");
  ASSERT_FALSE(big.ok());
  EXPECT_NE(big.status().message().find("longer than"), std::string::npos);
  EXPECT_EQ(ReadTokenFile("/no/such/file.txt").status().code(), Status::Code::kNotFound);
}

TEST(Tokens, VariedLikeRoutesWithoutAMatchRule) {
  auto a = ParseTokenSequence("match\nE4|q\nD4|q\nC4|h\nD4|q\nE4|q\n", "a.txt", "a");
  auto b = ParseTokenSequence("C4|q\nG4|q\nA4|q\nG4|h\n", "b.txt", "b");
  ASSERT_TRUE(a.ok() && b.ok());
  EXPECT_TRUE(AreTokens({*a, *b}));
  VaryParams p;
  p.var_ic = p.ref_ic;  // the identity mapping
  auto v = Vary({*a, *b}, p);
  ASSERT_TRUE(v.ok()) << v.status().message();
  ASSERT_EQ(v->moves.size(), 10u);
  EXPECT_EQ(v->moves[0].text, "match");  // a token "match" is itself
  EXPECT_TRUE(v->moves[0].notes.empty());
  auto again = Vary({*a, *b}, *VaryParams::Preset("more"));
  auto twice = Vary({*a, *b}, *VaryParams::Preset("more"));
  ASSERT_TRUE(again.ok() && twice.ok());
  EXPECT_EQ(again->mapping, twice->mapping);
}

TEST(Tokens, MixingTokensAndRoutesIsRefused) {
  auto a = ParseTokenSequence("E4|q\n", "a.txt", "a");
  auto r = ParseCrdl("---\nR jug\n", "r");
  ASSERT_TRUE(a.ok() && r.ok());
  std::vector<InputRoute> mixed = {*a, {"r", *r}};
  EXPECT_FALSE(AreTokens(mixed));
  Status s = CheckInputKinds(mixed);
  EXPECT_EQ(s.code(), Status::Code::kInvalidInput);
  EXPECT_NE(s.message().find("--tokens"), std::string::npos);
}

}  // namespace
}  // namespace sb::chaos
