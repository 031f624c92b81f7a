#include "crdl/route.h"

#include <gtest/gtest.h>

#include <cstring>

namespace sb {
namespace {

constexpr const char* kFigure1 =
    "Problem 13 from the CU-hosted RMR CCS\n"
    "name: Problem 13\n"
    "grade: 5.10\n"
    "\n"
    "A few large moves between moderate crimps.\n"
    "---\n"
    "R slopey ledge\n"
    "L match\n"
    "# a comment\n"
    "\n"
    "right medium crimp sidepull\n"
    "LEFT diagonal sloper\n";

TEST(Crdl, ParsesHeaderMetadataAndMoves) {
  auto r = ParseCrdl(kFigure1, "fig1.crdl");
  ASSERT_TRUE(r.ok()) << r.status().message();
  EXPECT_EQ(r->Meta("name").value(), "Problem 13");
  EXPECT_EQ(r->Meta("GRADE").value(), "5.10");
  EXPECT_FALSE(r->Meta("setter").has_value());
  ASSERT_EQ(r->header.size(), 5u);
  EXPECT_EQ(r->header[0].key, "");
  EXPECT_EQ(r->header[0].value, "Problem 13 from the CU-hosted RMR CCS");
  ASSERT_EQ(r->moves.size(), 4u);
  EXPECT_EQ(r->moves[0].hand, Hand::kRight);
  EXPECT_EQ(r->moves[0].text, "slopey ledge");
  EXPECT_EQ(r->moves[1].hand, Hand::kLeft);
  EXPECT_EQ(r->moves[2].hand, Hand::kRight);
  EXPECT_EQ(r->moves[2].text, "medium crimp sidepull");
  EXPECT_EQ(r->moves[2].line, 11);
  EXPECT_EQ(r->moves[3].hand, Hand::kLeft);
  EXPECT_EQ(r->Name(), "Problem 13");
}

TEST(Crdl, CrlfAndBomTolerated) {
  auto r = ParseCrdl("\xEF\xBB\xBFname: x\r\n---\r\nR jug\r\nL crimp\r\n", "a.crdl");
  ASSERT_TRUE(r.ok()) << r.status().message();
  EXPECT_EQ(r->moves[1].text, "crimp");
  EXPECT_EQ(r->Meta("name").value(), "x");
}

TEST(Crdl, RoundTrip) {
  auto r = ParseCrdl(kFigure1, "fig1.crdl");
  ASSERT_TRUE(r.ok());
  std::string printed = PrintCrdl(*r);
  auto again = ParseCrdl(printed, "printed");
  ASSERT_TRUE(again.ok()) << again.status().message();
  EXPECT_EQ(*again, *r);
  EXPECT_EQ(PrintCrdl(*again), printed);
}

TEST(Crdl, UrlInDescriptionIsNotMetadata) {
  auto r = ParseCrdl("see http://example.org\nurl:http://x\n---\nR jug\n", "a");
  ASSERT_TRUE(r.ok());
  EXPECT_FALSE(r->Meta("url").has_value());
}

struct BadCase {
  const char* text;
  const char* message;
};

TEST(Crdl, ErrorsNameFileLineAndColumn) {
  const BadCase cases[] = {
      {"name: a\n---\nR jug\nR crimp\nL pinch\nR edge\nQ jug\n",
       "route.crdl:7:1: expected hand L or R, got \"Q\""},
      {"---\nR jug\n  Lx crimp\n", "route.crdl:3:3: expected hand L or R, got \"Lx\""},
      {"name: a\nR jug\n", "route.crdl:2:1: missing \"---\" line between the header and the moves"},
      {"---\nR jug\nL\n", "route.crdl:3:2: empty move text after hand L"},
      {"---\nR jug\nleft    \n", "route.crdl:3:5: empty move text after hand L"},
      {"name: a\n --- \nR jug\n", "route.crdl:2:1: the separator line must be exactly \"---\""},
      {"---\nR ju\xFFg\n", "route.crdl:2:5: invalid UTF-8"},
      {"---\nR a\xED\xA0\x80\n", "route.crdl:2:4: invalid UTF-8"},      // surrogate U+D800
      {"---\nR \xF4\x90\x80\x80\n", "route.crdl:2:3: invalid UTF-8"},   // above U+10FFFF
      {"n\xC0\xAF: x\n---\nR a\n", "route.crdl:1:2: invalid UTF-8"},    // overlong '/'
      {"---\nR \xE0\x80\xAF\n", "route.crdl:2:3: invalid UTF-8"},       // overlong, 3 bytes
      {"---\nR (crux)\n", "route.crdl:2:2: empty move text after hand R"},
      {"", "route.crdl:1:1: missing \"---\" line between the header and the moves"},
  };
  for (const BadCase& c : cases) {
    auto r = ParseCrdl(c.text, "route.crdl");
    ASSERT_FALSE(r.ok()) << c.text;
    EXPECT_EQ(r.status().code(), Status::Code::kInvalidInput);
    EXPECT_EQ(r.status().message(), c.message);
    ASSERT_TRUE(r.status().location().has_value());
    EXPECT_EQ(r.status().location()->file, "route.crdl");
    EXPECT_GT(r.status().location()->line, 0);
    EXPECT_GT(r.status().location()->column, 0);
  }
}

TEST(Crdl, CruxMarkerIsAFlagNotText) {
  auto r = ParseCrdl("---\nR jug\nL small crimp (crux)\nR sloper  (CRUX) \nL pinch(crux)\n", "c");
  ASSERT_TRUE(r.ok()) << r.status().message();
  ASSERT_EQ(r->moves.size(), 4u);
  EXPECT_FALSE(r->moves[0].crux);
  EXPECT_TRUE(r->moves[1].crux);
  EXPECT_EQ(r->moves[1].text, "small crimp");
  EXPECT_TRUE(r->moves[2].crux);
  EXPECT_EQ(r->moves[2].text, "sloper");
  EXPECT_FALSE(r->moves[3].crux);  // the marker needs whitespace before it
  EXPECT_EQ(r->moves[3].text, "pinch(crux)");
  std::string printed = PrintCrdl(*r);
  EXPECT_NE(printed.find("L small crimp (crux)\n"), std::string::npos);
  EXPECT_NE(printed.find("R sloper (crux)\n"), std::string::npos);
  auto again = ParseCrdl(printed, "p");
  ASSERT_TRUE(again.ok());
  EXPECT_EQ(*again, *r);
}

TEST(Crdl, PrintIsAFixedPoint) {
  // Extra CRs at line ends and doubled byte-order marks used to survive into
  // the printed text and read differently the second time.
  for (const char* text :
       {"name: a\r\r\nfree text\r\r\r\n---\r\nR jug\r\r\n",
        "\xEF\xBB\xBF\xEF\xBB\xBFname: x\n---\nR jug\n", "\xEF\xBB\xBF\xEF\xBB\xBF---\nL a (crux)\r\r\n",
        "desc \t\n\n\n---\nleft  x  y  \n", "\r\r\na\n---\nL m"}) {
    auto r = ParseCrdl(text, "t");
    ASSERT_TRUE(r.ok()) << r.status().message();
    std::string once = PrintCrdl(*r);
    auto again = ParseCrdl(once, "t");
    ASSERT_TRUE(again.ok()) << again.status().message();
    EXPECT_EQ(*again, *r);
    EXPECT_EQ(PrintCrdl(*again), once);
    EXPECT_EQ(once.find('\r'), std::string::npos);
  }
  auto bom = ParseCrdl("\xEF\xBB\xBF\xEF\xBB\xBFname: x\n---\nR jug\n", "t");
  EXPECT_EQ(bom->Meta("name").value_or(""), "x");
}

TEST(Crdl, InputsAboveTheSizeLimitAreRefusedBeforeParsing) {
  std::string big(kMaxCrdlBytes + 1, 'a');
  auto r = ParseCrdl(big, "big.crdl");
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.status().message().find("limit"), std::string::npos);
  auto zero = ReadCrdlFile("/dev/zero");  // endless input: stops at the limit
  ASSERT_FALSE(zero.ok());
  EXPECT_NE(zero.status().message().find("/dev/zero: larger than"), std::string::npos);
}

TEST(Crdl, ArbitraryBytesGiveARouteOrALocatedError) {
  // Random mixtures of CRDL pieces and raw bytes: never a crash, and every
  // error names the file, a line and a column.
  const char* pieces[] = {"---", "---\n", "\n", "\r\n", "L ", "R ", "left ", "name: x", "# c",
                          " ", "match", "jug", "\xC3\xA9", "\t", "Q", ":", "\r", " (crux)",
                          "\xEF\xBB\xBF"};
  const char* bad[] = {"\xFF", "\0", "\xED\xA0\x80", "\xF4\x90\x80\x80", "\xC0\xAF"};
  uint64_t state = 42;
  auto next = [&] {
    state = state * 6364136223846793005ull + 1442695040888963407ull;
    return static_cast<uint32_t>(state >> 33);
  };
  int ok = 0;
  for (int i = 0; i < 4000; ++i) {
    std::string text;
    int n = next() % 30;
    for (int k = 0; k < n; ++k) {
      uint32_t kind = next() % 32;
      if (kind == 0) {
        text.push_back(static_cast<char>(next() & 0xFF));
      } else if (kind == 1) {
        const char* p = bad[next() % (sizeof bad / sizeof *bad)];
        text.append(p, p[0] == '\0' ? 1 : std::strlen(p));
      } else {
        text.append(pieces[next() % (sizeof pieces / sizeof *pieces)]);
      }
    }
    auto r = ParseCrdl(text, "fuzz.crdl");
    if (r.ok()) {
      ++ok;  // with moves or none (issue 32)
      auto again = ParseCrdl(PrintCrdl(*r), "printed");
      ASSERT_TRUE(again.ok()) << again.status().message();
      EXPECT_EQ(*again, *r);
      EXPECT_EQ(PrintCrdl(*again), PrintCrdl(*r));
    } else {
      const std::string& m = r.status().message();
      EXPECT_EQ(m.rfind("fuzz.crdl:", 0), 0u) << m;
      EXPECT_EQ(m.find('\n'), std::string::npos) << m;  // one line
    }
  }
  EXPECT_GT(ok, 0);
}

TEST(Crdl, MatchText) {
  EXPECT_TRUE(IsMatchText("match"));
  EXPECT_TRUE(IsMatchText(" MATCH. "));
  EXPECT_TRUE(IsMatchText("Match!"));
  EXPECT_FALSE(IsMatchText("match on jug"));
  EXPECT_FALSE(IsMatchText("rematch"));
}

TEST(Crdl, SetMetaReplacesOrAppends) {
  Route r;
  r.SetMeta("name", "a");
  r.SetMeta("Name", "b");
  EXPECT_EQ(r.header.size(), 1u);
  EXPECT_EQ(r.Name(), "b");
  r.SetMeta("grade", "V3");
  EXPECT_EQ(r.header.size(), 2u);
}

// Issue 32: a route whose moves are not recorded parses, with no moves, and
// prints back to the same route.
TEST(Crdl, RouteWithoutMovesParsesAndPrintsBack) {
  auto r = ParseCrdl("name: Gelber Riss\ngrade: 4\ncolour: gelb\n---\n\n# none yet\n", "route.crdl");
  ASSERT_TRUE(r.ok()) << r.status().message();
  EXPECT_TRUE(r->moves.empty());
  EXPECT_EQ(r->Name(), "Gelber Riss");
  auto again = ParseCrdl(PrintCrdl(*r), "again.crdl");
  ASSERT_TRUE(again.ok());
  EXPECT_EQ(*again, *r);
}

}  // namespace
}  // namespace sb

