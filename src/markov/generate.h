// Forward simulation from a trained model.
#ifndef SB_MARKOV_GENERATE_H_
#define SB_MARKOV_GENERATE_H_

#include <cstdint>
#include <span>
#include <vector>

#include "markov/model.h"

namespace sb::markov {

struct GenerateOptions {
  int length = 10;      // symbols to produce, >= 0
  bool sample = false;  // false: greedy (most likely, lowest id on ties)
  uint64_t seed = 1;    // PRNG seed when sampling
};

// Produces `length` symbols after `start` (which is context only, not
// repeated in the output). Candidates are the symbols seen in training
// (Model::SeenSymbols), their probabilities renormalised; so an unknown-token
// id is never produced. Sampling uses std::mt19937_64 and its own inverse-CDF
// draw (53-bit uniform), so a seed gives the same output on every platform.
// Returns an empty vector when the model saw no symbols. Thread-safe.
std::vector<int32_t> Generate(const Model& model, std::span<const int32_t> start,
                              const GenerateOptions& options);

}  // namespace sb::markov

#endif  // SB_MARKOV_GENERATE_H_
