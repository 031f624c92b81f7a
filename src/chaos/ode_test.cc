#include "chaos/ode.h"

#include <cmath>

#include <gtest/gtest.h>

namespace sb::chaos {
namespace {

// Reference points computed independently with 50-digit decimal arithmetic
// (Python's decimal module): 100 steps of h = 0.015 from (-13, -12, 52) on
// Lorenz (16, 45, 4).
TEST(Ode, Rk4MatchesHighPrecisionLorenzPoint) {
  auto t = Trajectory(System::Lorenz(), IntegratorKind::kRk4, 0.015, {-13, -12, 52}, 0, 100);
  ASSERT_EQ(t.size(), 100u);
  const State expect = {-11.688674265407153, -17.893220506131673, 30.739779115003866};
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(t[99][i], expect[i], 1e-12 * std::abs(expect[i]));
}

TEST(Ode, Rkf45MatchesHighPrecisionLorenzPoint) {
  auto t = Trajectory(System::Lorenz(), IntegratorKind::kRkf45, 0.015, {-13, -12, 52}, 0, 100);
  const State expect = {-11.687862750138201, -17.893853448204489, 30.734688797641851};
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(t[99][i], expect[i], 1e-12 * std::abs(expect[i]));
}

TEST(Ode, FirstPointIsAfterOneStepAndSkipDropsPoints) {
  State ic = {-13, -12, 52};
  auto t = Trajectory(System::Lorenz(), IntegratorKind::kRk4, 0.015, ic, 0, 5);
  State s = ic;
  Step(System::Lorenz(), IntegratorKind::kRk4, 0.015, s);
  EXPECT_EQ(t[0], s);
  EXPECT_NE(t[0], ic);
  auto skipped = Trajectory(System::Lorenz(), IntegratorKind::kRk4, 0.015, ic, 3, 2);
  EXPECT_EQ(skipped[0], t[3]);
  EXPECT_EQ(skipped[1], t[4]);
}

TEST(Ode, Rk4ConvergesAtFourthOrder) {
  // Halving h over a fixed time should cut the error by about 16.
  auto run = [](double h, int steps) {
    return Trajectory(System::Rossler(), IntegratorKind::kRk4, h, {1, 1, 0}, 0, steps).back();
  };
  State fine = run(0.001, 1000);
  State a = run(0.02, 50), b = run(0.01, 100);
  double ea = std::abs(a[0] - fine[0]), eb = std::abs(b[0] - fine[0]);
  EXPECT_GT(ea / eb, 12.0);
  EXPECT_LT(ea / eb, 20.0);
}

TEST(Ode, RosslerDerivative) {
  double dx, dy, dz;
  RosslerDeriv<double>(0.2, 0.2, 5.7, 1.0, 2.0, 3.0, dx, dy, dz);
  EXPECT_DOUBLE_EQ(dx, -5.0);
  EXPECT_DOUBLE_EQ(dy, 1.0 + 0.2 * 2.0);
  EXPECT_DOUBLE_EQ(dz, 0.2 + 3.0 * (1.0 - 5.7));
}

TEST(Ode, ParseNames) {
  EXPECT_EQ(*ParseSystemKind("Rossler"), SystemKind::kRossler);
  EXPECT_FALSE(ParseSystemKind("duffing").ok());
  EXPECT_EQ(*ParseIntegratorKind("rkf45"), IntegratorKind::kRkf45);
  EXPECT_FALSE(ParseIntegratorKind("euler").ok());
}

}  // namespace
}  // namespace sb::chaos
