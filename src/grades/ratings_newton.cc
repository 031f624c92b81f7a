#include "grades/ratings_newton.h"

#include <cstdio>

namespace sb::grades::newton {

std::string Num(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%g", v);
  return b;
}

double PriorMean(const RatingProblem& p) {
  double sum = 0;
  int n = 0;
  for (const auto& s : p.setter) {
    if (s) {
      sum += *s;
      ++n;
    }
  }
  if (n > 0) return sum / n;
  double felt = 0;
  int fn = 0;
  for (int r = 0; r < p.num_routes(); ++r) {
    felt += p.felt_sum[size_t(r)];
    fn += p.felt_count[size_t(r)];
  }
  return fn > 0 ? felt / fn : 0;
}

Result<bool> UseExactIntervals(IntervalMethod method, size_t r_n) {
  const bool exact = method == IntervalMethod::kExact ||
                     (method == IntervalMethod::kAuto && r_n <= kMaxExactRoutes);
  if (exact && r_n > kMaxExactRoutes) {
    return Status::InvalidInput("intervals: exact intervals are limited to " +
                                std::to_string(kMaxExactRoutes) + " routes, got " +
                                std::to_string(r_n) + " (use approximate)");
  }
  return exact;
}

RoutePriors::RoutePriors(const RatingProblem& p, const RatingParams& k, double m)
    : p_(p), k_(k) {
  const size_t r_n = size_t(p.num_routes());
  mean_.resize(r_n);
  prec_.resize(r_n);
  for (size_t r = 0; r < r_n; ++r) {
    const auto& s = p.setter[r];
    const double sd = s ? k.setter_sd : k.open_route_sd;
    mean_[r] = s ? *s : m;
    prec_[r] = 1 / (sd * sd) + p.felt_count[r] / (k.felt_sd * k.felt_sd);
  }
}

void RoutePriors::AddObjective(const std::vector<double>& x, size_t off, double* f) const {
  const double pf = 1 / (k_.felt_sd * k_.felt_sd);
  for (size_t r = 0; r < mean_.size(); ++r) {
    const double d = x[off + r];
    const auto& s = p_.setter[r];
    const double sd = s ? k_.setter_sd : k_.open_route_sd;
    *f += 0.5 * (d - mean_[r]) * (d - mean_[r]) / (sd * sd);
    *f += 0.5 * pf * (p_.felt_count[r] * d * d - 2 * d * p_.felt_sum[r]);
  }
}

void RoutePriors::SetGradient(const std::vector<double>& x, size_t off, std::vector<double>* g,
                              std::vector<double>* h) const {
  const double pf = 1 / (k_.felt_sd * k_.felt_sd);
  for (size_t r = 0; r < mean_.size(); ++r) {
    const double d = x[off + r];
    const auto& s = p_.setter[r];
    const double sd = s ? k_.setter_sd : k_.open_route_sd;
    (*g)[off + r] = (d - mean_[r]) / (sd * sd) + pf * (p_.felt_count[r] * d - p_.felt_sum[r]);
    (*h)[off + r] = prec_[r];
  }
}

void PairsByClimber(size_t n, const std::vector<RatingPair>& pairs, std::vector<size_t>* start,
                    std::vector<size_t>* idx) {
  start->assign(n + 1, 0);
  for (const RatingPair& q : pairs) ++(*start)[size_t(q.climber) + 1];
  for (size_t c = 0; c < n; ++c) (*start)[c + 1] += (*start)[c];
  idx->resize(pairs.size());
  std::vector<size_t> fill(start->begin(), start->end() - 1);
  for (size_t i = 0; i < pairs.size(); ++i) (*idx)[fill[size_t(pairs[i].climber)]++] = i;
}

void OffsetDerivatives(const std::vector<RatingPair>& pairs, double kk, double b,
                       const std::vector<double>& x, size_t off, double* g, double* h) {
  *g = 0;
  *h = 0;
  for (const RatingPair& q : pairs) {
    if (!(q.session_wins | q.session_losses)) continue;
    const double ps = Sigmoid(kk * (x[size_t(q.climber)] - x[off + size_t(q.route)]) + b);
    const double ns = double(q.session_wins) + double(q.session_losses);
    *g += ns * ps - q.session_wins;
    *h += ns * ps * (1 - ps);
  }
}

Status SchurVariances(std::vector<double>* s, size_t r_n, std::vector<double>* w,
                      std::vector<double>* sd, double* log_det) {
  // Cholesky, lower triangle in place (row-major).
  for (size_t j = 0; j < r_n; ++j) {
    double* rj = &(*s)[j * r_n];
    double dsum = rj[j];
    for (size_t k = 0; k < j; ++k) dsum -= rj[k] * rj[k];
    if (!(dsum > 0)) return Status::Internal("ratings: the Hessian is not positive definite");
    const double ljj = std::sqrt(dsum);
    if (log_det != nullptr) *log_det += 2 * std::log(ljj);
    rj[j] = ljj;
    for (size_t i = j + 1; i < r_n; ++i) {
      double* ri = &(*s)[i * r_n];
      double t = ri[j];
      for (size_t k = 0; k < j; ++k) t -= ri[k] * rj[k];
      ri[j] = t / ljj;
    }
  }
  // W = L^-1, lower triangular, row-major: row i of W from rows < i.
  w->assign(r_n * r_n, 0);
  for (size_t i = 0; i < r_n; ++i) {
    const double* li = &(*s)[i * r_n];
    double* wi = &(*w)[i * r_n];
    for (size_t k = 0; k < i; ++k) {
      const double lik = li[k];
      if (lik == 0) continue;
      const double* wk = &(*w)[k * r_n];
      for (size_t j = 0; j <= k; ++j) wi[j] -= lik * wk[j];
    }
    for (size_t j = 0; j < i; ++j) wi[j] /= li[i];
    wi[i] = 1 / li[i];
  }
  // (S^-1)_rr = sum over rows of W's column r squared.
  std::vector<double> var(r_n, 0);
  for (size_t i = 0; i < r_n; ++i) {
    const double* wi = &(*w)[i * r_n];
    for (size_t j = 0; j <= i; ++j) var[j] += wi[j] * wi[j];
  }
  sd->resize(r_n);
  for (size_t r = 0; r < r_n; ++r) (*sd)[r] = std::sqrt(var[r]);
  return Status::Ok();
}

}  // namespace sb::grades::newton
