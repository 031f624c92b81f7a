#include "grades/ratings_drift.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>
#include <string>

#include "grades/ratings_newton.h"
#include "grades/ratings_synth_draw.h"
#include "grades/scale.h"

namespace sb::grades {

namespace {

constexpr double kDaysPerYear = 365.25;
// Newton iterations before giving up (the problem is convex; the drifting
// gyms take 10 to 25 from the prior).
constexpr int kMaxNewton = 200;

using newton::PairTerms;
using newton::Softplus;

// The games' negative log-likelihood of one pair at a - d = diff.
double PairLoss(const RatingPair& q, double kk, double b, double diff) {
  const double z = kk * diff;
  double f = 0;
  if (q.wins) f += q.wins * Softplus(-z);
  if (q.losses) f += q.losses * Softplus(z);
  if (q.session_wins) f += q.session_wins * Softplus(-(z + b));
  if (q.session_losses) f += q.session_losses * Softplus(z + b);
  return f;
}

// The drifting fit's working state: x = [nodes (N), difficulties (R)].
class DriftSolver {
 public:
  DriftSolver(const DriftProblem& p, const RatingParams& k, double m, double w, double b)
      : p_(p),
        k_(k),
        m_(m),
        b_(b),
        n_(size_t(p.num_nodes())),
        r_(size_t(p.base.num_routes())),
        routes_(p.base, k, m) {
    // Chain precisions between consecutive nodes of a climber (0 across climbers).
    link_.assign(n_, 0);
    first_.assign(n_, false);
    for (size_t c = 0; c + 1 < p.climber_start.size(); ++c) {
      const size_t s = size_t(p.climber_start[c]), e = size_t(p.climber_start[c + 1]);
      if (s < e) first_[s] = true;
      for (size_t j = s; j + 1 < e; ++j) {
        const double dt = double(p.node_day[j + 1] - p.node_day[j]) / kDaysPerYear;
        link_[j] = 1 / (w * w * dt);
      }
    }
    h_.resize(p.pairs.size());
    diag_.resize(n_ + r_);
    piv_.resize(n_);
    mul_.resize(n_);
  }

  double Objective(const std::vector<double>& x) const {
    const double kk = k_.logit_per_unit;
    const double pa = 1 / (k_.climber_sd * k_.climber_sd);
    double f = 0;
    for (const RatingPair& q : p_.pairs) {
      f += PairLoss(q, kk, b_, x[size_t(q.climber)] - x[n_ + size_t(q.route)]);
    }
    for (size_t j = 0; j < n_; ++j) {
      if (first_[j]) f += 0.5 * pa * (x[j] - m_) * (x[j] - m_);
      if (link_[j] > 0) f += 0.5 * link_[j] * (x[j + 1] - x[j]) * (x[j + 1] - x[j]);
    }
    routes_.AddObjective(x, n_, &f);
    return f;
  }

  void GradientAndHessian(const std::vector<double>& x, std::vector<double>* g) {
    const double kk = k_.logit_per_unit;
    const double pa = 1 / (k_.climber_sd * k_.climber_sd);
    g->assign(n_ + r_, 0);
    std::fill(diag_.begin(), diag_.begin() + long(n_), 0.0);
    for (size_t j = 0; j < n_; ++j) {
      if (first_[j]) {
        (*g)[j] += pa * (x[j] - m_);
        diag_[j] += pa;
      }
      if (link_[j] > 0) {
        const double t = link_[j] * (x[j + 1] - x[j]);
        (*g)[j] -= t;
        (*g)[j + 1] += t;
        diag_[j] += link_[j];
        diag_[j + 1] += link_[j];
      }
    }
    routes_.SetGradient(x, n_, g, &diag_);
    newton::AddPairGradient(p_.pairs, kk, b_, x, n_, g, &h_, &diag_);
    // Each climber's tridiagonal block, factorised (L D L^T): the
    // preconditioner of the Newton step and the chain's inverse.
    for (size_t j = 0; j < n_; ++j) {
      if (first_[j]) {
        piv_[j] = diag_[j];
        mul_[j] = 0;
      } else {
        mul_[j] = -link_[j - 1] / piv_[j - 1];
        piv_[j] = diag_[j] + mul_[j] * link_[j - 1];
      }
    }
  }

  // y = H v.
  void Multiply(const std::vector<double>& v, std::vector<double>* y) const {
    for (size_t i = 0; i < n_ + r_; ++i) (*y)[i] = diag_[i] * v[i];
    for (size_t j = 0; j + 1 < n_; ++j) {
      if (link_[j] > 0) {
        (*y)[j] -= link_[j] * v[j + 1];
        (*y)[j + 1] -= link_[j] * v[j];
      }
    }
    newton::SubtractPairProducts(p_.pairs, h_, v, n_, y);
  }

  // z = M^-1 r: each climber's chain solved exactly (tridiagonal), routes
  // by their diagonal.
  void Precondition(const std::vector<double>& r, std::vector<double>* z) const {
    for (size_t j = 0; j < n_; ++j) (*z)[j] = first_[j] ? r[j] : r[j] - mul_[j] * (*z)[j - 1];
    for (size_t j = n_; j-- > 0;) {
      double v = (*z)[j] / piv_[j];
      if (j + 1 < n_ && !first_[j + 1]) v -= mul_[j + 1] * (*z)[j + 1];
      (*z)[j] = v;
    }
    for (size_t i = n_; i < n_ + r_; ++i) (*z)[i] = r[i] / diag_[i];
  }

  // Solves H s = -g to relative residual eta by CG preconditioned by the
  // climbers' chains.
  int SolveNewtonStep(const std::vector<double>& g, double eta, std::vector<double>* s) const {
    return newton::SolveCg(
        g, eta, s, [this](const std::vector<double>& v, std::vector<double>* y) { Multiply(v, y); },
        [this](const std::vector<double>& r, std::vector<double>* z) { Precondition(r, z); });
  }

  void OffsetDerivatives(const std::vector<double>& x, double* g, double* h) const {
    newton::OffsetDerivatives(p_.pairs, k_.logit_per_unit, b_, x, n_, g, h);
  }
  void set_offset(double b) { b_ = b; }
  double offset() const { return b_; }
  const std::vector<double>& h() const { return h_; }
  const std::vector<double>& diag() const { return diag_; }
  const std::vector<double>& link() const { return link_; }
  const std::vector<double>& piv() const { return piv_; }
  const std::vector<double>& mul() const { return mul_; }

 private:
  const DriftProblem& p_;
  const RatingParams& k_;
  const double m_;
  double b_;
  const size_t n_, r_;
  std::vector<double> link_;
  std::vector<bool> first_;
  newton::RoutePriors routes_;
  std::vector<double> h_, diag_, piv_, mul_;
};

// One climber's chain block inverted (dense, L x L, row-major) from the
// solver's L D L^T factors.
void ChainInverse(const DriftSolver& s, size_t lo, size_t hi, std::vector<double>* inv) {
  const size_t len = hi - lo;
  inv->assign(len * len, 0);
  std::vector<double> z(len);
  for (size_t col = 0; col < len; ++col) {
    for (size_t j = 0; j < len; ++j) {
      const double r = j == col ? 1.0 : 0.0;
      z[j] = j == 0 ? r : r - s.mul()[lo + j] * z[j - 1];
    }
    for (size_t j = len; j-- > 0;) {
      double v = z[j] / s.piv()[lo + j];
      if (j + 1 < len) v -= s.mul()[lo + j + 1] * z[j + 1];
      z[j] = v;
    }
    for (size_t j = 0; j < len; ++j) (*inv)[j * len + col] = z[j];
  }
}

// Variances of the routes and each climber's latest node; the log
// determinant of the Hessian (exact only). Exact: S = D_r - sum_c B_c^T
// T_c^-1 B_c (dense), Cholesky, W = L^-1.
Status DriftVariances(const DriftProblem& p, const DriftSolver& s, bool exact, DriftFit* out,
                      double* log_det) {
  const size_t n = size_t(p.num_nodes()), r_n = size_t(p.base.num_routes());
  const size_t c_n = size_t(p.base.num_climbers);
  std::vector<size_t> start, idx;
  newton::PairsByClimber(n, p.pairs, &start, &idx);
  const std::vector<double>& h = s.h();
  const std::vector<double>& diag = s.diag();
  RatingFit& fit = out->fit;
  fit.difficulty_sd.assign(r_n, 0);
  fit.ability_sd.assign(c_n, 0);
  double ld = 0;
  for (size_t j = 0; j < n; ++j) ld += std::log(s.piv()[j]);
  std::vector<double> inv;
  // Per climber: the latest node's in-chain variance (routes held).
  std::vector<double> latest_var(c_n, 0);
  if (!exact) {
    std::vector<double> rp(diag.begin() + long(n), diag.end());
    for (size_t c = 0; c < c_n; ++c) {
      const size_t lo = size_t(p.climber_start[c]), hi = size_t(p.climber_start[c + 1]);
      ChainInverse(s, lo, hi, &inv);
      const size_t len = hi - lo;
      for (size_t j = 0; j < len; ++j) {
        for (size_t u = start[lo + j]; u < start[lo + j + 1]; ++u) {
          const size_t i = idx[u];
          rp[size_t(p.pairs[i].route)] -= h[i] * h[i] * inv[j * len + j];
        }
      }
      fit.ability_sd[c] = std::sqrt(inv[len * len - 1]);
    }
    for (size_t r = 0; r < r_n; ++r) fit.difficulty_sd[r] = std::sqrt(1 / rp[r]);
    *log_det = 0;
    return Status::Ok();
  }
  std::vector<double> sm(r_n * r_n, 0);
  for (size_t r = 0; r < r_n; ++r) sm[r * r_n + r] = diag[n + r];
  for (size_t c = 0; c < c_n; ++c) {
    const size_t lo = size_t(p.climber_start[c]), hi = size_t(p.climber_start[c + 1]);
    ChainInverse(s, lo, hi, &inv);
    const size_t len = hi - lo;
    latest_var[c] = inv[len * len - 1];
    for (size_t j = 0; j < len; ++j) {
      for (size_t u = start[lo + j]; u < start[lo + j + 1]; ++u) {
        const size_t i = idx[u];
        const size_t ri = size_t(p.pairs[i].route);
        for (size_t k = 0; k < len; ++k) {
          const double t = inv[j * len + k];
          for (size_t v = start[lo + k]; v < start[lo + k + 1]; ++v) {
            const size_t l = idx[v];
            sm[ri * r_n + size_t(p.pairs[l].route)] -= h[i] * h[l] * t;
          }
        }
      }
    }
  }
  std::vector<double> w;
  SB_RETURN_IF_ERROR(newton::SchurVariances(&sm, r_n, &w, &fit.difficulty_sd, &ld));
  // Latest node l of climber c: var = Tinv_ll + v^T S^-1 v, v_r = sum over
  // the chain's pairs of h_i Tinv[node_i, l].
  std::vector<double> v(r_n);
  for (size_t c = 0; c < c_n; ++c) {
    const size_t lo = size_t(p.climber_start[c]), hi = size_t(p.climber_start[c + 1]);
    ChainInverse(s, lo, hi, &inv);
    const size_t len = hi - lo;
    std::fill(v.begin(), v.end(), 0.0);
    size_t lowest = r_n;
    for (size_t j = 0; j < len; ++j) {
      for (size_t u = start[lo + j]; u < start[lo + j + 1]; ++u) {
        const size_t i = idx[u];
        const size_t r = size_t(p.pairs[i].route);
        v[r] += h[i] * inv[j * len + len - 1];
        lowest = std::min(lowest, r);
      }
    }
    double q = 0;
    if (lowest < r_n) {
      for (size_t row = lowest; row < r_n; ++row) {
        double t = 0;
        for (size_t col = lowest; col <= row; ++col) t += w[row * r_n + col] * v[col];
        q += t * t;
      }
    }
    fit.ability_sd[c] = std::sqrt(latest_var[c] + q);
  }
  *log_det = ld;
  return Status::Ok();
}

}  // namespace

const char* DriftModeName(DriftMode m) {
  switch (m) {
    case DriftMode::kOff:
      return "off";
    case DriftMode::kOn:
      return "on";
    case DriftMode::kAuto:
      return "auto";
  }
  return "off";
}

Result<DriftMode> ParseDriftMode(std::string_view text, std::string_view field) {
  for (DriftMode m : {DriftMode::kOff, DriftMode::kOn, DriftMode::kAuto}) {
    if (text == DriftModeName(m)) return m;
  }
  return Status::InvalidInput(std::string(field) + ": expected on, off or auto, got '" +
                              std::string(text) + "'");
}

int DayNumber(std::string_view s) {
  // Days from civil (Hinnant's algorithm), proleptic Gregorian.
  const int y0 = (s[0] - '0') * 1000 + (s[1] - '0') * 100 + (s[2] - '0') * 10 + (s[3] - '0');
  const int m = (s[5] - '0') * 10 + (s[6] - '0');
  const int d = (s[8] - '0') * 10 + (s[9] - '0');
  const int y = y0 - (m <= 2);
  const int era = (y >= 0 ? y : y - 399) / 400;
  const int yoe = y - era * 400;
  const int doy = (153 * (m + (m > 2 ? -3 : 9)) + 2) / 5 + d - 1;
  const int doe = yoe * 365 + yoe / 4 - yoe / 100 + doy;
  return era * 146097 + doe - 719468;
}

bool DriftApplies(DriftMode mode, int first_day, int last_day) {
  if (mode == DriftMode::kOn) return true;
  if (mode == DriftMode::kOff) return false;
  return last_day - first_day > kSeasonDays;
}

Result<DriftProblem> BuildDriftProblem(const RatingProblem& base,
                                       std::span<const DatedTick> ticks, int node_days) {
  if (node_days < 1) return Status::InvalidInput("node_days: expected 1 or more");
  DriftProblem p;
  p.base = base;
  p.base.pairs.clear();
  p.base.pairs.shrink_to_fit();
  p.node_days = node_days;
  const size_t c_n = size_t(base.num_climbers);
  if (!ticks.empty()) {
    p.first_day = ticks[0].day;
    p.last_day = ticks[0].day;
  }
  for (const DatedTick& t : ticks) {
    if (t.climber < 0 || size_t(t.climber) >= c_n || t.route < 0 || t.route >= base.num_routes()) {
      return Status::InvalidInput("ratings: dated tick: index out of range");
    }
    p.first_day = std::min(p.first_day, t.day);
    p.last_day = std::max(p.last_day, t.day);
  }
  // Nodes: (climber, week), sorted; a climber without ticks gets one.
  std::vector<uint64_t> keys;
  keys.reserve(ticks.size() + c_n);
  auto week = [&](int day) { return uint32_t((day - p.first_day) / node_days); };
  for (const DatedTick& t : ticks) keys.push_back(uint64_t(uint32_t(t.climber)) << 32 | week(t.day));
  std::vector<bool> has(c_n, false);
  for (const DatedTick& t : ticks) has[size_t(t.climber)] = true;
  for (size_t c = 0; c < c_n; ++c) {
    if (!has[c]) keys.push_back(uint64_t(c) << 32);
  }
  std::sort(keys.begin(), keys.end());
  keys.erase(std::unique(keys.begin(), keys.end()), keys.end());
  p.climber_start.assign(c_n + 1, 0);
  p.node_climber.resize(keys.size());
  p.node_day.resize(keys.size());
  for (size_t j = 0; j < keys.size(); ++j) {
    const size_t c = size_t(keys[j] >> 32);
    p.node_climber[j] = int32_t(c);
    p.node_day[j] = p.first_day + int32_t(keys[j] & 0xffffffffu) * node_days;
    ++p.climber_start[c + 1];
  }
  for (size_t c = 0; c < c_n; ++c) p.climber_start[c + 1] += p.climber_start[c];
  // Games per (route, node).
  RatingProblemBuilder b;
  b.EnsureClimbers(int(keys.size()));
  b.EnsureRoutes(base.num_routes());
  for (const DatedTick& t : ticks) {
    const uint64_t key = uint64_t(uint32_t(t.climber)) << 32 | week(t.day);
    const int node = int(std::lower_bound(keys.begin(), keys.end(), key) - keys.begin());
    b.AddTick(node, t.route, t.games);
  }
  p.pairs = b.Build().pairs;
  return p;
}

Result<DriftFit> FitDriftRatings(const DriftProblem& problem, const RatingParams& params,
                                 const DriftOptions& drift, const RatingFitOptions& options) {
  SB_RETURN_IF_ERROR(params.Validate());
  SB_RETURN_IF_ERROR(problem.base.Validate());
  if (drift.sd && !(std::isfinite(*drift.sd) && *drift.sd > 0)) {
    return Status::InvalidInput("--drift-sd: expected a number > 0");
  }
  const size_t n = size_t(problem.num_nodes()), r_n = size_t(problem.base.num_routes());
  const size_t c_n = size_t(problem.base.num_climbers);
  SB_ASSIGN_OR_RETURN(const bool exact, newton::UseExactIntervals(options.intervals, r_n));
  const double m = newton::PriorMean(problem.base);
  const bool session = problem.base.model == RatingModel::kSession;
  const bool estimate_offset = session && !options.session_offset;
  std::vector<double> grid_w;
  if (drift.sd) {
    grid_w.push_back(*drift.sd);
  } else if (exact) {
    grid_w.assign(std::begin(kDriftSdGrid), std::end(kDriftSdGrid));
  } else {
    grid_w.push_back(kDefaultDriftSd);
  }
  // Start: every node at m, every route at its setter's grade; each grid
  // point starts from the last one fitted.
  std::vector<double> x(n + r_n);
  for (size_t j = 0; j < n; ++j) x[j] = m;
  for (size_t r = 0; r < r_n; ++r) x[n + r] = problem.base.setter[r].value_or(m);
  double b = session ? options.session_offset.value_or(kSessionOffsetPriorMean) : 0.0;
  DriftFit best;
  std::vector<std::pair<double, double>> grid;
  auto fit_at = [&](double w) -> Result<DriftFit> {
    DriftSolver solver(problem, params, m, w, b);
    DriftFit out;
    out.fit.prior_mean = m;
    out.fit.model = problem.base.model;
    out.fit.session_tries = problem.base.session_tries;
    newton::NewtonStats st;
    const bool converged = newton::MinimizeNewtonWithOffset(
        solver, &x, options.gradient_tolerance, kMaxNewton, estimate_offset, &st);
    out.fit.newton_iterations = st.newton_iterations;
    out.fit.cg_iterations = st.cg_iterations;
    out.fit.gradient_max = st.gradient_max;
    if (!converged) {
      return Status::Internal("ratings: Newton did not converge with drift (largest gradient " +
                              std::to_string(out.fit.gradient_max) + ")");
    }
    b = solver.offset();
    out.fit.session_offset = session ? b : 0.0;
    out.fit.exact_intervals = exact;
    out.drift_sd = w;
    out.drift_sd_estimated = !drift.sd && exact;
    out.node_value.assign(x.begin(), x.begin() + long(n));
    out.fit.difficulty.assign(x.begin() + long(n), x.end());
    out.fit.ability.resize(c_n);
    out.latest_day.resize(c_n);
    for (size_t c = 0; c < c_n; ++c) {
      const size_t last = size_t(problem.climber_start[c + 1]) - 1;
      out.fit.ability[c] = x[last];
      out.latest_day[c] = problem.node_day[last];
    }
    double log_det = 0;
    SB_RETURN_IF_ERROR(DriftVariances(problem, solver, exact, &out, &log_det));
    if (exact) {
      // Laplace: log p(data | w) = -f(x*) + log det(prior precision)/2 -
      // log det(H)/2 + terms free of w; the chain's share of the prior's
      // determinant is sum over links of log(link precision).
      double prior_ld = 0;
      for (double l : solver.link()) {
        if (l > 0) prior_ld += std::log(l);
      }
      out.log_evidence = -solver.Objective(x) + 0.5 * prior_ld - 0.5 * log_det;
    }
    return out;
  };
  if (grid_w.size() == 1) {
    SB_ASSIGN_OR_RETURN(best, fit_at(grid_w[0]));
    return best;
  }
  // The log evidence over the grid, taken as unimodal: from the default w,
  // walk the grid the way the evidence rises and stop where it falls.
  const int size = int(grid_w.size());
  std::vector<std::optional<DriftFit>> fits(static_cast<size_t>(size));
  auto eval = [&](int i) -> Status {
    if (!fits[size_t(i)]) {
      SB_ASSIGN_OR_RETURN(DriftFit f, fit_at(grid_w[size_t(i)]));
      fits[size_t(i)] = std::move(f);
    }
    return Status::Ok();
  };
  auto ev = [&](int i) { return fits[size_t(i)]->log_evidence; };
  int i = int(std::find(grid_w.begin(), grid_w.end(), kDefaultDriftSd) - grid_w.begin());
  if (i >= size - 1) i = size - 2;
  SB_RETURN_IF_ERROR(eval(i));
  SB_RETURN_IF_ERROR(eval(i + 1));
  int dir = 1;
  if (ev(i + 1) > ev(i)) {
    ++i;
  } else {
    dir = -1;
  }
  while (i + dir >= 0 && i + dir < size) {
    SB_RETURN_IF_ERROR(eval(i + dir));
    if (ev(i + dir) <= ev(i)) break;
    i += dir;
  }
  for (int k = 0; k < size; ++k) {
    if (fits[size_t(k)]) grid.emplace_back(grid_w[size_t(k)], ev(k));
  }
  best = std::move(*fits[size_t(i)]);
  best.grid = std::move(grid);
  return best;
}

std::vector<Interval> SkewedRouteIntervals(const RatingProblem& base,
                                           std::span<const RatingPair> pairs,
                                           std::span<const double> ability_of_pair,
                                           const RatingParams& params, const RatingFit& fit) {
  const size_t r_n = size_t(base.num_routes());
  const double kk = params.logit_per_unit;
  const double b = fit.session_offset;
  const double pf = 1 / (params.felt_sd * params.felt_sd);
  std::vector<Interval> out(r_n);
  size_t i0 = 0;
  for (size_t r = 0; r < r_n; ++r) {
    size_t i1 = i0;
    while (i1 < pairs.size() && size_t(pairs[i1].route) == r) ++i1;
    const auto& s = base.setter[r];
    const double mu = s ? *s : fit.prior_mean;
    const double psd = s ? params.setter_sd : params.open_route_sd;
    const double pp = 1 / (psd * psd);
    auto f = [&](double d) {
      double v = 0.5 * pp * (d - mu) * (d - mu) +
                 0.5 * pf * (base.felt_count[r] * d * d - 2 * d * base.felt_sum[r]);
      for (size_t i = i0; i < i1; ++i) v += PairLoss(pairs[i], kk, b, ability_of_pair[i] - d);
      return v;
    };
    const double dhat = fit.difficulty[r], sd = fit.difficulty_sd[r];
    double hc = pp + pf * base.felt_count[r];
    for (size_t i = i0; i < i1; ++i) {
      double dz = 0, h = 0;
      PairTerms(pairs[i], kk, b, ability_of_pair[i] - dhat, &dz, &h);
      hc += h;
    }
    // f rescaled to the marginal precision: rise threshold kZ80^2/2 * hc sd^2.
    const double f0 = f(dhat);
    const double rise = 0.5 * kZ80 * kZ80 * hc * sd * sd;
    auto edge = [&](double dir) {
      double lo = 0, hi = sd;
      while (f(dhat + dir * hi) - f0 < rise && hi < 1e3) {
        lo = hi;
        hi *= 2;
      }
      for (int it = 0; it < 60; ++it) {
        const double mid = 0.5 * (lo + hi);
        (f(dhat + dir * mid) - f0 < rise ? lo : hi) = mid;
      }
      return 0.5 * (lo + hi);
    };
    out[r].lo = dhat - edge(-1);
    out[r].hi = dhat + edge(+1);
    i0 = i1;
  }
  return out;
}

SendChances PredictSendUncertain(const RatingParams& params, RatingModel model,
                                 double session_offset, double session_tries, double ability,
                                 double ability_sd, double difficulty) {
  if (!(ability_sd > 0)) {
    return PredictSend(params, model, session_offset, session_tries, ability, difficulty);
  }
  const double k = params.logit_per_unit;
  const double scale = 1 / std::sqrt(1 + M_PI * k * k * ability_sd * ability_sd / 8);
  RatingParams scaled = params;
  scaled.logit_per_unit = k * scale;
  return PredictSend(scaled, model, session_offset * scale, session_tries, ability, difficulty);
}

Result<DriftingGym> MakeDriftingGym(const SynthGymParams& sp, const DriftGymParams& dp) {
  SB_RETURN_IF_ERROR(sp.Validate());
  if (sp.climbers > 20000) return Status::InvalidInput("--climbers: at most 20000 when drifting");
  if (dp.route_days < 1 || dp.route_days > 365) {
    return Status::InvalidInput("route_days: expected 1 to 365");
  }
  if (!std::isfinite(dp.trend_mean)) return Status::InvalidInput("--trend-mean: expected a number");
  if (!(std::isfinite(dp.trend_sd) && dp.trend_sd >= 0)) {
    return Status::InvalidInput("--trend-sd: expected a number >= 0");
  }
  if (!(std::isfinite(dp.wiener_sd) && dp.wiener_sd >= 0)) {
    return Status::InvalidInput("--wiener-sd: expected a number >= 0");
  }
  synth::Draw draw(sp.seed);
  DriftingGym out;
  SynthGym& gym = out.gym;
  const size_t c_n = size_t(sp.climbers);
  constexpr int kDays = 365;
  std::vector<float> path(c_n * kDays);
  gym.true_ability.resize(c_n);
  const double step = dp.wiener_sd * std::sqrt(1.0 / kDays);
  for (size_t c = 0; c < c_n; ++c) {
    const double a0 = std::clamp(sp.ability_mean + sp.ability_sd * draw.Normal(), -1.0, 15.0);
    const double trend = dp.trend_mean + dp.trend_sd * draw.Normal();
    double wiener = 0;
    for (int t = 0; t < kDays; ++t) {
      if (t > 0) wiener += step * draw.Normal();
      path[c * kDays + size_t(t)] = float(a0 + trend * t / kDays + wiener);
    }
    gym.true_ability[c] = path[c * kDays + kDays - 1];
  }
  gym.true_difficulty.resize(size_t(sp.routes));
  gym.setter_grade.resize(size_t(sp.routes));
  std::vector<int> set_day(size_t(sp.routes));
  for (size_t r = 0; r < size_t(sp.routes); ++r) {
    synth::DrawRoute(draw, sp, &gym.true_difficulty[r], &gym.setter_grade[r]);
    set_day[r] = draw.Below(kDays - dp.route_days + 1);
  }
  // Climbers by ability on each week's first day, to find the one nearest
  // a target at a route's mid-life.
  constexpr int kWeeks = (kDays + 6) / 7;
  std::vector<synth::NearestClimber> by_week;
  by_week.reserve(kWeeks);
  for (int wk = 0; wk < kWeeks; ++wk) {
    const size_t t = size_t(std::min(kDays - 1, wk * 7));
    by_week.emplace_back(c_n, [&](size_t c) { return double(path[c * kDays + t]); });
  }
  std::vector<int> seen;
  gym.ticks.reserve(size_t(sp.routes) * size_t(sp.ticks_per_route));
  for (int r = 0; r < sp.routes; ++r) {
    const double d = gym.true_difficulty[size_t(r)];
    const int wk = std::min(kWeeks - 1, (set_day[size_t(r)] + dp.route_days / 2) / 7);
    seen.clear();
    for (int k = 0; k < sp.ticks_per_route; ++k) {
      SynthTick tick;
      tick.climber = synth::PickClimber(draw, sp, d, by_week[size_t(wk)], &seen);
      tick.route = r;
      tick.day = set_day[size_t(r)] + draw.Below(dp.route_days);
      const double a = path[size_t(tick.climber) * kDays + size_t(tick.day)];
      const synth::Session session = synth::DrawSession(draw, sp, synth::TryChance(sp, a, d));
      synth::FinishTick(draw, sp, session, a, d, &tick);
      gym.ticks.push_back(tick);
      out.ability_at_tick.push_back(a);
    }
  }
  return out;
}

std::vector<DatedTick> SynthDatedTicks(const SynthGym& gym, RatingModel model) {
  const int day0 = DayNumber("2026-01-01");
  std::vector<DatedTick> out;
  out.reserve(gym.ticks.size());
  for (const SynthTick& t : gym.ticks) {
    auto games = TickGamesFor(model, t.outcome, t.attempts);
    out.push_back({t.climber, t.route, day0 + t.day, games.ok() ? *games : Games{}});
  }
  return out;
}

Result<DriftEvaluation> EvaluateDriftingGym(const DriftingGym& dg, const RatingParams& params,
                                            bool drift, const DriftOptions& drift_options,
                                            const RatingFitOptions& options, RatingModel model) {
  const SynthGym& gym = dg.gym;
  const RatingProblem problem = SynthProblem(gym, model);
  DriftEvaluation ev;
  ev.drift = drift;
  RatingFit fit;
  std::vector<RatingPair> pairs;
  std::vector<double> ability_of_pair;
  if (drift) {
    const std::vector<DatedTick> dated = SynthDatedTicks(gym, model);
    SB_ASSIGN_OR_RETURN(DriftProblem dp, BuildDriftProblem(problem, dated));
    SB_ASSIGN_OR_RETURN(DriftFit df, FitDriftRatings(dp, params, drift_options, options));
    fit = std::move(df.fit);
    ev.drift_sd = df.drift_sd;
    pairs = dp.pairs;
    for (const RatingPair& q : pairs) ability_of_pair.push_back(df.node_value[size_t(q.climber)]);
  } else {
    SB_ASSIGN_OR_RETURN(fit, FitRatings(problem, params, options));
    pairs = problem.pairs;
    for (const RatingPair& q : pairs) ability_of_pair.push_back(fit.ability[size_t(q.climber)]);
  }
  ev.routes = CompareWithTruth(gym, fit.difficulty, fit.difficulty_sd);
  ev.routes.exact_intervals = fit.exact_intervals;
  const size_t n = gym.true_difficulty.size();
  const std::vector<Interval> skew = SkewedRouteIntervals(problem, pairs, ability_of_pair, params,
                                                          fit);
  int skew_covered = 0;
  for (size_t r = 0; r < n; ++r) {
    const double truth = gym.true_difficulty[r];
    if (truth >= skew[r].lo && truth <= skew[r].hi) ++skew_covered;
    ev.skewed_width += skew[r].hi - skew[r].lo;
  }
  ev.skewed_coverage = double(skew_covered) / double(n);
  ev.skewed_width /= double(n);
  // Climbers: the truth on the day of their last tick.
  const size_t c_n = gym.true_ability.size();
  std::vector<int> last_day(c_n, -1);
  std::vector<double> truth(c_n, 0);
  for (size_t i = 0; i < gym.ticks.size(); ++i) {
    const SynthTick& t = gym.ticks[i];
    if (t.day >= last_day[size_t(t.climber)]) {
      last_day[size_t(t.climber)] = t.day;
      truth[size_t(t.climber)] =
          i < dg.ability_at_tick.size() ? dg.ability_at_tick[i] : gym.true_ability[size_t(t.climber)];
    }
  }
  int seen = 0, c_cov = 0;
  for (size_t c = 0; c < c_n; ++c) {
    if (last_day[c] < 0) continue;
    ++seen;
    const double v = fit.ability[c], sd = fit.ability_sd[c];
    ev.climber_mae += std::abs(v - truth[c]);
    if (truth[c] >= v - kZ80 * sd && truth[c] <= v + kZ80 * sd) ++c_cov;
  }
  if (seen > 0) {
    ev.climber_mae /= seen;
    ev.climber_coverage = double(c_cov) / seen;
  }
  return ev;
}

}  // namespace sb::grades
