#include "markov/generate.h"

#include <random>

namespace sb::markov {

std::vector<int32_t> Generate(const Model& model, std::span<const int32_t> start,
                              const GenerateOptions& options) {
  std::vector<int32_t> out;
  const std::vector<int32_t> cands = model.SeenSymbols();
  if (cands.empty() || options.length <= 0) return out;
  std::mt19937_64 rng(options.seed);
  std::vector<int32_t> hist(start.begin(), start.end());
  std::vector<double> dist(model.alphabet_size());
  const size_t D = static_cast<size_t>(model.depth());
  for (int n = 0; n < options.length; ++n) {
    const size_t b = hist.size() > D ? hist.size() - D : 0;
    model.Distribution(std::span<const int32_t>(hist.data() + b, hist.size() - b), dist);
    int32_t pick = cands.front();
    if (!options.sample) {
      double best = -1;
      for (int32_t s : cands) {
        if (dist[s] > best) {
          best = dist[s];
          pick = s;
        }
      }
    } else {
      double total = 0;
      for (int32_t s : cands) total += dist[s];
      const double u = static_cast<double>(rng() >> 11) * 0x1.0p-53 * total;
      double acc = 0;
      pick = cands.back();
      for (int32_t s : cands) {
        acc += dist[s];
        if (u < acc) {
          pick = s;
          break;
        }
      }
    }
    out.push_back(pick);
    hist.push_back(pick);
  }
  return out;
}

}  // namespace sb::markov
