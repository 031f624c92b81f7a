// The cumulative-logit model: it recovers known parameters from synthetic
// data, its optimum is the one SciPy finds for the same penalised
// likelihood, its derivatives are right, and bad input is refused.
#include "grades/ordinal.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <random>
#include <sstream>
#include <string>

#include "base/files.h"
#include "base/text.h"

namespace sb::grades {
namespace {

// Draws n rows from the model with the given thresholds and weights
// (features standard normal), with a fixed seed.
OrdinalData Synthetic(const std::vector<double>& theta, const std::vector<double>& w, size_t n,
                      uint32_t seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> normal;
  std::uniform_real_distribution<double> uniform(0, 1);
  OrdinalData d;
  d.features = static_cast<int>(w.size());
  d.classes = static_cast<int>(theta.size()) + 1;
  OrdinalModel truth{theta, w};
  for (size_t i = 0; i < n; ++i) {
    std::vector<double> x(w.size());
    for (double& v : x) v = normal(rng);
    std::vector<double> p = truth.Probabilities(x);
    double u = uniform(rng), c = 0;
    int y = d.classes - 1;
    for (int j = 0; j < d.classes; ++j) {
      c += p[static_cast<size_t>(j)];
      if (u < c) {
        y = j;
        break;
      }
    }
    d.x.insert(d.x.end(), x.begin(), x.end());
    d.y.push_back(y);
  }
  return d;
}

TEST(Ordinal, RecoversKnownParameters) {
  const std::vector<double> theta = {-1.5, 0.0, 1.2, 2.5};
  const std::vector<double> w = {1.0, -0.7, 0.0};
  OrdinalData d = Synthetic(theta, w, 20000, 7);
  auto fit = FitOrdinal(d, 1e-3);
  ASSERT_TRUE(fit.ok()) << fit.status().message();
  // Standard errors at n = 20000 are about 0.02; 0.08 is four of them.
  for (size_t j = 0; j < theta.size(); ++j) {
    EXPECT_NEAR(fit->model.thresholds[j], theta[j], 0.08) << "theta " << j;
  }
  for (size_t k = 0; k < w.size(); ++k) EXPECT_NEAR(fit->model.weights[k], w[k], 0.08) << k;
  EXPECT_LT(fit->iterations, 30);
}

TEST(Ordinal, PenaltyShrinksWeightsTowardZero) {
  OrdinalData d = Synthetic({-1, 1}, {1.5, -1.0}, 400, 3);
  double prev = 1e300;
  for (double l2 : {0.01, 1.0, 100.0, 1e4}) {
    auto fit = FitOrdinal(d, l2);
    ASSERT_TRUE(fit.ok());
    double norm = 0;
    for (double w : fit->model.weights) norm += w * w;
    EXPECT_LT(norm, prev) << l2;
    prev = norm;
  }
  EXPECT_LT(prev, 1e-3);
}

TEST(Ordinal, GradientVanishesAtTheOptimum) {
  OrdinalData d = Synthetic({-0.5, 0.7, 2.0}, {0.8, 0.3}, 300, 11);
  const double l2 = 2.0;
  auto fit = FitOrdinal(d, l2);
  ASSERT_TRUE(fit.ok());
  // Central differences of the objective in every parameter.
  std::vector<double*> params;
  OrdinalModel m = fit->model;
  for (double& t : m.thresholds) params.push_back(&t);
  for (double& w : m.weights) params.push_back(&w);
  for (double* p : params) {
    const double h = 1e-6, keep = *p;
    *p = keep + h;
    const double up = OrdinalObjective(m, d, l2);
    *p = keep - h;
    const double down = OrdinalObjective(m, d, l2);
    *p = keep;
    EXPECT_NEAR((up - down) / (2 * h), 0.0, 1e-5);
  }
  // And any move away increases the objective.
  m.weights[0] += 0.01;
  EXPECT_GT(OrdinalObjective(m, d, l2), fit->objective);
}

TEST(Ordinal, ProbabilitiesAndQuantiles) {
  OrdinalModel m{{-1.0, 0.5, 2.0}, {1.0}};
  const double x = 0.3;
  std::vector<double> p = m.Probabilities(std::vector<double>{x});
  ASSERT_EQ(p.size(), 4u);
  double sum = 0;
  for (double v : p) sum += v;
  EXPECT_NEAR(sum, 1.0, 1e-15);
  auto sigma = [](double t) { return 1 / (1 + std::exp(-t)); };
  EXPECT_NEAR(p[0], sigma(-1.0 - x), 1e-15);
  EXPECT_NEAR(p[0] + p[1], sigma(0.5 - x), 1e-15);
  EXPECT_EQ(Quantile(p, 0.5), 1);  // P(y <= 0) = 0.21, P(y <= 1) = 0.55
  EXPECT_EQ(Quantile(std::vector<double>{0.1, 0.2, 0.7}, 0.1), 0);
  EXPECT_EQ(Quantile(std::vector<double>{0.1, 0.2, 0.7}, 0.9), 2);
  // Extreme linear predictors stay finite and normalised.
  for (double big : {-800.0, 800.0}) {
    std::vector<double> q = m.Probabilities(std::vector<double>{big});
    double s = 0;
    for (double v : q) {
      EXPECT_TRUE(std::isfinite(v));
      s += v;
    }
    EXPECT_NEAR(s, 1.0, 1e-12);
  }
}

TEST(Ordinal, RefusesBadInput) {
  OrdinalData d;
  d.features = 1;
  d.classes = 3;
  d.x = {0.1, 0.2, 0.3};
  d.y = {0, 1, 1};
  auto missing = FitOrdinal(d, 1.0);
  ASSERT_FALSE(missing.ok());
  EXPECT_NE(missing.status().message().find("class 2 has no observation"), std::string::npos);
  d.y = {0, 1, 3};
  EXPECT_FALSE(FitOrdinal(d, 1.0).ok());
  d.y = {0, 1, 2};
  EXPECT_FALSE(FitOrdinal(d, 0.0).ok());  // penalty needed with features
  d.x = {0.1, NAN, 0.3};
  EXPECT_FALSE(FitOrdinal(d, 1.0).ok());
  d.x = {0.1, 0.2};
  EXPECT_FALSE(FitOrdinal(d, 1.0).ok());
  d.classes = 1;
  EXPECT_FALSE(FitOrdinal(d, 1.0).ok());
  // No features: thresholds at the logits of the cumulative frequencies.
  OrdinalData t;
  t.classes = 3;
  t.y = {0, 1, 1, 2};
  auto fit = FitOrdinal(t, 1.0);
  ASSERT_TRUE(fit.ok());
  EXPECT_NEAR(fit->model.thresholds[0], std::log(0.25 / 0.75), 1e-9);
  EXPECT_NEAR(fit->model.thresholds[1], std::log(0.75 / 0.25), 1e-9);
}

// SciPy minimises the same penalised negative log-likelihood (BFGS from a
// different start); the optima must agree.
TEST(Ordinal, MatchesSciPy) {
  const char* python = "/usr/bin/python3";
  if (access(python, X_OK) != 0) GTEST_SKIP() << python << " not found (Debian python3-scipy)";
  if (std::system("/usr/bin/python3 -c 'import scipy' 2>/dev/null") != 0) {
    GTEST_SKIP() << "SciPy is not installed for /usr/bin/python3 (python3-scipy)";
  }
  OrdinalData d = Synthetic({-1.0, 0.2, 1.4}, {0.9, -0.4, 0.2}, 250, 5);
  const double l2 = 0.7;
  auto fit = FitOrdinal(d, l2);
  ASSERT_TRUE(fit.ok());
  const auto dir =
      std::filesystem::temp_directory_path() / ("sb_ordinal_scipy_" + std::to_string(getpid()));
  std::filesystem::create_directories(dir);
  std::ostringstream data;
  data.precision(17);
  for (size_t i = 0; i < d.rows(); ++i) {
    data << d.y[i];
    for (int k = 0; k < d.features; ++k) data << ' ' << d.x[i * 3 + static_cast<size_t>(k)];
    data << '\n';
  }
  ASSERT_TRUE(WriteFileAtomic((dir / "data.txt").string(), data.str()).ok());
  const std::string script =
      "import numpy as np\n"
      "from scipy.optimize import minimize\n"
      "from scipy.special import expit\n"
      "a = np.loadtxt('" +
      (dir / "data.txt").string() +
      "')\n"
      "y = a[:, 0].astype(int); X = a[:, 1:]; J = 4; l2 = 0.7\n"
      "def unpack(b):\n"
      "    th = np.cumsum(np.concatenate([[b[0]], np.exp(b[1:J-1])]))\n"
      "    return th, b[J-1:]\n"
      "def f(b):\n"
      "    th, w = unpack(b); eta = X @ w\n"
      "    t = np.concatenate([[-np.inf], th, [np.inf]])\n"
      "    up = expit(t[y + 1] - eta); lo = expit(t[y] - eta)\n"
      "    return -np.sum(np.log(up - lo)) + 0.5 * l2 * w @ w\n"
      "r = minimize(f, np.zeros(J - 1 + X.shape[1]), method='BFGS', options={'gtol': 1e-10})\n"
      "th, w = unpack(r.x)\n"
      "print(' '.join(repr(float(v)) for v in np.concatenate([th, w, [r.fun]])))\n";
  ASSERT_TRUE(WriteFileAtomic((dir / "fit.py").string(), script).ok());
  const std::string cmd =
      std::string(python) + " " + (dir / "fit.py").string() + " > " + (dir / "out.txt").string();
  ASSERT_EQ(std::system(cmd.c_str()), 0) << cmd;
  auto out = ReadFile((dir / "out.txt").string());
  ASSERT_TRUE(out.ok());
  std::istringstream in(*out);
  std::vector<double> ref;
  for (double v; in >> v;) ref.push_back(v);
  ASSERT_EQ(ref.size(), 3u + 3u + 1u) << *out;
  for (size_t j = 0; j < 3; ++j) EXPECT_NEAR(fit->model.thresholds[j], ref[j], 1e-5) << j;
  for (size_t k = 0; k < 3; ++k) EXPECT_NEAR(fit->model.weights[k], ref[3 + k], 1e-5) << k;
  EXPECT_NEAR(fit->objective, ref[6], 1e-8);
  EXPECT_LE(fit->objective, ref[6] + 1e-10);  // Newton is at least as low
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace sb::grades
