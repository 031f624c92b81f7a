#include "difficulty/logistic.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace sb::difficulty {
namespace {

// A deterministic pseudo-random stream (splitmix64), so data need no seed state.
struct Stream {
  uint64_t s;
  double Next() {
    uint64_t z = (s += 0x9e3779b97f4a7c15ull);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    z ^= z >> 31;
    return static_cast<double>(z >> 11) / 9007199254740992.0;
  }
};

// 300 rows: two continuous columns, three 0/1 indicators, one constant column.
Dataset Synthetic() {
  Dataset d;
  d.cols = 6;
  Stream r{42};
  for (int i = 0; i < 300; ++i) {
    double a = r.Next() * 2 - 1, b = r.Next() * 3;
    double c = r.Next() < 0.3, e = r.Next() < 0.1, g = r.Next() < 0.6;
    double s = -1.0 + 1.5 * a - 0.4 * b + 1.2 * c + 0.8 * e;
    double p = 1 / (1 + std::exp(-s));
    d.x.insert(d.x.end(), {a, b, c, e, g, 7.0});
    d.label.push_back(r.Next() < p);
  }
  return d;
}

// Runs /usr/bin/python3 (Debian's, with SciPy) on `script`; "" when unavailable.
std::string RunPython(const std::string& script, const std::string& tag) {
  if (!std::filesystem::exists("/usr/bin/python3")) return "";
  std::filesystem::path dir = std::filesystem::temp_directory_path() /
                              ("sb_difficulty_" + tag + "_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  std::ofstream(dir / "check.py") << script;
  std::string out_path = (dir / "out.txt").string();
  std::string cmd =
      "/usr/bin/python3 " + (dir / "check.py").string() + " > " + out_path + " 2>/dev/null";
  int rc = std::system(cmd.c_str());
  std::stringstream ss;
  ss << std::ifstream(out_path).rdbuf();
  std::filesystem::remove_all(dir);
  return rc == 0 ? ss.str() : "";
}

std::string Num(double v) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

TEST(RocAucTest, MannWhitneyWithTies) {
  EXPECT_DOUBLE_EQ(RocAuc({0.1, 0.2, 0.8, 0.9}, {0, 0, 1, 1}), 1.0);
  EXPECT_DOUBLE_EQ(RocAuc({0.9, 0.8, 0.2, 0.1}, {0, 0, 1, 1}), 0.0);
  EXPECT_DOUBLE_EQ(RocAuc({0.5, 0.5, 0.5}, {0, 1, 0}), 0.5);
  // Positives 0.3, 0.5; negatives 0.1, 0.5, 0.6: pairs won 1 + 1.5 = 2.5 of 6.
  EXPECT_DOUBLE_EQ(RocAuc({0.3, 0.1, 0.5, 0.5, 0.6}, {1, 0, 1, 0, 0}), 2.5 / 6.0);
  EXPECT_DOUBLE_EQ(RocAuc({0.3, 0.4}, {1, 1}), 0.5);  // one class only
}

TEST(RocAucTest, AgreesWithSciPy) {
  Stream r{7};
  std::vector<double> s;
  std::vector<uint8_t> y;
  std::string ps = "[", py = "[";
  for (int i = 0; i < 500; ++i) {
    double v = std::floor(r.Next() * 20) / 20;  // many ties
    uint8_t l = r.Next() < 0.25 + 0.5 * v;
    s.push_back(v);
    y.push_back(l);
    ps += Num(v) + ",";
    py += std::to_string(l) + ",";
  }
  ps += "]";
  py += "]";
  std::string out = RunPython(
      "from scipy.stats import mannwhitneyu\n"
      "s=" +
          ps + "\ny=" + py +
          "\n"
          "pos=[a for a,b in zip(s,y) if b]; neg=[a for a,b in zip(s,y) if not b]\n"
          "u=mannwhitneyu(pos,neg).statistic\nprint('%.17g' % (u/(len(pos)*len(neg))))\n",
      "auc");
  if (out.empty()) GTEST_SKIP() << "/usr/bin/python3 with SciPy not available";
  EXPECT_NEAR(RocAuc(s, y), std::stod(out), 1e-12);
}

TEST(FitLogisticTest, AgreesWithSciPyOnTheSameObjective) {
  Dataset d = Synthetic();
  const double lambda = 3.0;
  LogisticFit fit = FitLogistic(d, lambda);
  EXPECT_GT(fit.iterations, 0);
  // The constant column is left out.
  EXPECT_EQ(fit.weight[5], 0.0);
  EXPECT_EQ(fit.scale[5], 1.0);
  std::string rows = "[";
  for (size_t i = 0; i < d.rows(); ++i) {
    rows += "[";
    for (int c = 0; c < d.cols; ++c) rows += Num(d.row(i)[c]) + ",";
    rows += std::to_string(d.label[i]) + "],";
  }
  rows += "]";
  std::string out = RunPython(
      "import numpy as np\nfrom scipy.optimize import minimize\n"
      "D=np.array(" +
          rows +
          ")\nX=D[:,:-1]; y=D[:,-1]\n"
          "X=X[:,:5]\nmu=X.mean(0); sd=X.std(0); Z=(X-mu)/sd\nlam=" +
          Num(lambda) +
          "\n"
          "def f(b):\n"
          "  s=b[0]+Z@b[1:]\n"
          "  p=1/(1+np.exp(-s))\n"
          "  g=np.concatenate([[np.sum(p-y)], Z.T@(p-y)+lam*b[1:]])\n"
          "  return np.sum(np.logaddexp(0,s)-y*s)+0.5*lam*b[1:]@b[1:], g\n"
          "r=minimize(f,np.zeros(6),jac=True,method='BFGS',options={'gtol':1e-12,'maxiter':10000})"
          "\n"
          "print(' '.join('%.17g'%v for v in r.x))\n",
      "fit");
  if (out.empty()) GTEST_SKIP() << "/usr/bin/python3 with SciPy not available";
  std::istringstream in(out);
  double want[6];
  for (double& w : want) in >> w;
  EXPECT_NEAR(fit.intercept, want[0], 1e-6);  // both on the standardised scale
  for (int c = 0; c < 5; ++c) EXPECT_NEAR(fit.weight[c], want[c + 1], 1e-6) << "column " << c;
}

TEST(FitLogisticTest, DeterministicAndShrinksWithThePenalty) {
  Dataset d = Synthetic();
  LogisticFit a = FitLogistic(d, 1.0), b = FitLogistic(d, 1.0), strong = FitLogistic(d, 1e4);
  EXPECT_EQ(a.weight, b.weight);
  EXPECT_EQ(a.intercept, b.intercept);
  double na = 0, ns = 0;
  for (int c = 0; c < 5; ++c) {
    na += a.weight[c] * a.weight[c];
    ns += strong.weight[c] * strong.weight[c];
  }
  EXPECT_LT(ns, na / 100);
  // The fit predicts: probabilities follow the generating direction.
  double lo[6] = {-1, 3, 0, 0, 0, 7}, hi[6] = {1, 0, 1, 1, 0, 7};
  EXPECT_LT(a.Probability(lo), 0.1);
  EXPECT_GT(a.Probability(hi), 0.6);
  EXPECT_LE(MeanLogLikelihood(a, d), 0.0);
  EXPECT_GT(MeanLogLikelihood(a, d), MeanLogLikelihood(strong, d));
}

TEST(FitLogisticTest, EmptyAndSeparableDataStayFinite) {
  Dataset empty;
  empty.cols = 2;
  LogisticFit e = FitLogistic(empty, 1.0);
  EXPECT_EQ(e.weight, (std::vector<double>{0, 0}));
  Dataset sep;
  sep.cols = 1;
  for (int i = 0; i < 20; ++i) {
    sep.x.push_back(i);
    sep.label.push_back(i >= 10);
  }
  LogisticFit s = FitLogistic(sep, 0.1);
  EXPECT_TRUE(std::isfinite(s.weight[0]) && std::isfinite(s.intercept));
  EXPECT_GT(s.weight[0], 0.0);
}

}  // namespace
}  // namespace sb::difficulty
