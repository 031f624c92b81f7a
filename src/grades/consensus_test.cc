// Consensus and drift: percentiles and the sign test against NumPy/SciPy,
// and the drift flag's rules.
#include "grades/consensus.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "base/files.h"

namespace sb::grades {
namespace {

TEST(Consensus, MedianSpreadAndCount) {
  const std::vector<double> felt = {4, 3.75, 5, 4.25, 6};
  auto c = ConsensusOf(felt);
  ASSERT_TRUE(c.ok());
  EXPECT_EQ(c->count, 5);
  EXPECT_DOUBLE_EQ(c->median, 4.25);
  EXPECT_DOUBLE_EQ(c->low, 4);
  EXPECT_DOUBLE_EQ(c->high, 5);
  EXPECT_EQ(c->band, 4);
  auto two = ConsensusOf(std::vector<double>{10, 11});
  ASSERT_TRUE(two.ok());
  EXPECT_DOUBLE_EQ(two->median, 10.5);
  EXPECT_EQ(two->band, 10);  // halves go down
  EXPECT_FALSE(ConsensusOf({}).ok());
  EXPECT_FALSE(ConsensusOf(std::vector<double>{1, NAN}).ok());
}

TEST(Consensus, DriftNeedsMoreThanOneBandAndASignificantSignTest) {
  // Setter says V3; six climbers all feel V6: flagged (p = 2 / 64).
  Drift d = DriftOf(3, std::vector<double>{6, 6, 5.75, 6.25, 6, 6});
  EXPECT_TRUE(d.flagged);
  EXPECT_EQ(d.bands, 3);
  EXPECT_EQ(d.above, 6);
  EXPECT_NEAR(d.p_value, 2.0 / 64, 1e-15);
  // Five such votes are not enough (p = 2 / 32 > 0.05).
  EXPECT_FALSE(DriftOf(3, std::vector<double>{6, 6, 6, 6, 6}).flagged);
  // One band off is no drift, however many votes.
  EXPECT_FALSE(DriftOf(3, std::vector<double>(30, 4.0)).flagged);
  // Votes in the setter's band are ties: they drop out of the test.
  Drift ties = DriftOf(3, std::vector<double>{3, 3, 3, 3, 3, 3, 3, 6, 6, 6, 6, 6, 6, 6, 6});
  EXPECT_EQ(ties.above, 8);
  EXPECT_EQ(ties.below, 0);
  EXPECT_TRUE(ties.flagged);
  // Easier than graded.
  Drift soft = DriftOf(8, std::vector<double>(10, 5.0));
  EXPECT_TRUE(soft.flagged);
  EXPECT_EQ(soft.bands, -3);
  EXPECT_FALSE(DriftOf(8, {}).flagged);
}

// The percentiles are NumPy's default and the p-values SciPy's binomtest.
TEST(Consensus, MatchesNumPyAndSciPy) {
  const char* python = "/usr/bin/python3";
  if (access(python, X_OK) != 0) GTEST_SKIP() << python << " not found (Debian python3-scipy)";
  if (std::system("/usr/bin/python3 -c 'import scipy.stats' 2>/dev/null") != 0) {
    GTEST_SKIP() << "SciPy is not installed for /usr/bin/python3 (python3-scipy)";
  }
  const std::vector<double> felt = {9.625, 10.125, 10.375, 11, 9.75, 12.25, 10, 10.5, 13};
  const auto dir =
      std::filesystem::temp_directory_path() / ("sb_consensus_scipy_" + std::to_string(getpid()));
  std::filesystem::create_directories(dir);
  std::ostringstream script;
  script.precision(17);
  script << "import numpy as np\nfrom scipy.stats import binomtest\nv = np.array([";
  for (size_t i = 0; i < felt.size(); ++i) script << (i ? "," : "") << felt[i];
  script << "])\nprint(repr(float(np.percentile(v, 25))), repr(float(np.median(v))), "
            "repr(float(np.percentile(v, 75))))\n"
            "for n in range(1, 31):\n"
            "    print(' '.join(repr(float(binomtest(k, n, 0.5).pvalue)) for k in range(n + 1)))\n";
  ASSERT_TRUE(WriteFileAtomic((dir / "check.py").string(), script.str()).ok());
  const std::string cmd =
      std::string(python) + " " + (dir / "check.py").string() + " > " + (dir / "out.txt").string();
  ASSERT_EQ(std::system(cmd.c_str()), 0) << cmd;
  auto out = ReadFile((dir / "out.txt").string());
  ASSERT_TRUE(out.ok());
  std::istringstream in(*out);
  double q1, med, q3;
  ASSERT_TRUE(in >> q1 >> med >> q3);
  auto c = ConsensusOf(felt);
  ASSERT_TRUE(c.ok());
  EXPECT_NEAR(c->low, q1, 1e-12);
  EXPECT_NEAR(c->median, med, 1e-12);
  EXPECT_NEAR(c->high, q3, 1e-12);
  for (int n = 1; n <= 30; ++n) {
    for (int k = 0; k <= n; ++k) {
      double ref = 0;
      ASSERT_TRUE(in >> ref) << n << " " << k;
      EXPECT_NEAR(SignTestPValue(k, n), ref, 1e-12 * std::max(1.0, ref)) << k << "/" << n;
    }
  }
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace sb::grades
