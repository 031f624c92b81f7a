// PPM-C and the Markov chain against hand-computed small cases.
#include <gtest/gtest.h>

#include <cmath>
#include <numeric>
#include <vector>

#include "markov/model.h"

namespace sb::markov {
namespace {

// Training "a b a b c" as ids 0 1 0 1 2, alphabet 4 (id 3 never seen), D = 1.
// Order-0 counts a:2 b:2 c:1; after a: {b:2}; after b: {a:1, c:1}; the
// context "c" never occurs (c is last).
const std::vector<int32_t> kTrain = {0, 1, 0, 1, 2};

std::unique_ptr<Model> Make(Algorithm alg) {
  auto r = Model::Train({alg, 1, 4, 1.0}, kTrain);
  EXPECT_TRUE(r.ok());
  return std::move(r).value();
}

TEST(PpmC, HandComputed) {
  auto m = Make(Algorithm::kPpmC);
  const std::vector<int32_t> a = {0}, b = {1}, c = {2};
  // After a: n=2, q=1 -> P(b) = 2/3, escape 1/3; b excluded at order 0 leaves
  // a:2, c:1 (n=3, q=2): P(a) = 1/3*2/5, P(c) = 1/3*1/5; escape 2/5 to
  // order -1 with a, b, c excluded: P(d) = 1/3*2/5*1/1.
  EXPECT_DOUBLE_EQ(m->Probability(a, 1), 2.0 / 3);
  EXPECT_DOUBLE_EQ(m->Probability(a, 0), 2.0 / 15);
  EXPECT_DOUBLE_EQ(m->Probability(a, 2), 1.0 / 15);
  EXPECT_DOUBLE_EQ(m->Probability(a, 3), 2.0 / 15);
  // After b: n=2, q=2 -> P(a) = P(c) = 1/4.
  EXPECT_DOUBLE_EQ(m->Probability(b, 0), 0.25);
  EXPECT_DOUBLE_EQ(m->Probability(b, 2), 0.25);
  // Context c unseen: order 0 (n=5, q=3): a 2/8, b 2/8, c 1/8, d 3/8 * 1/1.
  EXPECT_DOUBLE_EQ(m->Probability(c, 0), 0.25);
  EXPECT_DOUBLE_EQ(m->Probability(c, 2), 0.125);
  EXPECT_DOUBLE_EQ(m->Probability(c, 3), 0.375);
  // -log2 P("a b") = -log2(2/8) - log2(2/3).
  const std::vector<int32_t> ab = {0, 1};
  EXPECT_NEAR(m->LogLoss(ab), 2 + std::log2(1.5), 1e-12);
}

TEST(Markov, HandComputed) {
  auto m = Make(Algorithm::kMarkov);
  const std::vector<int32_t> a = {0}, b = {1}, c = {2};
  EXPECT_DOUBLE_EQ(m->Probability(a, 1), 3.0 / 6);  // (2+1)/(2+4)
  EXPECT_DOUBLE_EQ(m->Probability(a, 3), 1.0 / 6);
  EXPECT_DOUBLE_EQ(m->Probability(b, 0), 2.0 / 6);
  EXPECT_DOUBLE_EQ(m->Probability(c, 0), 0.25);      // unseen context: uniform
  EXPECT_DOUBLE_EQ(m->Probability({}, 0), 3.0 / 9);  // order 0 at the start
}

TEST(CountModels, DistributionMatchesProbabilityAndSumsToOne) {
  std::vector<int32_t> seq;
  uint32_t x = 12345;
  for (int i = 0; i < 2000; ++i) {
    x = x * 1103515245u + 12345u;
    seq.push_back(static_cast<int32_t>((x >> 16) % 7));
  }
  for (Algorithm alg : {Algorithm::kPpmC, Algorithm::kMarkov, Algorithm::kDeCtw}) {
    auto r = Model::Train({alg, 3, 9, 0.5}, seq);
    ASSERT_TRUE(r.ok());
    const Model& m = **r;
    std::vector<double> dist(9);
    for (size_t start : {size_t{0}, size_t{5}, size_t{100}}) {
      for (size_t len : {size_t{0}, size_t{1}, size_t{3}}) {
        std::span<const int32_t> ctx(seq.data() + start, len);
        m.Distribution(ctx, dist);
        EXPECT_NEAR(std::accumulate(dist.begin(), dist.end(), 0.0), 1.0, 1e-12);
        for (int s = 0; s < 9; ++s) EXPECT_NEAR(dist[s], m.Probability(ctx, s), 1e-15);
        std::vector<std::pair<int32_t, double>> likely;
        m.LikelySymbols(ctx, 0.05, &likely);
        for (int s = 0; s < 9; ++s) {
          if (dist[s] < 0.05) continue;
          bool found = false;
          for (auto [sym, p] : likely) found |= (sym == s && std::fabs(p - dist[s]) < 1e-15);
          EXPECT_TRUE(found) << AlgorithmName(alg) << " symbol " << s;
        }
      }
    }
  }
}

TEST(Model, RejectsBadInput) {
  EXPECT_FALSE(Model::Train({Algorithm::kDeCtw, 0, 4, 1.0}, kTrain).ok());
  EXPECT_FALSE(Model::Train({Algorithm::kDeCtw, 2, 1, 1.0}, kTrain).ok());
  EXPECT_FALSE(Model::Train({Algorithm::kDeCtw, 2, 2, 1.0}, kTrain).ok());  // id 2 >= K
  EXPECT_FALSE(Model::Train({Algorithm::kMarkov, 2, 4, 0.0}, kTrain).ok());
  EXPECT_TRUE(Model::Train({Algorithm::kDeCtw, 2, 4, 1.0}, {}).ok());  // empty training is fine
  EXPECT_FALSE(Model::Train({Algorithm::kDeCtw, 2, 100000, 1.0}, kTrain).ok());  // chain too deep
  EXPECT_TRUE(Model::Train({Algorithm::kPpmC, 2, 100000, 1.0}, kTrain).ok());
}

}  // namespace
}  // namespace sb::markov
