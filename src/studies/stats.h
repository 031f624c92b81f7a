// The statistics of a climber survey (paper sections 8-9, appendix B), each
// following SciPy 1.10's definition and p-value method so results can be
// checked against scipy.stats to 1e-9 (docs/studies.md gives every formula).
//
// Conventions: inputs are plain vectors of doubles; a result that SciPy
// reports as nan (too few observations, constant input, an undefined ratio)
// is a quiet NaN here too. All functions are pure and thread-safe; none
// throws (the Boost.Math special functions behind the p-values are called
// with a no-throw policy inside stats.cc).
#ifndef SB_STUDIES_STATS_H_
#define SB_STUDIES_STATS_H_

#include <string>
#include <vector>

namespace sb::studies {

// A test statistic and its two-sided p-value.
struct TestResult {
  double statistic = 0;
  double p = 0;
};

// Average ("mid") ranks, 1-based, of `v` in input order (scipy.stats.rankdata
// with method='average').
std::vector<double> AverageRanks(const std::vector<double>& v);

// Sum over groups of tied values of (t^3 - t), t the group size.
double TieTerm(const std::vector<double>& v);

// Arithmetic mean; NaN for an empty input.
double Mean(const std::vector<double>& v);
// Sample variance with divisor n - 1 (numpy var(ddof=1)); NaN for n < 2.
double SampleVariance(const std::vector<double>& v);
// Median (numpy.median: mean of the two middle values for even n); NaN when empty.
double Median(std::vector<double> v);
// Quantile q in [0, 1] with linear interpolation between order statistics
// (numpy.percentile's default method, Hyndman-Fan type 7); NaN when empty.
double Quantile(std::vector<double> v, double q);

// Cronbach's alpha of a respondents x items matrix (every row the same
// length k): alpha = k/(k-1) * (1 - sum_i var(item_i) / var(row sums)), sample
// variances (ddof 1). NaN when k < 2, fewer than 2 rows, or the variance of
// the row sums is 0.
double CronbachAlpha(const std::vector<std::vector<double>>& rows);

// Mann-Whitney U / Wilcoxon rank-sum test, two-sided, as
// scipy.stats.mannwhitneyu(x, y) (use_continuity=True, method='auto'):
// statistic = U of x = R_x - n_x(n_x+1)/2 with average ranks; the p-value is
// exact (the null distribution of U, no tie correction) when min(n_x, n_y) <= 8
// and no value is tied, else the normal approximation with tie-corrected
// variance and continuity correction 0.5. p is clipped to [0, 1]. NaN when
// either sample is empty.
struct MannWhitneyResult {
  double u = 0;
  double p = 0;
  bool exact = false;  // which p-value method was used
};
MannWhitneyResult MannWhitneyU(const std::vector<double>& x, const std::vector<double>& y);

// Welch's unequal-variance t-test, two-sided, as
// scipy.stats.ttest_ind(x, y, equal_var=False): t = (mean_x - mean_y) /
// sqrt(s_x^2/n_x + s_y^2/n_y), Welch-Satterthwaite degrees of freedom (1 when
// both variances are 0), p = 2 * T_df(-|t|). NaN when n_x or n_y < 2 or when
// both variances are 0 and the means are equal; t = +-inf and p = 0 when both
// variances are 0 and the means differ.
struct WelchResult {
  double t = 0;
  double df = 0;
  double p = 0;
};
WelchResult WelchT(const std::vector<double>& x, const std::vector<double>& y);

// Kendall's tau-b with scipy.stats.kendalltau's p-value (method='auto'): the
// exact null distribution when neither variable has ties and (n <= 33 or
// min(discordant, concordant) <= 1), else the normal approximation with the
// tie-corrected variance of (concordant - discordant). O(n log n). NaN for
// fewer than 2 pairs or when one variable is constant. x and y have equal size.
TestResult KendallTauB(const std::vector<double>& x, const std::vector<double>& y);

// Pearson's r with scipy.stats.pearsonr's exact p-value: under the null r
// follows a Beta(n/2-1, n/2-1) on [-1, 1] (equivalently t = r sqrt((n-2)/(1-r^2))
// with n-2 degrees of freedom), p = 2 * P(R >= |r|). n == 2 gives r = +-1, p = 1.
// NaN for n < 2 or a constant input. x and y have equal size.
TestResult PearsonR(const std::vector<double>& x, const std::vector<double>& y);

// Kendall's coefficient of concordance W of m raters ranking the same n
// objects (`ranks[j][i]` = rater j's rank of object i, any numbers: each row
// is re-ranked with average ranks so ties are allowed). With R_i the column
// sums of those ranks and S = sum (R_i - m(n+1)/2)^2,
//   W = 12 S / (m^2 (n^3 - n) - m sum_j T_j),   T_j = sum (t^3 - t) over rater j's ties,
// chi2 = m (n - 1) W (Friedman's tie-corrected statistic, equal to
// scipy.stats.friedmanchisquare for n >= 3) and p = P(chi2_{n-1} >= chi2).
// NaN when m < 1 or n < 2 or every rater ties every object.
struct KendallWResult {
  double w = 0;
  double chi2 = 0;
  int df = 0;
  double p = 0;
  int raters = 0;
};
KendallWResult KendallW(const std::vector<std::vector<double>>& ranks);

// Distribution helpers used by the tests above, exposed for reuse and tests.
// Upper tail of the standard normal, P(Z > z).
double NormalSf(double z);
// Lower tail of Student's t with `df` > 0 degrees of freedom, P(T <= t)
// (scipy.special.stdtr).
double StudentTCdf(double df, double t);
// Upper tail of chi-squared with `df` > 0 degrees of freedom, P(X > x).
double ChiSquaredSf(double df, double x);
// Regularized incomplete beta I_x(a, b).
double RegularizedBeta(double a, double b, double x);
// Two-sided exact p-value of the Mann-Whitney U statistic: 2 P(U >= u) under
// the null for samples of sizes m and n without ties (u the larger of U and
// mn - U), clipped to 1. NaN unless min(m, n) <= kMaxExactMannWhitney and
// max(m, n) <= kMaxExactMannWhitneyLarger. O(min(m,n)^2 max(m,n)) time.
double MannWhitneyExactP(int m, int n, double u);
// The largest smaller sample for which MannWhitneyU uses the exact p-value
// (SciPy's switch: exact when either sample has at most 8 values, no ties).
inline constexpr int kMaxExactMannWhitney = 8;
// The largest larger sample for which the exact counts fit in 128-bit
// integers (C(200008, 8) < 2^127); far above the response-file limits.
inline constexpr int kMaxExactMannWhitneyLarger = 200000;

}  // namespace sb::studies

#endif  // SB_STUDIES_STATS_H_
