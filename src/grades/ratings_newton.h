// The numerics the rating fits share (ratings.cc, ratings_drift.cc,
// ratings_session.cc): the logistic's pieces, one pair's games, the damped
// inexact Newton driver with its preconditioned CG step, the session
// offset's alternation, and the dense Schur-complement variances of the
// exact intervals. Internal to src/grades (not part of the module's API).
//
// Every routine keeps its callers' floating-point operations in their
// order, so a fit is bit-identical to the one each file made on its own.
#ifndef SB_GRADES_RATINGS_NEWTON_H_
#define SB_GRADES_RATINGS_NEWTON_H_

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <string>
#include <vector>

#include "base/status.h"
#include "grades/ratings.h"

namespace sb::grades::newton {

// log(1 + exp(x)) without overflow or loss of precision.
inline double Softplus(double x) {
  return x > 0 ? x + std::log1p(std::exp(-x)) : std::log1p(std::exp(x));
}

// 1 / (1 + exp(-x)).
inline double Sigmoid(double x) {
  if (x >= 0) return 1 / (1 + std::exp(-x));
  const double e = std::exp(x);
  return e / (1 + e);
}

// v as "%g" (error messages).
std::string Num(double v);

// The prior mean m of climbers and of routes without a setter's grade: the
// mean of the setters' grades, else of the felt grades, else 0.
double PriorMean(const RatingProblem& p);

// Whether a fit of r_n routes takes exact intervals under `method`. Errors:
// kInvalidInput for kExact above kMaxExactRoutes.
Result<bool> UseExactIntervals(IntervalMethod method, size_t r_n);

// One pair's games at a - d = diff (b: the session offset): the derivative
// of their negative log-likelihood per unit of a (dz) and their Fisher
// information (h).
inline void PairTerms(const RatingPair& q, double kk, double b, double diff, double* dz,
                      double* h) {
  const double pr = Sigmoid(kk * diff);
  const double n = double(q.wins) + double(q.losses);
  *dz = kk * (n * pr - q.wins);
  *h = kk * kk * n * pr * (1 - pr);
  if (q.session_wins | q.session_losses) {
    const double ps = Sigmoid(kk * diff + b);
    const double ns = double(q.session_wins) + double(q.session_losses);
    *dz += kk * (ns * ps - q.session_wins);
    *h += kk * kk * ns * ps * (1 - ps);
  }
}

// The pairs' games at x (climber or node c at x[c], route r at x[off + r]):
// adds their gradient to g and their Fisher information to diag (at both
// ends), and keeps pair i's in h[i].
inline void AddPairGradient(const std::vector<RatingPair>& pairs, double kk, double b,
                            const std::vector<double>& x, size_t off, std::vector<double>* g,
                            std::vector<double>* h, std::vector<double>* diag) {
  for (size_t i = 0; i < pairs.size(); ++i) {
    const RatingPair& q = pairs[i];
    const size_t a = size_t(q.climber), d = off + size_t(q.route);
    double dz = 0, w = 0;
    PairTerms(q, kk, b, x[a] - x[d], &dz, &w);
    (*g)[a] += dz;
    (*g)[d] -= dz;
    (*h)[i] = w;
    (*diag)[a] += w;
    (*diag)[d] += w;
  }
}

// y -= the pairs' off-diagonal part of the Hessian (-h[i] between pair i's
// climber and route) times v.
inline void SubtractPairProducts(const std::vector<RatingPair>& pairs, const std::vector<double>& h,
                                 const std::vector<double>& v, size_t off,
                                 std::vector<double>* y) {
  for (size_t i = 0; i < pairs.size(); ++i) {
    const RatingPair& q = pairs[i];
    const size_t a = size_t(q.climber), d = off + size_t(q.route);
    (*y)[a] -= h[i] * v[d];
    (*y)[d] -= h[i] * v[a];
  }
}

// The pairs by climber (or node), CSR: climber c's pair indices are
// idx[start[c]] .. idx[start[c + 1] - 1], in pair order; n climbers.
void PairsByClimber(size_t n, const std::vector<RatingPair>& pairs, std::vector<size_t>* start,
                    std::vector<size_t>* idx);

// The routes' Gaussian terms: the setter's grade (or m) at setter_sd (or
// open_route_sd) and the felt grades at felt_sd; x holds route r at off + r.
class RoutePriors {
 public:
  RoutePriors(const RatingProblem& p, const RatingParams& k, double m);
  // Adds the routes' terms to *f.
  void AddObjective(const std::vector<double>& x, size_t off, double* f) const;
  // Sets g[off + r] to route r's gradient and h[off + r] to its precision.
  void SetGradient(const std::vector<double>& x, size_t off, std::vector<double>* g,
                   std::vector<double>* h) const;

 private:
  const RatingProblem& p_;
  const RatingParams& k_;
  std::vector<double> mean_, prec_;
};

// The session offset's gradient and second derivative of the games (its
// prior not included) at x: climber (or node) c at x[c], route r at
// x[off + r].
void OffsetDerivatives(const std::vector<RatingPair>& pairs, double kk, double b,
                       const std::vector<double>& x, size_t off, double* g, double* h);

// Solves H s = -g to relative residual eta by preconditioned conjugate
// gradients from s = 0; multiply(v, &y) sets y = H v, precondition(r, &z)
// sets z = M^-1 r. At most min(n, 5000) iterations (CG converges in n in
// exact arithmetic; every iterate is a descent direction, so stopping early
// is safe). Returns the iterations.
template <typename Multiply, typename Precondition>
int SolveCg(const std::vector<double>& g, double eta, std::vector<double>* s,
            const Multiply& multiply, const Precondition& precondition) {
  const size_t n = g.size();
  s->assign(n, 0);
  std::vector<double> r(n), z(n), dir(n), hd(n);
  double g2 = 0;
  for (size_t i = 0; i < n; ++i) {
    r[i] = -g[i];
    g2 += g[i] * g[i];
  }
  precondition(r, &z);
  double rz = 0;
  for (size_t i = 0; i < n; ++i) {
    dir[i] = z[i];
    rz += r[i] * z[i];
  }
  const double target = eta * eta * g2;
  const int max_iter = int(std::min<size_t>(n, 5000));
  int it = 0;
  double r2 = g2;
  while (it < max_iter && r2 > target) {
    multiply(dir, &hd);
    double dhd = 0;
    for (size_t i = 0; i < n; ++i) dhd += dir[i] * hd[i];
    if (!(dhd > 0)) break;
    const double alpha = rz / dhd;
    r2 = 0;
    for (size_t i = 0; i < n; ++i) {
      (*s)[i] += alpha * dir[i];
      r[i] -= alpha * hd[i];
      r2 += r[i] * r[i];
    }
    precondition(r, &z);
    double rz_new = 0;
    for (size_t i = 0; i < n; ++i) rz_new += r[i] * z[i];
    const double beta = rz_new / rz;
    rz = rz_new;
    for (size_t i = 0; i < n; ++i) dir[i] = z[i] + beta * dir[i];
    ++it;
  }
  return it;
}

// SolveCg preconditioned by the diagonal (Jacobi).
template <typename Multiply>
int SolveJacobiCg(const std::vector<double>& g, double eta, const std::vector<double>& diag,
                  std::vector<double>* s, const Multiply& multiply) {
  return SolveCg(g, eta, s, multiply, [&](const std::vector<double>& r, std::vector<double>* z) {
    for (size_t i = 0; i < r.size(); ++i) (*z)[i] = r[i] / diag[i];
  });
}

// What a Newton run did; counts add up over calls.
struct NewtonStats {
  int newton_iterations = 0;
  int cg_iterations = 0;
  double gradient_max = 0;  // largest |gradient| component at the last check
};

// Largest relative residual of a Newton step's CG solve. A CG iteration
// costs one pass over the pairs without exp(), a Newton iteration several
// with it, so solving each step well (1e-2) pays: looser steps (0.5) took
// three to four times the Newton iterations on the synthetic gyms.
inline constexpr double kMaxForcing = 1e-2;

// Minimises the solver's objective from *x by Newton's method: each step
// solved by s.SolveNewtonStep(g, eta, &step) with the forcing term eta =
// min(kMaxForcing, sqrt(max |g|)) (loose far from the optimum, exact near it:
// Eisenstat & Walker), then a backtracking (Armijo) line search; once the
// predicted decrease is below the objective's rounding the full step is
// taken (quadratic convergence region). Stops when max |g| <= tolerance
// (returns true) or after max_iterations steps (false). The solver has
// double Objective(x), void GradientAndHessian(x, &g) (which also sets what
// SolveNewtonStep uses) and int SolveNewtonStep(g, eta, &step).
template <typename Solver>
bool MinimizeNewton(Solver& s, std::vector<double>* x, double tolerance, int max_iterations,
                    NewtonStats* st) {
  std::vector<double> g, step, trial(x->size());
  double f = s.Objective(*x);
  for (int it = 0; it <= max_iterations; ++it) {
    s.GradientAndHessian(*x, &g);
    double gmax = 0;
    for (double v : g) gmax = std::max(gmax, std::abs(v));
    st->gradient_max = gmax;
    if (gmax <= tolerance) return true;
    if (it == max_iterations) break;
    ++st->newton_iterations;
    const double eta = std::min(kMaxForcing, std::sqrt(gmax));
    st->cg_iterations += s.SolveNewtonStep(g, eta, &step);
    double slope = 0;
    for (size_t i = 0; i < x->size(); ++i) slope += g[i] * step[i];
    const bool judge = -slope > 1e-10 * (1 + std::abs(f));
    double t = 1, f_new = f;
    for (int half = 0; half < 60; ++half, t *= 0.5) {
      for (size_t i = 0; i < x->size(); ++i) trial[i] = (*x)[i] + t * step[i];
      f_new = s.Objective(trial);
      if (!judge || f_new <= f + 1e-4 * t * slope) break;
    }
    x->swap(trial);
    f = f_new;
  }
  return false;
}

// Alternations of the session offset with the other values before giving up.
inline constexpr int kMaxOffsetRounds = 200;
// Largest step of the session offset in one alternation (logit).
inline constexpr double kMaxOffsetStep = 2.0;

// MinimizeNewton with the session model's offset b estimated too
// (estimate_offset): blocks alternate (Newton on the other values with b
// held, then one Newton step on b, prior N(kSessionOffsetPriorMean,
// kSessionOffsetPriorSd^2), with them held) until b's gradient is below the
// tolerance as well; the objective is jointly convex, so this reaches the
// joint optimum. The solver also has OffsetDerivatives(x, &g, &h), offset()
// and set_offset(b). Returns whether it converged.
template <typename Solver>
bool MinimizeNewtonWithOffset(Solver& s, std::vector<double>* x, double tolerance,
                              int max_iterations, bool estimate_offset, NewtonStats* st) {
  bool converged = false;
  for (int round = 0; round < kMaxOffsetRounds; ++round) {
    converged = MinimizeNewton(s, x, tolerance, max_iterations, st);
    if (!converged || !estimate_offset) break;
    double gb = 0, hb = 0;
    s.OffsetDerivatives(*x, &gb, &hb);
    const double pb = 1 / (kSessionOffsetPriorSd * kSessionOffsetPriorSd);
    gb += pb * (s.offset() - kSessionOffsetPriorMean);
    hb += pb;
    if (std::abs(gb) <= tolerance) break;
    converged = false;
    s.set_offset(s.offset() - std::clamp(gb / hb, -kMaxOffsetStep, kMaxOffsetStep));
  }
  return converged;
}

// The exact intervals' dense step: *s is the routes' Schur complement S
// (r_n x r_n, row-major), factorised in place (Cholesky, lower triangle);
// *w = L^-1 (lower triangular, row-major); sd[r] = sqrt((S^-1)_rr). With
// log_det, adds log det S to *log_det. Errors: kInternal when S is not
// positive definite.
Status SchurVariances(std::vector<double>* s, size_t r_n, std::vector<double>* w,
                      std::vector<double>* sd, double* log_det = nullptr);

}  // namespace sb::grades::newton

#endif  // SB_GRADES_RATINGS_NEWTON_H_
