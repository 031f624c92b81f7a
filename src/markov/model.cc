#include "markov/model.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "markov/counts.h"
#include "markov/dectw.h"

namespace sb::markov {
namespace {
constexpr long kMaxUnseenDeCtw = 4096;
}  // namespace

const char* AlgorithmName(Algorithm a) {
  switch (a) {
    case Algorithm::kDeCtw:
      return "dectw";
    case Algorithm::kPpmC:
      return "ppmc";
    case Algorithm::kMarkov:
      return "markov";
  }
  return "?";
}

Result<Algorithm> ParseAlgorithm(const std::string& name) {
  if (name == "dectw") return Algorithm::kDeCtw;
  if (name == "ppmc") return Algorithm::kPpmC;
  if (name == "markov") return Algorithm::kMarkov;
  return Status::InvalidInput("unknown algorithm '" + name + "' (want dectw, ppmc or markov)");
}

Status ValidateSpec(const ModelSpec& spec) {
  if (spec.algorithm != Algorithm::kDeCtw && spec.algorithm != Algorithm::kPpmC &&
      spec.algorithm != Algorithm::kMarkov) {
    return Status::InvalidInput("unknown algorithm");
  }
  if (spec.depth < 1 || spec.depth > 32) {
    return Status::InvalidInput("depth must be in 1..32, got " + std::to_string(spec.depth));
  }
  if (spec.alphabet_size < 2 || spec.alphabet_size > 1000000) {
    return Status::InvalidInput("alphabet size must be in 2..1000000, got " +
                                std::to_string(spec.alphabet_size));
  }
  if (!(spec.alpha > 0) || !std::isfinite(spec.alpha)) {
    return Status::InvalidInput("smoothing alpha must be a positive number");
  }
  return Status::Ok();
}

Result<std::unique_ptr<Model>> Model::Train(const ModelSpec& spec,
                                            std::span<const int32_t> sequence) {
  SB_RETURN_IF_ERROR(ValidateSpec(spec));
  if (sequence.size() >= (size_t{1} << 31) / static_cast<size_t>(spec.depth + 1)) {
    return Status::InvalidInput("training sequence too long");
  }
  for (size_t i = 0; i < sequence.size(); ++i) {
    if (sequence[i] < 0 || sequence[i] >= spec.alphabet_size) {
      return Status::InvalidInput("symbol " + std::to_string(sequence[i]) + " at position " +
                                  std::to_string(i) + " is outside [0, " +
                                  std::to_string(spec.alphabet_size) + ")");
    }
  }
  if (spec.algorithm == Algorithm::kDeCtw) {
    // The reference's Huffman decomposition chains the ids that never occur
    // (depth = their number), so paths grow quadratically with them.
    std::vector<char> seen(spec.alphabet_size, 0);
    for (int32_t s : sequence) seen[s] = 1;
    const long unseen = std::count(seen.begin(), seen.end(), 0);
    if (unseen > kMaxUnseenDeCtw) {
      return Status::InvalidInput("DE-CTW: " + std::to_string(unseen) +
                                  " ids of the alphabet never occur in training (at most " +
                                  std::to_string(kMaxUnseenDeCtw) + "); use a smaller alphabet");
    }
  }
  std::unique_ptr<Model> m;
  switch (spec.algorithm) {
    case Algorithm::kDeCtw:
      m = std::make_unique<internal::DeCtwModel>(spec, sequence);
      break;
    case Algorithm::kPpmC:
      m = std::make_unique<internal::PpmCModel>(spec, sequence);
      break;
    case Algorithm::kMarkov:
      m = std::make_unique<internal::MarkovModel>(spec, sequence);
      break;
  }
  return m;
}

Result<std::unique_ptr<Model>> Model::FromState(const ModelSpec& spec,
                                                std::span<const int32_t> sequence,
                                                std::string_view state,
                                                std::shared_ptr<const void> backing) {
  SB_RETURN_IF_ERROR(ValidateSpec(spec));
  for (size_t i = 0; i < sequence.size(); ++i) {
    if (sequence[i] < 0 || sequence[i] >= spec.alphabet_size) {
      return Status::InvalidInput("symbol out of range at position " + std::to_string(i));
    }
  }
  Status st;
  std::unique_ptr<Model> m;
  switch (spec.algorithm) {
    case Algorithm::kDeCtw: {
      auto d = std::make_unique<internal::DeCtwModel>(spec, sequence, internal::kLoadOnly);
      st = d->LoadState(state, std::move(backing));
      m = std::move(d);
      break;
    }
    case Algorithm::kPpmC: {
      auto p = std::make_unique<internal::PpmCModel>(spec, sequence, internal::kLoadOnly);
      st = p->LoadState(state);
      m = std::move(p);
      break;
    }
    case Algorithm::kMarkov: {
      auto p = std::make_unique<internal::MarkovModel>(spec, sequence, internal::kLoadOnly);
      st = p->LoadState(state);
      m = std::move(p);
      break;
    }
  }
  if (!st.ok()) return st;
  return m;
}

double Model::LogLoss(std::span<const int32_t> sequence,
                      std::span<const int32_t> initial_context) const {
  std::vector<int32_t> buf(initial_context.begin(), initial_context.end());
  buf.insert(buf.end(), sequence.begin(), sequence.end());
  const size_t off = initial_context.size();
  double eval = 0.0;
  for (size_t i = 0; i < sequence.size(); ++i) {
    const size_t pos = off + i;
    const size_t start = pos > static_cast<size_t>(spec_.depth) ? pos - spec_.depth : 0;
    eval +=
        std::log(Probability(std::span<const int32_t>(buf.data() + start, pos - start), buf[pos]));
  }
  return eval * -(1 / std::log(2.0));
}

void Model::LikelySymbols(std::span<const int32_t> context, double min_prob,
                          std::vector<std::pair<int32_t, double>>* out) const {
  out->clear();
  std::vector<double> dist(alphabet_size());
  Distribution(context, dist);
  for (int s = 0; s < alphabet_size(); ++s)
    if (dist[s] >= min_prob) out->push_back({s, dist[s]});
}

std::vector<int32_t> Model::SeenSymbols() const {
  std::vector<int32_t> out;
  for (size_t s = 0; s < symbol_counts_.size(); ++s)
    if (symbol_counts_[s] > 0) out.push_back(static_cast<int32_t>(s));
  return out;
}

}  // namespace sb::markov
