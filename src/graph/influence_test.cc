// Mutual information and the Chow-Liu tree, checked against SciPy
// (/usr/bin/python3 with Debian's python3-scipy), run by the test itself.
#include "graph/influence.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <random>
#include <set>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "graph/graph.h"

namespace sb::graph {
namespace {

std::vector<Sequence> Correlated(uint64_t seed, int k, int lines, int len) {
  std::mt19937_64 rng(seed);
  std::vector<Sequence> out;
  for (int l = 0; l < lines; ++l) {
    Sequence s;
    for (int i = 0; i < len; ++i) {
      std::vector<int> v(k);
      v[0] = static_cast<int>(rng() % 5);
      for (int f = 1; f < k; ++f) {
        // Feature f copies feature (f-1)/2 with probability 1/(f+1).
        const int parent = (f - 1) / 2;
        v[f] = rng() % (f + 1) == 0 ? v[parent] : static_cast<int>(rng() % (3 + f));
      }
      Token t;
      for (int f = 0; f < k; ++f) t.push_back("x" + std::to_string(v[f]));
      s.push_back(t);
    }
    out.push_back(s);
  }
  return out;
}

TEST(Influence, TopologicalOrderPutsParentsFirst) {
  const std::vector<InfluencePair> pairs{{0, 2}, {1, 0}, {3, 1}};
  EXPECT_EQ(TopologicalOrder(pairs, 4), (std::vector<int>{2, 0, 1, 3}));
  EXPECT_EQ(TopologicalOrder({}, 3), (std::vector<int>{0, 1, 2}));
}

TEST(Influence, ChowLiuTreeOnAChain) {
  // MI strongest along 0-1-2-3: the tree is that chain, oriented from 0.
  std::vector<std::vector<double>> mi{
      {1, 0.9, 0.1, 0.0}, {0.9, 1, 0.8, 0.2}, {0.1, 0.8, 1, 0.7}, {0.0, 0.2, 0.7, 1}};
  EXPECT_EQ(ChowLiuTree(mi), (std::vector<InfluencePair>{{1, 0}, {2, 1}, {3, 2}}));
}

TEST(Influence, MutualInformationAndTreeMatchScipy) {
  const std::string python = "/usr/bin/python3";
  if (access(python.c_str(), X_OK) != 0) GTEST_SKIP() << "/usr/bin/python3 not found";
  const int k = 6;
  const auto corpus = Correlated(11, k, 40, 25);
  const auto mi = MutualInformation(corpus, k);
  const auto tree = ChowLiuTree(mi);
  char dir[] = "/tmp/sb_influence_XXXXXX";
  ASSERT_NE(mkdtemp(dir), nullptr);
  const std::string data = std::string(dir) + "/tokens.txt";
  {
    std::ofstream f(data);
    for (const auto& s : corpus)
      for (const auto& t : s) f << FormatToken(t) << "\n";
  }
  const std::string script = std::string(dir) + "/mi.py";
  {
    std::ofstream f(script);
    f << R"(import sys
import numpy as np
from scipy.stats import entropy
from scipy.sparse.csgraph import minimum_spanning_tree
rows = [l.split('|') for l in open(sys.argv[1]).read().split()]
k = len(rows[0])
cols = [[r[f] for r in rows] for f in range(k)]
def H(*cs):
    from collections import Counter
    return entropy(list(Counter(zip(*cs)).values()))
mi = np.zeros((k, k))
for i in range(k):
    for j in range(k):
        mi[i, j] = H(cols[i]) + H(cols[j]) - H(cols[i], cols[j]) if i != j else H(cols[i])
for i in range(k):
    print(' '.join('%.17g' % v for v in mi[i]))
w = (mi.max() + 1.0) - mi
np.fill_diagonal(w, 0)
t = minimum_spanning_tree(w).toarray()
print(' '.join('%d-%d' % (min(i, j), max(i, j)) for i in range(k) for j in range(k) if t[i, j] != 0))
)";
  }
  const std::string out = std::string(dir) + "/out.txt";
  const std::string cmd = python + " " + script + " " + data + " > " + out;
  ASSERT_EQ(std::system(cmd.c_str()), 0) << cmd;
  std::ifstream in(out);
  for (int i = 0; i < k; ++i) {
    for (int j = 0; j < k; ++j) {
      double v = 0;
      in >> v;
      EXPECT_NEAR(mi[i][j], v, 1e-12) << i << "," << j;
    }
  }
  std::set<std::pair<int, int>> want, got;
  std::string edge;
  while (in >> edge) {
    const size_t dash = edge.find('-');
    want.insert({std::stoi(edge.substr(0, dash)), std::stoi(edge.substr(dash + 1))});
  }
  for (const auto& p : tree) got.insert({std::min(p.child, p.parent), std::max(p.child, p.parent)});
  EXPECT_EQ(got, want);
  EXPECT_EQ(tree.size(), static_cast<size_t>(k - 1));
  std::system(("rm -rf " + std::string(dir)).c_str());
}

TEST(Influence, LearnedGraphsStoreTheTree) {
  const auto corpus = Correlated(3, 4, 20, 10);
  TrainOptions o;
  o.influence = InfluenceMode::kLearned;
  auto g = GraphModel::Train(corpus, 4, o);
  ASSERT_TRUE(g.ok());
  EXPECT_EQ(g->influence(), ChowLiuTree(MutualInformation(corpus, 4)));
  EXPECT_EQ(g->options().influence, InfluenceMode::kLearned);
  // Every training token is admissible under its own pair counts.
  for (const auto& s : corpus)
    for (const auto& t : s) EXPECT_TRUE(g->Admissible(*g->Encode(t, "t")));
}

}  // namespace
}  // namespace sb::graph
