// Forward simulation from a trained model.
#ifndef SB_MARKOV_GENERATE_H_
#define SB_MARKOV_GENERATE_H_

#include <cstdint>
#include <span>
#include <vector>

#include "base/status.h"
#include "markov/model.h"

namespace sb::markov {

// At most this many generated symbols per call (a few MB of output; each
// symbol costs one Distribution() over the alphabet).
inline constexpr int kMaxGenerateLength = 1'000'000;
// Sampling temperature range.
inline constexpr double kMaxTemperature = 100.0;
// Longest n-gram no_repeat_ngram may name.
inline constexpr int kMaxNoRepeatNgram = 16;

struct GenerateOptions {
  int length = 10;      // symbols to produce, 0..kMaxGenerateLength
  bool sample = false;  // false: greedy (most likely, lowest id on ties)
  uint64_t seed = 1;    // PRNG seed when sampling
  // Sampling only: draw from P^(1/T) renormalised; T < 1 sharpens towards
  // greedy, T > 1 flattens. (0, kMaxTemperature].
  double temperature = 1.0;
  // A symbol may follow itself at most max_run - 1 times (at most max_run in
  // a row, counting the start context); 0 = no limit. The default 2 keeps
  // greedy generation from collapsing into one repeated symbol ("jug jug
  // jug ..."), which a peaked model otherwise does.
  int max_run = 2;
  // n >= 2: never produce an n-gram that already occurs in the start context
  // plus the output (breaks longer cycles); 0 = off. At most kMaxNoRepeatNgram.
  int no_repeat_ngram = 0;
};

// Checks the ranges documented on GenerateOptions. Errors: kInvalidInput
// naming the option.
Status ValidateGenerateOptions(const GenerateOptions& options);

// Produces `length` symbols after `start` (which is context only, not
// repeated in the output). Candidates are the symbols seen in training
// (Model::SeenSymbols), their probabilities renormalised; so an unknown-token
// id is never produced. At each step the symbols max_run and no_repeat_ngram
// forbid are left out (when they would leave nothing, the n-gram rule is
// dropped for that step, then the run rule). Sampling uses std::mt19937_64
// and its own inverse-CDF draw (53-bit uniform), so a seed gives the same
// output on every platform. Returns an empty vector when the model saw no
// symbols. `options` must be valid. Thread-safe.
std::vector<int32_t> Generate(const Model& model, std::span<const int32_t> start,
                              const GenerateOptions& options);

}  // namespace sb::markov

#endif  // SB_MARKOV_GENERATE_H_
