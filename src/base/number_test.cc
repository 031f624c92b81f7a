#include "base/number.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <limits>

namespace sb {
namespace {

TEST(Number, FormatDoubleIsShortestRoundTrip) {
  EXPECT_EQ(FormatDouble(0.015), "0.015");
  EXPECT_EQ(FormatDouble(16.0), "16");
  EXPECT_EQ(FormatDouble(-13.5), "-13.5");
  EXPECT_EQ(FormatDouble(-0.0), "0");
  EXPECT_EQ(FormatDouble(0.1, 17), "0.10000000000000001");
  EXPECT_EQ(FormatDouble(std::nan("")), "nan");
  EXPECT_EQ(FormatDouble(-INFINITY), "-inf");
  for (double v : {1e-300, 1.0 / 3.0, 6.02214076e23, -2.5e-7}) {
    double back = 0;
    ASSERT_TRUE(ParseDouble(FormatDouble(v), &back));
    EXPECT_EQ(back, v);
  }
  const double t[3] = {-13, -12, 52.5};
  EXPECT_EQ(FormatTriple(t), "-13,-12,52.5");
}

TEST(Number, ParseIntTakesWholeDecimalsInRange) {
  int64_t v = 0;
  EXPECT_TRUE(ParseInt("42", &v));
  EXPECT_EQ(v, 42);
  EXPECT_TRUE(ParseInt("-7", &v));
  EXPECT_EQ(v, -7);
  for (const char* bad : {"", " 1", "1 ", "+1", "1x", "0x10", "1.0", "99999999999999999999"}) {
    EXPECT_FALSE(ParseInt(bad, &v)) << bad;
  }
  int8_t small = 0;
  EXPECT_FALSE(ParseInt("300", &small));
  uint32_t u = 0;
  EXPECT_FALSE(ParseInt("-1", &u));
}

TEST(Number, ParseDoubleAndTripleRefuseNonFinite) {
  double d = 0;
  EXPECT_TRUE(ParseDouble("1e3", &d));
  EXPECT_EQ(d, 1000);
  for (const char* bad : {"", "nan", "inf", "-inf", "1e400", "1,5", " 1"}) {
    EXPECT_FALSE(ParseDouble(bad, &d)) << bad;
  }
  double t[3];
  EXPECT_TRUE(ParseTriple(" -13, -12 ,52", t));
  EXPECT_EQ(t[2], 52);
  EXPECT_FALSE(ParseTriple("1,2", t));
  EXPECT_FALSE(ParseTriple("1,2,nan", t));
  EXPECT_FALSE(ParseTriple("1,2,3,4", t));
}

}  // namespace
}  // namespace sb
