// Per-band Markov chains over move symbols: one first-order chain per grade
// band, all over one vocabulary, and the posterior over bands they give a
// route (docs/grades.md, "Markov feature").
//
// Each chain is the fixed-order Markov chain of src/markov (Algorithm::kMarkov,
// depth 1, additive smoothing alpha): P(first move) = (c(x) + a) / (N + a K),
// P(x | previous s) = (c(s, x) + a) / (c(s) + a K), K = vocabulary + 1
// (unknown symbols), except that its counts are kept per route (no pair
// spans two routes) and stored as counts, so an estimator file holds
// weights, never training sequences. chains_test.cc checks the
// probabilities against markov::Model on the same sequence.
#ifndef SB_GRADES_CHAINS_H_
#define SB_GRADES_CHAINS_H_

#include <cstdint>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "base/status.h"
#include "markov/token_model.h"

namespace sb::grades {

// The smoothing constant: 1/2, the Krichevsky-Trofimov (Jeffreys) prior
// that DE-CTW's leaf estimators use too; fixed, not tuned.
inline constexpr double kChainAlpha = 0.5;

// One band's counts. `unigram[x]` counts every position holding x;
// `pairs[{s, x}]` counts x following s inside a route; `follow[s]` is the
// sum of pairs[{s, *}].
struct ChainCounts {
  int band = 0;
  int routes = 0;
  uint64_t positions = 0;
  std::map<int32_t, uint64_t> unigram;
  std::map<std::pair<int32_t, int32_t>, uint64_t> pairs;
  std::map<int32_t, uint64_t> follow;
};

// All bands' chains over one vocabulary. Immutable after construction;
// const methods are thread-safe.
class BandChains {
 public:
  BandChains() = default;
  // Trains one chain per distinct band (ascending) from routes' symbol
  // sequences; the vocabulary is every symbol seen. `bands[i]` is route i's
  // band. Routes may be empty. Errors: kInvalidInput for size mismatch or no routes.
  static Result<BandChains> Train(const std::vector<std::vector<std::string>>& routes,
                                  const std::vector<int>& bands, double alpha = kChainAlpha);
  // Rebuilds from stored parts (the estimator file). Errors: kInvalidInput
  // when counts are inconsistent (ids outside the vocabulary, sums that do
  // not add up, bands not ascending).
  static Result<BandChains> FromParts(std::vector<std::string> vocabulary,
                                      std::vector<ChainCounts> chains, double alpha);

  // Natural-log likelihood of a route under each band's chain (band order).
  std::vector<double> LogLikelihoods(const std::vector<std::string>& symbols) const;
  // Posterior over bands with the training band frequencies (routes per
  // band) as prior; sums to 1.
  std::vector<double> Posterior(const std::vector<std::string>& symbols) const;
  // Posterior mean band: the Markov feature.
  double PosteriorMeanBand(const std::vector<std::string>& symbols) const;

  const markov::Vocabulary& vocabulary() const { return vocab_; }
  const std::vector<ChainCounts>& chains() const { return chains_; }
  double alpha() const { return alpha_; }
  // K: vocabulary size + 1 (the unknown symbol).
  double alphabet() const { return static_cast<double>(vocab_.size()) + 1; }

 private:
  markov::Vocabulary vocab_;
  std::vector<ChainCounts> chains_;
  double alpha_ = kChainAlpha;
};

}  // namespace sb::grades

#endif  // SB_GRADES_CHAINS_H_
