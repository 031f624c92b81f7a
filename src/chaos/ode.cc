#include "chaos/ode.h"

#include "base/text.h"

namespace sb::chaos {

Result<SystemKind> ParseSystemKind(std::string_view s) {
  std::string l = ToLower(s);
  if (l == "lorenz") return SystemKind::kLorenz;
  if (l == "rossler" || l == "rössler" || l == "roessler") return SystemKind::kRossler;
  return Status::InvalidInput("unknown system \"" + std::string(s) + "\" (lorenz or rossler)");
}

const char* SystemKindName(SystemKind k) {
  return k == SystemKind::kLorenz ? "lorenz" : "rossler";
}

Result<IntegratorKind> ParseIntegratorKind(std::string_view s) {
  std::string l = ToLower(s);
  if (l == "rk4") return IntegratorKind::kRk4;
  if (l == "rkf45") return IntegratorKind::kRkf45;
  return Status::InvalidInput("unknown integrator \"" + std::string(s) + "\" (rk4 or rkf45)");
}

const char* IntegratorKindName(IntegratorKind k) {
  return k == IntegratorKind::kRk4 ? "rk4" : "rkf45";
}

std::array<double, 3> DefaultParams(SystemKind k) {
  return k == SystemKind::kLorenz ? std::array<double, 3>{16.0, 45.0, 4.0}
                                  : std::array<double, 3>{0.2, 0.2, 5.7};
}

namespace {

template <typename Deriv>
void Advance(const Deriv& f, IntegratorKind integrator, double h, State& s) {
  if (integrator == IntegratorKind::kRk4) {
    double half = h / 2.0, sixth = h / 6.0;
    Rk4Step<double>(f, h, half, sixth, s[0], s[1], s[2]);
  } else {
    Rkf45Step<double>(f, h, s[0], s[1], s[2]);
  }
}

template <typename Deriv>
std::vector<State> Integrate(const Deriv& f, IntegratorKind integrator, double h, State s,
                             int skip, int n) {
  std::vector<State> out;
  out.reserve(n > 0 ? n : 0);
  for (int i = 0; i < skip; ++i) Advance(f, integrator, h, s);
  for (int k = 0; k < n; ++k) {
    Advance(f, integrator, h, s);
    out.push_back(s);
  }
  return out;
}

struct LorenzF {
  double a, r, b;
  void operator()(double x, double y, double z, double& dx, double& dy, double& dz) const {
    LorenzDeriv<double>(a, r, b, x, y, z, dx, dy, dz);
  }
};
struct RosslerF {
  double a, b, c;
  void operator()(double x, double y, double z, double& dx, double& dy, double& dz) const {
    RosslerDeriv<double>(a, b, c, x, y, z, dx, dy, dz);
  }
};

}  // namespace

void Step(const System& sys, IntegratorKind integrator, double h, State& s) {
  const auto& p = sys.params;
  if (sys.kind == SystemKind::kLorenz) {
    Advance(LorenzF{p[0], p[1], p[2]}, integrator, h, s);
  } else {
    Advance(RosslerF{p[0], p[1], p[2]}, integrator, h, s);
  }
}

std::vector<State> Trajectory(const System& sys, IntegratorKind integrator, double h,
                              const State& ic, int skip, int n) {
  const auto& p = sys.params;
  if (sys.kind == SystemKind::kLorenz) {
    return Integrate(LorenzF{p[0], p[1], p[2]}, integrator, h, ic, skip, n);
  }
  return Integrate(RosslerF{p[0], p[1], p[2]}, integrator, h, ic, skip, n);
}

}  // namespace sb::chaos
