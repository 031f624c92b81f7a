#include "grades/ratings_session.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <string>

#include "grades/ratings_newton.h"

namespace sb::grades {

namespace {

using newton::Num;
using newton::Sigmoid;
using newton::Softplus;

// One game: z = sum coef * x[index] (up to five terms), won or lost, with
// a weight (1, or the later tries' weight).
struct Game {
  std::array<int32_t, 5> idx{};
  std::array<double, 5> coef{};
  int n = 0;
  bool win = false;
  double weight = 1;
};

// One Gaussian prior term: (sum coef * x[index] - mean)^2 / 2 sd^2.
struct Prior {
  std::array<int32_t, 3> idx{};
  std::array<double, 3> coef{};
  int n = 0;
  double mean = 0, precision = 0;
};

// Layout of x: abilities (C), difficulties (R), zone difficulties (R),
// route offsets (R), climber offsets (C), b, delta.
struct Layout {
  size_t c, r;
  size_t a(size_t i) const { return i; }
  size_t d(size_t i) const { return c + i; }
  size_t z(size_t i) const { return c + r + i; }
  size_t e(size_t i) const { return c + 2 * r + i; }
  size_t u(size_t i) const { return c + 3 * r + i; }
  size_t b() const { return 2 * c + 3 * r; }
  size_t delta() const { return b() + 1; }
  size_t size() const { return b() + 2; }
};

class Problem {
 public:
  std::vector<Game> games;
  std::vector<Prior> priors;
  size_t n = 0;

  double Objective(const std::vector<double>& x) const {
    double f = 0;
    for (const Game& g : games) {
      const double z = Z(g, x);
      f += g.weight * (g.win ? Softplus(-z) : Softplus(z));
    }
    for (const Prior& p : priors) {
      const double r = R(p, x);
      f += 0.5 * p.precision * r * r;
    }
    return f;
  }

  // Gradient into g, each game's weight p (1 - p) into w_, the diagonal into diag_.
  void GradientAndHessian(const std::vector<double>& x, std::vector<double>* g) {
    g->assign(n, 0);
    diag_.assign(n, 0);
    w_.resize(games.size());
    for (size_t i = 0; i < games.size(); ++i) {
      const Game& q = games[i];
      const double p = Sigmoid(Z(q, x));
      const double r = q.weight * (p - (q.win ? 1.0 : 0.0));
      w_[i] = q.weight * p * (1 - p);
      for (int t = 0; t < q.n; ++t) {
        (*g)[size_t(q.idx[size_t(t)])] += r * q.coef[size_t(t)];
        diag_[size_t(q.idx[size_t(t)])] += w_[i] * q.coef[size_t(t)] * q.coef[size_t(t)];
      }
    }
    for (const Prior& p : priors) {
      const double r = p.precision * R(p, x);
      for (int t = 0; t < p.n; ++t) {
        (*g)[size_t(p.idx[size_t(t)])] += r * p.coef[size_t(t)];
        diag_[size_t(p.idx[size_t(t)])] += p.precision * p.coef[size_t(t)] * p.coef[size_t(t)];
      }
    }
  }

  // y = H v (H = A' W A + P' L P at the last Gradient()).
  void Multiply(const std::vector<double>& v, std::vector<double>* y) const {
    y->assign(n, 0);
    for (size_t i = 0; i < games.size(); ++i) {
      const Game& q = games[i];
      double s = 0;
      for (int t = 0; t < q.n; ++t) s += q.coef[size_t(t)] * v[size_t(q.idx[size_t(t)])];
      s *= w_[i];
      for (int t = 0; t < q.n; ++t) (*y)[size_t(q.idx[size_t(t)])] += s * q.coef[size_t(t)];
    }
    for (const Prior& p : priors) {
      double s = 0;
      for (int t = 0; t < p.n; ++t) s += p.coef[size_t(t)] * v[size_t(p.idx[size_t(t)])];
      s *= p.precision;
      for (int t = 0; t < p.n; ++t) (*y)[size_t(p.idx[size_t(t)])] += s * p.coef[size_t(t)];
    }
  }

  // Solves H s = -g to relative residual eta by Jacobi-preconditioned CG.
  int SolveNewtonStep(const std::vector<double>& g, double eta, std::vector<double>* s) const {
    return newton::SolveJacobiCg(
        g, eta, diag_, s,
        [this](const std::vector<double>& v, std::vector<double>* y) { Multiply(v, y); });
  }

 private:
  static double Z(const Game& g, const std::vector<double>& x) {
    double z = 0;
    for (int t = 0; t < g.n; ++t) z += g.coef[size_t(t)] * x[size_t(g.idx[size_t(t)])];
    return z;
  }
  static double R(const Prior& p, const std::vector<double>& x) {
    double r = -p.mean;
    for (int t = 0; t < p.n; ++t) r += p.coef[size_t(t)] * x[size_t(p.idx[size_t(t)])];
    return r;
  }
  std::vector<double> w_, diag_;
};

}  // namespace

Status SessionModelParams::Validate() const {
  const std::pair<const char*, double> positive[] = {{"logit_per_unit", logit_per_unit},
                                                     {"climber_sd", climber_sd},
                                                     {"route_sd", route_sd},
                                                     {"offset_sd", offset_sd},
                                                     {"delta_sd", delta_sd}};
  for (const auto& [name, v] : positive) {
    if (!std::isfinite(v) || !(v > 0)) {
      return Status::InvalidInput(std::string("session model: ") + name +
                                  ": expected a number > 0, got " + Num(v));
    }
  }
  const std::pair<const char*, double> nonneg[] = {{"zone_sd", zone_sd},
                                                   {"route_offset_sd", route_offset_sd},
                                                   {"climber_offset_sd", climber_offset_sd},
                                                   {"later_tries_weight", later_tries_weight}};
  for (const auto& [name, v] : nonneg) {
    if (!std::isfinite(v) || v < 0) {
      return Status::InvalidInput(std::string("session model: ") + name +
                                  ": expected a number >= 0, got " + Num(v));
    }
  }
  if (!std::isfinite(offset_mean) || !std::isfinite(prior_mean)) {
    return Status::InvalidInput("session model: offset_mean and prior_mean must be finite");
  }
  return Status::Ok();
}

Result<SessionModelFit> FitSessionModel(const std::vector<SessionObs>& obs, int climbers,
                                        int routes, const SessionModelParams& k,
                                        const std::vector<RoutePrior>& route_prior) {
  SB_RETURN_IF_ERROR(k.Validate());
  if (climbers < 0 || routes < 0) return Status::InvalidInput("session model: negative counts");
  if (!route_prior.empty() && route_prior.size() != size_t(routes)) {
    return Status::InvalidInput("session model: route priors: expected " + std::to_string(routes) +
                                ", got " + std::to_string(route_prior.size()));
  }
  for (size_t r = 0; r < route_prior.size(); ++r) {
    if (!std::isfinite(route_prior[r].mean) || !std::isfinite(route_prior[r].sd) ||
        !(route_prior[r].sd > 0)) {
      return Status::InvalidInput("session model: route prior " + std::to_string(r) +
                                  ": expected a finite mean and an sd > 0");
    }
  }
  const Layout L{size_t(climbers), size_t(routes)};
  const double kk = k.logit_per_unit;
  const bool zones = k.zone_sd > 0, route_off = k.route_offset_sd > 0,
             climber_off = k.climber_offset_sd > 0;
  Problem P;
  P.n = L.size();
  for (size_t i = 0; i < obs.size(); ++i) {
    const SessionObs& o = obs[i];
    if (o.climber < 0 || o.climber >= climbers || o.route < 0 || o.route >= routes) {
      return Status::InvalidInput("session model: observation " + std::to_string(i) +
                                  ": index out of range");
    }
    auto bad_tries = [](const std::optional<int>& t) {
      return t && (*t < 0 || *t > kMaxTickAttempts);
    };
    if (bad_tries(o.tries) || bad_tries(o.zone_tries) || (o.top && o.tries && *o.tries == 0)) {
      return Status::InvalidInput("session model: observation " + std::to_string(i) +
                                  ": tries: expected 0 to " + std::to_string(kMaxTickAttempts) +
                                  " (1 or more with a top)");
    }
    const int32_t a = int32_t(L.a(size_t(o.climber))), d = int32_t(L.d(size_t(o.route))),
                  z = int32_t(L.z(size_t(o.route)));
    if (!(o.tries && *o.tries == 0)) {
      Game first;
      first.idx = {a, d};
      first.coef = {kk, -kk};
      first.n = 2;
      first.win = o.top && o.tries && *o.tries == 1;
      P.games.push_back(first);
      Game session = first;
      session.idx[2] = int32_t(L.b());
      session.coef[2] = 1;
      session.n = 3;
      if (route_off) {
        session.idx[size_t(session.n)] = int32_t(L.e(size_t(o.route)));
        session.coef[size_t(session.n++)] = 1;
      }
      if (climber_off) {
        session.idx[size_t(session.n)] = int32_t(L.u(size_t(o.climber)));
        session.coef[size_t(session.n++)] = 1;
      }
      session.win = o.top;
      P.games.push_back(session);
      // The tries after the first as per-try games at a small weight: a top
      // in n is a won try and n - 2 lost ones, no top in n is n - 1 lost.
      const int n = o.tries.value_or(0);
      if (k.later_tries_weight > 0 && n > 1) {
        Game later = first;
        later.weight = k.later_tries_weight;
        if (o.top) {
          later.win = true;
          P.games.push_back(later);
        }
        const int lost = o.top ? n - 2 : n - 1;
        if (lost > 0) {
          later.win = false;
          later.weight = k.later_tries_weight * lost;
          P.games.push_back(later);
        }
      }
    }
    if (zones && o.zone && !(o.zone_tries && *o.zone_tries == 0)) {
      Game zfirst;
      zfirst.idx = {a, z};
      zfirst.coef = {kk, -kk};
      zfirst.n = 2;
      if (o.zone_tries) {
        zfirst.win = *o.zone && *o.zone_tries == 1;
        P.games.push_back(zfirst);
      }
      Game zsession = zfirst;
      zsession.idx[2] = int32_t(L.b());
      zsession.coef[2] = 1;
      zsession.n = 3;
      zsession.win = *o.zone;
      P.games.push_back(zsession);
    }
  }
  auto prior1 = [&](size_t i, double mean, double sd) {
    Prior p;
    p.idx[0] = int32_t(i);
    p.coef[0] = 1;
    p.n = 1;
    p.mean = mean;
    p.precision = 1 / (sd * sd);
    P.priors.push_back(p);
  };
  // Unused parts (an sd of 0) are pinned at 0 by a unit prior: they appear
  // in no game, so they stay at 0 and change nothing else.
  for (size_t c = 0; c < L.c; ++c) prior1(L.a(c), k.prior_mean, k.climber_sd);
  for (size_t r = 0; r < L.r; ++r) {
    if (route_prior.empty()) {
      prior1(L.d(r), k.prior_mean, k.route_sd);
    } else {
      prior1(L.d(r), route_prior[r].mean, route_prior[r].sd);
    }
  }
  for (size_t r = 0; r < L.r; ++r) {
    if (zones) {
      Prior p;  // z_r - d_r + delta ~ N(0, zone_sd^2)
      p.idx = {int32_t(L.z(r)), int32_t(L.d(r)), int32_t(L.delta())};
      p.coef = {1, -1, 1};
      p.n = 3;
      p.precision = 1 / (k.zone_sd * k.zone_sd);
      P.priors.push_back(p);
    } else {
      prior1(L.z(r), 0, 1);
    }
  }
  for (size_t r = 0; r < L.r; ++r) prior1(L.e(r), 0, route_off ? k.route_offset_sd : 1);
  for (size_t c = 0; c < L.c; ++c) prior1(L.u(c), 0, climber_off ? k.climber_offset_sd : 1);
  prior1(L.b(), k.offset_mean, k.offset_sd);
  prior1(L.delta(), 0, k.delta_sd);

  std::vector<double> x(L.size(), 0);
  for (size_t c = 0; c < L.c; ++c) x[L.a(c)] = k.prior_mean;
  for (size_t r = 0; r < L.r; ++r) {
    x[L.d(r)] = x[L.z(r)] = route_prior.empty() ? k.prior_mean : route_prior[r].mean;
  }
  x[L.b()] = k.offset_mean;
  SessionModelFit fit;
  fit.prior_mean = k.prior_mean;
  newton::NewtonStats st;
  constexpr double kTolerance = 1e-9;
  const bool converged = newton::MinimizeNewton(P, &x, kTolerance, 200, &st);
  fit.newton_iterations = st.newton_iterations;
  fit.cg_iterations = st.cg_iterations;
  fit.gradient_max = st.gradient_max;
  if (!converged) {
    return Status::Internal("session model: Newton did not converge (largest gradient " +
                            Num(fit.gradient_max) + ")");
  }
  auto slice = [&](size_t from, size_t n) {
    return std::vector<double>(x.begin() + long(from), x.begin() + long(from + n));
  };
  fit.ability = slice(L.a(0), L.c);
  fit.difficulty = slice(L.d(0), L.r);
  fit.zone_difficulty = slice(L.z(0), L.r);
  fit.route_offset = slice(L.e(0), L.r);
  fit.climber_offset = slice(L.u(0), L.c);
  fit.offset = x[L.b()];
  fit.delta = x[L.delta()];
  return fit;
}

Result<std::vector<SessionObs>> SessionObsOfProblem(const RatingProblem& problem) {
  if (problem.model != RatingModel::kSession) {
    return Status::InvalidInput("session model: the problem is not a session model's");
  }
  std::vector<SessionObs> obs;
  for (const RatingPair& q : problem.pairs) {
    if (q.wins + q.losses != q.session_wins + q.session_losses || q.wins > q.session_wins) {
      return Status::InvalidInput("session model: pair (" + std::to_string(q.climber) + ", " +
                                  std::to_string(q.route) + "): games disagree");
    }
    SessionObs o;
    o.climber = q.climber;
    o.route = q.route;
    o.top = true;
    o.tries = 1;
    for (int i = 0; i < q.wins; ++i) obs.push_back(o);  // flashes
    o.tries = 2;
    for (int i = q.wins; i < q.session_wins; ++i) obs.push_back(o);  // sends
    o.top = false;
    o.tries = 1;
    for (int i = 0; i < q.session_losses; ++i) obs.push_back(o);  // attempts
  }
  return obs;
}

std::vector<RoutePrior> RoutePriorsOfProblem(const RatingProblem& problem,
                                             const RatingParams& params, double prior_mean) {
  std::vector<RoutePrior> out(size_t(problem.num_routes()));
  for (size_t r = 0; r < out.size(); ++r) {
    const auto& s = problem.setter[r];
    const double sd = s ? params.setter_sd : params.open_route_sd;
    const double p0 = 1 / (sd * sd), pf = 1 / (params.felt_sd * params.felt_sd);
    const double prec = p0 + pf * problem.felt_count[r];
    out[r].mean = (p0 * (s ? *s : prior_mean) + pf * problem.felt_sum[r]) / prec;
    out[r].sd = std::sqrt(1 / prec);
  }
  return out;
}

Result<GymSessionFit> FitGymSessionModel(const RatingProblem& problem, const RatingParams& params,
                                         double prior_mean, const SessionModelParams& k) {
  GymSessionFit out;
  out.params = k;
  out.params.prior_mean = prior_mean;
  out.params.climber_sd = params.climber_sd;
  out.params.logit_per_unit = params.logit_per_unit;
  // The session problem keeps no try counts (a send reads as 2 tries): no
  // later-tries games.
  out.params.later_tries_weight = 0;
  SB_ASSIGN_OR_RETURN(std::vector<SessionObs> obs, SessionObsOfProblem(problem));
  SB_ASSIGN_OR_RETURN(out.fit,
                      FitSessionModel(obs, problem.num_climbers, problem.num_routes(), out.params,
                                      RoutePriorsOfProblem(problem, params, prior_mean)));
  return out;
}

Result<RatingEvaluation> EvaluateSynthGymSession(const SynthGym& gym, const RatingParams& params,
                                                 const SessionModelParams& k) {
  const RatingProblem problem = SynthProblem(gym, RatingModel::kSession);
  // Every synthetic route has a setter's grade: m is their mean.
  SB_ASSIGN_OR_RETURN(GymSessionFit gf,
                      FitGymSessionModel(problem, params, newton::PriorMean(problem), k));
  return CompareWithTruth(gym, gf.fit.difficulty);  // no intervals
}

SendChances PredictSessionModel(const SessionModelParams& params, const SessionModelFit& fit,
                                int climber, int route,
                                std::optional<double> unseen_difficulty) {
  const bool seen_c = climber >= 0 && size_t(climber) < fit.ability.size();
  const bool seen_r = route >= 0 && size_t(route) < fit.difficulty.size();
  const double a = seen_c ? fit.ability[size_t(climber)] : fit.prior_mean;
  const double d =
      seen_r ? fit.difficulty[size_t(route)] : unseen_difficulty.value_or(fit.prior_mean);
  const double u = seen_c ? fit.climber_offset[size_t(climber)] : 0.0;
  const double e = seen_r ? fit.route_offset[size_t(route)] : 0.0;
  const double z = params.logit_per_unit * (a - d);
  SendChances s;
  s.p_flash = Sigmoid(z);
  s.p_send = Sigmoid(z + fit.offset + e + u);
  return s;
}

}  // namespace sb::grades
