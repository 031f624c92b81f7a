#include "grades/ordinal.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

namespace sb::grades {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
// Newton stops when half the squared Newton decrement (the predicted
// decrease of the objective) is below this: far below any difference the
// estimates could show.
constexpr double kDecrementTolerance = 1e-14;
// When no step decreases the objective any more (rounding), the fit is
// accepted if the predicted decrease is below this (relative) amount.
constexpr double kStallTolerance = 1e-9;
// Armijo constant of the backtracking line search (Boyd & Vandenberghe 9.2).
constexpr double kArmijo = 1e-4;
constexpr int kMaxHalvings = 60;

double Sigmoid(double t) {
  if (t >= 0) return 1.0 / (1.0 + std::exp(-t));
  const double e = std::exp(t);
  return e / (1.0 + e);
}

// f(t) = sigma(t) sigma(-t), the logistic density.
double Density(double t) {
  if (std::isinf(t)) return 0;
  return Sigmoid(t) * Sigmoid(-t);
}

// P(b < Z <= a) for a logistic Z, accurate in both tails.
double IntervalProbability(double a, double b) {
  if (b > 0) return Sigmoid(-b) - Sigmoid(-a);
  return Sigmoid(a) - Sigmoid(b);
}

// Upper (a) and lower (b) cut of class y given eta.
void Cuts(const std::vector<double>& theta, int y, double eta, double* a, double* b) {
  const int last = static_cast<int>(theta.size());
  *a = y < last ? theta[static_cast<size_t>(y)] - eta : kInf;
  *b = y > 0 ? theta[static_cast<size_t>(y) - 1] - eta : -kInf;
}

bool Increasing(const std::vector<double>& t) {
  for (size_t i = 1; i < t.size(); ++i) {
    if (!(t[i] > t[i - 1])) return false;
  }
  return true;
}

// In-place Cholesky factorisation of a symmetric m x m matrix (row-major);
// false when it is not positive definite.
bool Cholesky(std::vector<double>* a, size_t m) {
  std::vector<double>& A = *a;
  for (size_t j = 0; j < m; ++j) {
    double d = A[j * m + j];
    for (size_t k = 0; k < j; ++k) d -= A[j * m + k] * A[j * m + k];
    if (!(d > 0)) return false;
    const double l = std::sqrt(d);
    A[j * m + j] = l;
    for (size_t i = j + 1; i < m; ++i) {
      double s = A[i * m + j];
      for (size_t k = 0; k < j; ++k) s -= A[i * m + k] * A[j * m + k];
      A[i * m + j] = s / l;
    }
  }
  return true;
}

// Solves L L^T x = b with the factor from Cholesky.
std::vector<double> CholeskySolve(const std::vector<double>& L, size_t m, std::vector<double> b) {
  for (size_t i = 0; i < m; ++i) {
    double s = b[i];
    for (size_t k = 0; k < i; ++k) s -= L[i * m + k] * b[k];
    b[i] = s / L[i * m + i];
  }
  for (size_t i = m; i-- > 0;) {
    double s = b[i];
    for (size_t k = i + 1; k < m; ++k) s -= L[k * m + i] * b[k];
    b[i] = s / L[i * m + i];
  }
  return b;
}

OrdinalModel Unpack(const std::vector<double>& beta, int classes) {
  OrdinalModel m;
  const auto split = beta.begin() + (classes - 1);
  m.thresholds.assign(beta.begin(), split);
  m.weights.assign(split, beta.end());
  return m;
}

// Gradient and Hessian of the penalised objective at `model`.
void Derivatives(const OrdinalModel& model, const OrdinalData& d, double l2,
                 std::vector<double>* grad, std::vector<double>* hess) {
  const size_t t = model.thresholds.size(), p = model.weights.size(), m = t + p;
  grad->assign(m, 0.0);
  hess->assign(m * m, 0.0);
  std::vector<double>& g = *grad;
  std::vector<double>& H = *hess;
  for (size_t i = 0; i < d.rows(); ++i) {
    std::span<const double> x(d.x.data() + i * p, p);
    double a, b;
    Cuts(model.thresholds, d.y[i], model.Eta(x), &a, &b);
    const double pr = std::max(IntervalProbability(a, b), std::numeric_limits<double>::min());
    const double fa = Density(a), fb = Density(b);
    const double ga = fa / pr, gb = -fb / pr;
    const double dfa = std::isinf(a) ? 0 : fa * (Sigmoid(-a) - Sigmoid(a));
    const double dfb = std::isinf(b) ? 0 : fb * (Sigmoid(-b) - Sigmoid(b));
    const double haa = dfa / pr - ga * ga, hbb = -dfb / pr - gb * gb, hab = -ga * gb;
    // Direction vectors of a and b in parameter space: unit on a threshold,
    // -x on the weights. Accumulate -(log p) derivatives.
    const long ia = std::isinf(a) ? -1 : d.y[i];
    const long ib = std::isinf(b) ? -1 : d.y[i] - 1;
    auto dir = [&](long th, size_t k) -> double {  // component k of da or db
      if (k < t) return static_cast<long>(k) == th ? 1.0 : 0.0;
      return -x[k - t];
    };
    for (size_t k = 0; k < m; ++k) {
      const double da_k = ia >= 0 ? dir(ia, k) : 0.0;
      const double db_k = ib >= 0 ? dir(ib, k) : 0.0;
      if (da_k == 0 && db_k == 0) continue;
      g[k] -= ga * da_k + gb * db_k;
      for (size_t l = 0; l < m; ++l) {
        const double da_l = ia >= 0 ? dir(ia, l) : 0.0;
        const double db_l = ib >= 0 ? dir(ib, l) : 0.0;
        H[k * m + l] -= haa * da_k * da_l + hbb * db_k * db_l + hab * (da_k * db_l + db_k * da_l);
      }
    }
  }
  for (size_t k = 0; k < p; ++k) {
    g[t + k] += l2 * model.weights[k];
    H[(t + k) * m + t + k] += l2;
  }
}

Status Validate(const OrdinalData& d, double l2) {
  if (d.classes < 2) return Status::InvalidInput("ordinal model: needs at least 2 classes");
  if (d.features < 0 || d.x.size() != d.rows() * static_cast<size_t>(d.features)) {
    return Status::InvalidInput("ordinal model: x has " + std::to_string(d.x.size()) +
                                " values, expected rows x features");
  }
  if (d.features > 0 && !(l2 > 0)) {
    return Status::InvalidInput("ordinal model: the L2 penalty must be > 0");
  }
  std::vector<size_t> count(static_cast<size_t>(d.classes), 0);
  for (int y : d.y) {
    if (y < 0 || y >= d.classes) {
      return Status::InvalidInput("ordinal model: class " + std::to_string(y) + " outside 0.." +
                                  std::to_string(d.classes - 1));
    }
    ++count[static_cast<size_t>(y)];
  }
  for (size_t c = 0; c < count.size(); ++c) {
    if (count[c] == 0) {
      return Status::InvalidInput("ordinal model: class " + std::to_string(c) +
                                  " has no observation");
    }
  }
  for (double v : d.x) {
    if (!std::isfinite(v)) return Status::InvalidInput("ordinal model: a feature is not finite");
  }
  return Status::Ok();
}

}  // namespace

double OrdinalModel::Eta(std::span<const double> x) const {
  double s = 0;
  for (size_t k = 0; k < weights.size(); ++k) s += weights[k] * x[k];
  return s;
}

std::vector<double> OrdinalModel::Probabilities(std::span<const double> x) const {
  const double eta = Eta(x);
  std::vector<double> p(thresholds.size() + 1);
  for (size_t j = 0; j < p.size(); ++j) {
    double a, b;
    Cuts(thresholds, static_cast<int>(j), eta, &a, &b);
    p[j] = IntervalProbability(a, b);
  }
  return p;
}

double OrdinalObjective(const OrdinalModel& model, const OrdinalData& d, double l2) {
  const size_t p = model.weights.size();
  double nll = 0;
  for (size_t i = 0; i < d.rows(); ++i) {
    double a, b;
    Cuts(model.thresholds, d.y[i], model.Eta({d.x.data() + i * p, p}), &a, &b);
    nll -= std::log(std::max(IntervalProbability(a, b), std::numeric_limits<double>::min()));
  }
  if (model.weights.empty()) return nll;
  double w2 = 0;
  for (double w : model.weights) w2 += w * w;
  return nll + 0.5 * l2 * w2;
}

Result<OrdinalFit> FitOrdinal(const OrdinalData& d, double l2) {
  SB_RETURN_IF_ERROR(Validate(d, l2));
  const size_t t = static_cast<size_t>(d.classes) - 1, p = static_cast<size_t>(d.features);
  const size_t m = t + p;
  // Start at the optimum with w = 0: thresholds at the logits of the
  // cumulative class frequencies.
  std::vector<double> beta(m, 0.0);
  std::vector<size_t> count(static_cast<size_t>(d.classes), 0);
  for (int y : d.y) ++count[static_cast<size_t>(y)];
  double cum = 0;
  for (size_t j = 0; j < t; ++j) {
    cum += static_cast<double>(count[j]) / static_cast<double>(d.rows());
    beta[j] = std::log(cum / (1 - cum));
  }
  OrdinalModel model = Unpack(beta, d.classes);
  double obj = OrdinalObjective(model, d, l2);
  std::vector<double> g, H;
  for (int it = 0; it < kMaxNewtonSteps; ++it) {
    Derivatives(model, d, l2, &g, &H);
    std::vector<double> L = H;
    double jitter = 0;
    double maxdiag = 0;
    for (size_t k = 0; k < m; ++k) maxdiag = std::max(maxdiag, std::fabs(H[k * m + k]));
    while (!Cholesky(&L, m)) {
      // Numerically semi-definite: a tiny ridge keeps the step a descent direction.
      jitter = jitter == 0 ? 1e-12 * std::max(maxdiag, 1.0) : jitter * 10;
      if (jitter > maxdiag + 1) return Status::Internal("ordinal model: Hessian not positive");
      L = H;
      for (size_t k = 0; k < m; ++k) L[k * m + k] += jitter;
    }
    std::vector<double> neg_g(m);
    for (size_t k = 0; k < m; ++k) neg_g[k] = -g[k];
    const std::vector<double> step = CholeskySolve(L, m, neg_g);
    double decrement = 0;  // -g . step >= 0
    for (size_t k = 0; k < m; ++k) decrement += neg_g[k] * step[k];
    if (decrement / 2 <= kDecrementTolerance * std::max(1.0, std::fabs(obj))) {
      return OrdinalFit{std::move(model), obj, it};
    }
    double s = 1;
    bool moved = false;
    for (int h = 0; h < kMaxHalvings; ++h, s /= 2) {
      std::vector<double> trial(m);
      for (size_t k = 0; k < m; ++k) trial[k] = beta[k] + s * step[k];
      OrdinalModel tm = Unpack(trial, d.classes);
      if (!Increasing(tm.thresholds)) continue;
      const double tobj = OrdinalObjective(tm, d, l2);
      if (tobj <= obj - kArmijo * s * decrement) {
        beta = std::move(trial);
        model = std::move(tm);
        obj = tobj;
        moved = true;
        break;
      }
    }
    if (!moved) {
      // No representable decrease left: at the optimum up to rounding, unless
      // the step still promised a real decrease.
      if (decrement / 2 <= kStallTolerance * std::max(1.0, std::fabs(obj))) {
        return OrdinalFit{std::move(model), obj, it};
      }
      return Status::Internal("ordinal model: the line search found no decrease");
    }
  }
  return Status::Internal("ordinal model: Newton's method did not converge in " +
                          std::to_string(kMaxNewtonSteps) + " steps");
}

int Quantile(std::span<const double> probabilities, double q) {
  double cum = 0;
  for (size_t c = 0; c < probabilities.size(); ++c) {
    cum += probabilities[c];
    if (cum >= q - 1e-12) return static_cast<int>(c);
  }
  return static_cast<int>(probabilities.size()) - 1;
}

}  // namespace sb::grades
