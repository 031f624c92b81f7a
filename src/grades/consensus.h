// The climbers' consensus on a route's grade and the setter's drift from
// it (docs/grades.md, "Consensus and drift"). Inputs are difficulties on
// one discipline's axis (Difficulty() of each felt grade and of the
// setter's grade), so votes in any scale mix.
//
//   std::vector<double> felt = ...;                 // Difficulty(ParseGrade(vote), d)
//   auto c = ConsensusOf(felt);                     // c->median, c->low, c->high, c->count
//   Drift dr = DriftOf(setter_value, felt);         // dr.flagged, dr.bands, dr.p_value
#ifndef SB_GRADES_CONSENSUS_H_
#define SB_GRADES_CONSENSUS_H_

#include <span>

#include "base/status.h"

namespace sb::grades {

// The median felt difficulty with its spread (the quartiles) and count.
struct Consensus {
  int count = 0;
  double median = 0;
  double low = 0;   // 25th percentile
  double high = 0;  // 75th percentile
  int band = 0;     // Band(median)
};

// Percentiles are linear interpolation between order statistics (numpy's
// default, Hyndman & Fan type 7). Errors: kInvalidInput for no votes or a
// value that is not finite. Pure; thread-safe.
Result<Consensus> ConsensusOf(std::span<const double> felt);

// The significance level of the drift flag's sign test.
inline constexpr double kDriftSignificance = 0.05;

// Whether the climbers disagree with the setter: votes whose band is above
// the setter's band against votes below (votes in the setter's band are
// ties and drop out, as in the sign test), and the consensus band.
struct Drift {
  bool flagged = false;  // |bands| > 1 and p_value < kDriftSignificance
  int bands = 0;         // consensus band - setter's band (0 without votes)
  int above = 0;         // votes harder than the setter's band
  int below = 0;         // votes easier
  double p_value = 1;    // exact two-sided sign test of above vs below
};

// "Enough votes" is the sign test's: with every vote on one side it needs
// six (2 x 0.5^6 < 0.05 < 2 x 0.5^5), more when votes are split; so the flag
// needs no hand-set vote count. No votes: not flagged. Pure; thread-safe.
Drift DriftOf(double setter_value, std::span<const double> felt);

// Exact two-sided binomial sign test p-value for k successes in n trials
// with p = 1/2: min(1, 2 P(X <= min(k, n - k))). Pure.
double SignTestPValue(int k, int n);

}  // namespace sb::grades

#endif  // SB_GRADES_CONSENSUS_H_
