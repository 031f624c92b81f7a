// Variable-order Markov models over integer symbol ids: DE-CTW (as in the
// reference library the Strange Beta paper used), PPM-C and a fixed-order
// Markov chain with additive smoothing, behind one interface.
#ifndef SB_MARKOV_MODEL_H_
#define SB_MARKOV_MODEL_H_

#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "base/status.h"

namespace sb::markov {

// Which predictor a model uses.
enum class Algorithm : uint32_t {
  kDeCtw = 0,   // decomposed context-tree weighting (Begleiter et al. 2004)
  kPpmC = 1,    // PPM with escape method C and exclusion, order <= depth
  kMarkov = 2,  // fixed-order Markov chain, additive (Lidstone) smoothing
};

// "dectw", "ppmc" or "markov". Never fails.
const char* AlgorithmName(Algorithm a);
// Parses AlgorithmName() output. Errors: kInvalidInput naming the value.
Result<Algorithm> ParseAlgorithm(const std::string& name);

// What to train. Symbols are ids 0..alphabet_size-1.
struct ModelSpec {
  Algorithm algorithm = Algorithm::kDeCtw;
  int depth = 5;  // context length D, 1..32
  int alphabet_size =
      2;               // K, 2..1,000,000; unseen ids still count (DE-CTW, PPM-C order -1, Markov)
  double alpha = 1.0;  // additive smoothing constant (kMarkov only), > 0
};

// Checks the ranges documented on ModelSpec. Errors: kInvalidInput.
Status ValidateSpec(const ModelSpec& spec);

// A trained predictor. Immutable after training: every const method is
// thread-safe. Contexts are given oldest symbol first (the natural order of
// a sequence); only the last `depth()` symbols matter.
class Model {
 public:
  virtual ~Model() = default;

  // Trains a new model on one sequence (several routes are concatenated by
  // the caller, as the reference did). Errors: kInvalidInput for a bad spec,
  // an id outside [0, alphabet_size), or (DE-CTW) more than 4096 alphabet ids
  // that never occur (the reference's decomposition chains them).
  static Result<std::unique_ptr<Model>> Train(const ModelSpec& spec,
                                              std::span<const int32_t> sequence);

  const ModelSpec& spec() const { return spec_; }
  int alphabet_size() const { return spec_.alphabet_size; }
  int depth() const { return spec_.depth; }

  // P(symbol | context). `symbol` must be in [0, K) and context ids too
  // (checked by callers; out-of-range ids are undefined behaviour here).
  virtual double Probability(std::span<const int32_t> context, int32_t symbol) const = 0;

  // Writes P(s | context) for every s in [0, K) into `out` (size K). Sums to 1
  // up to rounding.
  virtual void Distribution(std::span<const int32_t> context, std::span<double> out) const = 0;

  // Appends to `out` (cleared first) every symbol s with
  // P(s | context) >= min_prob as (s, P), in no particular order; it may
  // also include less likely symbols. The probabilities equal Probability().
  // DE-CTW prunes its decomposition tree, so a high min_prob is much cheaper
  // than Distribution(). The default uses Distribution().
  virtual void LikelySymbols(std::span<const int32_t> context, double min_prob,
                             std::vector<std::pair<int32_t, double>>* out) const;

  // An opaque key of the context's predictive state: two contexts with the
  // same key have the same next-symbol distribution (for DE-CTW: the deepest
  // trained context node and whether the context reached full depth). For
  // memoising searches; not stable across models or builds.
  virtual uint64_t ContextKey(std::span<const int32_t> context) const = 0;

  // True iff `context` (oldest first, at most depth() symbols) occurred in
  // full as the context of some training position. When [y, c] is not
  // trained, the prediction after (..., y, c, a...) does not depend on y or
  // anything older (for all three algorithms); interpolation uses this.
  virtual bool Trained(std::span<const int32_t> context) const = 0;

  // Total -log2 P(sequence) scored after `initial_context` (default: from an
  // empty context), without learning. Natural logs are summed and converted
  // at the end, as the reference did.
  double LogLoss(std::span<const int32_t> sequence,
                 std::span<const int32_t> initial_context = {}) const;

  // Model files (used by token_model.cc): appends the trained structures
  // (algorithm-specific layout, docs/formats.md "Markov model files") to
  // `out`, so loading needs no retraining. Deterministic.
  virtual void SaveState(std::string* out) const = 0;
  // Rebuilds a model of `spec` trained on `sequence` from bytes written by
  // SaveState (the sequence gives the symbol counts; nothing is retrained).
  // DE-CTW uses `state` in place when it can (8-byte aligned, little-endian
  // host) and then keeps `backing`, which must own those bytes, alive.
  // Errors: kInvalidInput naming the inconsistency. Never crashes and never
  // yields a model that reads out of bounds, whatever the bytes.
  static Result<std::unique_ptr<Model>> FromState(const ModelSpec& spec,
                                                  std::span<const int32_t> sequence,
                                                  std::string_view state,
                                                  std::shared_ptr<const void> backing = nullptr);

  // Number of times each id occurs in the training sequence (size K).
  const std::vector<uint32_t>& symbol_counts() const { return symbol_counts_; }
  // Ids that occur in the training sequence, ascending. These are the
  // candidates for generation and interpolation.
  std::vector<int32_t> SeenSymbols() const;

 protected:
  explicit Model(const ModelSpec& spec) : spec_(spec) {}
  ModelSpec spec_;
  std::vector<uint32_t> symbol_counts_;
};

}  // namespace sb::markov

#endif  // SB_MARKOV_MODEL_H_
