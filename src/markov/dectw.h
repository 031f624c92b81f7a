// Internal: the DE-CTW predictor. Use Model::Train with Algorithm::kDeCtw.
#ifndef SB_MARKOV_DECTW_H_
#define SB_MARKOV_DECTW_H_

#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "base/status.h"
#include "markov/flat_map.h"
#include "markov/model.h"

namespace sb::markov::internal {

// Decomposed CTW, reproducing vmm.algs.DCTWPredictor (Begleiter, El-Yaniv &
// Yona 2004): a Huffman-shaped binary decomposition of the alphabet, each
// internal node running a binary CTW (Volf estimator, alpha 16, beta bounds,
// count halving) over full-alphabet contexts. The reference keeps one
// context tree of abSize-ary nodes per decomposition node; here one shared
// context trie (hash edges) holds, per context, a binary trie of 24-byte
// states that follows the decomposition tree, allocated in 64K-state chunks.
// A context seen once is stored as just its symbol (its states would all be
// counts 1 / beta 1 along that symbol's path) and expanded on its second
// visit; most long contexts are seen once.
class DeCtwModel final : public Model {
 public:
  // Builds the decomposition and trains. `spec`/`sequence` must be valid
  // (checked by Model::Train).
  DeCtwModel(const ModelSpec& spec, std::span<const int32_t> sequence);
  // Counts and decomposition only; LoadState then fills the trained state.
  DeCtwModel(const ModelSpec& spec, std::span<const int32_t> sequence, LoadOnly);
  // The trained state: trie, edge table and binary states (model files;
  // arrays at 8-byte aligned offsets of the section, states as 24-byte
  // records, so a loaded model can use the file's bytes in place).
  void SaveState(std::string* out) const override;
  // Errors: kInvalidInput when the bytes are not a consistent state. The
  // model uses `state` in place when it is suitably aligned and the host is
  // little-endian, keeping `backing` (which must own `state`'s bytes) alive;
  // otherwise it copies.
  Status LoadState(std::string_view state, std::shared_ptr<const void> backing);

  double Probability(std::span<const int32_t> context, int32_t symbol) const override;
  void Distribution(std::span<const int32_t> context, std::span<double> out) const override;
  uint64_t ContextKey(std::span<const int32_t> context) const override;
  bool Trained(std::span<const int32_t> context) const override;
  void LikelySymbols(std::span<const int32_t> context, double min_prob,
                     std::vector<std::pair<int32_t, double>>* out) const override;

  // Bytes held by the trained structures (approximate).
  size_t MemoryBytes() const;

 private:
  struct State {
    double beta;
    uint16_t c[2];
    uint32_t child[2];
  };
  static_assert(sizeof(State) == 24, "model files store states as 24-byte records");
  // A state reference: a State index, or a virtual state of a context seen
  // once (kVirtual | symbol << 32 | level on that symbol's path), or kNoRef.
  using Ref = uint64_t;
  struct View {
    double beta;
    uint16_t c[2];
    Ref child[2];
  };
  static constexpr uint32_t kNone = FlatMap::kNone;
  static constexpr uint32_t kSingleton = 0x80000000u;  // trie_state_ tag: seen once
  static constexpr Ref kVirtual = uint64_t{1} << 63;
  static constexpr Ref kNoRef = ~uint64_t{0};
  View Get(Ref r) const;
  Ref RootRef(uint32_t trie_node) const;
  uint32_t Materialize(int32_t symbol);
  static constexpr int kChunkBits = 16;

  void BuildDecomposition();
  void Learn(std::span<const int32_t> seq);
  uint32_t NewState();
  State& S(uint32_t i) { return chunks_[i >> kChunkBits][i & ((1u << kChunkBits) - 1)]; }
  const State& S(uint32_t i) const {
    return chunks_[i >> kChunkBits][i & ((1u << kChunkBits) - 1)];
  }
  // Finds the trie nodes of the context (most recent symbol at hist[-1]),
  // returns how deep the existing path goes; fills nodes[0..returned].
  int WalkContext(const int32_t* hist_end, int len, uint32_t* nodes) const;
  // Weighted binary probabilities of one decomposition node given the states
  // cur[0..ds] (ds = -1: none) along a context of length L.
  void NodePw(const Ref* cur, int ds, int L, double out[2]) const;

  // Decomposition tree: internal nodes; child[dir] >= 0 internal, else
  // -(symbol+1). dir 0 = the reference's RIGHT, 1 = LEFT.
  struct DNode {
    int32_t child[2];
  };
  std::vector<DNode> dnodes_;
  int32_t droot_ = -1;
  std::vector<uint32_t> path_off_;  // K+1 offsets into path_node_/path_dir_
  std::vector<int32_t> path_node_;
  std::vector<uint8_t> path_dir_;

  FlatMap edges_;                     // (trie node, older symbol) -> trie node
  std::vector<uint32_t> trie_state_;  // trie node -> root State index, or kSingleton | symbol
  std::vector<std::unique_ptr<State[]>> chunks_;
  uint32_t num_states_ = 0;

  // What queries read: the training structures above, or a model file's
  // bytes (or copies of them) after LoadState.
  struct Views {
    const uint32_t* trie_state = nullptr;
    size_t trie_size = 0;
    const uint64_t* keys = nullptr;
    const uint32_t* values = nullptr;
    size_t mask = 0;
    const State* states = nullptr;  // loaded models; trained ones use chunks_
  };
  Views v_;
  bool loaded_ = false;
  std::shared_ptr<const void> backing_;
  std::vector<uint32_t> own_trie_, own_values_;
  std::vector<uint64_t> own_keys_;
  std::vector<State> own_states_;
  void SetTrainedViews();
  const State& QS(uint32_t i) const { return loaded_ ? v_.states[i] : S(i); }
};

}  // namespace sb::markov::internal

#endif  // SB_MARKOV_DECTW_H_
