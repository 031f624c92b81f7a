// ODE systems and fixed-step integrators for chaotic variation (paper section 6).
//
// The step formulas are templates over the number type so the landscape scan
// can run the same arithmetic on SIMD lanes (one initial condition per lane)
// and get bit-identical float64 results. They take every coefficient as T.
#ifndef SB_CHAOS_ODE_H_
#define SB_CHAOS_ODE_H_

#include <array>
#include <string>
#include <string_view>
#include <vector>

#include "base/status.h"

namespace sb::chaos {

using State = std::array<double, 3>;

enum class SystemKind { kLorenz, kRossler };
enum class IntegratorKind { kRk4, kRkf45 };

// An ODE system with its three parameters:
//   Lorenz  (a, r, b): x' = a(y-x), y' = x(r-z) - y, z' = xy - bz
//   Rössler (a, b, c): x' = -y - z, y' = x + ay,    z' = b + z(x-c)
struct System {
  SystemKind kind = SystemKind::kLorenz;
  std::array<double, 3> params = {16.0, 45.0, 4.0};

  static System Lorenz(double a = 16.0, double r = 45.0, double b = 4.0) {
    return {SystemKind::kLorenz, {a, r, b}};
  }
  static System Rossler(double a = 0.2, double b = 0.2, double c = 5.7) {
    return {SystemKind::kRossler, {a, b, c}};
  }
};

// "lorenz" / "rossler" (also "rössler"); errors name the bad value.
Result<SystemKind> ParseSystemKind(std::string_view s);
const char* SystemKindName(SystemKind k);
// "rk4" / "rkf45".
Result<IntegratorKind> ParseIntegratorKind(std::string_view s);
const char* IntegratorKindName(IntegratorKind k);
// The default parameters of a system (Lorenz 16,45,4; Rössler 0.2,0.2,5.7).
std::array<double, 3> DefaultParams(SystemKind k);

// Derivative of the Lorenz system at (x, y, z); p0..p2 = a, r, b.
template <typename T>
inline void LorenzDeriv(const T& p0, const T& p1, const T& p2, const T& x, const T& y,
                        const T& z, T& dx, T& dy, T& dz) {
  dx = p0 * (y - x);
  dy = x * (p1 - z) - y;
  dz = x * y - p2 * z;
}

// Derivative of the Rössler system; p0..p2 = a, b, c.
template <typename T>
inline void RosslerDeriv(const T& p0, const T& p1, const T& p2, const T& x, const T& y,
                         const T& z, T& dx, T& dy, T& dz) {
  dx = T(0.0) - y - z;
  dy = x + p0 * y;
  dz = p1 + z * (x - p2);
}

// One classic 4th-order Runge–Kutta step of size h, in place.
// Deriv is a callable (x, y, z, dx&, dy&, dz&). `h`, `half` (= h/2) and
// `sixth` (= h/6) are passed in so they are computed once.
template <typename T, typename Deriv>
inline void Rk4Step(const Deriv& f, const T& h, const T& half, const T& sixth, T& x, T& y,
                    T& z) {
  T k1x, k1y, k1z, k2x, k2y, k2z, k3x, k3y, k3z, k4x, k4y, k4z;
  f(x, y, z, k1x, k1y, k1z);
  f(x + half * k1x, y + half * k1y, z + half * k1z, k2x, k2y, k2z);
  f(x + half * k2x, y + half * k2y, z + half * k2z, k3x, k3y, k3z);
  f(x + h * k3x, y + h * k3y, z + h * k3z, k4x, k4y, k4z);
  T two(2.0);
  x = x + sixth * (k1x + two * k2x + two * k3x + k4x);
  y = y + sixth * (k1y + two * k2y + two * k3y + k4y);
  z = z + sixth * (k1z + two * k2z + two * k3z + k4z);
}

// One fixed Runge–Kutta–Fehlberg 4(5) step of size h, advancing with the
// 5th-order solution (as the original website did), in place.
template <typename T, typename Deriv>
inline void Rkf45Step(const Deriv& f, const T& h, T& x, T& y, T& z) {
  T k1x, k1y, k1z, k2x, k2y, k2z, k3x, k3y, k3z, k4x, k4y, k4z, k5x, k5y, k5z, k6x, k6y, k6z;
  f(x, y, z, k1x, k1y, k1z);
  T c21(1.0 / 4.0);
  f(x + h * (c21 * k1x), y + h * (c21 * k1y), z + h * (c21 * k1z), k2x, k2y, k2z);
  T c31(3.0 / 32.0), c32(9.0 / 32.0);
  f(x + h * (c31 * k1x + c32 * k2x), y + h * (c31 * k1y + c32 * k2y),
    z + h * (c31 * k1z + c32 * k2z), k3x, k3y, k3z);
  T c41(1932.0 / 2197.0), c42(-7200.0 / 2197.0), c43(7296.0 / 2197.0);
  f(x + h * (c41 * k1x + c42 * k2x + c43 * k3x), y + h * (c41 * k1y + c42 * k2y + c43 * k3y),
    z + h * (c41 * k1z + c42 * k2z + c43 * k3z), k4x, k4y, k4z);
  T c51(439.0 / 216.0), c52(-8.0), c53(3680.0 / 513.0), c54(-845.0 / 4104.0);
  f(x + h * (c51 * k1x + c52 * k2x + c53 * k3x + c54 * k4x),
    y + h * (c51 * k1y + c52 * k2y + c53 * k3y + c54 * k4y),
    z + h * (c51 * k1z + c52 * k2z + c53 * k3z + c54 * k4z), k5x, k5y, k5z);
  T c61(-8.0 / 27.0), c62(2.0), c63(-3544.0 / 2565.0), c64(1859.0 / 4104.0), c65(-11.0 / 40.0);
  f(x + h * (c61 * k1x + c62 * k2x + c63 * k3x + c64 * k4x + c65 * k5x),
    y + h * (c61 * k1y + c62 * k2y + c63 * k3y + c64 * k4y + c65 * k5y),
    z + h * (c61 * k1z + c62 * k2z + c63 * k3z + c64 * k4z + c65 * k5z), k6x, k6y, k6z);
  T b1(16.0 / 135.0), b3(6656.0 / 12825.0), b4(28561.0 / 56430.0), b5(-9.0 / 50.0),
      b6(2.0 / 55.0);
  x = x + h * (b1 * k1x + b3 * k3x + b4 * k4x + b5 * k5x + b6 * k6x);
  y = y + h * (b1 * k1y + b3 * k3y + b4 * k4y + b5 * k5y + b6 * k6y);
  z = z + h * (b1 * k1z + b3 * k3z + b4 * k4z + b5 * k5z + b6 * k6z);
}

// Advances `s` by one step of the chosen integrator. Pure; thread-safe.
void Step(const System& sys, IntegratorKind integrator, double h, State& s);

// Integrates from `ic`: point k (k = 1..n) is the state after k + skip steps;
// the IC itself is never a point. Returns n points. Pure; thread-safe.
std::vector<State> Trajectory(const System& sys, IntegratorKind integrator, double h,
                              const State& ic, int skip, int n);

}  // namespace sb::chaos

#endif  // SB_CHAOS_ODE_H_
