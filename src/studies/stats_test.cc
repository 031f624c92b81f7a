// Every statistic of stats.h against SciPy (scipy_reference.py under
// /usr/bin/python3) on generated samples with ties, small sizes and the
// degenerate cases where SciPy answers nan or inf, to 1e-9.
#include "studies/stats.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>
#include <numeric>
#include <random>

#include "studies/studies_test_util.h"

namespace sb::studies {
namespace {

using nlohmann::json;
using testing::Close;

class Gen {
 public:
  explicit Gen(uint64_t seed) : g_(seed) {}
  // Integers in [lo, hi]: ties are likely.
  std::vector<double> Ints(size_t n, int lo, int hi) {
    std::vector<double> v;
    for (size_t i = 0; i < n; ++i) v.push_back(lo + double(g_() % uint64_t(hi - lo + 1)));
    return v;
  }
  // Distinct reals (a shuffled grid plus an offset): no ties.
  std::vector<double> Distinct(size_t n, double offset = 0) {
    std::vector<double> v(n);
    for (size_t i = 0; i < n; ++i) v[i] = offset + 0.37 * double(i) + double(g_() % 1000) * 1e-7;
    Shuffle(&v);
    return v;
  }
  void Shuffle(std::vector<double>* v) {
    for (size_t k = v->size(); k > 1; --k) std::swap((*v)[k - 1], (*v)[g_() % k]);
  }

 private:
  std::mt19937_64 g_;
};

struct Case {
  std::string label;
  json spec;
  std::vector<double> mine;
};

std::vector<Case> MannWhitneyCases(Gen& g) {
  std::vector<Case> cases;
  auto add = [&](const std::string& label, std::vector<double> x, std::vector<double> y) {
    MannWhitneyResult r = MannWhitneyU(x, y);
    cases.push_back({label, {{"fn", "mannwhitneyu"}, {"x", x}, {"y", y}}, {r.u, r.p}});
  };
  const std::vector<std::pair<int, int>> sizes = {{1, 1}, {1, 2},   {2, 2},   {1, 8},   {3, 4},
                                                  {5, 5}, {8, 8},   {2, 30},  {8, 40},  {3, 200},
                                                  {9, 9}, {12, 15}, {30, 44}, {44, 44}, {8, 60}};
  for (auto [m, n] : sizes) {
    const std::string tag = std::to_string(m) + "x" + std::to_string(n);
    std::vector<double> all = g.Distinct(size_t(m + n));
    add("mwu distinct " + tag, {all.begin(), all.begin() + m}, {all.begin() + m, all.end()});
    add("mwu ties " + tag, g.Ints(size_t(m), -6, 6), g.Ints(size_t(n), -4, 8));
  }
  add("mwu separated exact", {1, 2, 3, 4}, {5, 6, 7, 8, 9});
  add("mwu separated 8x8", g.Distinct(8), g.Distinct(8, 100));
  add("mwu all tied", {2, 2, 2}, {2, 2, 2, 2});
  add("mwu one tie exact->asymptotic", {1, 2, 3}, {3, 4, 5});
  add("mwu empty", {}, {1, 2, 3});
  return cases;
}

std::vector<Case> WelchCases(Gen& g) {
  std::vector<Case> cases;
  auto add = [&](const std::string& label, std::vector<double> x, std::vector<double> y) {
    WelchResult r = WelchT(x, y);
    cases.push_back({label, {{"fn", "welch"}, {"x", x}, {"y", y}}, {r.t, r.p}});
  };
  for (auto [m, n] : std::vector<std::pair<int, int>>{{2, 2}, {2, 3}, {5, 7}, {20, 25}, {44, 44}}) {
    const std::string tag = std::to_string(m) + "x" + std::to_string(n);
    add("welch ints " + tag, g.Ints(size_t(m), 0, 10), g.Ints(size_t(n), 2, 14));
    add("welch reals " + tag, g.Distinct(size_t(m)), g.Distinct(size_t(n), 0.5));
  }
  add("welch constant, different means", {3, 3, 3}, {5, 5});
  add("welch constant, equal means", {4, 4}, {4, 4, 4});
  add("welch one constant", {1, 1, 1}, {0, 2, 5, 9});
  add("welch n = 1", {1}, {2, 3, 4});
  add("welch far apart", {0, 0.001, 0.002}, {1000, 1000.001, 1000.003});
  return cases;
}

std::vector<Case> KendallCases(Gen& g) {
  std::vector<Case> cases;
  auto add = [&](const std::string& label, std::vector<double> x, std::vector<double> y) {
    TestResult r = KendallTauB(x, y);
    cases.push_back({label, {{"fn", "kendalltau"}, {"x", x}, {"y", y}}, {r.statistic, r.p}});
  };
  for (int n : {2, 3, 5, 10, 20, 33, 34, 50, 100, 176}) {
    const std::string tag = std::to_string(n);
    add("tau distinct n=" + tag, g.Distinct(size_t(n)), g.Distinct(size_t(n)));
    add("tau ties n=" + tag, g.Ints(size_t(n), 1, 4), g.Ints(size_t(n), -10, 10));
    std::vector<double> x = g.Distinct(size_t(n)), y = x;
    for (double& v : y) v = 2 * v + (v > 3 ? 1 : 0);  // monotone: c = 0 or all concordant
    add("tau concordant n=" + tag, x, y);
  }
  for (int n : {40, 200}) {
    std::vector<double> x(static_cast<size_t>(n)), y(static_cast<size_t>(n));
    std::iota(x.begin(), x.end(), 0.0);
    y = x;
    std::swap(y[5], y[6]);  // exactly one discordant pair
    add("tau one swap n=" + std::to_string(n), x, y);
    std::swap(y[10], y[11]);
    add("tau two swaps n=" + std::to_string(n), x, y);
  }
  add("tau constant x", {1, 1, 1, 1}, {1, 2, 3, 4});
  add("tau n=1", {1}, {2});
  return cases;
}

std::vector<Case> PearsonCases(Gen& g) {
  std::vector<Case> cases;
  auto add = [&](const std::string& label, std::vector<double> x, std::vector<double> y) {
    TestResult r = PearsonR(x, y);
    cases.push_back({label, {{"fn", "pearsonr"}, {"x", x}, {"y", y}}, {r.statistic, r.p}});
  };
  for (int n : {2, 3, 4, 10, 44, 176}) {
    const std::string tag = std::to_string(n);
    add("pearson ints n=" + tag, g.Ints(size_t(n), 1, 4), g.Ints(size_t(n), 0, 100));
    add("pearson reals n=" + tag, g.Distinct(size_t(n)), g.Distinct(size_t(n)));
  }
  add("pearson perfect", {1, 2, 3, 4, 5}, {2, 4, 6, 8, 10});
  add("pearson perfect negative", {1, 2, 3, 4, 5, 6}, {6, 5, 4, 3, 2, 1});
  add("pearson constant", {1, 2, 3}, {7, 7, 7});
  return cases;
}

std::vector<Case> ConcordanceCases(Gen& g) {
  std::vector<Case> cases;
  auto add = [&](const std::string& label, const std::vector<std::vector<double>>& ranks) {
    KendallWResult r = KendallW(ranks);
    // The reference returns [w, chi2, p, friedman chi2, friedman p].
    cases.push_back({label, {{"fn", "kendall_w"}, {"ranks", ranks}}, {r.w, r.chi2, r.p}});
  };
  for (int m : {1, 2, 5, 44}) {
    for (int n : {2, 3, 4, 6}) {
      std::vector<std::vector<double>> perm, tied;
      for (int j = 0; j < m; ++j) {
        std::vector<double> row(static_cast<size_t>(n));
        std::iota(row.begin(), row.end(), 1.0);
        g.Shuffle(&row);
        perm.push_back(row);
        tied.push_back(g.Ints(size_t(n), 1, n - 1));
      }
      const std::string tag = "m=" + std::to_string(m) + " n=" + std::to_string(n);
      add("W permutations " + tag, perm);
      add("W ties " + tag, tied);
    }
  }
  add("W full agreement", {{1, 2, 3, 4}, {1, 2, 3, 4}, {1, 2, 3, 4}});
  add("W all tied", {{1, 1, 1}, {2, 2, 2}});
  return cases;
}

std::vector<Case> MiscCases(Gen& g) {
  std::vector<Case> cases;
  for (int rows : {2, 3, 6, 44, 176}) {
    for (int k : {2, 3, 5, 14}) {
      std::vector<std::vector<double>> m;
      std::vector<double> base = g.Ints(size_t(rows), -1, 1);
      for (int r = 0; r < rows; ++r) {
        std::vector<double> row = g.Ints(size_t(k), -2, 2);
        for (double& v : row) v = std::clamp(v + base[size_t(r)], -2.0, 2.0);  // some consistency
        m.push_back(row);
      }
      cases.push_back({"alpha " + std::to_string(rows) + "x" + std::to_string(k),
                       {{"fn", "cronbach"}, {"rows", m}},
                       {CronbachAlpha(m)}});
    }
  }
  cases.push_back({"alpha constant",
                   {{"fn", "cronbach"}, {"rows", {{1, 1}, {1, 1}, {1, 1}}}},
                   {CronbachAlpha({{1, 1}, {1, 1}, {1, 1}})}});
  for (int n : {1, 2, 5, 44}) {
    std::vector<double> v = g.Ints(size_t(n), 0, 6);
    cases.push_back(
        {"ranks n=" + std::to_string(n), {{"fn", "rankdata"}, {"x", v}}, AverageRanks(v)});
    cases.push_back({"quantiles n=" + std::to_string(n),
                     {{"fn", "quantiles"}, {"x", v}},
                     {Median(v), Quantile(v, 0.25), Quantile(v, 0.75)}});
  }
  const double points[][7] = {
      // z, t, df, chi2 x, a, b, beta x
      {-40, -50, 1, 0.1, 0.5, 0.5, 0.001}, {-5, -3.2, 2.5, 3.7, 1, 1, 0.5},
      {-1, -1, 10, 12, 21, 21, 0.2},       {0, 0, 100, 60, 0.5, 3, 0.999},
      {0.5, 2.2, 43, 0, 86, 86, 0.45},     {3, 7, 1e6, 400, 2.5, 7.5, 0.01},
      {10, 40, 3, 1e-8, 1000, 1000, 0.49}, {38, -0.1, 0.7, 25, 1.5, 1.5, 1},
  };
  for (const auto& p : points) {
    cases.push_back({"distributions z=" + std::to_string(p[0]),
                     {{"fn", "distributions"},
                      {"z", p[0]},
                      {"t", p[1]},
                      {"df", p[2]},
                      {"x", p[3]},
                      {"a", p[4]},
                      {"b", p[5]},
                      {"bx", p[6]}},
                     {NormalSf(p[0]), StudentTCdf(p[2], p[1]), ChiSquaredSf(p[2], p[3]),
                      RegularizedBeta(p[4], p[5], p[6])}});
  }
  return cases;
}

TEST(StatsVsScipy, EveryFunctionOnGeneratedSamples) {
  if (std::string why = testing::ScipyUnavailable(); !why.empty()) GTEST_SKIP() << why;
  Gen g(20240611);
  std::vector<Case> cases;
  for (auto* make :
       {MannWhitneyCases, WelchCases, KendallCases, PearsonCases, ConcordanceCases, MiscCases}) {
    std::vector<Case> more = make(g);
    cases.insert(cases.end(), more.begin(), more.end());
  }
  json in;
  in["cases"] = json::array();
  for (const Case& c : cases) in["cases"].push_back(c.spec);
  json out = testing::RunScipy(in, testing::TestDir("stats"));
  ASSERT_FALSE(out.is_null());
  ASSERT_EQ(out["cases"].size(), cases.size());
  for (size_t i = 0; i < cases.size(); ++i) {
    const json& ref = out["cases"][i];
    ASSERT_GE(ref.size(), cases[i].mine.size()) << cases[i].label;
    for (size_t k = 0; k < cases[i].mine.size(); ++k) {
      EXPECT_TRUE(Close(cases[i].mine[k], ref[k])) << cases[i].label << " value " << k;
    }
    if (cases[i].spec["fn"] == "kendall_w" && !ref[3].is_null()) {
      // For 3+ objects W's chi2 and p equal Friedman's tie-corrected test.
      EXPECT_TRUE(Close(cases[i].mine[1], ref[3])) << cases[i].label << " friedman chi2";
      EXPECT_TRUE(Close(cases[i].mine[2], ref[4])) << cases[i].label << " friedman p";
    }
  }
}

// The choice of p-value method follows SciPy's switch.
TEST(Stats, MannWhitneyMethodSwitch) {
  EXPECT_TRUE(MannWhitneyU({1, 2, 3}, {4, 5, 6, 7, 8, 9, 10, 11, 12, 13}).exact);
  EXPECT_FALSE(MannWhitneyU({1, 2, 3}, {3, 5, 6}).exact);  // a tie
  std::vector<double> x(9), y(9);
  std::iota(x.begin(), x.end(), 0.0);
  std::iota(y.begin(), y.end(), 100.0);
  EXPECT_FALSE(MannWhitneyU(x, y).exact);  // both larger than 8
}

TEST(Stats, ExactMannWhitneyMatchesEnumeration) {
  // All C(7,3) = 35 splits of the ranks 1..7 into samples of 3 and 4. The
  // two-sided p-value of U is 2 P(U' >= max(U, 12 - U)), which by symmetry is
  // the share of splits whose max(U', 12 - U') is at least as large.
  std::vector<double> us;
  for (int mask = 0; mask < 128; ++mask) {
    if (__builtin_popcount(mask) != 3) continue;
    double r = 0;
    for (int b = 0; b < 7; ++b) r += (mask >> b & 1) ? b + 1 : 0;
    us.push_back(r - 6);
  }
  ASSERT_EQ(us.size(), 35u);
  for (double u : us) {
    const double big = std::max(u, 12 - u);
    double count = 0;
    for (double v : us) count += std::max(v, 12 - v) >= big ? 1 : 0;
    EXPECT_NEAR(MannWhitneyExactP(3, 4, big), count / 35.0, 1e-15) << u;
  }
}

TEST(Stats, KendallTauMatchesPairCountingOnALargeTiedSample) {
  Gen g(7);
  const std::vector<double> x = g.Ints(3000, 1, 20), y = g.Ints(3000, -5, 5);
  double con = 0, dis = 0, tx = 0, ty = 0;  // pairs tied only in x / only in y are excluded
  for (size_t i = 0; i < x.size(); ++i) {
    for (size_t j = i + 1; j < x.size(); ++j) {
      const double s = (x[i] - x[j]) * (y[i] - y[j]);
      con += s > 0;
      dis += s < 0;
      tx += x[i] == x[j];
      ty += y[i] == y[j];
    }
  }
  const double pairs = 3000.0 * 2999 / 2;
  const double tau = (con - dis) / std::sqrt((pairs - tx) * (pairs - ty));
  EXPECT_NEAR(KendallTauB(x, y).statistic, tau, 1e-12);
}

}  // namespace
}  // namespace sb::studies
