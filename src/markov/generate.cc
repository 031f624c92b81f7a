#include "markov/generate.h"

#include <cmath>
#include <random>
#include <set>
#include <string>

namespace sb::markov {

Status ValidateGenerateOptions(const GenerateOptions& o) {
  if (o.length < 0 || o.length > kMaxGenerateLength) {
    return Status::InvalidInput("--length must be in 0.." + std::to_string(kMaxGenerateLength));
  }
  if (!(o.temperature > 0) || !(o.temperature <= kMaxTemperature)) {
    return Status::InvalidInput("--temperature must be in (0, 100]");
  }
  if (o.max_run < 0 || o.max_run > kMaxGenerateLength) {
    return Status::InvalidInput("--max-run must be >= 0 (0 = no limit)");
  }
  if (o.no_repeat_ngram != 0 && (o.no_repeat_ngram < 2 || o.no_repeat_ngram > kMaxNoRepeatNgram)) {
    return Status::InvalidInput("--no-repeat-ngram must be 0 (off) or 2.." +
                                std::to_string(kMaxNoRepeatNgram));
  }
  return Status::Ok();
}

namespace {

// True when appending s to hist would make more than max_run equal symbols
// in a row.
bool RunTooLong(const std::vector<int32_t>& hist, int32_t s, int max_run) {
  if (max_run <= 0 || hist.size() < static_cast<size_t>(max_run)) return false;
  for (size_t i = hist.size() - max_run; i < hist.size(); ++i)
    if (hist[i] != s) return false;
  return true;
}

}  // namespace

std::vector<int32_t> Generate(const Model& model, std::span<const int32_t> start,
                              const GenerateOptions& options) {
  std::vector<int32_t> out;
  const std::vector<int32_t> cands = model.SeenSymbols();
  if (cands.empty() || options.length <= 0) return out;
  std::mt19937_64 rng(options.seed);
  std::vector<int32_t> hist(start.begin(), start.end());
  std::vector<double> dist(model.alphabet_size());
  std::vector<double> weight(cands.size());
  const size_t D = static_cast<size_t>(model.depth());
  const size_t n = static_cast<size_t>(options.no_repeat_ngram);
  std::set<std::vector<int32_t>> ngrams;
  if (n >= 2) {
    for (size_t i = 0; i + n <= hist.size(); ++i)
      ngrams.insert({hist.begin() + i, hist.begin() + i + n});
  }
  const double inv_t = 1.0 / options.temperature;
  for (int step = 0; step < options.length; ++step) {
    const size_t b = hist.size() > D ? hist.size() - D : 0;
    model.Distribution(std::span<const int32_t>(hist.data() + b, hist.size() - b), dist);
    // Allowed candidates: both rules, then the run rule only, then all.
    std::vector<int32_t> prefix;
    if (n >= 2 && hist.size() >= n - 1) prefix.assign(hist.end() - (n - 1), hist.end());
    auto blocked = [&](int32_t s, int level) {
      if (level >= 2) return false;
      if (RunTooLong(hist, s, options.max_run)) return true;
      if (level == 0 && !prefix.empty()) {
        prefix.push_back(s);
        const bool seen = ngrams.count(prefix) > 0;
        prefix.pop_back();
        return seen;
      }
      return false;
    };
    int level = 0;
    for (; level < 2; ++level) {
      bool any = false;
      for (int32_t s : cands) any = any || !blocked(s, level);
      if (any) break;
    }
    int32_t pick = -1;
    if (!options.sample) {
      double best = -1;
      for (int32_t s : cands) {
        if (!blocked(s, level) && dist[s] > best) {
          best = dist[s];
          pick = s;
        }
      }
    } else {
      double total = 0;
      for (size_t i = 0; i < cands.size(); ++i) {
        const int32_t s = cands[i];
        weight[i] = blocked(s, level)            ? 0.0
                    : options.temperature == 1.0 ? dist[s]
                                                 : std::pow(dist[s], inv_t);
        total += weight[i];
      }
      const double u = static_cast<double>(rng() >> 11) * 0x1.0p-53 * total;
      double acc = 0;
      for (size_t i = 0; i < cands.size(); ++i) {
        if (weight[i] <= 0) continue;
        pick = cands[i];  // the last allowed one if rounding leaves u >= acc
        acc += weight[i];
        if (u < acc) break;
      }
      if (pick < 0) {  // every weight underflowed: fall back to greedy
        double best = -1;
        for (int32_t s : cands) {
          if (!blocked(s, level) && dist[s] > best) {
            best = dist[s];
            pick = s;
          }
        }
      }
    }
    out.push_back(pick);
    hist.push_back(pick);
    if (n >= 2 && hist.size() >= n) ngrams.insert({hist.end() - n, hist.end()});
  }
  return out;
}

}  // namespace sb::markov
