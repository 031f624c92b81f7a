// A* / greedy / memory-bounded search against an exhaustive shortest path
// over the product state space (issue 16 "must show").
#include "graph/search.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "graph/graph.h"

namespace sb::graph {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// A random corpus of `lines` sequences over k features with `m` values
// each; features 2.. follow feature 1 loosely so influence pairs matter.
std::vector<Sequence> RandomCorpus(uint64_t seed, int k, int m, int lines, int len) {
  std::mt19937_64 rng(seed);
  std::vector<Sequence> out;
  for (int l = 0; l < lines; ++l) {
    Sequence s;
    std::vector<int> v(k);
    for (int f = 0; f < k; ++f) v[f] = static_cast<int>(rng() % m);
    for (int i = 0; i < len; ++i) {
      Token t;
      for (int f = 0; f < k; ++f) t.push_back("v" + std::to_string(v[f]));
      s.push_back(t);
      // Feature 0 moves by +1 or +2 (mod m) mostly; the others drift, or
      // copy feature 0.
      v[0] = (v[0] + 1 + static_cast<int>(rng() % 2)) % m;
      for (int f = 1; f < k; ++f) {
        const uint64_t r = rng() % 4;
        if (r == 0)
          v[f] = v[0];
        else if (r == 1)
          v[f] = (v[f] + 1) % m;
        else if (r == 2)
          v[f] = static_cast<int>(rng() % m);
      }
    }
    out.push_back(std::move(s));
  }
  return out;
}

// The cheapest cost of a path from -> to with at most L inserted states,
// by dynamic programming over the whole product space (layer d = states
// after d transitions). Inserted states must be admissible (when
// `influence`), the goal is exempt.
double Exhaustive(const GraphModel& g, const std::vector<int32_t>& from,
                  const std::vector<int32_t>& to, int L, bool influence) {
  const int k = g.num_features();
  std::vector<std::vector<int32_t>> states;
  std::vector<int32_t> s(k, 0);
  for (;;) {
    states.push_back(s);
    int f = 0;
    while (f < k && ++s[f] == static_cast<int32_t>(g.values(f).size())) s[f++] = 0;
    if (f == k) break;
  }
  const size_t n = states.size();
  auto index = [&](const std::vector<int32_t>& x) {
    size_t i = 0, mul = 1;
    for (int f = 0; f < k; ++f) {
      i += x[f] * mul;
      mul *= g.values(f).size();
    }
    return i;
  };
  const size_t goal = index(to);
  std::vector<double> cur(n, kInf), next(n);
  cur[index(from)] = 0;
  double best = kInf;
  for (int d = 1; d <= L + 1; ++d) {
    std::fill(next.begin(), next.end(), kInf);
    for (size_t u = 0; u < n; ++u) {
      if (cur[u] == kInf) continue;
      if (d > 1 && u == goal) continue;  // arriving at the goal ends a path
      for (size_t v = 0; v < n; ++v) {
        const bool is_goal = v == goal;
        if (!is_goal && d == L + 1) continue;  // only the goal after L inserted
        if (!is_goal && influence && !g.Admissible(states[v])) continue;
        const double c = TransitionCost(g, states[u], states[v]);
        if (c == kInf) continue;
        next[v] = std::min(next[v], cur[u] + c);
      }
    }
    best = std::min(best, next[goal]);
    cur.swap(next);
  }
  return best;
}

double PathCost(const GraphModel& g, const std::vector<int32_t>& from, const SearchResult& r,
                const std::vector<int32_t>& to) {
  std::vector<std::vector<int32_t>> path{from};
  path.insert(path.end(), r.inserted.begin(), r.inserted.end());
  path.push_back(to);
  double c = 0;
  for (size_t i = 0; i + 1 < path.size(); ++i) c += TransitionCost(g, path[i], path[i + 1]);
  return c;
}

struct Case {
  uint64_t seed;
  int k, m;
  InfluenceMode influence;
  double alpha;
  bool reverse;
};

class SearchVsExhaustive : public ::testing::TestWithParam<Case> {};

TEST_P(SearchVsExhaustive, CostsMatch) {
  const Case c = GetParam();
  const auto corpus = RandomCorpus(c.seed, c.k, c.m, 6, 7);
  TrainOptions to;
  to.influence = c.influence;
  to.alpha = c.alpha;
  to.reverse_edges = c.reverse;
  auto g = GraphModel::Train(corpus, c.k, to);
  ASSERT_TRUE(g.ok()) << g.status().message();
  std::mt19937_64 rng(c.seed * 7 + 1);
  int found = 0, compared = 0;
  for (int trial = 0; trial < 12; ++trial) {
    std::vector<int32_t> a(c.k), b(c.k);
    for (int f = 0; f < c.k; ++f) {
      a[f] = static_cast<int32_t>(rng() % g->values(f).size());
      b[f] = static_cast<int32_t>(rng() % g->values(f).size());
    }
    for (int L : {0, 1, 3, 6}) {
      for (bool influence : {true, false}) {
        const double want =
            Exhaustive(*g, a, b, L, influence && c.influence != InfluenceMode::kNone);
        SearchOptions o;
        o.max_length = L;
        o.use_influence = influence;
        auto astar = Interpolate(*g, a, b, o);
        ASSERT_TRUE(astar.ok()) << astar.status().message();
        o.strategy = Strategy::kGreedy;
        auto greedy = Interpolate(*g, a, b, o);
        ASSERT_TRUE(greedy.ok());
        // Forced depth first: a budget too small for the best-first phase.
        SearchOptions small = o;
        small.strategy = Strategy::kAStar;
        small.memory_bytes = kMinMemoryBytes;
        auto bounded = Interpolate(*g, a, b, small);
        ASSERT_TRUE(bounded.ok());
        EXPECT_LE(bounded->stats.peak_bytes, kMinMemoryBytes);
        ++compared;
        if (want == kInf) {
          EXPECT_EQ(astar->outcome, Outcome::kNoPath) << "L=" << L;
          EXPECT_EQ(greedy->outcome, Outcome::kNoPath);
          if (bounded->outcome != Outcome::kLimit) {
            EXPECT_EQ(bounded->outcome, Outcome::kNoPath);
          }
          continue;
        }
        ++found;
        ASSERT_EQ(astar->outcome, Outcome::kFound) << "L=" << L << " want " << want;
        EXPECT_NEAR(astar->cost, want, 1e-9 * (1 + want)) << "L=" << L;
        EXPECT_NEAR(PathCost(*g, a, *astar, b), astar->cost, 1e-12 * (1 + want));
        EXPECT_LE(static_cast<int>(astar->inserted.size()), L);
        for (const auto& s : astar->inserted) {
          if (influence) {
            EXPECT_TRUE(g->Admissible(s));
          }
        }
        ASSERT_EQ(greedy->outcome, Outcome::kFound);
        EXPECT_GE(greedy->cost, astar->cost - 1e-9 * (1 + want));
        EXPECT_LE(static_cast<int>(greedy->inserted.size()), L);
        if (bounded->outcome == Outcome::kFound) {
          EXPECT_NEAR(bounded->cost, want, 1e-9 * (1 + want));
        } else {
          EXPECT_EQ(bounded->outcome, Outcome::kLimit);
        }
      }
    }
  }
  EXPECT_GT(found, 0);
  EXPECT_GT(compared, 0);
}

INSTANTIATE_TEST_SUITE_P(Synthetic, SearchVsExhaustive,
                         ::testing::Values(Case{1, 3, 4, InfluenceMode::kNone, 0, false},
                                           Case{2, 3, 4, InfluenceMode::kLearned, 0, false},
                                           Case{3, 4, 3, InfluenceMode::kLearned, 0, true},
                                           Case{4, 3, 4, InfluenceMode::kLearned, 0.5, false},
                                           Case{5, 2, 6, InfluenceMode::kLearned, 0, false},
                                           Case{6, 4, 3, InfluenceMode::kNone, 0.1, true}));

}  // namespace
}  // namespace sb::graph
