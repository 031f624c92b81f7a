// DE-CTW against a direct transcription of the reference's algorithm (one
// context tree per decomposition node, std::map nodes, no sharing, no
// "seen once" compression) on random sequences: the optimised structure must
// give the same probabilities, including count halving and beta bounds.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <map>
#include <random>
#include <vector>

#include "markov/model.h"

namespace sb::markov {
namespace {

class NaiveDeCtw {
 public:
  NaiveDeCtw(int k, int depth, const std::vector<int32_t>& seq) : k_(k), depth_(depth) {
    BuildTree(seq);
    for (size_t i = 0; i < seq.size(); ++i) {
      const auto ctx = Context(seq, i);
      for (auto [n, dir] : paths_[seq[i]]) Learn(n, ctx, dir);
    }
  }

  double Probability(const std::vector<int32_t>& history, int32_t x) const {
    const auto ctx = Context(history, history.size());
    std::vector<double> p;
    for (auto [n, dir] : paths_[x]) p.push_back(Predict(n, ctx, dir));
    double r = 1.0;
    for (size_t i = p.size(); i > 0; --i) r = p[i - 1] * r;
    return r;
  }

 private:
  struct Node {
    int c[2] = {0, 0};
    double beta = 1.0;
  };
  using Key = std::pair<int, std::vector<int32_t>>;

  std::vector<int32_t> Context(const std::vector<int32_t>& seq, size_t i) const {
    std::vector<int32_t> ctx;  // most recent first
    for (size_t d = 1; d <= static_cast<size_t>(depth_) && d <= i; ++d) ctx.push_back(seq[i - d]);
    return ctx;
  }

  void BuildTree(const std::vector<int32_t>& seq) {
    // Huffman as in the reference (see dectw.cc), keeping leaf depths.
    std::vector<long> count(k_, 0);
    for (int32_t s : seq) ++count[s];
    struct H {
      int sym, a, b;
    };
    std::vector<H> h;
    std::map<long, std::map<int, int>> cm;
    for (int s = 0; s < k_; ++s) {
      h.push_back({s, -1, -1});
      cm[count[s]][s] = s;
    }
    while (cm.size() > 1 || cm.begin()->second.size() > 1) {
      auto it = cm.begin();
      const long c1 = it->first;
      int key = it->second.rbegin()->first;
      const int n1 = it->second.rbegin()->second;
      it->second.erase(key);
      if (it->second.empty()) {
        cm.erase(it);
        it = cm.begin();
      }
      const long c2 = it->first;
      const int key2 = it->second.rbegin()->first;
      const int n2 = it->second.rbegin()->second;
      it->second.erase(key2);
      if (it->second.empty()) cm.erase(it);
      h.push_back({-1, n1, n2});
      cm[c1 + c2][std::max(key, key2)] = static_cast<int>(h.size()) - 1;
    }
    std::map<int, std::map<int, int>> levels;  // level -> key -> node (>=0 internal, <0 leaf)
    std::vector<std::pair<int, int>> st{{cm.begin()->second.begin()->second, 0}};
    while (!st.empty()) {
      auto [n, d] = st.back();
      st.pop_back();
      if (h[n].sym >= 0) {
        levels[d][h[n].sym] = -(h[n].sym + 1);
      } else {
        st.push_back({h[n].a, d + 1});
        st.push_back({h[n].b, d + 1});
      }
    }
    std::vector<std::array<int, 2>> kids;
    while (levels.size() > 1 || levels.rbegin()->second.size() > 1) {
      auto lit = std::prev(levels.end());
      const int level = lit->first;
      auto& one = lit->second;
      const int s1 = one.rbegin()->first, n1 = one.rbegin()->second;
      one.erase(s1);
      const int s2 = one.rbegin()->first, n2 = one.rbegin()->second;
      one.erase(s2);
      if (one.empty()) levels.erase(lit);
      kids.push_back({n1, n2});
      levels[level - 1][n2 < 0 ? s2 : (n1 < 0 ? s1 : s2)] = static_cast<int>(kids.size()) - 1;
    }
    paths_.assign(k_, {});
    std::vector<std::pair<int, std::vector<std::pair<int, int>>>> ps{
        {levels.rbegin()->second.rbegin()->second, {}}};
    while (!ps.empty()) {
      auto [n, p] = ps.back();
      ps.pop_back();
      for (int dir = 0; dir < 2; ++dir) {
        auto q = p;
        q.push_back({n, dir});
        if (kids[n][dir] < 0) {
          paths_[-kids[n][dir] - 1] = q;
        } else {
          ps.push_back({kids[n][dir], q});
        }
      }
    }
  }

  static void Count(Node* s, int label) {
    if (++s->c[label] > 256) {
      for (int i = 0; i < 2; ++i) s->c[i] = s->c[i] >> (1 + s->c[i] % 2);
    }
  }

  void Learn(int n, const std::vector<int32_t>& ctx, int label) {
    const int L = static_cast<int>(ctx.size());
    std::vector<Node*> nodes;
    for (int d = 0; d <= L; ++d) {
      nodes.push_back(&tree_[{n, std::vector<int32_t>(ctx.begin(), ctx.begin() + d)}]);
    }
    Node* s = nodes[L];
    double e[2];
    for (int v = 0; v < 2; ++v) e[v] = (s->c[v] + 1.0 / 16) / (s->c[0] + s->c[1] + 2 / 16.0);
    Count(s, label);
    for (int d = L - 1; d >= 0; --d) {
      s = nodes[d];
      const double child = e[label];
      const double bt = s->beta / (s->c[0] + s->c[1] + 2 / 16.0);
      double den = 0;
      for (int v = 0; v < 2; ++v) {
        e[v] += bt * (s->c[v] + 1.0 / 16);
        den += e[v];
      }
      for (int v = 0; v < 2; ++v) e[v] /= den;
      if (s->beta > 1500000) {
        s->beta /= 2;
      } else if (s->beta < 1.0 / 1500000) {
        s->beta *= 2;
      } else {
        s->beta = bt * (s->c[label] + 1.0 / 16) / child;
      }
      Count(s, label);
    }
  }

  double Predict(int n, const std::vector<int32_t>& ctx, int label) const {
    const int L = static_cast<int>(ctx.size());
    auto get = [&](int d) {
      auto it = tree_.find({n, std::vector<int32_t>(ctx.begin(), ctx.begin() + d)});
      return it == tree_.end() ? Node() : it->second;
    };
    Node s = get(L);
    double e[2];
    for (int v = 0; v < 2; ++v) e[v] = (s.c[v] + 1.0 / 16) / (s.c[0] + s.c[1] + 2 / 16.0);
    for (int d = L - 1; d >= 0; --d) {
      s = get(d);
      const double bt = s.beta / (s.c[0] + s.c[1] + 2 / 16.0);
      double den = 0;
      for (int v = 0; v < 2; ++v) {
        e[v] += bt * (s.c[v] + 1.0 / 16);
        den += e[v];
      }
      for (int v = 0; v < 2; ++v) e[v] /= den;
    }
    return e[label];
  }

  int k_, depth_;
  std::vector<std::vector<std::pair<int, int>>> paths_;
  std::map<Key, Node> tree_;
};

TEST(DeCtw, MatchesNaiveTranscription) {
  std::mt19937_64 rng(17);
  for (int k : {2, 3, 7, 20}) {
    for (int depth : {1, 2, 4}) {
      // Peaked order-1 data with noise: long runs push counts past 256 and
      // betas to their bounds.
      std::vector<int32_t> seq{0};
      const int used = k > 3 ? k - 2 : k;  // leave ids unseen when possible
      while (seq.size() < 1500) {
        const uint64_t r = rng() % 20;
        seq.push_back(r < 15 ? (seq.back() + 1) % used : static_cast<int32_t>(rng() % used));
      }
      NaiveDeCtw naive(k, depth, seq);
      auto m = Model::Train({Algorithm::kDeCtw, depth, k, 1.0}, seq);
      ASSERT_TRUE(m.ok());
      std::vector<int32_t> test;
      for (int i = 0; i < 60; ++i) test.push_back(static_cast<int32_t>(rng() % k));
      for (size_t i = 0; i < test.size(); ++i) {
        std::vector<int32_t> hist(test.begin(), test.begin() + i);
        const double want = naive.Probability(hist, test[i]);
        const double got = (*m)->Probability(hist, test[i]);
        ASSERT_NEAR(got / want, 1.0, 1e-12) << "k " << k << " D " << depth << " at " << i;
      }
      // Contexts taken from the training data (deep, trained paths).
      for (size_t i = 200; i < 1500; i += 97) {
        std::vector<int32_t> hist(seq.begin() + (i - 6), seq.begin() + i);
        for (int32_t x = 0; x < k; ++x) {
          ASSERT_NEAR((*m)->Probability(hist, x) / naive.Probability(hist, x), 1.0, 1e-12)
              << "k " << k << " D " << depth << " pos " << i << " x " << x;
        }
      }
    }
  }
}

}  // namespace
}  // namespace sb::markov
