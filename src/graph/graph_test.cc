// Token files, training counts and weights, the graph file format.
#include "graph/graph.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "base/hash.h"
#include "graph/tokens.h"

namespace sb::graph {
namespace {

TokenFile Parse(const std::string& text) {
  auto t = ParseTokenFile(text, "t.tok");
  EXPECT_TRUE(t.ok()) << t.status().message();
  return t.ok() ? *t : TokenFile{};
}

TEST(Tokens, ParsesLinesAndTokens) {
  TokenFile t = Parse("# comment\na|x b|y\n\n  c|x\ta|y  \r\n");
  EXPECT_EQ(t.k, 2);
  ASSERT_EQ(t.sequences.size(), 2u);
  EXPECT_EQ(t.tokens, 4u);
  EXPECT_EQ(t.sequences[0][1], (Token{"b", "y"}));
  EXPECT_EQ(t.sequences[1][1], (Token{"a", "y"}));
  EXPECT_EQ(FormatToken(t.sequences[1][0]), "c|x");
}

TEST(Tokens, ErrorsNameFileLineAndColumn) {
  auto a = ParseTokenFile("a|b c|d\nx|y z\n", "m.tok");
  ASSERT_FALSE(a.ok());
  EXPECT_EQ(a.status().message(), "m.tok:2:5: token 'z' has 1 values, expected 2");
  auto b = ParseTokenFile("a||b\n", "m.tok");
  ASSERT_FALSE(b.ok());
  EXPECT_EQ(b.status().message(), "m.tok:1:1: empty value 2 in token 'a||b'");
  auto c = ParseTokenFile("a|b\nc|\xff\n", "m.tok");
  ASSERT_FALSE(c.ok());
  EXPECT_EQ(c.status().message(), "m.tok:2:3: invalid UTF-8");
  auto d = ParseTokenFile("a|b", "m.tok", 3);
  ASSERT_FALSE(d.ok());
  EXPECT_EQ(d.status().message(), "m.tok:1:1: token 'a|b' has 2 values, expected 3");
}

TEST(Graph, WeightsAreNegativeLogConditionals) {
  // Feature 1: a->b twice, a->c once, b->a once. Feature 2 constant x.
  TokenFile t = Parse("a|x b|x a|x c|x\na|x b|x\n");
  auto g = GraphModel::Train(t.sequences, t.k, {});
  ASSERT_TRUE(g.ok()) << g.status().message();
  const int32_t a = g->ValueId(0, "a"), b = g->ValueId(0, "b"), c = g->ValueId(0, "c");
  // C(a) = 3 transitions leave a: 2 to b, 1 to c.
  EXPECT_DOUBLE_EQ(g->Weight(0, a, b), std::log(3.0) - std::log(2.0));
  EXPECT_DOUBLE_EQ(g->Weight(0, a, c), std::log(3.0));
  EXPECT_DOUBLE_EQ(g->Weight(0, b, a), 0.0);
  EXPECT_TRUE(std::isinf(g->Weight(0, a, a)));  // never observed: no edge
  EXPECT_TRUE(std::isinf(g->Weight(0, c, a)));  // c ends a line
  EXPECT_EQ(g->OutEdges(0, c).size(), 0u);
  EXPECT_DOUBLE_EQ(g->Weight(1, 0, 0), 0.0);
  EXPECT_EQ(g->Occurrences(0, a), 3u);
}

TEST(Graph, SmoothingAndReverseEdges) {
  TokenFile t = Parse("a b a c\n");  // k = 1
  TrainOptions o;
  o.alpha = 0.5;
  auto g = GraphModel::Train(t.sequences, 1, o);
  ASSERT_TRUE(g.ok());
  const int32_t a = g->ValueId(0, "a"), b = g->ValueId(0, "b"), c = g->ValueId(0, "c");
  // C(a) = 2 (to b, to c), M = 3: w = ln(2 + 1.5) - ln(C + 0.5).
  EXPECT_DOUBLE_EQ(g->Weight(0, a, b), std::log(3.5) - std::log(1.5));
  EXPECT_DOUBLE_EQ(g->Weight(0, a, a), std::log(3.5) - std::log(0.5));
  EXPECT_EQ(g->OutEdges(0, c).size(), 3u);  // complete
  TrainOptions r;
  r.reverse_edges = true;
  auto h = GraphModel::Train(t.sequences, 1, r);
  ASSERT_TRUE(h.ok());
  // a->b, b->a, a->c forward; reversed: b->a, a->b, c->a. C(a) = 3 (a->b
  // twice, a->c once), C(c) = 1.
  EXPECT_DOUBLE_EQ(h->Weight(0, c, a), 0.0);
  EXPECT_DOUBLE_EQ(h->Weight(0, a, b), std::log(3.0) - std::log(2.0));
}

TEST(Graph, AdmissibilityFromInfluencePairs) {
  TokenFile t = Parse("a|x b|y a|x\nb|y b|y\n");
  TrainOptions o;
  o.influence = InfluenceMode::kGiven;
  o.pairs = {{1, 0}};  // feature 2's parent is feature 1
  auto g = GraphModel::Train(t.sequences, 2, o);
  ASSERT_TRUE(g.ok());
  const int32_t a = g->ValueId(0, "a"), b = g->ValueId(0, "b");
  const int32_t x = g->ValueId(1, "x"), y = g->ValueId(1, "y");
  EXPECT_TRUE(g->Admissible(std::vector<int32_t>{a, x}));
  EXPECT_FALSE(g->Admissible(std::vector<int32_t>{a, y}));
  EXPECT_EQ(g->PairCount(0, b, y), 3u);
  o.min_pair_count = 3;
  auto h = GraphModel::Train(t.sequences, 2, o);
  ASSERT_TRUE(h.ok());
  EXPECT_FALSE(h->Admissible(std::vector<int32_t>{a, x}));  // only twice together
  EXPECT_TRUE(h->Admissible(std::vector<int32_t>{b, y}));
}

GraphModel Sample() {
  TokenFile t = Parse("R|move|jug L|dyno|crimp R|move|jug\nL|move|crimp R|cross|sloper\n");
  TrainOptions o;
  o.influence = InfluenceMode::kLearned;
  o.reverse_edges = true;
  auto g = GraphModel::Train(t.sequences, 3, o);
  EXPECT_TRUE(g.ok());
  EXPECT_TRUE(g->set_metadata({{"grammar", "climbing"}, {"tokens", "climbing"}}).ok());
  return *g;
}

TEST(GraphFile, RoundTripIsByteIdentical) {
  GraphModel g = Sample();
  const std::string bytes = g.Serialize();
  auto back = GraphModel::Parse(bytes, "g.sbg");
  ASSERT_TRUE(back.ok()) << back.status().message();
  EXPECT_EQ(back->Serialize(), bytes);
  EXPECT_EQ(back->influence(), g.influence());
  EXPECT_EQ(back->metadata(), g.metadata());
  EXPECT_FALSE(g.set_metadata({{"Bad Key", "x"}}).ok());
  EXPECT_FALSE(g.set_metadata({{"k", "line\nbreak"}}).ok());
  EXPECT_EQ(back->influence().size(), 2u);
  EXPECT_DOUBLE_EQ(back->Weight(0, 1, 0), g.Weight(0, 1, 0));
  EXPECT_TRUE(bytes.starts_with("strangebeta-graph 1\nfeatures 3\n"));
}

TEST(GraphFile, DamagedFilesAreRefusedWithAPlace) {
  const std::string bytes = Sample().Serialize();
  // Every truncation is refused, never a crash.
  for (size_t n = 0; n < bytes.size(); ++n) {
    auto r = GraphModel::Parse(bytes.substr(0, n), "g.sbg");
    EXPECT_FALSE(r.ok()) << n;
  }
  // A flipped byte in the body: checksum mismatch.
  std::string flipped = bytes;
  flipped[40] ^= 1;
  auto f = GraphModel::Parse(flipped, "g.sbg");
  ASSERT_FALSE(f.ok());
  EXPECT_EQ(f.status().message(), "g.sbg: checksum mismatch (file truncated or corrupted)");
  EXPECT_EQ(GraphModel::Parse(bytes.substr(0, bytes.size() - 10), "g.sbg").status().message(),
            "g.sbg: truncated: the file does not end with its checksum line");
  EXPECT_EQ(GraphModel::Parse("strangebeta-graph 2\n", "g.sbg").status().message(),
            "g.sbg:1: unsupported graph format version '2' (this build reads 1)");
  EXPECT_EQ(GraphModel::Parse("SBVOMM", "g.sbg").status().message(),
            "g.sbg:1: not a strangebeta graph file (expected 'strangebeta-graph 1')");
}

// A body with a valid checksum but bad content: errors name the line.
std::string WithChecksum(const std::string& body) {
  char sum[40];
  std::snprintf(sum, sizeof sum, "checksum %016llx\n",
                static_cast<unsigned long long>(Fnv1a64(body)));
  return body + sum;
}

TEST(GraphFile, ContentErrorsNameTheLine) {
  const std::string head =
      "strangebeta-graph 1\nfeatures 1\nalpha 0\nreverse-edges 0\nmin-pair-count 1\n"
      "influence none 0\nmetadata 0\nvalues 1 2\na 1\nb 1\ntransitions 1 1\n";
  auto ok = GraphModel::Parse(WithChecksum(head + "0 1 1\nend\n"), "g.sbg");
  ASSERT_TRUE(ok.ok()) << ok.status().message();
  EXPECT_DOUBLE_EQ(ok->Weight(0, 0, 1), 0.0);
  EXPECT_EQ(GraphModel::Parse(WithChecksum(head + "0 2 1\nend\n"), "g.sbg").status().message(),
            "g.sbg:12: '2' is not an integer in 0..1");
  EXPECT_EQ(GraphModel::Parse(WithChecksum(head + "0 1 0\nend\n"), "g.sbg").status().message(),
            "g.sbg:12: a count must be >= 1");
  EXPECT_EQ(GraphModel::Parse(WithChecksum(head + "0 1 1\n"), "g.sbg").status().message(),
            "g.sbg:13: truncated: expected 'end'");
  EXPECT_EQ(GraphModel::Parse(WithChecksum(head + "0 1 1\nend\nx\n"), "g.sbg").status().message(),
            "g.sbg:14: unexpected content after 'end'");
  std::string unsorted = head;
  unsorted.replace(unsorted.find("a 1\nb 1"), 7, "b 1\na 1");
  EXPECT_EQ(GraphModel::Parse(WithChecksum(unsorted + "0 1 1\nend\n"), "g.sbg").status().message(),
            "g.sbg:10: values are not in ascending order");
}

TEST(GraphFile, InfluenceFileErrors) {
  auto p = ParseInfluenceFile("# body\n2 1\n3 1\n", "i.txt", 3);
  ASSERT_TRUE(p.ok());
  EXPECT_EQ(*p, (std::vector<InfluencePair>{{1, 0}, {2, 0}}));
  EXPECT_EQ(ParseInfluenceFile("2 1\n4 1\n", "i.txt", 3).status().message(),
            "i.txt:2: pair '4 1': feature positions must be in 1..3");
  EXPECT_EQ(ParseInfluenceFile("2 x\n", "i.txt", 3).status().message(),
            "i.txt:1: expected 'child parent' (two 1-based feature positions), got '2 x'");
  EXPECT_EQ(ParseInfluenceFile("2 1\n1 2\n", "i.txt", 3).status().message(),
            "i.txt:2: pair '1 2' closes a cycle");
  EXPECT_EQ(ParseInfluenceFile("2 2\n", "i.txt", 3).status().message(),
            "i.txt:1: pair '2 2': a feature cannot be its own parent");
  EXPECT_EQ(ParseInfluenceFile("2 1\n2 1\n", "i.txt", 3).status().message(),
            "i.txt:2: pair '2 1' is given twice");
}

}  // namespace
}  // namespace sb::graph
