#include "grades/chains.h"

#include <algorithm>
#include <cmath>
#include <set>

namespace sb::grades {

namespace {

uint64_t Get(const std::map<int32_t, uint64_t>& m, int32_t k) {
  auto it = m.find(k);
  return it == m.end() ? 0 : it->second;
}

}  // namespace

Result<BandChains> BandChains::Train(const std::vector<std::vector<std::string>>& routes,
                                     const std::vector<int>& bands, double alpha) {
  if (routes.size() != bands.size()) {
    return Status::InvalidInput("band chains: routes and bands differ in number");
  }
  if (routes.empty()) return Status::InvalidInput("band chains: no routes");
  if (!(alpha > 0)) return Status::InvalidInput("band chains: alpha must be > 0");
  std::set<std::string> seen;
  for (const auto& r : routes) seen.insert(r.begin(), r.end());
  BandChains c;
  c.vocab_ = markov::Vocabulary(std::vector<std::string>(seen.begin(), seen.end()));
  c.alpha_ = alpha;
  std::map<int, ChainCounts> by_band;
  for (size_t i = 0; i < routes.size(); ++i) {
    ChainCounts& cc = by_band[bands[i]];
    cc.band = bands[i];
    ++cc.routes;
    int32_t prev = -1;
    for (const std::string& s : routes[i]) {
      const int32_t id = c.vocab_.Id(s);
      ++cc.positions;
      ++cc.unigram[id];
      if (prev >= 0) {
        ++cc.pairs[{prev, id}];
        ++cc.follow[prev];
      }
      prev = id;
    }
  }
  for (auto& [band, cc] : by_band) c.chains_.push_back(std::move(cc));
  return c;
}

Result<BandChains> BandChains::FromParts(std::vector<std::string> vocabulary,
                                         std::vector<ChainCounts> chains, double alpha) {
  if (!(alpha > 0) || !std::isfinite(alpha)) {
    return Status::InvalidInput("band chains: alpha must be > 0");
  }
  if (chains.empty()) return Status::InvalidInput("band chains: no chains");
  for (size_t i = 1; i < vocabulary.size(); ++i) {
    if (!(vocabulary[i - 1] < vocabulary[i])) {
      return Status::InvalidInput("band chains: vocabulary not strictly ascending");
    }
  }
  const int32_t k = static_cast<int32_t>(vocabulary.size());  // ids 0..k-1 known
  for (size_t i = 0; i < chains.size(); ++i) {
    const ChainCounts& c = chains[i];
    if (i > 0 && !(chains[i - 1].band < c.band)) {
      return Status::InvalidInput("band chains: bands not strictly ascending");
    }
    if (c.routes < 1) return Status::InvalidInput("band chains: a chain without routes");
    uint64_t total = 0;
    for (const auto& [id, n] : c.unigram) {
      if (id < 0 || id >= k || n == 0) return Status::InvalidInput("band chains: bad symbol count");
      total += n;
    }
    if (total != c.positions) {
      return Status::InvalidInput("band chains: symbol counts do not sum to the positions");
    }
    std::map<int32_t, uint64_t> follow;
    for (const auto& [pair, n] : c.pairs) {
      if (pair.first < 0 || pair.first >= k || pair.second < 0 || pair.second >= k || n == 0) {
        return Status::InvalidInput("band chains: bad pair count");
      }
      follow[pair.first] += n;
    }
    if (follow != c.follow) {
      return Status::InvalidInput("band chains: pair counts do not sum to the follow counts");
    }
  }
  BandChains out;
  out.vocab_ = markov::Vocabulary(std::move(vocabulary));
  if (out.vocab_.size() != static_cast<size_t>(k)) {
    return Status::InvalidInput("band chains: duplicate vocabulary entries");
  }
  out.chains_ = std::move(chains);
  out.alpha_ = alpha;
  return out;
}

std::vector<double> BandChains::LogLikelihoods(const std::vector<std::string>& symbols) const {
  std::vector<int32_t> ids;
  ids.reserve(symbols.size());
  for (const std::string& s : symbols) ids.push_back(vocab_.Id(s));
  const double a = alpha_, K = alphabet();
  std::vector<double> out;
  out.reserve(chains_.size());
  for (const ChainCounts& c : chains_) {
    double ll = 0;
    for (size_t i = 0; i < ids.size(); ++i) {
      if (i == 0) {
        ll += std::log((static_cast<double>(Get(c.unigram, ids[0])) + a) /
                       (static_cast<double>(c.positions) + a * K));
        continue;
      }
      auto it = c.pairs.find({ids[i - 1], ids[i]});
      const double n = it == c.pairs.end() ? 0 : static_cast<double>(it->second);
      ll += std::log((n + a) / (static_cast<double>(Get(c.follow, ids[i - 1])) + a * K));
    }
    out.push_back(ll);
  }
  return out;
}

std::vector<double> BandChains::Posterior(const std::vector<std::string>& symbols) const {
  std::vector<double> lp = LogLikelihoods(symbols);
  double routes = 0;
  for (const ChainCounts& c : chains_) routes += c.routes;
  for (size_t b = 0; b < lp.size(); ++b) lp[b] += std::log(chains_[b].routes / routes);
  const double mx = *std::max_element(lp.begin(), lp.end());
  double sum = 0;
  for (double& v : lp) sum += (v = std::exp(v - mx));
  for (double& v : lp) v /= sum;
  return lp;
}

double BandChains::PosteriorMeanBand(const std::vector<std::string>& symbols) const {
  const std::vector<double> p = Posterior(symbols);
  double m = 0;
  for (size_t b = 0; b < p.size(); ++b) m += p[b] * chains_[b].band;
  return m;
}

}  // namespace sb::grades
