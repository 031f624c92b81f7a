#include "grades/consensus.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "grades/scale.h"

namespace sb::grades {

namespace {

// Type-7 percentile of sorted values.
double Percentile(const std::vector<double>& sorted, double q) {
  const double h = (static_cast<double>(sorted.size()) - 1) * q;
  const size_t lo = static_cast<size_t>(std::floor(h));
  const size_t hi = std::min(lo + 1, sorted.size() - 1);
  return sorted[lo] + (h - static_cast<double>(lo)) * (sorted[hi] - sorted[lo]);
}

}  // namespace

Result<Consensus> ConsensusOf(std::span<const double> felt) {
  if (felt.empty()) return Status::InvalidInput("consensus: no felt grades");
  std::vector<double> v(felt.begin(), felt.end());
  for (double x : v) {
    if (!std::isfinite(x)) return Status::InvalidInput("consensus: a felt grade is not finite");
  }
  std::sort(v.begin(), v.end());
  Consensus c;
  c.count = static_cast<int>(v.size());
  c.median = Percentile(v, 0.5);
  c.low = Percentile(v, 0.25);
  c.high = Percentile(v, 0.75);
  c.band = Band(c.median);
  return c;
}

double SignTestPValue(int k, int n) {
  if (n <= 0) return 1;
  const int m = std::min(k, n - k);
  // P(X <= m) for X ~ Binomial(n, 1/2), summed in log space.
  double tail = 0;
  for (int i = 0; i <= m; ++i) {
    tail += std::exp(std::lgamma(n + 1.0) - std::lgamma(i + 1.0) - std::lgamma(n - i + 1.0) -
                     n * std::log(2.0));
  }
  return std::min(1.0, 2 * tail);
}

Drift DriftOf(double setter_value, std::span<const double> felt) {
  Drift d;
  auto c = ConsensusOf(felt);
  if (!c.ok()) return d;
  const int setter = Band(setter_value);
  for (double x : felt) {
    const int b = Band(x);
    d.above += b > setter;
    d.below += b < setter;
  }
  d.bands = c->band - setter;
  d.p_value = SignTestPValue(d.above, d.above + d.below);
  d.flagged = std::abs(d.bands) > 1 && d.p_value < kDriftSignificance;
  return d;
}

}  // namespace sb::grades
