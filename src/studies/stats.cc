#include "studies/stats.h"

#include <algorithm>
#include <boost/math/distributions/students_t.hpp>
#include <boost/math/special_functions/beta.hpp>
#include <boost/math/special_functions/erf.hpp>
#include <boost/math/special_functions/gamma.hpp>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numeric>

namespace sb::studies {
namespace {

namespace bmp = boost::math::policies;
// Boost.Math reports errors by throwing unless told otherwise; every call
// here uses this policy so that nothing throws (a bad argument yields NaN,
// an overflow infinity) and the module keeps its no-exception contract.
using NoThrow =
    bmp::policy<bmp::domain_error<bmp::ignore_error>, bmp::pole_error<bmp::ignore_error>,
                bmp::overflow_error<bmp::ignore_error>, bmp::underflow_error<bmp::ignore_error>,
                bmp::evaluation_error<bmp::ignore_error>, bmp::rounding_error<bmp::ignore_error>,
                bmp::indeterminate_result_error<bmp::ignore_error>>;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

double Clip01(double p) { return std::isnan(p) ? p : std::clamp(p, 0.0, 1.0); }

// Sorted copies of the sizes of groups of equal values.
std::vector<int64_t> TieGroups(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  std::vector<int64_t> groups;
  for (size_t i = 0; i < v.size();) {
    size_t j = i;
    while (j < v.size() && v[j] == v[i]) ++j;
    groups.push_back(int64_t(j - i));
    i = j;
  }
  return groups;
}

// Dense ranks 1..d of `v` (equal values share a rank).
std::vector<int64_t> DenseRanks(const std::vector<double>& v) {
  std::vector<size_t> idx(v.size());
  std::iota(idx.begin(), idx.end(), size_t{0});
  std::stable_sort(idx.begin(), idx.end(), [&](size_t a, size_t b) { return v[a] < v[b]; });
  std::vector<int64_t> r(v.size());
  int64_t rank = 0;
  for (size_t k = 0; k < idx.size(); ++k) {
    if (k == 0 || v[idx[k]] != v[idx[k - 1]]) ++rank;
    r[idx[k]] = rank;
  }
  return r;
}

// Number of pairs i < j with a[i] > a[j] (strict); sorts `a` (merge sort).
int64_t CountInversions(std::vector<int64_t>& a) {
  std::vector<int64_t> buf(a.size());
  int64_t inv = 0;
  for (size_t width = 1; width < a.size(); width *= 2) {
    for (size_t lo = 0; lo < a.size(); lo += 2 * width) {
      size_t mid = std::min(lo + width, a.size()), hi = std::min(lo + 2 * width, a.size());
      size_t i = lo, j = mid, k = lo;
      while (i < mid && j < hi) {
        if (a[j] < a[i]) {
          inv += int64_t(mid - i);
          buf[k++] = a[j++];
        } else {
          buf[k++] = a[i++];
        }
      }
      while (i < mid) buf[k++] = a[i++];
      while (j < hi) buf[k++] = a[j++];
    }
    std::swap(a, buf);
  }
  return inv;
}

// For the dense ranks of one variable: sum C(t,2), sum t(t-1)(t-2) and
// sum t(t-1)(2t+5) over groups of size t (scipy's count_rank_tie).
struct RankTies {
  int64_t pairs = 0;
  double v0 = 0, v1 = 0;
};
RankTies CountRankTies(const std::vector<int64_t>& dense) {
  int64_t max_rank = dense.empty() ? 0 : *std::max_element(dense.begin(), dense.end());
  std::vector<int64_t> count(size_t(max_rank) + 1, 0);
  for (int64_t r : dense) ++count[size_t(r)];
  RankTies t;
  for (int64_t c : count) {
    if (c <= 1) continue;
    t.pairs += c * (c - 1) / 2;
    double cd = double(c);
    t.v0 += cd * (cd - 1) * (cd - 2);
    t.v1 += cd * (cd - 1) * (2 * cd + 5);
  }
  return t;
}

// Exact two-sided p-value of Kendall's tau without ties for n items whose
// concordant-pair count is `c` (scipy.stats._mstats_basic._kendall_p_exact,
// same branches and the same floating-point recurrence).
double KendallExactP(int64_t n, int64_t c) {
  const int64_t total = n * (n - 1) / 2;
  c = std::min(c, total - c);
  if (n <= 2) return 1.0;
  auto factorial = [](int64_t k) {
    double f = 1;
    for (int64_t i = 2; i <= k; ++i) f *= double(i);
    return f;
  };
  double prob;
  if (c == 0) {
    prob = n < 171 ? 2.0 / factorial(n) : 0.0;
  } else if (c == 1) {
    prob = n < 172 ? 2.0 / factorial(n - 1) : 0.0;
  } else if (4 * c == n * (n - 1)) {
    prob = 1.0;
  } else {
    // new[k] = number of permutations of j items with k inversions (k <= c),
    // built up for j = 3..n; for n >= 171 each step is divided by j.
    std::vector<double> counts(size_t(c) + 1, 0.0), prev;
    counts[0] = counts[1] = 1.0;
    for (int64_t j = 3; j <= n; ++j) {
      double run = 0;
      for (double& v : counts) {
        run += v;
        v = n < 171 ? run : run / double(j);
      }
      if (j <= c) {
        prev = counts;
        for (int64_t k = j; k <= c; ++k) counts[size_t(k)] -= prev[size_t(k - j)];
      }
    }
    double sum = 0;
    for (double v : counts) sum += v;
    prob = n < 171 ? 2.0 * sum / factorial(n) : sum;
  }
  return Clip01(prob);
}

}  // namespace

std::vector<double> AverageRanks(const std::vector<double>& v) {
  std::vector<size_t> idx(v.size());
  std::iota(idx.begin(), idx.end(), size_t{0});
  std::stable_sort(idx.begin(), idx.end(), [&](size_t a, size_t b) { return v[a] < v[b]; });
  std::vector<double> r(v.size());
  for (size_t i = 0; i < idx.size();) {
    size_t j = i;
    while (j < idx.size() && v[idx[j]] == v[idx[i]]) ++j;
    double avg = (double(i + 1) + double(j)) / 2.0;  // mean of ranks i+1..j
    for (size_t k = i; k < j; ++k) r[idx[k]] = avg;
    i = j;
  }
  return r;
}

double TieTerm(const std::vector<double>& v) {
  double sum = 0;
  for (int64_t t : TieGroups(v)) sum += double(t) * double(t) * double(t) - double(t);
  return sum;
}

double Mean(const std::vector<double>& v) {
  if (v.empty()) return kNaN;
  double s = 0;
  for (double x : v) s += x;
  return s / double(v.size());
}

double SampleVariance(const std::vector<double>& v) {
  if (v.size() < 2) return kNaN;
  double m = Mean(v), ss = 0;
  for (double x : v) ss += (x - m) * (x - m);
  return ss / double(v.size() - 1);
}

double Median(std::vector<double> v) { return Quantile(std::move(v), 0.5); }

double Quantile(std::vector<double> v, double q) {
  if (v.empty()) return kNaN;
  std::sort(v.begin(), v.end());
  double h = (double(v.size()) - 1) * q;
  size_t lo = size_t(std::floor(h));
  if (lo + 1 >= v.size()) return v.back();
  double frac = h - double(lo);
  return v[lo] + frac * (v[lo + 1] - v[lo]);
}

double CronbachAlpha(const std::vector<std::vector<double>>& rows) {
  if (rows.size() < 2 || rows[0].size() < 2) return kNaN;
  const size_t k = rows[0].size();
  std::vector<double> totals(rows.size(), 0.0), column(rows.size());
  double item_var = 0;
  for (size_t i = 0; i < k; ++i) {
    for (size_t r = 0; r < rows.size(); ++r) {
      column[r] = rows[r][i];
      totals[r] += rows[r][i];
    }
    item_var += SampleVariance(column);
  }
  double total_var = SampleVariance(totals);
  if (!(total_var > 0)) return kNaN;
  return double(k) / double(k - 1) * (1.0 - item_var / total_var);
}

double NormalSf(double z) {
  if (std::isnan(z)) return kNaN;
  if (z == kInf) return 0.0;
  if (z == -kInf) return 1.0;
  return 0.5 * boost::math::erfc(z / std::sqrt(2.0), NoThrow());
}

double StudentTCdf(double df, double t) {
  if (std::isnan(t) || std::isnan(df) || !(df > 0)) return kNaN;
  if (t == kInf) return 1.0;
  if (t == -kInf) return 0.0;
  boost::math::students_t_distribution<double, NoThrow> dist(df);
  return t < 0 ? boost::math::cdf(dist, t)
               : 1.0 - boost::math::cdf(boost::math::complement(dist, t));
}

double ChiSquaredSf(double df, double x) {
  if (std::isnan(x) || !(df > 0)) return kNaN;
  if (x <= 0) return 1.0;
  if (x == kInf) return 0.0;
  return boost::math::gamma_q(df / 2.0, x / 2.0, NoThrow());
}

double RegularizedBeta(double a, double b, double x) {
  if (!(x > 0)) return x == 0 ? 0.0 : kNaN;
  if (!(x < 1)) return x == 1 ? 1.0 : kNaN;
  return boost::math::ibeta(a, b, x, NoThrow());
}

double MannWhitneyExactP(int m, int n, double u) {
  if (m <= 0 || n <= 0) return kNaN;
  const int64_t a = std::min(m, n), b = std::max(m, n);
  if (a > kMaxExactMannWhitney) return kNaN;
  // The number of arrangements with U = k is the coefficient of q^k in the
  // Gaussian binomial [a+b choose a]_q = prod_{i=1..a} (1 - q^(b+i)) / (1 - q^i).
  // Coefficients are at most C(a+b, a) <= C(8 + kMaxExactMannWhitneyLarger, 8)
  // < 2^127, so 128-bit integers hold them exactly.
  if (b > kMaxExactMannWhitneyLarger) return kNaN;
  using Int = __int128;
  std::vector<Int> poly(size_t(a * b + a) + 1, 0);  // room for the top terms before division
  poly[0] = 1;
  int64_t deg = 0;
  for (int64_t i = 1; i <= a; ++i) {
    const int64_t up = b + i;
    for (int64_t k = deg + up; k >= up; --k) poly[size_t(k)] -= poly[size_t(k - up)];
    for (int64_t k = i; k <= deg + b; ++k) poly[size_t(k)] += poly[size_t(k - i)];
    // The division is exact: the quotient has degree deg + b; clear the rest.
    for (int64_t k = deg + b + 1; k <= deg + up; ++k) poly[size_t(k)] = 0;
    deg += b;
  }
  // P(U >= u) = P(U <= mn - u) by symmetry; SciPy counts the mass at u too.
  const int64_t limit = a * b - int64_t(std::llround(u));
  Int tail = 0, total = 0;
  for (int64_t k = 0; k <= deg; ++k) {
    if (k <= limit) tail += poly[size_t(k)];
    total += poly[size_t(k)];
  }
  if (limit < 0) return 0.0;
  return Clip01(2.0 * double(static_cast<long double>(tail) / static_cast<long double>(total)));
}

MannWhitneyResult MannWhitneyU(const std::vector<double>& x, const std::vector<double>& y) {
  MannWhitneyResult out;
  const size_t n1 = x.size(), n2 = y.size();
  if (n1 == 0 || n2 == 0) return {kNaN, kNaN, false};
  std::vector<double> xy(x);
  xy.insert(xy.end(), y.begin(), y.end());
  const std::vector<double> ranks = AverageRanks(xy);
  double r1 = 0;
  for (size_t i = 0; i < n1; ++i) r1 += ranks[i];
  const double dn1 = double(n1), dn2 = double(n2);
  const double u1 = r1 - dn1 * (dn1 + 1) / 2;
  const double u = std::max(u1, dn1 * dn2 - u1);
  out.u = u1;
  const double tie = TieTerm(xy);
  out.exact = !(n1 > 8 && n2 > 8) && tie == 0;
  if (out.exact) {
    out.p = MannWhitneyExactP(int(n1), int(n2), u);
    return out;
  }
  const double n = dn1 + dn2;
  const double s = std::sqrt(dn1 * dn2 / 12 * ((n + 1) - tie / (n * (n - 1))));
  const double num = u - dn1 * dn2 / 2 - 0.5;
  double z;
  if (s > 0) {
    z = num / s;
  } else {
    z = num < 0 ? -kInf : (num > 0 ? kInf : kNaN);
  }
  out.p = Clip01(2.0 * NormalSf(z));
  return out;
}

WelchResult WelchT(const std::vector<double>& x, const std::vector<double>& y) {
  if (x.size() < 2 || y.size() < 2) return {kNaN, kNaN, kNaN};
  const double n1 = double(x.size()), n2 = double(y.size());
  const double vn1 = SampleVariance(x) / n1, vn2 = SampleVariance(y) / n2;
  WelchResult out;
  out.df = (vn1 + vn2) * (vn1 + vn2) / (vn1 * vn1 / (n1 - 1) + vn2 * vn2 / (n2 - 1));
  if (std::isnan(out.df)) out.df = 1;  // both variances 0: any df will do (SciPy)
  const double denom = std::sqrt(vn1 + vn2), d = Mean(x) - Mean(y);
  if (denom > 0) {
    out.t = d / denom;
  } else {
    out.t = d > 0 ? kInf : (d < 0 ? -kInf : kNaN);
  }
  out.p = 2.0 * StudentTCdf(out.df, -std::abs(out.t));
  return out;
}

TestResult KendallTauB(const std::vector<double>& x, const std::vector<double>& y) {
  const int64_t n = int64_t(x.size());
  if (n == 0 || x.size() != y.size()) return {kNaN, kNaN};
  const std::vector<int64_t> xr = DenseRanks(x), yr = DenseRanks(y);
  std::vector<size_t> idx(x.size());
  std::iota(idx.begin(), idx.end(), size_t{0});
  std::sort(idx.begin(), idx.end(),
            [&](size_t a, size_t b) { return xr[a] != xr[b] ? xr[a] < xr[b] : yr[a] < yr[b]; });
  std::vector<int64_t> ys(x.size());
  int64_t joint = 0, run = 0;
  for (size_t k = 0; k < idx.size(); ++k) {
    ys[k] = yr[idx[k]];
    bool same = k > 0 && xr[idx[k]] == xr[idx[k - 1]] && yr[idx[k]] == yr[idx[k - 1]];
    run = same ? run + 1 : 0;
    joint += run;  // adds C(t, 2) over a run of t equal pairs
  }
  const int64_t dis = CountInversions(ys);
  const RankTies xt = CountRankTies(xr), yt = CountRankTies(yr);
  const int64_t tot = n * (n - 1) / 2;
  if (xt.pairs == tot || yt.pairs == tot) return {kNaN, kNaN};
  const int64_t con_minus_dis = tot - xt.pairs - yt.pairs + joint - 2 * dis;
  double tau =
      double(con_minus_dis) / std::sqrt(double(tot - xt.pairs)) / std::sqrt(double(tot - yt.pairs));
  tau = std::clamp(tau, -1.0, 1.0);
  const bool no_ties = xt.pairs == 0 && yt.pairs == 0;
  if (no_ties && (n <= 33 || std::min(dis, tot - dis) <= 1)) {
    return {tau, KendallExactP(n, tot - dis)};
  }
  const double m = double(n) * (double(n) - 1);
  const double var = (m * (2 * double(n) + 5) - xt.v1 - yt.v1) / 18 +
                     (2 * double(xt.pairs) * double(yt.pairs)) / m +
                     xt.v0 * yt.v0 / (9 * m * (double(n) - 2));
  const double z = double(con_minus_dis) / std::sqrt(var);
  return {tau, 2.0 * NormalSf(std::abs(z))};
}

TestResult PearsonR(const std::vector<double>& x, const std::vector<double>& y) {
  const size_t n = x.size();
  if (n < 2 || y.size() != n) return {kNaN, kNaN};
  auto constant = [](const std::vector<double>& v) {
    return std::all_of(v.begin(), v.end(), [&](double e) { return e == v[0]; });
  };
  if (constant(x) || constant(y)) return {kNaN, kNaN};
  auto sign = [](double d) { return double((d > 0) - (d < 0)); };
  if (n == 2) return {sign(x[1] - x[0]) * sign(y[1] - y[0]), 1.0};
  const double mx = Mean(x), my = Mean(y);
  double nx = 0, ny = 0;
  for (size_t i = 0; i < n; ++i) {
    nx += (x[i] - mx) * (x[i] - mx);
    ny += (y[i] - my) * (y[i] - my);
  }
  nx = std::sqrt(nx);
  ny = std::sqrt(ny);
  double r = 0;
  for (size_t i = 0; i < n; ++i) r += ((x[i] - mx) / nx) * ((y[i] - my) / ny);
  r = std::clamp(r, -1.0, 1.0);
  const double ab = double(n) / 2 - 1;
  // P(R >= |r|) for R = 2X - 1, X ~ Beta(ab, ab): I_{(1-|r|)/2}(ab, ab).
  return {r, 2.0 * RegularizedBeta(ab, ab, (1 - std::abs(r)) / 2)};
}

KendallWResult KendallW(const std::vector<std::vector<double>>& ranks) {
  KendallWResult out{kNaN, kNaN, 0, kNaN, int(ranks.size())};
  const size_t m = ranks.size();
  if (m < 1 || ranks[0].size() < 2) return out;
  const size_t n = ranks[0].size();
  out.df = int(n) - 1;
  std::vector<double> col(n, 0.0);
  double ties = 0;
  for (const auto& row : ranks) {
    if (row.size() != n) return out;
    std::vector<double> r = AverageRanks(row);
    for (size_t i = 0; i < n; ++i) col[i] += r[i];
    ties += TieTerm(row);
  }
  const double dm = double(m), dn = double(n);
  const double mean = dm * (dn + 1) / 2;
  double s = 0;
  for (double c : col) s += (c - mean) * (c - mean);
  const double denom = dm * dm * (dn * dn * dn - dn) - dm * ties;
  if (!(denom > 0)) return out;
  out.w = 12 * s / denom;
  out.chi2 = dm * (dn - 1) * out.w;
  out.p = ChiSquaredSf(dn - 1, out.chi2);
  return out;
}

}  // namespace sb::studies
