#include "markov/dectw.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <map>
#include <utility>

#include "markov/bytes.h"

namespace sb::markov::internal {
namespace {

constexpr double kAlphaInv = 1.0 / 16;  // Volf estimator, alpha = 16
constexpr double kTwoDivAlpha = 2 / 16.0;
constexpr double kBetaHigh = 1500000;
constexpr double kBetaLow = 1.0 / 1500000;
constexpr int kMaxCount = 256;  // count halving threshold
constexpr int kMaxDepth = 32;

// The reference's rescaling: `c >> 1 + (c % 2)` parses as c >> (1 + c % 2).
inline void CountUpdate(uint16_t c[2], int label) {
  ++c[label];
  if (c[label] > kMaxCount) {
    for (int i = 0; i < 2; ++i) c[i] = static_cast<uint16_t>(c[i] >> (1 + c[i] % 2));
  }
}

}  // namespace

DeCtwModel::DeCtwModel(const ModelSpec& spec, std::span<const int32_t> sequence) : Model(spec) {
  symbol_counts_.assign(spec.alphabet_size, 0);
  for (int32_t s : sequence) ++symbol_counts_[s];
  BuildDecomposition();
  Learn(sequence);
  SetTrainedViews();
}

void DeCtwModel::SetTrainedViews() {
  v_.trie_state = trie_state_.data();
  v_.trie_size = trie_state_.size();
  v_.keys = edges_.raw_keys().data();
  v_.values = edges_.raw_values().data();
  v_.mask = edges_.mask();
  v_.states = nullptr;
  loaded_ = false;
}

DeCtwModel::DeCtwModel(const ModelSpec& spec, std::span<const int32_t> sequence, LoadOnly)
    : Model(spec) {
  symbol_counts_.assign(spec.alphabet_size, 0);
  for (int32_t s : sequence) ++symbol_counts_[s];
  BuildDecomposition();
}

// State section layout (little-endian; offsets relative to the section,
// which starts 8-byte aligned in the file): u64 T, T x u32 trie_state, zero
// padding to 8; u64 C, C x u64 edge keys, C x u32 edge values, padding to 8;
// u64 S, S x 24-byte records (f64 beta, u16 c0, u16 c1, u32 child0, u32
// child1, u32 zero).
namespace {

void PadTo8(std::string* out, size_t start) {
  while ((out->size() - start) % 8 != 0) out->push_back('\0');
}

}  // namespace

void DeCtwModel::SaveState(std::string* out) const {
  using internal::PutU32;
  using internal::PutU64;
  const size_t start = out->size();
  PutU64(out, v_.trie_size);
  for (size_t i = 0; i < v_.trie_size; ++i) PutU32(out, v_.trie_state[i]);
  PadTo8(out, start);
  const size_t cap = v_.mask + 1;
  PutU64(out, cap);
  for (size_t i = 0; i < cap; ++i) PutU64(out, v_.keys[i]);
  for (size_t i = 0; i < cap; ++i) PutU32(out, v_.values[i]);
  PadTo8(out, start);
  PutU64(out, num_states_);
  for (uint32_t i = 0; i < num_states_; ++i) {
    const State& st = QS(i);
    internal::PutF64(out, st.beta);
    PutU32(out, uint32_t{st.c[0]} | (uint32_t{st.c[1]} << 16));
    PutU32(out, st.child[0]);
    PutU32(out, st.child[1]);
    PutU32(out, 0);
  }
}

namespace {

// The next array of n elements of T at `*pos` of `s`: in place when aligned
// on a little-endian host, else copied (converted) into *own.
template <typename T>
const T* ArrayAt(std::string_view s, size_t* pos, uint64_t n, std::vector<T>* own) {
  if (n > (s.size() - *pos) / sizeof(T)) return nullptr;
  const char* p = s.data() + *pos;
  *pos += n * sizeof(T);
  if constexpr (std::endian::native == std::endian::little) {
    if (reinterpret_cast<uintptr_t>(p) % alignof(T) == 0) return reinterpret_cast<const T*>(p);
    own->resize(n);
    if (n > 0) std::memcpy(own->data(), p, n * sizeof(T));  // data() may be null when empty
    return own->data();
  } else {
    own->resize(n);
    for (uint64_t i = 0; i < n; ++i) {
      uint64_t v = 0;
      for (size_t b = 0; b < sizeof(T); ++b) {
        v |= uint64_t{static_cast<unsigned char>(p[i * sizeof(T) + b])} << (8 * b);
      }
      (*own)[i] = static_cast<T>(v);
    }
    return own->data();
  }
}

bool U64At(std::string_view s, size_t* pos, uint64_t* v) {
  if (s.size() - *pos < 8) return false;
  *v = 0;
  for (int i = 0; i < 8; ++i) *v |= uint64_t{static_cast<unsigned char>(s[*pos + i])} << (8 * i);
  *pos += 8;
  return true;
}

bool SkipPad(std::string_view s, size_t* pos) {
  while (*pos % 8 != 0) {
    if (*pos >= s.size() || s[*pos] != '\0') return false;
    ++*pos;
  }
  return true;
}

}  // namespace

Status DeCtwModel::LoadState(std::string_view state, std::shared_ptr<const void> backing) {
  auto bad = [](const std::string& why) { return Status::InvalidInput("DE-CTW state: " + why); };
  const uint32_t K = static_cast<uint32_t>(spec_.alphabet_size);
  size_t pos = 0;
  uint64_t t = 0, cap = 0, ns = 0;
  Views v;
  if (!U64At(state, &pos, &t) || t == 0 || t >= kSingleton ||
      (v.trie_state = ArrayAt(state, &pos, t, &own_trie_)) == nullptr) {
    return bad("truncated or empty trie");
  }
  v.trie_size = t;
  if (!SkipPad(state, &pos) || !U64At(state, &pos, &cap) || cap < 16 || (cap & (cap - 1)) != 0 ||
      (v.keys = ArrayAt(state, &pos, cap, &own_keys_)) == nullptr ||
      (v.values = ArrayAt(state, &pos, cap, &own_values_)) == nullptr) {
    return bad("truncated or malformed edge table");
  }
  v.mask = cap - 1;
  if (!SkipPad(state, &pos) || !U64At(state, &pos, &ns) || ns >= kSingleton ||
      ns > (state.size() - pos) / sizeof(State)) {
    return bad("truncated states");
  }
  {
    // Records: f64 beta, u16 c0, u16 c1, u32 child0, u32 child1, u32 zero
    // = the State layout on little-endian hosts.
    const char* p = state.data() + pos;
    if (std::endian::native == std::endian::little &&
        reinterpret_cast<uintptr_t>(p) % alignof(State) == 0) {
      v.states = reinterpret_cast<const State*>(p);
    } else {
      own_states_.resize(ns);
      for (uint64_t i = 0; i < ns; ++i) {
        internal::ByteReader r(std::string_view(p + i * sizeof(State), sizeof(State)));
        uint32_t counts = 0;
        r.F64(&own_states_[i].beta);
        r.U32(&counts);
        own_states_[i].c[0] = static_cast<uint16_t>(counts & 0xffff);
        own_states_[i].c[1] = static_cast<uint16_t>(counts >> 16);
        r.U32(&own_states_[i].child[0]);
        r.U32(&own_states_[i].child[1]);
      }
      v.states = own_states_.data();
    }
    pos += ns * sizeof(State);
  }
  if (pos != state.size()) return bad("trailing bytes");
  // Everything a query follows must stay in range.
  for (uint64_t i = 0; i < t; ++i) {
    const uint32_t x = v.trie_state[i];
    if (x == kNone) continue;
    if ((x & kSingleton) ? (x & ~kSingleton) >= K : x >= ns) return bad("bad trie state");
  }
  uint64_t used = 0;
  for (uint64_t i = 0; i < cap; ++i) {
    const uint64_t key = v.keys[i];
    if (key == FlatMap::kEmpty) continue;
    ++used;
    if ((key >> 32) >= t || (key & 0xffffffffu) >= K || v.values[i] >= t || v.values[i] == 0) {
      return bad("bad trie edge");
    }
  }
  if (used * 2 > cap) return bad("edge table more than half full");
  for (uint64_t i = 0; i < ns; ++i) {
    const State& st = v.states[i];
    if ((st.child[0] != kNone && st.child[0] >= ns) ||
        (st.child[1] != kNone && st.child[1] >= ns)) {
      return bad("bad state child");
    }
  }
  v_ = v;
  num_states_ = static_cast<uint32_t>(ns);
  loaded_ = true;
  backing_ = std::move(backing);
  return Status::Ok();
}

// Mirrors DecompositionTreeBuilder.buildStatic: a Huffman tree from the
// counts (ordered map count -> symbol -> node, popping the highest symbol of
// the lowest count twice; the merged node is keyed by the larger id), of
// which only the leaf depths are kept; then a rebuild level by level from
// the deepest level, pairing the two highest keys (right = highest).
void DeCtwModel::BuildDecomposition() {
  const int K = spec_.alphabet_size;
  struct HNode {
    int sym;  // >= 0 leaf
    int a, b;
  };
  std::vector<HNode> h;
  h.reserve(2 * K);
  std::map<uint64_t, std::map<int, int>> count_map;
  for (int s = 0; s < K; ++s) {
    h.push_back({s, -1, -1});
    count_map[symbol_counts_[s]][s] = s;
  }
  while (count_map.size() > 1 || count_map.begin()->second.size() > 1) {
    auto it = count_map.begin();
    const uint64_t count1 = it->first;
    int super_sym = it->second.rbegin()->first;
    const int node1 = it->second.rbegin()->second;
    it->second.erase(std::prev(it->second.end()));
    if (it->second.empty()) {
      count_map.erase(it);
      it = count_map.begin();
    }
    const uint64_t count2 = it->first;
    const int key2 = it->second.rbegin()->first;
    const int node2 = it->second.rbegin()->second;
    if (super_sym < key2) super_sym = key2;  // (the reference's swap() is a no-op)
    it->second.erase(std::prev(it->second.end()));
    if (it->second.empty()) count_map.erase(it);
    h.push_back({-1, node1, node2});
    count_map[count1 + count2][super_sym] = static_cast<int>(h.size()) - 1;
  }
  const int hroot = count_map.begin()->second.begin()->second;

  // Leaf depths.
  std::map<int, std::map<int, int32_t>> levels;  // level -> key -> node (<0 leaf)
  std::vector<std::pair<int, int>> stack{{hroot, 0}};
  while (!stack.empty()) {
    auto [n, d] = stack.back();
    stack.pop_back();
    if (h[n].sym >= 0) {
      levels[d][h[n].sym] = -(h[n].sym + 1);
    } else {
      stack.push_back({h[n].a, d + 1});
      stack.push_back({h[n].b, d + 1});
    }
  }
  dnodes_.clear();
  while (levels.size() > 1 || levels.rbegin()->second.size() > 1) {
    auto lit = std::prev(levels.end());
    const int level = lit->first;
    auto& one = lit->second;
    const int sym1 = one.rbegin()->first;
    const int32_t node1 = one.rbegin()->second;
    one.erase(std::prev(one.end()));
    // A full binary tree always has an even number of nodes at its deepest
    // level, so a second node exists.
    const int sym2 = one.rbegin()->first;
    const int32_t node2 = one.rbegin()->second;
    one.erase(std::prev(one.end()));
    if (one.empty()) levels.erase(lit);
    dnodes_.push_back({{node1, node2}});  // right = node1, left = node2
    const int32_t id = static_cast<int32_t>(dnodes_.size()) - 1;
    const int super_sym = node2 < 0 ? sym2 : (node1 < 0 ? sym1 : sym2);
    levels[level - 1][super_sym] = id;
  }
  droot_ = levels.rbegin()->second.rbegin()->second;

  // Root-to-leaf paths of every symbol.
  std::vector<std::vector<std::pair<int32_t, uint8_t>>> paths(K);
  std::vector<std::pair<int32_t, std::vector<std::pair<int32_t, uint8_t>>>> st;
  if (droot_ >= 0) st.push_back({droot_, {}});
  while (!st.empty()) {
    auto [n, p] = std::move(st.back());
    st.pop_back();
    for (uint8_t dir = 0; dir < 2; ++dir) {
      auto q = p;
      q.push_back({n, dir});
      const int32_t c = dnodes_[n].child[dir];
      if (c < 0) {
        paths[-c - 1] = std::move(q);
      } else {
        st.push_back({c, std::move(q)});
      }
    }
  }
  path_off_.assign(K + 1, 0);
  path_node_.clear();
  path_dir_.clear();
  for (int s = 0; s < K; ++s) {
    path_off_[s] = static_cast<uint32_t>(path_node_.size());
    for (auto [n, dir] : paths[s]) {
      path_node_.push_back(n);
      path_dir_.push_back(dir);
    }
  }
  path_off_[K] = static_cast<uint32_t>(path_node_.size());
}

uint32_t DeCtwModel::NewState() {
  const uint32_t i = num_states_++;
  if ((i >> kChunkBits) >= chunks_.size()) {
    chunks_.push_back(std::make_unique<State[]>(size_t{1} << kChunkBits));
  }
  State& s = S(i);
  s.beta = 1.0;
  s.c[0] = s.c[1] = 0;
  s.child[0] = s.child[1] = kNone;
  return i;
}

// The states of a context seen once, followed by `symbol`: counts 1 in the
// symbol's direction and beta exactly 1 along its path (a fresh node's
// update leaves beta at 8 * (1/16) / 0.5 = 1).
uint32_t DeCtwModel::Materialize(int32_t symbol) {
  uint32_t first = kNone, prev = kNone;
  int prev_dir = 0;
  for (uint32_t k = path_off_[symbol]; k < path_off_[symbol + 1]; ++k) {
    const uint32_t i = NewState();
    const int dir = path_dir_[k];
    S(i).c[dir] = 1;
    if (prev == kNone) {
      first = i;
    } else {
      S(prev).child[prev_dir] = i;
    }
    prev = i;
    prev_dir = dir;
  }
  return first;
}

DeCtwModel::View DeCtwModel::Get(Ref r) const {
  View v;
  if ((r & kVirtual) == 0) {
    const State& s = QS(static_cast<uint32_t>(r));
    v.beta = s.beta;
    v.c[0] = s.c[0];
    v.c[1] = s.c[1];
    for (int i = 0; i < 2; ++i) v.child[i] = s.child[i] == kNone ? kNoRef : Ref{s.child[i]};
    return v;
  }
  const uint32_t sym = static_cast<uint32_t>((r >> 32) & 0x7fffffffu);
  const uint32_t k = static_cast<uint32_t>(r & 0xffffffffu);
  const uint32_t at = path_off_[sym] + k;
  const int dir = path_dir_[at];
  v.beta = 1.0;
  v.c[dir] = 1;
  v.c[1 - dir] = 0;
  v.child[1 - dir] = kNoRef;
  v.child[dir] = at + 1 < path_off_[sym + 1] ? (r + 1) : kNoRef;
  return v;
}

DeCtwModel::Ref DeCtwModel::RootRef(uint32_t trie_node) const {
  const uint32_t v = v_.trie_state[trie_node];
  if (v == kNone) return kNoRef;
  if (v & kSingleton) return kVirtual | (Ref{v & ~kSingleton} << 32);
  return v;
}

void DeCtwModel::Learn(std::span<const int32_t> seq) {
  const int D = spec_.depth;
  trie_state_.assign(1, kNone);
  uint32_t t[kMaxDepth + 1];
  uint32_t cur[kMaxDepth + 1];
  for (size_t i = 0; i < seq.size(); ++i) {
    const int32_t x = seq[i];
    const int L = static_cast<int>(std::min<size_t>(i, D));
    t[0] = 0;
    int first_new = L + 1;
    for (int d = 1; d <= L; ++d) {
      bool inserted;
      uint32_t& v = edges_.FindOrInsert(EdgeKey(t[d - 1], seq[i - d]),
                                        static_cast<uint32_t>(trie_state_.size()), &inserted);
      t[d] = v;
      if (inserted) {
        trie_state_.push_back(kSingleton | static_cast<uint32_t>(x));
        if (first_new > L) first_new = d;
      }
    }
    // Contexts seen before get real states (expanding a context seen once);
    // new ones stay "seen once, followed by x", which is exactly their
    // trained state, and they contribute (0.5, 0.5) upwards.
    const int lx = first_new - 1;  // deepest context with real states
    for (int d = 0; d <= lx; ++d) {
      uint32_t& v = trie_state_[t[d]];
      if (v == kNone) {
        v = NewState();
      } else if (v & kSingleton) {
        const uint32_t st = Materialize(static_cast<int32_t>(v & ~kSingleton));
        trie_state_[t[d]] = st;
      }
      cur[d] = trie_state_[t[d]];
    }
    const uint32_t pb = path_off_[x], pe = path_off_[x + 1];
    for (uint32_t k = pb; k < pe; ++k) {
      const int label = path_dir_[k];
      double etha[2];
      int start;
      if (lx == L) {
        // Deepest node: the estimator only.
        State* s = &S(cur[L]);
        const double all = s->c[0] + s->c[1];
        for (int v = 0; v < 2; ++v) etha[v] = (s->c[v] + kAlphaInv) / (all + kTwoDivAlpha);
        CountUpdate(s->c, label);
        start = L - 1;
      } else {
        etha[0] = etha[1] = 0.5;
        start = lx;
      }
      for (int d = start; d >= 0; --d) {
        State* s = &S(cur[d]);
        const double child_pw = etha[label];
        const double all = s->c[0] + s->c[1];
        const double beta_tag = s->beta / (all + kTwoDivAlpha);
        double den = 0.0;
        for (int v = 0; v < 2; ++v) {
          etha[v] += beta_tag * (s->c[v] + kAlphaInv);
          den += etha[v];
        }
        for (int v = 0; v < 2; ++v) etha[v] /= den;
        if (s->beta > kBetaHigh) {
          s->beta /= 2.0;
        } else if (s->beta < kBetaLow) {
          s->beta *= 2.0;
        } else {
          s->beta = (beta_tag * (s->c[label] + kAlphaInv)) / child_pw;
        }
        CountUpdate(s->c, label);
      }
      if (k + 1 < pe) {
        for (int d = 0; d <= lx; ++d) {
          uint32_t nx = S(cur[d]).child[label];
          if (nx == kNone) {
            nx = NewState();  // may allocate a chunk; S() references stay valid
            S(cur[d]).child[label] = nx;
          }
          cur[d] = nx;
        }
      }
    }
  }
}

int DeCtwModel::WalkContext(const int32_t* hist_end, int len, uint32_t* nodes) const {
  nodes[0] = 0;
  int d = 0;
  while (d < len) {
    const uint32_t n =
        FlatMap::FindIn(v_.keys, v_.values, v_.mask, EdgeKey(nodes[d], hist_end[-(d + 1)]));
    if (n == kNone) break;
    nodes[++d] = n;
  }
  return d;
}

void DeCtwModel::NodePw(const Ref* cur, int ds, int L, double out[2]) const {
  double etha[2];
  int start;
  if (ds == L) {
    const View s = Get(cur[L]);
    const double all = s.c[0] + s.c[1];
    for (int v = 0; v < 2; ++v) etha[v] = (s.c[v] + kAlphaInv) / (all + kTwoDivAlpha);
    start = L - 1;
  } else {
    // An untrained node returns exactly (0.5, 0.5), internal or not.
    etha[0] = etha[1] = 0.5;
    start = ds;
  }
  for (int d = start; d >= 0; --d) {
    const View s = Get(cur[d]);
    const double all = s.c[0] + s.c[1];
    const double beta_tag = s.beta / (all + kTwoDivAlpha);
    double den = 0.0;
    for (int v = 0; v < 2; ++v) {
      etha[v] += beta_tag * (s.c[v] + kAlphaInv);
      den += etha[v];
    }
    for (int v = 0; v < 2; ++v) etha[v] /= den;
  }
  out[0] = etha[0];
  out[1] = etha[1];
}

double DeCtwModel::Probability(std::span<const int32_t> context, int32_t symbol) const {
  if (droot_ < 0) return 1.0;
  const int L = static_cast<int>(std::min<size_t>(context.size(), spec_.depth));
  uint32_t t[kMaxDepth + 1];
  Ref cur[kMaxDepth + 1];
  const int lm = WalkContext(context.data() + context.size(), L, t);
  int ds = -1;
  for (int d = 0; d <= lm; ++d) {
    cur[d] = RootRef(t[d]);
    if (cur[d] == kNoRef) break;
    ds = d;
  }
  double p[64];
  std::vector<double> pbig;
  const uint32_t pb = path_off_[symbol], pe = path_off_[symbol + 1];
  double* pp = p;
  if (pe - pb > 64) {
    pbig.resize(pe - pb);
    pp = pbig.data();
  }
  for (uint32_t k = pb; k < pe; ++k) {
    const int label = path_dir_[k];
    double pw[2];
    NodePw(cur, ds, L, pw);
    pp[k - pb] = pw[label];
    int nds = -1;
    for (int d = 0; d <= ds; ++d) {
      cur[d] = Get(cur[d]).child[label];
      if (cur[d] == kNoRef) break;
      nds = d;
    }
    ds = nds;
  }
  // The reference multiplies from the leaf up: p0 * (p1 * (... * 1.0)).
  double r = 1.0;
  for (uint32_t k = pe; k > pb; --k) r = pp[k - pb - 1] * r;
  return r;
}

void DeCtwModel::Distribution(std::span<const int32_t> context, std::span<double> out) const {
  const int K = spec_.alphabet_size;
  if (droot_ < 0) {
    std::fill(out.begin(), out.end(), 0.0);
    out[0] = 1.0;
    return;
  }
  const int L = static_cast<int>(std::min<size_t>(context.size(), spec_.depth));
  uint32_t t[kMaxDepth + 1];
  const int lm = WalkContext(context.data() + context.size(), L, t);
  // Binary probabilities of every decomposition node, by a walk of the
  // decomposition tree carrying the state indices down.
  std::vector<double> pw(2 * dnodes_.size());
  struct Item {
    int32_t node;
    int ds;
    Ref cur[kMaxDepth + 1];
  };
  std::vector<Item> stack(1);
  stack[0].node = droot_;
  stack[0].ds = -1;
  for (int d = 0; d <= lm; ++d) {
    stack[0].cur[d] = RootRef(t[d]);
    if (stack[0].cur[d] == kNoRef) break;
    stack[0].ds = d;
  }
  while (!stack.empty()) {
    Item it = stack.back();
    stack.pop_back();
    NodePw(it.cur, it.ds, L, &pw[2 * it.node]);
    for (int dir = 0; dir < 2; ++dir) {
      const int32_t c = dnodes_[it.node].child[dir];
      if (c < 0) continue;
      Item nx;
      nx.node = c;
      nx.ds = -1;
      for (int d = 0; d <= it.ds; ++d) {
        nx.cur[d] = Get(it.cur[d]).child[dir];
        if (nx.cur[d] == kNoRef) break;
        nx.ds = d;
      }
      stack.push_back(nx);
    }
  }
  for (int s = 0; s < K; ++s) {
    double r = 1.0;
    for (uint32_t k = path_off_[s + 1]; k > path_off_[s]; --k) {
      r = pw[2 * path_node_[k - 1] + path_dir_[k - 1]] * r;
    }
    out[s] = r;
  }
}

void DeCtwModel::LikelySymbols(std::span<const int32_t> context, double min_prob,
                               std::vector<std::pair<int32_t, double>>* out) const {
  out->clear();
  if (droot_ < 0) {
    out->push_back({0, 1.0});
    return;
  }
  const int L = static_cast<int>(std::min<size_t>(context.size(), spec_.depth));
  uint32_t t[kMaxDepth + 1];
  const int lm = WalkContext(context.data() + context.size(), L, t);
  // Walk the decomposition tree top-down, skipping subtrees whose mass (an
  // upper bound of every symbol below) is under min_prob.
  const double cut = min_prob * (1 - 1e-12);
  std::vector<double> pw(2 * dnodes_.size());
  struct Item {
    int32_t node;
    int ds;
    double mass;
    Ref cur[kMaxDepth + 1];
  };
  std::vector<Item> stack(1);
  stack[0].node = droot_;
  stack[0].ds = -1;
  stack[0].mass = 1.0;
  for (int d = 0; d <= lm; ++d) {
    stack[0].cur[d] = RootRef(t[d]);
    if (stack[0].cur[d] == kNoRef) break;
    stack[0].ds = d;
  }
  while (!stack.empty()) {
    const Item it = stack.back();
    stack.pop_back();
    NodePw(it.cur, it.ds, L, &pw[2 * it.node]);
    for (int dir = 0; dir < 2; ++dir) {
      const double mass = it.mass * pw[2 * it.node + dir];
      if (mass < cut) continue;
      const int32_t c = dnodes_[it.node].child[dir];
      if (c < 0) {
        const int32_t s = -c - 1;
        double r = 1.0;  // the same product order as Probability()
        for (uint32_t k = path_off_[s + 1]; k > path_off_[s]; --k) {
          r = pw[2 * path_node_[k - 1] + path_dir_[k - 1]] * r;
        }
        out->push_back({s, r});
        continue;
      }
      Item nx;
      nx.node = c;
      nx.ds = -1;
      nx.mass = mass;
      for (int d = 0; d <= it.ds; ++d) {
        nx.cur[d] = Get(it.cur[d]).child[dir];
        if (nx.cur[d] == kNoRef) break;
        nx.ds = d;
      }
      stack.push_back(nx);
    }
  }
}

bool DeCtwModel::Trained(std::span<const int32_t> context) const {
  if (context.size() > static_cast<size_t>(spec_.depth)) return false;
  const int L = static_cast<int>(context.size());
  uint32_t t[kMaxDepth + 1];
  return WalkContext(context.data() + context.size(), L, t) == L;
}

uint64_t DeCtwModel::ContextKey(std::span<const int32_t> context) const {
  const int L = static_cast<int>(std::min<size_t>(context.size(), spec_.depth));
  uint32_t t[kMaxDepth + 1];
  const int lm = WalkContext(context.data() + context.size(), L, t);
  // Below the deepest trained node only "is the path complete" matters:
  // untrained nodes give (0.5, 0.5) whatever their depth.
  return (uint64_t{t[lm]} << 1) | (lm == L ? 1u : 0u);
}

size_t DeCtwModel::MemoryBytes() const {
  return chunks_.size() * (sizeof(State) << kChunkBits) + edges_.MemoryBytes() +
         trie_state_.capacity() * 4 + path_node_.capacity() * 5 + dnodes_.capacity() * 8;
}

}  // namespace sb::markov::internal
