// Interpolation equals brute force on small alphabets; generation is
// deterministic for a seed; the smoothing API on string tokens.
#include "markov/interpolate.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <set>
#include <vector>

#include "markov/generate.h"
#include "markov/model.h"
#include "markov/token_model.h"

namespace sb::markov {
namespace {

// A peaked order-1 stream over k symbols (each symbol has two likely
// successors, plus noise).
std::vector<int32_t> Stream(int k, size_t n, uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::vector<int32_t> out{0};
  while (out.size() < n) {
    const uint64_t r = rng() % 10;
    const int32_t prev = out.back();
    out.push_back(r < 6   ? (prev * 3 + 1) % k
                  : r < 9 ? (prev + 2) % k
                          : static_cast<int32_t>(rng() % k));
  }
  return out;
}

struct Brute {
  double bits = std::numeric_limits<double>::infinity();
  std::vector<int32_t> ins;
};

void BruteForce(const Model& m, const std::vector<int32_t>& before,
                const std::vector<int32_t>& after, const std::vector<int32_t>& cands, int j,
                std::vector<int32_t>* cur, Brute* best) {
  std::vector<int32_t> full = before;
  full.insert(full.end(), cur->begin(), cur->end());
  full.insert(full.end(), after.begin(), after.end());
  const double bits = m.LogLoss(full);
  if (bits < best->bits) {
    best->bits = bits;
    best->ins = *cur;
  }
  if (static_cast<int>(cur->size()) == j) return;
  for (int32_t c : cands) {
    cur->push_back(c);
    BruteForce(m, before, after, cands, j, cur, best);
    cur->pop_back();
  }
}

TEST(Interpolate, EqualsBruteForce) {
  std::mt19937_64 rng(3);
  int cases = 0;
  for (Algorithm alg : {Algorithm::kDeCtw, Algorithm::kPpmC, Algorithm::kMarkov}) {
    for (int k : {3, 5, 8}) {
      for (int depth : {1, 2, 3}) {
        const auto train = Stream(k, 300, 11 + k + depth);
        auto r = Model::Train({alg, depth, k + 1, 0.5}, train);  // id k never seen
        ASSERT_TRUE(r.ok());
        const Model& m = **r;
        for (int trial = 0; trial < 4; ++trial) {
          std::vector<int32_t> before, after;
          const int nb = static_cast<int>(rng() % 5), na = static_cast<int>(rng() % 5);
          for (int i = 0; i < nb; ++i) before.push_back(static_cast<int32_t>(rng() % k));
          for (int i = 0; i < na; ++i) after.push_back(static_cast<int32_t>(rng() % k));
          for (int j = 0; j <= 3; ++j) {
            InsertionOptions opt;
            opt.max_insert = j;
            auto got = BestInsertion(m, before, after, opt);
            ASSERT_TRUE(got.ok());
            Brute brute;
            std::vector<int32_t> cur;
            BruteForce(m, before, after, m.SeenSymbols(), j, &cur, &brute);
            EXPECT_NEAR(got->bits, brute.bits, 1e-9 * std::max(1.0, brute.bits))
                << AlgorithmName(alg) << " k " << k << " D " << depth << " j " << j;
            EXPECT_LE(static_cast<int>(got->inserted.size()), j);
            // The reported bits are those of the reported insertion.
            std::vector<int32_t> full = before;
            full.insert(full.end(), got->inserted.begin(), got->inserted.end());
            full.insert(full.end(), after.begin(), after.end());
            EXPECT_DOUBLE_EQ(got->bits, m.LogLoss(full));
            EXPECT_GE(got->saved_bits(), 0.0);
            ++cases;
          }
        }
      }
    }
  }
  EXPECT_EQ(cases, 3 * 3 * 3 * 4 * 4);
}

// --exactly J: the best of all K^J insertions of exactly J symbols (the
// paper's N^j search), even when inserting nothing is cheaper.
TEST(Interpolate, ExactlyJEqualsBruteForce) {
  std::mt19937_64 rng(8);
  int cases = 0, worse_than_nothing = 0;
  for (Algorithm alg : {Algorithm::kDeCtw, Algorithm::kPpmC, Algorithm::kMarkov}) {
    for (int k : {3, 6}) {
      const auto train = Stream(k, 300, 5 + k);
      auto r = Model::Train({alg, 2, k + 1, 0.5}, train);
      ASSERT_TRUE(r.ok());
      const Model& m = **r;
      const std::vector<int32_t> cands = m.SeenSymbols();
      for (int trial = 0; trial < 4; ++trial) {
        std::vector<int32_t> before, after;
        for (int i = 0; i < 3; ++i) before.push_back(static_cast<int32_t>(rng() % k));
        for (int i = 0; i < 3; ++i) after.push_back(static_cast<int32_t>(rng() % k));
        for (int j = 0; j <= 3; ++j) {
          // Brute force over exactly j symbols.
          double best = std::numeric_limits<double>::infinity();
          std::vector<int32_t> cur(j, 0), best_ins;
          std::vector<size_t> idx(j, 0);
          for (;;) {
            for (int i = 0; i < j; ++i) cur[i] = cands[idx[i]];
            std::vector<int32_t> full = before;
            full.insert(full.end(), cur.begin(), cur.end());
            full.insert(full.end(), after.begin(), after.end());
            const double bits = m.LogLoss(full);
            if (bits < best) {
              best = bits;
              best_ins = cur;
            }
            int i = j - 1;
            while (i >= 0 && ++idx[i] == cands.size()) idx[i--] = 0;
            if (i < 0) break;
          }
          InsertionOptions opt;
          opt.max_insert = j;
          opt.exactly = true;
          for (int threads : {1, 2}) {
            opt.threads = threads;
            auto got = BestInsertion(m, before, after, opt);
            ASSERT_TRUE(got.ok());
            ASSERT_EQ(static_cast<int>(got->inserted.size()), j);
            EXPECT_NEAR(got->bits, best, 1e-9 * std::max(1.0, best))
                << AlgorithmName(alg) << " k " << k << " j " << j;
          }
          worse_than_nothing += best > m.LogLoss([&] {
            std::vector<int32_t> f = before;
            f.insert(f.end(), after.begin(), after.end());
            return f;
          }());
          ++cases;
        }
      }
    }
  }
  EXPECT_EQ(cases, 3 * 2 * 4 * 4);
  EXPECT_GT(worse_than_nothing, 0);  // the case --exactly exists for
}

TEST(Interpolate, TwoThreadsGiveTheSequentialAnswer) {
  // Includes brute force with both splits on small alphabets, and the
  // sequential search on a larger one (where the split is used by default).
  std::mt19937_64 rng(5);
  for (Algorithm alg : {Algorithm::kDeCtw, Algorithm::kPpmC, Algorithm::kMarkov}) {
    for (int k : {4, 7, 80}) {
      const auto train = Stream(k, k > 10 ? 3000 : 300, 17 + k);
      auto r = Model::Train({alg, 3, k + 1, 0.5}, train);
      ASSERT_TRUE(r.ok());
      const Model& m = **r;
      for (int trial = 0; trial < 3; ++trial) {
        std::vector<int32_t> before, after;
        for (int i = 0; i < 4; ++i) before.push_back(static_cast<int32_t>(rng() % k));
        for (int i = 0; i < 4; ++i) after.push_back(static_cast<int32_t>(rng() % k));
        const int j = k > 10 ? 2 : 3;  // keep the large case quick
        InsertionOptions one, two;
        one.max_insert = two.max_insert = j;
        one.threads = 1;
        two.threads = 2;
        auto a = BestInsertion(m, before, after, one);
        auto b = BestInsertion(m, before, after, two);
        ASSERT_TRUE(a.ok() && b.ok());
        EXPECT_EQ(a->inserted, b->inserted) << AlgorithmName(alg) << " k " << k;
        EXPECT_EQ(a->bits, b->bits);
        if (k <= 10) {
          Brute brute;
          std::vector<int32_t> cur;
          BruteForce(m, before, after, m.SeenSymbols(), j, &cur, &brute);
          EXPECT_NEAR(b->bits, brute.bits, 1e-9 * std::max(1.0, brute.bits));
        }
      }
    }
  }
}

TEST(Interpolate, RejectsBadArguments) {
  auto r = Model::Train({Algorithm::kDeCtw, 2, 3, 1.0}, std::vector<int32_t>{0, 1, 2, 0});
  ASSERT_TRUE(r.ok());
  InsertionOptions opt;
  opt.max_insert = kMaxInsert + 1;
  EXPECT_FALSE(BestInsertion(**r, {}, {}, opt).ok());
  opt.max_insert = 1;
  EXPECT_FALSE(BestInsertion(**r, std::vector<int32_t>{7}, {}, opt).ok());
}

TEST(Generate, GreedyAndSeededSamplingAreDeterministic) {
  const auto train = Stream(5, 500, 1);
  auto r = Model::Train({Algorithm::kDeCtw, 2, 5, 1.0}, train);
  ASSERT_TRUE(r.ok());
  const std::vector<int32_t> start = {0};
  GenerateOptions greedy;
  greedy.length = 12;
  greedy.max_run = 0;  // plain greedy
  const auto g1 = Generate(**r, start, greedy);
  ASSERT_EQ(g1.size(), 12u);
  // Greedy picks the most likely symbol each step.
  std::vector<int32_t> hist = start;
  std::vector<double> dist(5);
  for (int32_t s : g1) {
    (*r)->Distribution(hist, dist);
    for (int t = 0; t < 5; ++t) EXPECT_LE(dist[t], dist[s]);
    hist.push_back(s);
  }
  GenerateOptions sampled;
  sampled.length = 200;
  sampled.sample = true;
  sampled.seed = 99;
  const auto s1 = Generate(**r, start, sampled);
  const auto s2 = Generate(**r, start, sampled);
  EXPECT_EQ(s1, s2);
  sampled.seed = 100;
  EXPECT_NE(Generate(**r, start, sampled), s1);
  // Sampled text is typical: its bits per symbol are near the model's.
  EXPECT_LT((*r)->LogLoss(s1) / s1.size(), 2.0);
}

// A peaked model makes plain greedy generation repeat one symbol; max_run
// and no_repeat_ngram stop it, and temperature sharpens sampling.
TEST(Generate, RunAndNgramLimits) {
  std::vector<int32_t> train;
  for (int i = 0; i < 300; ++i) train.push_back(i % 10 == 9 ? 1 + (i / 10) % 3 : 0);
  auto r = Model::Train({Algorithm::kDeCtw, 2, 4, 1.0}, train);
  ASSERT_TRUE(r.ok());
  GenerateOptions plain;
  plain.length = 30;
  plain.max_run = 0;
  const auto collapsed = Generate(**r, {}, plain);
  EXPECT_EQ(std::count(collapsed.begin(), collapsed.end(), 0), 30);
  GenerateOptions runs = plain;
  runs.max_run = 2;
  const auto g = Generate(**r, {}, runs);
  ASSERT_EQ(g.size(), 30u);
  for (size_t i = 2; i < g.size(); ++i) {
    EXPECT_FALSE(g[i] == g[i - 1] && g[i] == g[i - 2]) << i;
  }
  GenerateOptions ngram = plain;
  ngram.no_repeat_ngram = 3;
  ngram.length = 20;
  const auto h = Generate(**r, {}, ngram);
  // A trigram repeats only when every continuation of its first two symbols
  // was used before (the rule is then dropped for that step).
  std::set<std::vector<int32_t>> seen;
  for (size_t i = 0; i + 3 <= h.size(); ++i) {
    const std::vector<int32_t> tri(h.begin() + i, h.begin() + i + 3);
    if (seen.count(tri)) {
      for (int32_t c = 0; c < 4; ++c) {
        EXPECT_TRUE(seen.count({tri[0], tri[1], c})) << "repeat at " << i;
      }
    }
    seen.insert(tri);
  }
  EXPECT_GE(seen.size(), 10u);
  // A cold temperature samples the likely symbol more often than T = 1.
  GenerateOptions hot = runs, cold = runs;
  hot.sample = cold.sample = true;
  hot.length = cold.length = 2000;
  cold.temperature = 0.3;
  const auto a = Generate(**r, {}, hot), b = Generate(**r, {}, cold);
  EXPECT_GT(std::count(b.begin(), b.end(), 0), std::count(a.begin(), a.end(), 0));
  EXPECT_FALSE(ValidateGenerateOptions({.length = -1}).ok());
  GenerateOptions bad;
  bad.temperature = 0;
  EXPECT_FALSE(ValidateGenerateOptions(bad).ok());
  bad.temperature = 1;
  bad.no_repeat_ngram = 1;
  EXPECT_FALSE(ValidateGenerateOptions(bad).ok());
  bad.no_repeat_ngram = 0;
  bad.length = kMaxGenerateLength + 1;
  EXPECT_FALSE(ValidateGenerateOptions(bad).ok());
}

TEST(SuggestSmoothing, StringTokensAndUnknowns) {
  std::vector<std::string> train;
  for (int i = 0; i < 30; ++i) {
    for (const char* t : {"start", "jug", "crimp", "sloper", "top"}) train.push_back(t);
  }
  auto m = TokenModel::FromTokens({Algorithm::kDeCtw, 2, 0, 1.0}, train);
  ASSERT_TRUE(m.ok());
  // "jug" -> "top" skips "crimp sloper": inserting them helps.
  auto s = SuggestSmoothing(*m, {"start", "jug"}, {"top", "start"}, 2);
  ASSERT_TRUE(s.ok());
  EXPECT_EQ(s->insert, (std::vector<std::string>{"crimp", "sloper"}));
  EXPECT_GT(s->bits_saved, 1.0);
  EXPECT_NEAR(s->bits_without - s->bits_with, s->bits_saved, 1e-12);
  // Unknown tokens are scored (as the unknown id) but never suggested.
  auto u = SuggestSmoothing(*m, {"start", "mystery"}, {"crimp"}, 1);
  ASSERT_TRUE(u.ok());
  for (const auto& t : u->insert) EXPECT_NE(t, "<unk>");
  // Nothing to gain on a smooth boundary.
  auto n = SuggestSmoothing(*m, {"start", "jug"}, {"crimp", "sloper"}, 2);
  ASSERT_TRUE(n.ok());
  EXPECT_TRUE(n->insert.empty());
  EXPECT_EQ(n->bits_saved, 0.0);
}

}  // namespace
}  // namespace sb::markov
