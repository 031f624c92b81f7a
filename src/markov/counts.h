// Internal: count-based predictors (PPM-C and the fixed-order Markov chain)
// over one context trie of symbol counts. Use Model::Train.
#ifndef SB_MARKOV_COUNTS_H_
#define SB_MARKOV_COUNTS_H_

#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "base/status.h"
#include "markov/flat_map.h"
#include "markov/model.h"

namespace sb::markov::internal {

// For every context of length 0..D occurring in the training sequence (a
// context at position i is the up-to-D symbols before i), the counts of the
// symbols that followed it. Immutable after construction.
class CountTrie {
 public:
  CountTrie(int depth, std::span<const int32_t> seq);
  CountTrie() = default;  // empty; filled by LoadState

  // Model files: u64 N, (N + 1) x u32 offsets, u64 E, E x u32 symbols,
  // E x u32 counts, u64 C, C x u64 edge keys, C x u32 edge values.
  void SaveState(std::string* out) const;
  // Errors: kInvalidInput when the bytes are not a consistent trie over an
  // alphabet of `alphabet_size`.
  Status LoadState(std::string_view state, int alphabet_size);

  // Follows the context (most recent symbol at hist_end[-1]) for up to `len`
  // symbols; nodes[0] is the root. Returns the depth reached.
  int Walk(const int32_t* hist_end, int len, uint32_t* nodes) const;
  // The symbols seen after `node` (ascending) and their counts.
  std::span<const int32_t> Symbols(uint32_t node) const {
    return {syms_.data() + off_[node], syms_.data() + off_[node + 1]};
  }
  std::span<const uint32_t> Counts(uint32_t node) const {
    return {counts_.data() + off_[node], counts_.data() + off_[node + 1]};
  }
  uint64_t Total(uint32_t node) const { return total_[node]; }
  // Count of `sym` after `node` (binary search).
  uint32_t Count(uint32_t node, int32_t sym) const;

 private:
  FlatMap edges_;
  std::vector<uint32_t> off_;
  std::vector<int32_t> syms_;
  std::vector<uint32_t> counts_;
  std::vector<uint64_t> total_;
};

// PPM-C (Moffat 1990): from the longest available context (<= D) down to
// order 0, then order -1 (uniform over the alphabet). In a context with n
// counted and q distinct non-excluded symbols, a seen symbol gets c/(n+q)
// and the escape gets q/(n+q); symbols seen in longer contexts are excluded
// (from n and q) in shorter ones. Contexts with nothing left are skipped.
// Counts are the static counts of the whole training sequence.
class PpmCModel final : public Model {
 public:
  PpmCModel(const ModelSpec& spec, std::span<const int32_t> seq);
  PpmCModel(const ModelSpec& spec, std::span<const int32_t> seq, LoadOnly);
  void SaveState(std::string* out) const override { trie_.SaveState(out); }
  Status LoadState(std::string_view state) { return trie_.LoadState(state, spec_.alphabet_size); }
  double Probability(std::span<const int32_t> context, int32_t symbol) const override;
  void Distribution(std::span<const int32_t> context, std::span<double> out) const override;
  uint64_t ContextKey(std::span<const int32_t> context) const override;
  bool Trained(std::span<const int32_t> context) const override;

 private:
  CountTrie trie_;
};

// Order-D Markov chain: P(x | s) = (c(s,x) + alpha) / (c(s) + alpha*K) where s
// is the last min(D, available) symbols; contexts shorter than D (start of a
// sequence) use the counts of that shorter context.
class MarkovModel final : public Model {
 public:
  MarkovModel(const ModelSpec& spec, std::span<const int32_t> seq);
  MarkovModel(const ModelSpec& spec, std::span<const int32_t> seq, LoadOnly);
  void SaveState(std::string* out) const override { trie_.SaveState(out); }
  Status LoadState(std::string_view state) { return trie_.LoadState(state, spec_.alphabet_size); }
  double Probability(std::span<const int32_t> context, int32_t symbol) const override;
  void Distribution(std::span<const int32_t> context, std::span<double> out) const override;
  uint64_t ContextKey(std::span<const int32_t> context) const override;
  bool Trained(std::span<const int32_t> context) const override;

 private:
  // The context node of exactly the wanted length, or kNone.
  uint32_t ContextNode(std::span<const int32_t> context) const;
  CountTrie trie_;
};

}  // namespace sb::markov::internal

#endif  // SB_MARKOV_COUNTS_H_
