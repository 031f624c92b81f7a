#include <gtest/gtest.h>

#include <cmath>
#include <numeric>
#include <string>
#include <vector>

#include "markov/model.h"

namespace sb::markov {
namespace {

std::vector<int32_t> Chars(const std::string& s) { return {s.begin(), s.end()}; }

std::vector<int32_t> Abracadabra5(const std::string& s) {
  std::vector<int32_t> out;
  for (char c : s) out.push_back(std::string("abcdr").find(c));
  return out;
}

std::unique_ptr<Model> TrainOrDie(Algorithm alg, int depth, int k,
                                  const std::vector<int32_t>& seq) {
  auto r = Model::Train({alg, depth, k, 1.0}, seq);
  EXPECT_TRUE(r.ok()) << r.status().message();
  return std::move(r).value();
}

std::string Repeat(const std::string& s, int n) {
  std::string out;
  for (int i = 0; i < n; ++i) out += s;
  return out;
}

// Test vectors of ../shared/peer/DECTW-NOTES.md (measured on the reference
// Java library); reproduced here as the module's specification.
struct Vector {
  int ab_size;
  int depth;
  double bits;
};

TEST(DeCtw, ReferenceVectors) {
  const std::string train = Repeat("abracadabra", 10);
  const std::string test = Repeat("abracadabra", 2) + "cadabraabra";
  const Vector vectors[] = {
      {256, 1, 27.759961191897660}, {256, 3, 7.8224784642926710}, {256, 5, 11.144810451821890},
      {5, 1, 27.733161817587636},   {5, 3, 7.795679089982649},    {5, 5, 11.118011077511866},
  };
  for (const Vector& v : vectors) {
    auto tr = v.ab_size == 256 ? Chars(train) : Abracadabra5(train);
    auto te = v.ab_size == 256 ? Chars(test) : Abracadabra5(test);
    auto m = TrainOrDie(Algorithm::kDeCtw, v.depth, v.ab_size, tr);
    const double bits = m->LogLoss(te);
    EXPECT_NEAR(bits / v.bits, 1.0, 1e-9)
        << "abSize " << v.ab_size << " D " << v.depth << " got " << bits;
  }
}

TEST(DeCtw, ReferenceSingleAbracadabra) {
  auto m = TrainOrDie(Algorithm::kDeCtw, 5, 256, Chars("abracadabra"));
  EXPECT_NEAR(m->LogLoss(Chars("cadabra")) / 4.771218318240812, 1.0, 1e-9);
  EXPECT_NEAR(m->Probability(Chars("abra"), 'c') / 0.6877076036731496, 1.0, 1e-9);
  std::vector<double> dist(256);
  m->Distribution(Chars("abra"), dist);
  EXPECT_NEAR(std::accumulate(dist.begin(), dist.end(), 0.0), 1.0, 1e-12);
  EXPECT_DOUBLE_EQ(dist['c'], m->Probability(Chars("abra"), 'c'));
}

}  // namespace
}  // namespace sb::markov

namespace sb::markov {
namespace {

// Alphabet {0, 1}, D = 1, trained on "0 1". Decomposition: one node, right =
// symbol 1 (label 0), left = symbol 0 (label 1). Position 0 (no context)
// counts label 1 at the root; position 1 (context [0]) gives the new node
// [0] counts (1, 0) and the root, with child Pw 0.5, all = 1, beta' = 1/1.125,
// becomes beta = beta' * (0 + 1/16) / 0.5 = 1/9, counts (1, 1).
// P(1 | [0]): node [0] estimates (1 + 1/16)/(1 + 2/16) = 17/18; the root adds
// beta/(2 + 1/8) * (1 + 1/16) = 1/18 to each side: (17/18 + 1/18)/(1 + 1/9) = 0.9.
// P(0 | [1]): the node [1] does not exist (0.5, 0.5), and the root's symmetric
// counts keep 0.5. P(1 | []) = Pe(root) = (1 + 1/16)/(2 + 1/8) = 0.5.
TEST(DeCtw, HandComputedBinary) {
  auto r = Model::Train({Algorithm::kDeCtw, 1, 2, 1.0}, std::vector<int32_t>{0, 1});
  ASSERT_TRUE(r.ok());
  const Model& m = **r;
  EXPECT_NEAR(m.Probability(std::vector<int32_t>{0}, 1), 0.9, 1e-15);
  EXPECT_NEAR(m.Probability(std::vector<int32_t>{0}, 0), 0.1, 1e-15);
  EXPECT_NEAR(m.Probability(std::vector<int32_t>{1}, 0), 0.5, 1e-15);
  EXPECT_NEAR(m.Probability({}, 1), 0.5, 1e-15);
}

// Count halving (c > 256) and beta bounds are exercised by a long run: the
// distribution still sums to one and the model stays finite.
TEST(DeCtw, LongRunStaysNormalised) {
  std::vector<int32_t> seq;
  for (int i = 0; i < 5000; ++i) seq.push_back(i % 7 == 0 ? 2 : (i % 2));
  auto r = Model::Train({Algorithm::kDeCtw, 4, 3, 1.0}, seq);
  ASSERT_TRUE(r.ok());
  std::vector<double> dist(3);
  (*r)->Distribution(std::span<const int32_t>(seq.data() + 100, 4), dist);
  EXPECT_NEAR(dist[0] + dist[1] + dist[2], 1.0, 1e-12);
  const double bits = (*r)->LogLoss(seq);
  EXPECT_TRUE(std::isfinite(bits));
  EXPECT_LT(bits / seq.size(), 0.5);  // periodic: far below log2(3) = 1.58
}

}  // namespace
}  // namespace sb::markov
