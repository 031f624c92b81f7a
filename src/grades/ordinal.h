// Ordinal regression: the cumulative-logit (proportional-odds) model with an
// L2 penalty on the weights, fitted by Newton's method (docs/grades.md,
// "The model").
//
//   P(y <= j | x) = sigma(theta_j - w . x),  j = 0..J-2,  theta increasing
//   minimise  -sum_i log P(y_i | x_i) + (l2 / 2) |w|^2      (theta unpenalised)
//
// The negative log-likelihood is convex in (theta, w) (Pratt 1981), so
// Newton's method with step halving finds the unique minimum for l2 > 0.
#ifndef SB_GRADES_ORDINAL_H_
#define SB_GRADES_ORDINAL_H_

#include <span>
#include <vector>

#include "base/status.h"

namespace sb::grades {

// A fitted model over J ordered classes 0..J-1 and p features. Value type.
struct OrdinalModel {
  std::vector<double> thresholds;  // J-1 values, strictly increasing
  std::vector<double> weights;     // p values

  int classes() const { return static_cast<int>(thresholds.size()) + 1; }
  // The linear predictor w . x (x has p values).
  double Eta(std::span<const double> x) const;
  // P(y = j | x) for j = 0..J-1 (sums to 1). Pure; thread-safe.
  std::vector<double> Probabilities(std::span<const double> x) const;
};

// The data: n rows of p features (row-major, x.size() == n * p) and the
// class of each row in 0..classes-1.
struct OrdinalData {
  std::vector<double> x;
  std::vector<int> y;
  int features = 0;
  int classes = 0;
  size_t rows() const { return y.size(); }
};

// Result of a fit: the model, the penalised objective at the optimum and
// how many Newton steps were taken.
struct OrdinalFit {
  OrdinalModel model;
  double objective = 0;
  int iterations = 0;
};

// The most Newton steps a fit takes (it converges in well under 50 on every
// problem seen; the cap only bounds time on pathological input).
inline constexpr int kMaxNewtonSteps = 200;

// Fits the model. Requirements: classes >= 2, every class observed at least
// once, x.size() == rows * features, l2 > 0 when features > 0. Errors:
// kInvalidInput naming the broken requirement; kInternal when Newton's
// method does not converge in kMaxNewtonSteps. Deterministic; thread-safe.
Result<OrdinalFit> FitOrdinal(const OrdinalData& data, double l2);

// The penalised objective of `model` on `data` (for tests and diagnostics).
double OrdinalObjective(const OrdinalModel& model, const OrdinalData& data, double l2);

// The smallest class c with P(y <= c) >= q (a quantile of the predictive
// distribution); q = 0.5 gives the median, which minimises the expected
// absolute error in classes. Pure.
int Quantile(std::span<const double> probabilities, double q);

}  // namespace sb::grades

#endif  // SB_GRADES_ORDINAL_H_
