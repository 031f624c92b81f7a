#include "graph/influence.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <set>
#include <utility>

#include "base/number.h"
#include "base/text.h"

namespace sb::graph {

const char* InfluenceModeName(InfluenceMode m) {
  switch (m) {
    case InfluenceMode::kNone:
      return "none";
    case InfluenceMode::kGiven:
      return "given";
    case InfluenceMode::kLearned:
      return "learned";
  }
  return "?";
}

namespace {

std::string PairText(const InfluencePair& p) {
  return std::to_string(p.child + 1) + " " + std::to_string(p.parent + 1);
}

// True when the pairs (edges parent -> child) contain a cycle.
bool HasCycle(const std::vector<InfluencePair>& pairs, int k) {
  std::vector<int> indegree(k, 0);
  std::vector<std::vector<int>> children(k);
  for (const auto& p : pairs) {
    children[p.parent].push_back(p.child);
    ++indegree[p.child];
  }
  std::vector<int> ready;
  for (int f = 0; f < k; ++f)
    if (indegree[f] == 0) ready.push_back(f);
  int seen = 0;
  while (!ready.empty()) {
    const int f = ready.back();
    ready.pop_back();
    ++seen;
    for (int c : children[f])
      if (--indegree[c] == 0) ready.push_back(c);
  }
  return seen != k;
}

Status CheckPair(const InfluencePair& p, int k) {
  if (p.child < 0 || p.child >= k || p.parent < 0 || p.parent >= k) {
    return Status::InvalidInput("pair '" + PairText(p) + "': feature positions must be in 1.." +
                                std::to_string(k));
  }
  if (p.child == p.parent) {
    return Status::InvalidInput("pair '" + PairText(p) + "': a feature cannot be its own parent");
  }
  return Status::Ok();
}

}  // namespace

Status ValidateInfluence(const std::vector<InfluencePair>& pairs, int k) {
  if (pairs.size() > kMaxInfluencePairs) {
    return Status::InvalidInput("more than " + std::to_string(kMaxInfluencePairs) +
                                " influence pairs");
  }
  std::set<std::pair<int, int>> seen;
  for (const auto& p : pairs) {
    SB_RETURN_IF_ERROR(CheckPair(p, k));
    if (!seen.insert({p.child, p.parent}).second) {
      return Status::InvalidInput("pair '" + PairText(p) + "' is given twice");
    }
  }
  if (HasCycle(pairs, k)) return Status::InvalidInput("the influence pairs form a cycle");
  return Status::Ok();
}

Result<std::vector<InfluencePair>> ParseInfluenceFile(std::string_view text,
                                                      const std::string& name, int k) {
  if (size_t bad = FindInvalidUtf8(text); bad != std::string_view::npos) {
    return Status::InvalidInput(name + ": invalid UTF-8 at byte " + std::to_string(bad));
  }
  std::vector<InfluencePair> pairs;
  std::set<std::pair<int, int>> seen;
  const auto lines = SplitLines(text);
  for (size_t l = 0; l < lines.size(); ++l) {
    std::string_view s = Trim(lines[l]);
    if (s.empty() || s.front() == '#') continue;
    int v[2] = {0, 0};
    for (int i = 0; i < 2; ++i) {
      s = Trim(s);
      size_t end = 0;
      while (end < s.size() && s[end] != ' ' && s[end] != '\t') ++end;
      const std::string_view num = s.substr(0, end);
      if (!ParseInt(num, &v[i])) {
        return Status::InvalidInputAt({name, static_cast<int>(l + 1), 0},
                                      "expected 'child parent' (two 1-based feature "
                                      "positions), got '" +
                                          std::string(Trim(lines[l])) + "'");
      }
      s.remove_prefix(end);
    }
    if (!Trim(s).empty()) {
      return Status::InvalidInputAt(
          {name, static_cast<int>(l + 1), 0},
          "expected 'child parent', got trailing text '" + std::string(Trim(s)) + "'");
    }
    InfluencePair p{v[0] - 1, v[1] - 1};
    if (Status st = CheckPair(p, k); !st.ok()) {
      return Status::InvalidInputAt({name, static_cast<int>(l + 1), 0}, "" + st.message());
    }
    if (!seen.insert({p.child, p.parent}).second) {
      return Status::InvalidInputAt({name, static_cast<int>(l + 1), 0},
                                    "pair '" + PairText(p) + "' is given twice");
    }
    if (pairs.size() == kMaxInfluencePairs) {
      return Status::InvalidInputAt({name, static_cast<int>(l + 1), 0},
                                    "more than " + std::to_string(kMaxInfluencePairs) + " pairs");
    }
    pairs.push_back(p);
    if (HasCycle(pairs, k)) {
      return Status::InvalidInputAt({name, static_cast<int>(l + 1), 0},
                                    "pair '" + PairText(p) + "' closes a cycle");
    }
  }
  return pairs;
}

std::vector<std::vector<double>> MutualInformation(const std::vector<Sequence>& sequences, int k) {
  // Value ids per feature (map order: byte-wise, deterministic).
  std::vector<std::map<std::string_view, int32_t>> ids(k);
  std::vector<std::vector<int32_t>> column(k);
  for (const auto& seq : sequences) {
    for (const auto& tok : seq) {
      for (int f = 0; f < k; ++f) {
        auto [it, inserted] = ids[f].try_emplace(tok[f], static_cast<int32_t>(ids[f].size()));
        column[f].push_back(it->second);
      }
    }
  }
  const size_t n = k > 0 ? column[0].size() : 0;
  std::vector<std::vector<double>> mi(k, std::vector<double>(k, 0.0));
  if (n == 0) return mi;
  const double ln_n = std::log(static_cast<double>(n));
  std::vector<std::vector<uint32_t>> marg(k);
  for (int f = 0; f < k; ++f) {
    marg[f].assign(ids[f].size(), 0);
    for (int32_t v : column[f]) ++marg[f][v];
  }
  std::vector<uint64_t> keys(n);
  for (int i = 0; i < k; ++i) {
    for (int j = i; j < k; ++j) {
      for (size_t t = 0; t < n; ++t) {
        keys[t] = (uint64_t{static_cast<uint32_t>(column[i][t])} << 32) |
                  static_cast<uint32_t>(column[j][t]);
      }
      std::sort(keys.begin(), keys.end());
      // I = sum p(a,b) (ln c(a,b) + ln n - ln c(a) - ln c(b)), over the runs
      // of equal (a, b) in ascending order.
      double sum = 0.0;
      for (size_t t = 0; t < n;) {
        size_t e = t;
        while (e < n && keys[e] == keys[t]) ++e;
        const double c = static_cast<double>(e - t);
        const double ca = marg[i][keys[t] >> 32];
        const double cb = marg[j][keys[t] & 0xffffffffu];
        sum += c * (std::log(c) + ln_n - std::log(ca) - std::log(cb));
        t = e;
      }
      const double v = std::max(0.0, sum / static_cast<double>(n));
      mi[i][j] = mi[j][i] = v;
    }
  }
  return mi;
}

std::vector<InfluencePair> ChowLiuTree(const std::vector<std::vector<double>>& mi) {
  const int k = static_cast<int>(mi.size());
  struct E {
    double w;
    int i, j;
  };
  std::vector<E> edges;
  for (int i = 0; i < k; ++i)
    for (int j = i + 1; j < k; ++j) edges.push_back({mi[i][j], i, j});
  std::stable_sort(edges.begin(), edges.end(), [](const E& a, const E& b) {
    if (a.w != b.w) return a.w > b.w;
    return std::make_pair(a.i, a.j) < std::make_pair(b.i, b.j);
  });
  std::vector<int> root(k);
  std::iota(root.begin(), root.end(), 0);
  auto find = [&](int x) {
    while (root[x] != x) x = root[x] = root[root[x]];
    return x;
  };
  std::vector<std::vector<int>> adj(k);
  for (const E& e : edges) {
    const int a = find(e.i), b = find(e.j);
    if (a == b) continue;
    root[a] = b;
    adj[e.i].push_back(e.j);
    adj[e.j].push_back(e.i);
  }
  std::vector<InfluencePair> out;
  if (k == 0) return out;
  std::vector<char> seen(k, 0);
  std::vector<int> queue{0};
  seen[0] = 1;
  for (size_t qi = 0; qi < queue.size(); ++qi) {
    const int p = queue[qi];
    std::vector<int> kids = adj[p];
    std::sort(kids.begin(), kids.end());
    for (int c : kids) {
      if (seen[c]) continue;
      seen[c] = 1;
      out.push_back({c, p});
      queue.push_back(c);
    }
  }
  return out;
}

std::vector<int> TopologicalOrder(const std::vector<InfluencePair>& pairs, int k) {
  std::vector<int> indegree(k, 0);
  std::vector<std::vector<int>> children(k);
  for (const auto& p : pairs) {
    children[p.parent].push_back(p.child);
    ++indegree[p.child];
  }
  std::set<int> ready;
  for (int f = 0; f < k; ++f)
    if (indegree[f] == 0) ready.insert(f);
  std::vector<int> order;
  while (!ready.empty()) {
    const int f = *ready.begin();
    ready.erase(ready.begin());
    order.push_back(f);
    for (int c : children[f])
      if (--indegree[c] == 0) ready.insert(c);
  }
  return order;
}

}  // namespace sb::graph
