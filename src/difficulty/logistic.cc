#include "difficulty/logistic.h"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace sb::difficulty {

namespace {

// log(1 + e^s) without overflow.
double Softplus(double s) { return s > 0 ? s + std::log1p(std::exp(-s)) : std::log1p(std::exp(s)); }

double Sigmoid(double s) {
  if (s >= 0) return 1.0 / (1.0 + std::exp(-s));
  double e = std::exp(s);
  return e / (1.0 + e);
}

// Solves A x = b for a symmetric positive definite A (p x p, row-major) by
// Cholesky. Returns false when A is not positive definite.
bool SolveSpd(std::vector<double> a, std::vector<double> b, int p, std::vector<double>* x) {
  for (int j = 0; j < p; ++j) {
    double d = a[j * p + j];
    for (int k = 0; k < j; ++k) d -= a[j * p + k] * a[j * p + k];
    if (!(d > 0)) return false;
    d = std::sqrt(d);
    a[j * p + j] = d;
    for (int i = j + 1; i < p; ++i) {
      double s = a[i * p + j];
      for (int k = 0; k < j; ++k) s -= a[i * p + k] * a[j * p + k];
      a[i * p + j] = s / d;
    }
  }
  for (int i = 0; i < p; ++i) {  // L y = b
    double s = b[i];
    for (int k = 0; k < i; ++k) s -= a[i * p + k] * b[k];
    b[i] = s / a[i * p + i];
  }
  for (int i = p - 1; i >= 0; --i) {  // L^T x = y
    double s = b[i];
    for (int k = i + 1; k < p; ++k) s -= a[k * p + i] * b[k];
    b[i] = s / a[i * p + i];
  }
  *x = std::move(b);
  return true;
}

}  // namespace

double LogisticFit::Score(const double* x) const {
  double s = intercept;
  for (size_t c = 0; c < weight.size(); ++c) s += weight[c] * ((x[c] - mean[c]) / scale[c]);
  return s;
}

double LogisticFit::Probability(const double* x) const { return Sigmoid(Score(x)); }

LogisticFit FitLogistic(const Dataset& data, double lambda) {
  const int d = data.cols;
  const size_t n = data.rows();
  LogisticFit fit;
  fit.mean.assign(d, 0.0);
  fit.scale.assign(d, 1.0);
  fit.weight.assign(d, 0.0);
  if (n == 0) return fit;

  // Standardisation: z = (x - mean) / sd; constant columns stay out (weight 0).
  std::vector<int> cols;  // active columns
  for (int c = 0; c < d; ++c) {
    double m = 0;
    for (size_t i = 0; i < n; ++i) m += data.row(i)[c];
    m /= static_cast<double>(n);
    double v = 0;
    for (size_t i = 0; i < n; ++i) v += (data.row(i)[c] - m) * (data.row(i)[c] - m);
    v /= static_cast<double>(n);
    fit.mean[c] = m;
    if (v > 0) {
      fit.scale[c] = std::sqrt(v);
      cols.push_back(c);
    }
  }
  // Newton's method runs in the raw coordinates, where the features are
  // sparse (most are 0/1 indicators): s = b + sum_k v_k x_k with the penalty
  // (lambda / 2) sum_k (v_k sd_k)^2, the same problem as on the standardised
  // features (w_k = v_k sd_k, intercept = b + sum_k v_k mean_k), so the
  // Hessian costs O(nnz^2) per row instead of O(p^2).
  const int p = static_cast<int>(cols.size()) + 1;         // parameter 0 = intercept
  std::vector<std::vector<std::pair<int, double>>> nz(n);  // (parameter, value) per row
  for (size_t i = 0; i < n; ++i) {
    nz[i].push_back({0, 1.0});
    for (int k = 1; k < p; ++k) {
      double x = data.row(i)[cols[k - 1]];
      if (x != 0.0) nz[i].push_back({k, x});
    }
  }
  std::vector<double> pen(p, 0.0);  // lambda sd_k^2
  for (int k = 1; k < p; ++k) pen[k] = lambda * fit.scale[cols[k - 1]] * fit.scale[cols[k - 1]];

  std::vector<double> beta(p, 0.0);
  auto score = [&](size_t i, const std::vector<double>& b) {
    double si = 0;
    for (const auto& [k, x] : nz[i]) si += b[k] * x;
    return si;
  };
  auto objective = [&](const std::vector<double>& b) {
    double f = 0;
    for (size_t i = 0; i < n; ++i) {
      double si = score(i, b);
      f += Softplus(si) - (data.label[i] ? si : 0.0);
    }
    for (int k = 1; k < p; ++k) f += 0.5 * pen[k] * b[k] * b[k];
    return f;
  };
  double f = objective(beta);
  const double tolerance = 1e-9 * (static_cast<double>(n) + 1.0);
  std::vector<double> grad(p), hess(static_cast<size_t>(p) * p), step, next(p);
  constexpr int kMaxIterations = 100;
  for (int it = 0; it < kMaxIterations; ++it) {
    std::fill(grad.begin(), grad.end(), 0.0);
    std::fill(hess.begin(), hess.end(), 0.0);
    for (size_t i = 0; i < n; ++i) {
      double mu = Sigmoid(score(i, beta));
      double r = mu - (data.label[i] ? 1.0 : 0.0);
      double w = mu * (1.0 - mu);
      const auto& row = nz[i];
      for (size_t a = 0; a < row.size(); ++a) {
        grad[row[a].first] += r * row[a].second;
        double wa = w * row[a].second;
        for (size_t b = 0; b <= a; ++b) hess[row[a].first * p + row[b].first] += wa * row[b].second;
      }
    }
    for (int k = 1; k < p; ++k) {
      grad[k] += pen[k] * beta[k];
      hess[k * p + k] += pen[k];
    }
    for (int k = 0; k < p; ++k) {
      for (int l = 0; l < k; ++l) hess[l * p + k] = hess[k * p + l];
    }
    // Stop on the gradient of the standardised problem:
    // d/dw_k = (g_k - g_0 mean_k) / sd_k, d/dintercept = g_0.
    double gmax = std::abs(grad[0]);
    for (int k = 1; k < p; ++k) {
      int c = cols[k - 1];
      gmax = std::max(gmax, std::abs((grad[k] - grad[0] * fit.mean[c]) / fit.scale[c]));
    }
    if (gmax < tolerance) break;
    // A tiny ridge on the intercept keeps the system solvable when every
    // probability saturates (separable data with a weak penalty).
    if (!SolveSpd(hess, grad, p, &step)) {
      hess[0] += 1e-12 * (static_cast<double>(n) + 1.0);
      if (!SolveSpd(hess, grad, p, &step)) break;
    }
    double t = 1.0, fn = f;
    for (int halvings = 0; halvings < 50; ++halvings, t *= 0.5) {
      for (int k = 0; k < p; ++k) next[k] = beta[k] - t * step[k];
      fn = objective(next);
      if (fn <= f) break;
    }
    fit.iterations = it + 1;
    if (!(fn <= f)) break;  // no descent: at the optimum within rounding
    beta = next;
    f = fn;
  }
  fit.intercept = beta[0];
  for (int k = 1; k < p; ++k) {
    int c = cols[k - 1];
    fit.weight[c] = beta[k] * fit.scale[c];
    fit.intercept += beta[k] * fit.mean[c];
  }
  return fit;
}

double MeanLogLikelihood(const LogisticFit& fit, const Dataset& data) {
  if (data.rows() == 0) return 0.0;
  double ll = 0;
  for (size_t i = 0; i < data.rows(); ++i) {
    double s = fit.Score(data.row(i));
    ll += (data.label[i] ? s : 0.0) - Softplus(s);
  }
  return ll / static_cast<double>(data.rows());
}

double RocAuc(const std::vector<double>& score, const std::vector<uint8_t>& label) {
  const size_t n = std::min(score.size(), label.size());
  std::vector<size_t> order(n);
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](size_t a, size_t b) { return score[a] < score[b]; });
  // Mid-ranks over tie groups; U = sum of positive ranks - P(P+1)/2.
  double rank_sum = 0, positives = 0;
  for (size_t i = 0; i < n;) {
    size_t j = i;
    while (j < n && score[order[j]] == score[order[i]]) ++j;
    double mid = (static_cast<double>(i + 1) + static_cast<double>(j)) / 2.0;
    for (size_t k = i; k < j; ++k) {
      if (label[order[k]]) {
        rank_sum += mid;
        positives += 1;
      }
    }
    i = j;
  }
  double negatives = static_cast<double>(n) - positives;
  if (positives == 0 || negatives == 0) return 0.5;
  return (rank_sum - positives * (positives + 1) / 2.0) / (positives * negatives);
}

}  // namespace sb::difficulty
