// Interpolation: the best insertion of 0..j symbols between a `before` and an
// `after` sequence, minimising -log2 P of the whole sequence (Strange Beta
// section 10.3; Stuart & Bradley's transition-graph view). This is the API
// the route-plan smoothing (`vary --smooth`) calls.
#ifndef SB_MARKOV_INTERPOLATE_H_
#define SB_MARKOV_INTERPOLATE_H_

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "base/status.h"
#include "markov/model.h"
#include "markov/token_model.h"

namespace sb::markov {

// Largest supported insertion length.
inline constexpr int kMaxInsert = 4;

struct InsertionOptions {
  int max_insert = 2;  // j: insert 0..j symbols, 0..kMaxInsert
  // true: exactly max_insert symbols (the paper's N^j search for one j),
  // even when inserting nothing would be cheaper.
  bool exactly = false;
  std::vector<int32_t> candidates;  // symbols that may be inserted; empty = Model::SeenSymbols()
  // 0 = automatic (two threads for max_insert >= 3 with 64+ candidates on a
  // multi-core machine), 1 = one thread. The answer is the same either way.
  int threads = 0;
};

struct InsertionResult {
  std::vector<int32_t> inserted;  // the best insertion (may be empty)
  double bits = 0;                // -log2 P(before + inserted + after), from an empty context
  double baseline_bits = 0;       // -log2 P(before + after)
  uint64_t nodes_visited = 0;     // search nodes expanded (for benchmarks)
  // Bits saved by the insertion (>= 0; 0 when nothing helps).
  double saved_bits() const { return baseline_bits - bits; }
};

// Exact search over all insertions of 0..max_insert candidate symbols (or
// of exactly max_insert with options.exactly), equal to brute force: depth-first branch and bound,
// children taken in increasing cost order and cut once the inserted symbols alone cost as much as
// the best complete sequence; only the first `depth` symbols of `after` depend on the insertion, so
// only those are rescored. On ties the shorter insertion, then the one found first (cheapest first
// symbols, then lowest id) wins. Errors: kInvalidInput for max_insert outside 0..kMaxInsert or ids
// outside [0, K). Thread-safe (the model is const). Cost: typically milliseconds for j <= 3 and K ~
// 300 on peaked models; the worst case (a flat model) is K^j leaf evaluations.
Result<InsertionResult> BestInsertion(const Model& model, std::span<const int32_t> before,
                                      std::span<const int32_t> after,
                                      const InsertionOptions& options = {});

// The plan module's smoothing call: the best insertion of up to
// `max_insert` tokens at a boundary between `before` (the route so far, in
// order) and `after` (the rest). Tokens the model's vocabulary does not know
// are scored as its unknown id and are never suggested.
struct SmoothingSuggestion {
  std::vector<std::string> insert;  // suggested tokens; empty = leave the boundary alone
  std::vector<int32_t> ids;         // the same as model ids
  double bits_without = 0;          // -log2 P(before + after)
  double bits_with = 0;             // -log2 P(before + insert + after)
  double bits_saved = 0;            // bits_without - bits_with (0 when insert is empty)
};

// Errors: kInvalidInput when a model without vocabulary gets a non-integer
// or out-of-range token, or max_insert is outside 0..kMaxInsert.
// Thread-safe.
Result<SmoothingSuggestion> SuggestSmoothing(const TokenModel& model,
                                             const std::vector<std::string>& before,
                                             const std::vector<std::string>& after,
                                             int max_insert = 2);

}  // namespace sb::markov

#endif  // SB_MARKOV_INTERPOLATE_H_
