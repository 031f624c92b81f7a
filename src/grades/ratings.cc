#include "grades/ratings.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <thread>
#include <utility>

#include "grades/ratings_newton.h"

namespace sb::grades {

namespace {

using newton::Num;
using newton::PairTerms;
using newton::PriorMean;
using newton::Sigmoid;
using newton::Softplus;
// Largest step of one coordinate pass, in grades: a 1-D Newton step from a
// point where the logistic is flat can be huge; two grades is far enough to
// cross a gym in a few passes without jumping past the optimum.
constexpr double kMaxCoordinateStep = 2.0;
// Coordinate passes before Newton when there is no warm start.
constexpr int kCoordinateRounds = 4;
// Problems below this many pairs run on one thread (threads cost more than
// they save).
constexpr size_t kMinPairsPerThread = 20000;

// Runs fn(begin, end) over [0, n) split into `threads` contiguous parts, the
// first on the calling thread. Each part must write only its own outputs.
template <typename Fn>
void ParallelFor(size_t n, int threads, const Fn& fn) {
  if (threads <= 1 || n < 2) {
    fn(size_t{0}, n);
    return;
  }
  const size_t t = std::min(size_t(threads), n);
  std::vector<std::thread> pool;
  pool.reserve(t - 1);
  for (size_t k = 1; k < t; ++k) {
    pool.emplace_back([&fn, n, t, k] { fn(n * k / t, n * (k + 1) / t); });
  }
  fn(size_t{0}, n / t);
  for (std::thread& th : pool) th.join();
}

// The fit's working state: x = [abilities (C), difficulties (R)].
//
// The per-pair passes run on threads without changing a bit: every sum of a
// route's or a climber's terms is made by one thread in pair order, the
// order of the single-threaded loop (a route's pairs are contiguous; a
// climber's come from an index built in pair order), so the results are the
// same for any thread count.
class Solver {
 public:
  Solver(const RatingProblem& p, const RatingParams& k, double m, double b = 0, int threads = 1)
      : p_(p),
        k_(k),
        m_(m),
        b_(b),
        c_(size_t(p.num_climbers)),
        r_(size_t(p.num_routes())),
        routes_(p, k, m) {
    threads_ = p.pairs.size() < kMinPairsPerThread ? 1 : std::max(1, threads);
    if (threads_ > 1) {
      route_start_.assign(r_ + 1, 0);
      for (const RatingPair& q : p.pairs) ++route_start_[size_t(q.route) + 1];
      for (size_t r = 0; r < r_; ++r) route_start_[r + 1] += route_start_[r];
      climber_start_.assign(c_ + 1, 0);
      for (const RatingPair& q : p.pairs) ++climber_start_[size_t(q.climber) + 1];
      for (size_t c = 0; c < c_; ++c) climber_start_[c + 1] += climber_start_[c];
      climber_pairs_.resize(p.pairs.size());
      std::vector<size_t> fill(climber_start_.begin(), climber_start_.end() - 1);
      for (size_t i = 0; i < p.pairs.size(); ++i) {
        climber_pairs_[fill[size_t(p.pairs[i].climber)]++] = uint32_t(i);
      }
      dz_.resize(p.pairs.size());
    }
    h_.resize(p.pairs.size());
    diag_.resize(c_ + r_);
  }

  // Negative log posterior (up to a constant) at x.
  double Objective(const std::vector<double>& x) const {
    const double kk = k_.logit_per_unit;
    const double pa = 1 / (k_.climber_sd * k_.climber_sd);
    double f = 0;
    for (const RatingPair& q : p_.pairs) {
      const double z = kk * (x[size_t(q.climber)] - x[c_ + size_t(q.route)]);
      if (q.wins) f += q.wins * Softplus(-z);
      if (q.losses) f += q.losses * Softplus(z);
      if (q.session_wins | q.session_losses) {
        if (q.session_wins) f += q.session_wins * Softplus(-(z + b_));
        if (q.session_losses) f += q.session_losses * Softplus(z + b_);
      }
    }
    for (size_t c = 0; c < c_; ++c) f += 0.5 * pa * (x[c] - m_) * (x[c] - m_);
    routes_.AddObjective(x, c_, &f);
    return f;
  }

  // Gradient into g; the pairs' Hessian weights into h_ and the Hessian's
  // diagonal into diag_.
  void GradientAndHessian(const std::vector<double>& x, std::vector<double>* g) {
    const double kk = k_.logit_per_unit;
    const double pa = 1 / (k_.climber_sd * k_.climber_sd);
    g->assign(c_ + r_, 0);
    for (size_t c = 0; c < c_; ++c) {
      (*g)[c] = pa * (x[c] - m_);
      diag_[c] = pa;
    }
    routes_.SetGradient(x, c_, g, &diag_);
    if (threads_ > 1) {
      // Routes (their pairs contiguous): each pair's terms, the route's sums.
      ParallelFor(r_, threads_, [&](size_t lo, size_t hi) {
        for (size_t r = lo; r < hi; ++r) {
          const size_t d = c_ + r;
          for (size_t i = route_start_[r]; i < route_start_[r + 1]; ++i) {
            const RatingPair& q = p_.pairs[i];
            const size_t a = size_t(q.climber);
            double dz = 0, h = 0;
            PairTerms(q, kk, b_, x[a] - x[d], &dz, &h);
            dz_[i] = dz;
            h_[i] = h;
            (*g)[d] -= dz;
            diag_[d] += h;
          }
        }
      });
      // Climbers: their pairs' terms in pair order.
      ParallelFor(c_, threads_, [&](size_t lo, size_t hi) {
        for (size_t c = lo; c < hi; ++c) {
          for (size_t u = climber_start_[c]; u < climber_start_[c + 1]; ++u) {
            const uint32_t i = climber_pairs_[u];
            (*g)[c] += dz_[i];
            diag_[c] += h_[i];
          }
        }
      });
      return;
    }
    newton::AddPairGradient(p_.pairs, kk, b_, x, c_, g, &h_, &diag_);
  }

  // y = H v.
  void Multiply(const std::vector<double>& v, std::vector<double>* y) const {
    if (threads_ > 1) {
      ParallelFor(r_, threads_, [&](size_t lo, size_t hi) {
        for (size_t r = lo; r < hi; ++r) {
          const size_t d = c_ + r;
          double yd = diag_[d] * v[d];
          for (size_t i = route_start_[r]; i < route_start_[r + 1]; ++i) {
            yd -= h_[i] * v[size_t(p_.pairs[i].climber)];
          }
          (*y)[d] = yd;
        }
      });
      ParallelFor(c_, threads_, [&](size_t lo, size_t hi) {
        for (size_t c = lo; c < hi; ++c) {
          double yc = diag_[c] * v[c];
          for (size_t u = climber_start_[c]; u < climber_start_[c + 1]; ++u) {
            const uint32_t i = climber_pairs_[u];
            yc -= h_[i] * v[c_ + size_t(p_.pairs[i].route)];
          }
          (*y)[c] = yc;
        }
      });
      return;
    }
    for (size_t i = 0; i < c_ + r_; ++i) (*y)[i] = diag_[i] * v[i];
    newton::SubtractPairProducts(p_.pairs, h_, v, c_, y);
  }

  // Solves H s = -g approximately (relative residual eta) by Jacobi-
  // preconditioned conjugate gradients from s = 0. Returns the iterations.
  int SolveNewtonStep(const std::vector<double>& g, double eta, std::vector<double>* s) {
    return newton::SolveJacobiCg(
        g, eta, diag_, s,
        [this](const std::vector<double>& v, std::vector<double>* y) { Multiply(v, y); });
  }

  // A starting point near the optimum: alternating passes in which every
  // climber (difficulties held), then every route (abilities held), takes
  // one damped one-dimensional Newton step (each block of the Hessian is
  // diagonal given the other, so these are exact independent 1-D Newton
  // steps). Far from the optimum, where a joint Newton step overshoots on
  // the flat logistic tails, this settles climbers who flash or fail
  // everything cheaply.
  void CoordinatePasses(std::vector<double>* x, int rounds) {
    const double kk = k_.logit_per_unit;
    const double pa = 1 / (k_.climber_sd * k_.climber_sd);
    std::vector<double> g(c_ + r_), h(c_ + r_);
    for (int round = 0; round < rounds; ++round) {
      for (int side = 0; side < 2; ++side) {
        const size_t lo = side == 0 ? 0 : c_, hi = side == 0 ? c_ : c_ + r_;
        for (size_t c = 0; c < c_ && side == 0; ++c) {
          g[c] = pa * ((*x)[c] - m_);
          h[c] = pa;
        }
        if (side == 1) routes_.SetGradient(*x, c_, &g, &h);
        if (threads_ > 1) {
          // One pass per side: a route's pairs are contiguous; a climber's
          // come from the index, in pair order (the loop below's order).
          auto term = [&](size_t i, double* dz, double* w) {
            const RatingPair& q = p_.pairs[i];
            const size_t a = size_t(q.climber), d = c_ + size_t(q.route);
            PairTerms(q, kk, b_, (*x)[a] - (*x)[d], dz, w);
          };
          if (side == 0) {
            ParallelFor(c_, threads_, [&](size_t clo, size_t chi) {
              for (size_t c = clo; c < chi; ++c) {
                for (size_t u = climber_start_[c]; u < climber_start_[c + 1]; ++u) {
                  double dz = 0, w = 0;
                  term(climber_pairs_[u], &dz, &w);
                  g[c] += dz;
                  h[c] += w;
                }
              }
            });
          } else {
            ParallelFor(r_, threads_, [&](size_t rlo, size_t rhi) {
              for (size_t r = rlo; r < rhi; ++r) {
                for (size_t i = route_start_[r]; i < route_start_[r + 1]; ++i) {
                  double dz = 0, w = 0;
                  term(i, &dz, &w);
                  g[c_ + r] += -dz;
                  h[c_ + r] += w;
                }
              }
            });
          }
        }
        for (const RatingPair& q : p_.pairs) {
          if (threads_ > 1) break;
          const size_t a = size_t(q.climber), d = c_ + size_t(q.route);
          double dz = 0, w = 0;
          PairTerms(q, kk, b_, (*x)[a] - (*x)[d], &dz, &w);
          const size_t i = side == 0 ? a : d;
          g[i] += side == 0 ? dz : -dz;
          h[i] += w;
        }
        for (size_t i = lo; i < hi; ++i) {
          (*x)[i] -= std::clamp(g[i] / h[i], -kMaxCoordinateStep, kMaxCoordinateStep);
        }
      }
    }
  }

  // The session offset's gradient and second derivative of the games (its
  // prior not included) at x.
  void OffsetDerivatives(const std::vector<double>& x, double* g, double* h) const {
    newton::OffsetDerivatives(p_.pairs, k_.logit_per_unit, b_, x, c_, g, h);
  }
  void set_offset(double b) { b_ = b; }
  double offset() const { return b_; }

  const std::vector<double>& h() const { return h_; }
  const std::vector<double>& diag() const { return diag_; }

 private:
  const RatingProblem& p_;
  const RatingParams& k_;
  const double m_;
  double b_;
  const size_t c_, r_;
  int threads_ = 1;
  // With threads: each route's first pair (r_ + 1), each climber's pairs in
  // pair order (CSR), the pairs' gradient terms.
  std::vector<size_t> route_start_, climber_start_;
  std::vector<uint32_t> climber_pairs_;
  std::vector<double> dz_;
  newton::RoutePriors routes_;
  std::vector<double> h_, diag_;
};

// Exact marginal variances: S = D_r - B^T D_c^-1 B (dense), S = L L^T,
// W = L^-1; var(d_r) = sum_k W_kr^2; var(a_c) = 1/H_cc + |W b_c|^2 / H_cc^2.
Status ExactVariances(const RatingProblem& p, const std::vector<double>& h,
                      const std::vector<double>& diag, RatingFit* fit) {
  const size_t c_n = size_t(p.num_climbers), r_n = size_t(p.num_routes());
  std::vector<size_t> start, idx;
  newton::PairsByClimber(c_n, p.pairs, &start, &idx);  // a climber's pairs in route order
  std::vector<double> s(r_n * r_n, 0);
  for (size_t r = 0; r < r_n; ++r) s[r * r_n + r] = diag[c_n + r];
  for (size_t c = 0; c < c_n; ++c) {
    const double inv = 1 / diag[c];
    for (size_t u = start[c]; u < start[c + 1]; ++u) {
      const size_t i = idx[u];
      const size_t ri = size_t(p.pairs[i].route);
      for (size_t v = start[c]; v < start[c + 1]; ++v) {
        const size_t j = idx[v];
        s[ri * r_n + size_t(p.pairs[j].route)] -= h[i] * h[j] * inv;
      }
    }
  }
  std::vector<double> w;
  SB_RETURN_IF_ERROR(newton::SchurVariances(&s, r_n, &w, &fit->difficulty_sd));
  std::vector<double> wb(r_n);
  for (size_t c = 0; c < c_n; ++c) {
    std::fill(wb.begin(), wb.end(), 0.0);
    size_t lowest = r_n;
    for (size_t u = start[c]; u < start[c + 1]; ++u) {
      const size_t i = idx[u];
      const size_t r = size_t(p.pairs[i].route);
      lowest = std::min(lowest, r);
      for (size_t row = r; row < r_n; ++row) wb[row] += w[row * r_n + r] * h[i];
    }
    double q = 0;
    for (size_t row = lowest; row < r_n; ++row) q += wb[row] * wb[row];
    fit->ability_sd[c] = std::sqrt(1 / diag[c] + q / (diag[c] * diag[c]));
  }
  return Status::Ok();
}

void ApproximateVariances(const RatingProblem& p, const std::vector<double>& h,
                          const std::vector<double>& diag, RatingFit* fit) {
  const size_t c_n = size_t(p.num_climbers), r_n = size_t(p.num_routes());
  std::vector<double> rp(diag.begin() + long(c_n), diag.end());
  std::vector<double> cp(diag.begin(), diag.begin() + long(c_n));
  for (size_t i = 0; i < p.pairs.size(); ++i) {
    const size_t c = size_t(p.pairs[i].climber), r = size_t(p.pairs[i].route);
    rp[r] -= h[i] * h[i] / diag[c];
    cp[c] -= h[i] * h[i] / diag[c_n + r];
  }
  for (size_t r = 0; r < r_n; ++r) fit->difficulty_sd[r] = std::sqrt(1 / rp[r]);
  for (size_t c = 0; c < c_n; ++c) fit->ability_sd[c] = std::sqrt(1 / cp[c]);
}

}  // namespace

const char* TickOutcomeName(TickOutcome o) {
  switch (o) {
    case TickOutcome::kFlash:
      return "flash";
    case TickOutcome::kSend:
      return "send";
    case TickOutcome::kAttempt:
      return "attempt";
  }
  return "flash";
}

Result<TickOutcome> ParseTickOutcome(std::string_view text, std::string_view field) {
  for (TickOutcome o : {TickOutcome::kFlash, TickOutcome::kSend, TickOutcome::kAttempt}) {
    if (text == TickOutcomeName(o)) return o;
  }
  return Status::InvalidInput(std::string(field) + ": expected flash, send or attempt, got '" +
                              std::string(text) + "'");
}

const char* RatingModelName(RatingModel m) {
  return m == RatingModel::kSession ? "session" : "tries";
}

Result<RatingModel> ParseRatingModel(std::string_view text, std::string_view field) {
  if (text == "tries") return RatingModel::kTries;
  if (text == "session") return RatingModel::kSession;
  return Status::InvalidInput(std::string(field) + ": expected tries or session, got '" +
                              std::string(text) + "'");
}

Result<Games> TickGamesFor(RatingModel model, TickOutcome outcome, std::optional<int> attempts) {
  SB_ASSIGN_OR_RETURN(Games g, TickGames(outcome, attempts));
  if (model == RatingModel::kTries) return g;
  switch (outcome) {
    case TickOutcome::kFlash:
      return Games{1, 0, 1, 0};
    case TickOutcome::kSend:
      return Games{0, 1, 1, 0};
    case TickOutcome::kAttempt:
      return Games{0, 1, 0, 1};
  }
  return Status::Internal("ratings: unknown outcome");
}

SendChances PredictSend(const RatingParams& params, RatingModel model, double session_offset,
                        double session_tries, double ability, double difficulty) {
  const double z = params.logit_per_unit * (ability - difficulty);
  SendChances out;
  out.p_flash = Sigmoid(z);
  if (model == RatingModel::kSession) {
    out.p_send = Sigmoid(z + session_offset);
  } else {
    // 1 - (1 - p)^T with 1 - p = s(-z), in logs for tails.
    const double t = std::max(1.0, session_tries);
    out.p_send = -std::expm1(-t * Softplus(z));
  }
  return out;
}

Result<Games> TickGames(TickOutcome outcome, std::optional<int> attempts) {
  if (attempts && (*attempts < 1 || *attempts > kMaxTickAttempts)) {
    return Status::InvalidInput("attempts: expected 1 to " + std::to_string(kMaxTickAttempts) +
                                ", got " + std::to_string(*attempts));
  }
  switch (outcome) {
    case TickOutcome::kFlash:
      if (attempts && *attempts != 1) {
        return Status::InvalidInput("attempts: a flash is one try, got " +
                                    std::to_string(*attempts) + " (use send)");
      }
      return Games{1, 0};
    case TickOutcome::kSend: {
      const int n = attempts.value_or(kSendDefaultAttempts);
      return Games{1, n - 1};
    }
    case TickOutcome::kAttempt:
      return Games{0, attempts.value_or(1)};
  }
  return Status::Internal("ratings: unknown outcome");
}

RatingParams RatingParams::For(Discipline d) {
  RatingParams k;
  if (d == Discipline::kBouldering) {
    k.logit_per_unit = std::log(3.0);
    k.climber_sd = 3;
    k.setter_sd = 1;
    k.open_route_sd = 3;
    k.felt_sd = 1.5;
  } else {
    // One YDS unit is four letters; 2.1x harder per letter.
    k.logit_per_unit = 4 * std::log(2.1);
    // The bouldering values in logit terms (one V grade = ln 3 logit =
    // ln 3 / (4 ln 2.1) = 0.37 YDS units).
    const double v = std::log(3.0) / k.logit_per_unit;
    k.climber_sd = 3 * v;
    k.setter_sd = 1 * v;
    k.open_route_sd = 3 * v;
    k.felt_sd = 1.5 * v;
  }
  return k;
}

Status RatingParams::Validate() const {
  const std::pair<const char*, double> fields[] = {{"logit_per_unit", logit_per_unit},
                                                   {"climber_sd", climber_sd},
                                                   {"setter_sd", setter_sd},
                                                   {"open_route_sd", open_route_sd},
                                                   {"felt_sd", felt_sd}};
  for (const auto& [name, v] : fields) {
    if (!std::isfinite(v) || !(v > 0)) {
      return Status::InvalidInput(std::string("ratings: ") + name +
                                  ": expected a number > 0, got " + Num(v));
    }
  }
  return Status::Ok();
}

Status RatingProblem::Validate() const {
  const size_t r_n = setter.size();
  if (num_climbers < 0 || felt_sum.size() != r_n || felt_count.size() != r_n ||
      route_ticks.size() != r_n || climber_ticks.size() != size_t(num_climbers)) {
    return Status::InvalidInput("ratings: problem arrays of different sizes");
  }
  for (size_t i = 0; i < pairs.size(); ++i) {
    const RatingPair& q = pairs[i];
    if (q.climber < 0 || q.climber >= num_climbers || q.route < 0 || size_t(q.route) >= r_n) {
      return Status::InvalidInput("ratings: pair " + std::to_string(i) + ": index out of range");
    }
    if (q.wins < 0 || q.losses < 0 || q.session_wins < 0 || q.session_losses < 0 ||
        q.wins + q.losses + q.session_wins + q.session_losses == 0) {
      return Status::InvalidInput("ratings: pair " + std::to_string(i) + ": no games");
    }
    if (i > 0 &&
        std::pair(pairs[i - 1].route, pairs[i - 1].climber) >= std::pair(q.route, q.climber)) {
      return Status::InvalidInput("ratings: pairs not sorted by (route, climber) or repeated");
    }
  }
  for (size_t r = 0; r < r_n; ++r) {
    if ((setter[r] && !std::isfinite(*setter[r])) || !std::isfinite(felt_sum[r]) ||
        felt_count[r] < 0) {
      return Status::InvalidInput("ratings: route " + std::to_string(r) + ": bad grade data");
    }
  }
  return Status::Ok();
}

void RatingProblemBuilder::EnsureClimbers(int n) {
  if (n > p_.num_climbers) {
    p_.num_climbers = n;
    p_.climber_ticks.resize(size_t(n), 0);
  }
}

void RatingProblemBuilder::EnsureRoutes(int n) {
  if (n > p_.num_routes()) {
    p_.setter.resize(size_t(n));
    p_.felt_sum.resize(size_t(n), 0);
    p_.felt_count.resize(size_t(n), 0);
    p_.route_ticks.resize(size_t(n), 0);
  }
}

void RatingProblemBuilder::AddTick(int climber, int route, Games games,
                                   std::optional<double> felt) {
  EnsureClimbers(climber + 1);
  EnsureRoutes(route + 1);
  entries_.push_back({(uint64_t(uint32_t(route)) << 32) | uint32_t(climber), games.wins,
                      games.losses, games.session_wins, games.session_losses});
  ++p_.climber_ticks[size_t(climber)];
  ++p_.route_ticks[size_t(route)];
  if (felt) {
    p_.felt_sum[size_t(route)] += *felt;
    ++p_.felt_count[size_t(route)];
  }
}

void RatingProblemBuilder::SetSetterGrade(int route, double value) {
  EnsureRoutes(route + 1);
  p_.setter[size_t(route)] = value;
}

RatingProblem RatingProblemBuilder::Build() {
  // Counting sort by route (routes are dense indices), then each route's
  // few entries by climber: linear in the ticks, where one sort of all
  // 5 million took a third of the fit.
  const size_t r_n = size_t(p_.num_routes());
  std::vector<size_t> start(r_n + 1, 0);
  for (const Entry& e : entries_) ++start[size_t(e.key >> 32) + 1];
  for (size_t r = 0; r < r_n; ++r) start[r + 1] += start[r];
  // Uninitialised (every slot is written below): no pass of zeros over
  // millions of entries.
  std::unique_ptr<Entry[]> sorted(new Entry[entries_.size()]);
  const size_t n_entries = entries_.size();
  {
    std::vector<size_t> fill(start.begin(), start.end() - 1);
    for (const Entry& e : entries_) sorted[fill[size_t(e.key >> 32)]++] = e;
  }
  entries_.clear();
  entries_.shrink_to_fit();
  for (size_t r = 0; r < r_n; ++r) {
    std::sort(sorted.get() + start[r], sorted.get() + start[r + 1],
              [](const Entry& a, const Entry& b) { return a.key < b.key; });
  }
  p_.pairs.clear();
  p_.pairs.reserve(n_entries);
  for (size_t k = 0; k < n_entries; ++k) {
    const Entry& e = sorted[k];
    if (!p_.pairs.empty()) {
      RatingPair& last = p_.pairs.back();
      if (((uint64_t(uint32_t(last.route)) << 32) | uint32_t(last.climber)) == e.key) {
        last.wins += e.wins;
        last.losses += e.losses;
        last.session_wins += e.session_wins;
        last.session_losses += e.session_losses;
        continue;
      }
    }
    p_.pairs.push_back({int32_t(e.key & 0xffffffffu), int32_t(e.key >> 32), e.wins, e.losses,
                        e.session_wins, e.session_losses});
  }
  p_.pairs.shrink_to_fit();
  p_.session_tries = tries_n_ > 0 ? tries_sum_ / double(tries_n_) : 0.0;
  RatingProblem out = std::move(p_);
  p_ = RatingProblem();
  tries_sum_ = 0;
  tries_n_ = 0;
  return out;
}

Result<RatingFit> FitRatings(const RatingProblem& problem, const RatingParams& params,
                             const RatingFitOptions& options) {
  SB_RETURN_IF_ERROR(params.Validate());
  SB_RETURN_IF_ERROR(problem.Validate());
  const size_t c_n = size_t(problem.num_climbers), r_n = size_t(problem.num_routes());
  SB_ASSIGN_OR_RETURN(const bool exact, newton::UseExactIntervals(options.intervals, r_n));
  RatingFit fit;
  fit.prior_mean = PriorMean(problem);
  fit.model = problem.model;
  fit.session_tries = problem.session_tries;
  const bool session = problem.model == RatingModel::kSession;
  const bool estimate_offset = session && !options.session_offset;
  const double m = fit.prior_mean;
  const int threads = options.threads > 0 ? options.threads
                                          : int(std::max(1u, std::thread::hardware_concurrency()));
  Solver solver(problem, params, m,
                session ? options.session_offset.value_or(kSessionOffsetPriorMean) : 0.0,
                problem.pairs.size() < size_t(UINT32_MAX) ? threads : 1);
  std::vector<double> x(c_n + r_n);
  const RatingFit* warm = options.warm_start;
  for (size_t c = 0; c < c_n; ++c) x[c] = m;
  for (size_t r = 0; r < r_n; ++r) x[c_n + r] = problem.setter[r].value_or(m);
  if (warm != nullptr && warm->ability.size() <= c_n && warm->difficulty.size() <= r_n) {
    // The last fit's values; climbers and routes added since start from
    // their priors and settle in one coordinate round.
    std::copy(warm->ability.begin(), warm->ability.end(), x.begin());
    std::copy(warm->difficulty.begin(), warm->difficulty.end(), x.begin() + long(c_n));
    if (warm->ability.size() < c_n || warm->difficulty.size() < r_n) {
      solver.CoordinatePasses(&x, 1);
    }
  } else {
    solver.CoordinatePasses(&x, kCoordinateRounds);
  }
  // The session model's offset b: blocks alternate with the rest
  // (newton::MinimizeNewtonWithOffset).
  newton::NewtonStats st;
  const bool converged =
      newton::MinimizeNewtonWithOffset(solver, &x, options.gradient_tolerance,
                                       options.max_newton_iterations, estimate_offset, &st);
  fit.newton_iterations = st.newton_iterations;
  fit.cg_iterations = st.cg_iterations;
  fit.gradient_max = st.gradient_max;
  fit.session_offset = session ? solver.offset() : 0.0;
  if (!converged) {
    return Status::Internal("ratings: Newton did not converge (largest gradient " +
                            Num(fit.gradient_max) + ")");
  }
  fit.ability.assign(x.begin(), x.begin() + long(c_n));
  fit.difficulty.assign(x.begin() + long(c_n), x.end());
  fit.ability_sd.resize(c_n);
  fit.difficulty_sd.resize(r_n);
  fit.exact_intervals = exact;
  if (exact) {
    SB_RETURN_IF_ERROR(ExactVariances(problem, solver.h(), solver.diag(), &fit));
  } else {
    ApproximateVariances(problem, solver.h(), solver.diag(), &fit);
  }
  return fit;
}

Result<RouteEvidence> EvidenceOf(const RatingProblem& problem, const RatingParams& params,
                                 const RatingFit& fit, int route) {
  if (route < 0 || route >= problem.num_routes()) {
    return Status::InvalidInput("ratings: route index " + std::to_string(route) + " out of range");
  }
  RouteEvidence e;
  const auto& s = problem.setter[size_t(route)];
  e.prior_mean = s ? *s : fit.prior_mean;
  e.prior_sd = s ? params.setter_sd : params.open_route_sd;
  e.felt_sum = problem.felt_sum[size_t(route)];
  e.felt_count = problem.felt_count[size_t(route)];
  e.ticks = problem.route_ticks[size_t(route)];
  auto lo = std::lower_bound(problem.pairs.begin(), problem.pairs.end(), route,
                             [](const RatingPair& q, int r) { return q.route < r; });
  for (auto it = lo; it != problem.pairs.end() && it->route == route; ++it) e.pairs.push_back(*it);
  return e;
}

void AddTickTo(RouteEvidence* e, int climber, Games games, std::optional<double> felt) {
  ++e->ticks;
  if (felt) {
    e->felt_sum += *felt;
    ++e->felt_count;
  }
  for (RatingPair& q : e->pairs) {
    if (q.climber == climber) {
      q.wins += games.wins;
      q.losses += games.losses;
      q.session_wins += games.session_wins;
      q.session_losses += games.session_losses;
      return;
    }
  }
  e->pairs.push_back(
      {climber, 0, games.wins, games.losses, games.session_wins, games.session_losses});
}

Result<RouteRating> RateRoute(const RouteEvidence& e, const RatingFit& fit,
                              const RatingParams& params) {
  SB_RETURN_IF_ERROR(params.Validate());
  const double kk = params.logit_per_unit;
  const double b = fit.session_offset;
  const double pp = 1 / (e.prior_sd * e.prior_sd);
  const double pf = 1 / (params.felt_sd * params.felt_sd);
  auto ability = [&](int c) {
    return size_t(c) < fit.ability.size() ? fit.ability[size_t(c)] : fit.prior_mean;
  };
  auto ability_sd = [&](int c) {
    return size_t(c) < fit.ability_sd.size() ? fit.ability_sd[size_t(c)] : params.climber_sd;
  };
  auto objective = [&](double d) {
    double f = 0.5 * pp * (d - e.prior_mean) * (d - e.prior_mean) +
               0.5 * pf * (e.felt_count * d * d - 2 * d * e.felt_sum);
    for (const RatingPair& q : e.pairs) {
      const double z = kk * (ability(q.climber) - d);
      f += q.wins * Softplus(-z) + q.losses * Softplus(z);
      if (q.session_wins | q.session_losses) {
        f += q.session_wins * Softplus(-(z + b)) + q.session_losses * Softplus(z + b);
      }
    }
    return f;
  };
  RouteRating out;
  double d = e.prior_mean;
  double f = objective(d);
  for (int it = 0; it < 100; ++it) {
    double g = pp * (d - e.prior_mean) + pf * (e.felt_count * d - e.felt_sum);
    double h = pp + pf * e.felt_count;
    for (const RatingPair& q : e.pairs) {
      const double pr = Sigmoid(kk * (ability(q.climber) - d));
      const double n = double(q.wins) + double(q.losses);
      g -= kk * (n * pr - q.wins);
      h += kk * kk * n * pr * (1 - pr);
      if (q.session_wins | q.session_losses) {
        const double ps = Sigmoid(kk * (ability(q.climber) - d) + b);
        const double ns = double(q.session_wins) + double(q.session_losses);
        g -= kk * (ns * ps - q.session_wins);
        h += kk * kk * ns * ps * (1 - ps);
      }
    }
    if (std::abs(g) <= 1e-12 * (1 + std::abs(d) * h)) break;
    ++out.newton_iterations;
    const double step = -g / h;
    double t = 1, f_new = f, d_new = d;
    for (int half = 0; half < 60; ++half, t *= 0.5) {
      d_new = d + t * step;
      f_new = objective(d_new);
      if (f_new <= f + 1e-4 * t * g * step + 1e-14 * std::abs(f)) break;
    }
    d = d_new;
    f = f_new;
  }
  double prec = pp + pf * e.felt_count;
  for (const RatingPair& q : e.pairs) {
    const double pr = Sigmoid(kk * (ability(q.climber) - d));
    const double n = double(q.wins) + double(q.losses);
    double h = kk * kk * n * pr * (1 - pr);
    if (q.session_wins | q.session_losses) {
      const double ps = Sigmoid(kk * (ability(q.climber) - d) + b);
      const double ns = double(q.session_wins) + double(q.session_losses);
      h += kk * kk * ns * ps * (1 - ps);
    }
    const double sd = ability_sd(q.climber);
    if (h > 0) prec += 1 / (1 / h + sd * sd);
  }
  out.value = d;
  out.sd = std::sqrt(1 / prec);
  return out;
}

}  // namespace sb::grades
