// L2-regularised logistic regression and ROC AUC: the statistics under the
// difficulty estimate (docs/setting.md). Small dense problems (hundreds of
// rows, tens of features); deterministic.
#ifndef SB_DIFFICULTY_LOGISTIC_H_
#define SB_DIFFICULTY_LOGISTIC_H_

#include <cstddef>
#include <cstdint>
#include <vector>

namespace sb::difficulty {

// A row-major n x d matrix of features with a 0/1 label per row.
struct Dataset {
  int cols = 0;
  std::vector<double> x;       // rows() * cols values
  std::vector<uint8_t> label;  // one per row
  size_t rows() const { return label.size(); }
  const double* row(size_t i) const { return x.data() + i * static_cast<size_t>(cols); }
};

// A fitted model on standardised features: score(x) = intercept +
// sum_c weight[c] * (x[c] - mean[c]) / scale[c]; P(label 1) = 1 / (1 + e^-score).
// A feature constant in the training data gets scale 1 and weight 0.
struct LogisticFit {
  std::vector<double> mean, scale, weight;
  double intercept = 0.0;
  int iterations = 0;  // Newton steps taken

  double Score(const double* x) const;
  double Probability(const double* x) const;
};

// Minimises  sum_i log(1 + e^{s_i}) - y_i s_i  +  (lambda / 2) |weight|^2
// over the standardised features (population standard deviation; the
// intercept is not penalised) by Newton's method with step halving, until the
// largest gradient component is below 1e-9 * (rows + 1). lambda > 0. An empty
// dataset gives the zero model. Pure; thread-safe.
LogisticFit FitLogistic(const Dataset& data, double lambda);

// The mean log-likelihood of `data` under `fit` (natural log, <= 0).
double MeanLogLikelihood(const LogisticFit& fit, const Dataset& data);

// Area under the ROC curve of `score` for `label` (the Mann-Whitney U over
// positives x negatives, ties counting one half). 0.5 when either class is
// empty. O(n log n). Pure.
double RocAuc(const std::vector<double>& score, const std::vector<uint8_t>& label);

}  // namespace sb::difficulty

#endif  // SB_DIFFICULTY_LOGISTIC_H_
