#include "markov/counts.h"

#include <algorithm>
#include <utility>

#include "markov/bytes.h"

namespace sb::markov::internal {
namespace {
constexpr int kMaxDepth = 32;
}  // namespace

CountTrie::CountTrie(int depth, std::span<const int32_t> seq) {
  FlatMap pair_counts;  // (node, sym) -> count
  uint32_t num_nodes = 1;
  uint32_t t[kMaxDepth + 1];
  for (size_t i = 0; i < seq.size(); ++i) {
    const int L = static_cast<int>(std::min<size_t>(i, depth));
    t[0] = 0;
    for (int d = 1; d <= L; ++d) {
      bool inserted;
      t[d] = edges_.FindOrInsert(EdgeKey(t[d - 1], seq[i - d]), num_nodes, &inserted);
      if (inserted) ++num_nodes;
    }
    for (int d = 0; d <= L; ++d) {
      bool inserted;
      uint32_t& c = pair_counts.FindOrInsert(EdgeKey(t[d], seq[i]), 0, &inserted);
      ++c;
    }
  }
  std::vector<std::pair<uint64_t, uint32_t>> entries;
  entries.reserve(pair_counts.size());
  pair_counts.ForEach([&](uint64_t k, uint32_t v) { entries.push_back({k, v}); });
  std::sort(entries.begin(), entries.end());
  off_.assign(num_nodes + 1, 0);
  total_.assign(num_nodes, 0);
  syms_.resize(entries.size());
  counts_.resize(entries.size());
  for (size_t e = 0; e < entries.size(); ++e) {
    const uint32_t node = static_cast<uint32_t>(entries[e].first >> 32);
    syms_[e] = static_cast<int32_t>(entries[e].first & 0xffffffffu);
    counts_[e] = entries[e].second;
    ++off_[node + 1];
    total_[node] += entries[e].second;
  }
  for (uint32_t n = 0; n < num_nodes; ++n) off_[n + 1] += off_[n];
}

void CountTrie::SaveState(std::string* out) const {
  using internal::PutArray;
  using internal::PutU64;
  PutU64(out, total_.size());
  PutArray(out, off_);
  PutU64(out, syms_.size());
  PutArray(out, syms_);
  PutArray(out, counts_);
  PutU64(out, edges_.raw_keys().size());
  PutArray(out, edges_.raw_keys());
  PutArray(out, edges_.raw_values());
}

Status CountTrie::LoadState(std::string_view state, int alphabet_size) {
  auto bad = [](const std::string& why) { return Status::InvalidInput("count trie: " + why); };
  internal::ByteReader r(state);
  uint64_t n = 0, e = 0, cap = 0;
  if (!r.U64(&n) || n == 0 || n >= FlatMap::kNone || !r.Array(n + 1, &off_)) {
    return bad("truncated nodes");
  }
  if (!r.U64(&e) || !r.Array(e, &syms_) || !r.Array(e, &counts_)) return bad("truncated counts");
  std::vector<uint64_t> keys;
  std::vector<uint32_t> values;
  if (!r.U64(&cap) || !r.Array(cap, &keys) || !r.Array(cap, &values)) {
    return bad("truncated edge table");
  }
  if (r.remaining() != 0) return bad("trailing bytes");
  if (!edges_.Adopt(std::move(keys), std::move(values))) return bad("malformed edge table");
  if (off_[0] != 0 || off_[n] != e) return bad("offsets do not span the counts");
  total_.assign(n, 0);
  for (uint64_t v = 0; v < n; ++v) {
    if (off_[v + 1] < off_[v]) return bad("offsets are not ascending");
    for (uint32_t i = off_[v]; i < off_[v + 1]; ++i) {
      if (syms_[i] < 0 || syms_[i] >= alphabet_size || counts_[i] == 0 ||
          (i > off_[v] && syms_[i] <= syms_[i - 1])) {
        return bad("bad symbol count");
      }
      total_[v] += counts_[i];
    }
  }
  bool edges_ok = true;
  edges_.ForEach([&](uint64_t key, uint32_t value) {
    if ((key >> 32) >= n || (key & 0xffffffffu) >= static_cast<uint64_t>(alphabet_size) ||
        value >= n || value == 0) {
      edges_ok = false;
    }
  });
  if (!edges_ok) return bad("bad trie edge");
  return Status::Ok();
}

int CountTrie::Walk(const int32_t* hist_end, int len, uint32_t* nodes) const {
  nodes[0] = 0;
  int d = 0;
  while (d < len) {
    const uint32_t n = edges_.Find(EdgeKey(nodes[d], hist_end[-(d + 1)]));
    if (n == FlatMap::kNone) break;
    nodes[++d] = n;
  }
  return d;
}

uint32_t CountTrie::Count(uint32_t node, int32_t sym) const {
  auto s = Symbols(node);
  auto it = std::lower_bound(s.begin(), s.end(), sym);
  if (it == s.end() || *it != sym) return 0;
  return counts_[off_[node] + (it - s.begin())];
}

PpmCModel::PpmCModel(const ModelSpec& spec, std::span<const int32_t> seq)
    : Model(spec), trie_(spec.depth, seq) {
  symbol_counts_.assign(spec.alphabet_size, 0);
  for (int32_t s : seq) ++symbol_counts_[s];
}

PpmCModel::PpmCModel(const ModelSpec& spec, std::span<const int32_t> seq, LoadOnly) : Model(spec) {
  symbol_counts_.assign(spec.alphabet_size, 0);
  for (int32_t s : seq) ++symbol_counts_[s];
}

double PpmCModel::Probability(std::span<const int32_t> context, int32_t symbol) const {
  const int L = static_cast<int>(std::min<size_t>(context.size(), spec_.depth));
  uint32_t t[kMaxDepth + 1];
  const int lm = trie_.Walk(context.data() + context.size(), L, t);
  std::vector<int32_t> excluded;  // sorted
  double p = 1.0;
  for (int d = lm; d >= 0; --d) {
    auto syms = trie_.Symbols(t[d]);
    auto counts = trie_.Counts(t[d]);
    uint64_t n = 0, q = 0;
    uint32_t cx = 0;
    for (size_t e = 0; e < syms.size(); ++e) {
      if (std::binary_search(excluded.begin(), excluded.end(), syms[e])) continue;
      n += counts[e];
      ++q;
      if (syms[e] == symbol) cx = counts[e];
    }
    if (n == 0) continue;
    const double denom = static_cast<double>(n + q);
    if (cx > 0) return p * (cx / denom);
    p *= q / denom;
    std::vector<int32_t> merged;
    merged.reserve(excluded.size() + syms.size());
    std::set_union(excluded.begin(), excluded.end(), syms.begin(), syms.end(),
                   std::back_inserter(merged));
    excluded.swap(merged);
  }
  return p / static_cast<double>(spec_.alphabet_size - excluded.size());
}

void PpmCModel::Distribution(std::span<const int32_t> context, std::span<double> out) const {
  const int K = spec_.alphabet_size;
  const int L = static_cast<int>(std::min<size_t>(context.size(), spec_.depth));
  uint32_t t[kMaxDepth + 1];
  const int lm = trie_.Walk(context.data() + context.size(), L, t);
  std::vector<char> excl(K, 0);
  size_t num_excl = 0;
  double p = 1.0;
  for (int d = lm; d >= 0; --d) {
    auto syms = trie_.Symbols(t[d]);
    auto counts = trie_.Counts(t[d]);
    uint64_t n = 0, q = 0;
    for (size_t e = 0; e < syms.size(); ++e) {
      if (excl[syms[e]]) continue;
      n += counts[e];
      ++q;
    }
    if (n == 0) continue;
    const double denom = static_cast<double>(n + q);
    for (size_t e = 0; e < syms.size(); ++e) {
      if (excl[syms[e]]) continue;
      out[syms[e]] = p * (counts[e] / denom);
    }
    p *= q / denom;
    for (int32_t s : syms) {
      if (!excl[s]) {
        excl[s] = 1;
        ++num_excl;
      }
    }
  }
  const double u = p / static_cast<double>(K - num_excl);
  for (int s = 0; s < K; ++s)
    if (!excl[s]) out[s] = u;
}

bool PpmCModel::Trained(std::span<const int32_t> context) const {
  if (context.size() > static_cast<size_t>(spec_.depth)) return false;
  const int L = static_cast<int>(context.size());
  uint32_t t[kMaxDepth + 1];
  return trie_.Walk(context.data() + context.size(), L, t) == L;
}

uint64_t PpmCModel::ContextKey(std::span<const int32_t> context) const {
  const int L = static_cast<int>(std::min<size_t>(context.size(), spec_.depth));
  uint32_t t[kMaxDepth + 1];
  return t[trie_.Walk(context.data() + context.size(), L, t)];
}

MarkovModel::MarkovModel(const ModelSpec& spec, std::span<const int32_t> seq)
    : Model(spec), trie_(spec.depth, seq) {
  symbol_counts_.assign(spec.alphabet_size, 0);
  for (int32_t s : seq) ++symbol_counts_[s];
}

MarkovModel::MarkovModel(const ModelSpec& spec, std::span<const int32_t> seq, LoadOnly)
    : Model(spec) {
  symbol_counts_.assign(spec.alphabet_size, 0);
  for (int32_t s : seq) ++symbol_counts_[s];
}

uint32_t MarkovModel::ContextNode(std::span<const int32_t> context) const {
  const int L = static_cast<int>(std::min<size_t>(context.size(), spec_.depth));
  uint32_t t[kMaxDepth + 1];
  const int lm = trie_.Walk(context.data() + context.size(), L, t);
  return lm == L ? t[L] : FlatMap::kNone;
}

bool MarkovModel::Trained(std::span<const int32_t> context) const {
  if (context.size() > static_cast<size_t>(spec_.depth)) return false;
  const int L = static_cast<int>(context.size());
  uint32_t t[kMaxDepth + 1];
  return trie_.Walk(context.data() + context.size(), L, t) == L;
}

uint64_t MarkovModel::ContextKey(std::span<const int32_t> context) const {
  return ContextNode(context);
}

double MarkovModel::Probability(std::span<const int32_t> context, int32_t symbol) const {
  const uint32_t node = ContextNode(context);
  const double a = spec_.alpha;
  const double k = spec_.alphabet_size;
  if (node == FlatMap::kNone) return a / (a * k);
  return (trie_.Count(node, symbol) + a) / (static_cast<double>(trie_.Total(node)) + a * k);
}

void MarkovModel::Distribution(std::span<const int32_t> context, std::span<double> out) const {
  const uint32_t node = ContextNode(context);
  const double a = spec_.alpha;
  const double k = spec_.alphabet_size;
  const double denom =
      (node == FlatMap::kNone ? 0.0 : static_cast<double>(trie_.Total(node))) + a * k;
  std::fill(out.begin(), out.end(), a / denom);
  if (node == FlatMap::kNone) return;
  auto syms = trie_.Symbols(node);
  auto counts = trie_.Counts(node);
  for (size_t e = 0; e < syms.size(); ++e) out[syms[e]] = (counts[e] + a) / denom;
}

}  // namespace sb::markov::internal
