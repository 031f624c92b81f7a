#include "chaos/search.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <memory>
#include <thread>

#include "base/number.h"
#include "base/text.h"
#include "chaos/tokens.h"

// GCC vector types as by-value arguments of inline templates: no ABI crosses
// a library boundary here.
#pragma GCC diagnostic ignored "-Wpsabi"

namespace sb::chaos {

namespace {

// ---------------------------------------------------------------------------
// Two ICs per step on the lanes of an SSE2 vector (a wider GCC vector is split
// into scalar compares without AVX), with the step templates of ode.h (as the
// landscape kernel does): the same float64 operations in the same order as
// chaos::Trajectory, so every lane is bit-identical to the scalar result
// (the build has -ffp-contract=off).

constexpr int kLanes = 2;
typedef double RawV __attribute__((vector_size(kLanes * 8)));

struct V {
  RawV v;
  V() = default;
  V(double s) : v(s - RawV{}) {}  // NOLINT: broadcast, as T(2.0) in the templates
  V(RawV r) : v(r) {}             // NOLINT
};
inline V operator+(const V& a, const V& b) { return V(a.v + b.v); }
inline V operator-(const V& a, const V& b) { return V(a.v - b.v); }
inline V operator*(const V& a, const V& b) { return V(a.v * b.v); }

struct LorenzV {
  V p0, p1, p2;
  void operator()(const V& x, const V& y, const V& z, V& dx, V& dy, V& dz) const {
    LorenzDeriv<V>(p0, p1, p2, x, y, z, dx, dy, dz);
  }
};
struct RosslerV {
  V p0, p1, p2;
  void operator()(const V& x, const V& y, const V& z, V& dx, V& dy, V& dz) const {
    RosslerDeriv<V>(p0, p1, p2, x, y, z, dx, dy, dz);
  }
};

typedef long long RawM __attribute__((vector_size(kLanes * 8)));

// Squared masked distance from lanes (x, y, z) to one reference point, summed
// x, y, z as MaskedDist2 (0.0 + t*t == t*t exactly, so the leading 0 is dropped).
template <unsigned M>
inline RawV Dist2(const RawV& x, const RawV& y, const RawV& z, double rx, double ry, double rz) {
  RawV d = RawV{};
  bool first = true;
  if constexpr ((M & 1u) != 0) {
    RawV t = x - rx;
    d = t * t;
    first = false;
  }
  if constexpr ((M & 2u) != 0) {
    RawV t = y - ry;
    d = first ? t * t : d + t * t;
    first = false;
  }
  if constexpr ((M & 4u) != 0) {
    RawV t = z - rz;
    d = first ? t * t : d + t * t;
  }
  return d;
}

// Up to this many reference points the nearest neighbours of all lanes are
// found by one brute-force pass (vectorised across lanes); beyond, through
// the shared NearestIndex. NearestIndex itself is brute force up to 64
// points, and both are exact (least distance, ties to the lowest index).
constexpr int kLaneBruteForceMax = 128;

// The reference points split by axis, for the lane pass.
struct RefSoA {
  std::vector<double> x, y, z;
};

// Integrates kLanes ICs: traj[l * n + j] = point j of lane l. When `ref` is
// given, also near[l * n + j] = the nearest reference index (brute force).
template <unsigned M, typename F>
void RunLanes(const F& f, IntegratorKind integrator, double h, const State* ics, int skip, int n,
              const RefSoA* ref, State* traj, int* near) {
  alignas(16) double c[3][kLanes];
  for (int l = 0; l < kLanes; ++l) {
    for (int a = 0; a < 3; ++a) c[a][l] = ics[l][a];
  }
  V x, y, z;
  std::memcpy(&x.v, c[0], sizeof(RawV));
  std::memcpy(&y.v, c[1], sizeof(RawV));
  std::memcpy(&z.v, c[2], sizeof(RawV));
  const V hv(h), half(h / 2.0), sixth(h / 6.0);
  auto step = [&] {
    if (integrator == IntegratorKind::kRk4) {
      Rk4Step<V>(f, hv, half, sixth, x, y, z);
    } else {
      Rkf45Step<V>(f, hv, x, y, z);
    }
  };
  for (int s = 0; s < skip; ++s) step();
  const RawV one = V(1.0).v;
  for (int j = 0; j < n; ++j) {
    step();
    std::memcpy(c[0], &x.v, sizeof(RawV));
    std::memcpy(c[1], &y.v, sizeof(RawV));
    std::memcpy(c[2], &z.v, sizeof(RawV));
    for (int l = 0; l < kLanes; ++l) {
      traj[static_cast<size_t>(l) * n + j] = {c[0][l], c[1][l], c[2][l]};
    }
    if (!ref) continue;
    const double* rx = ref->x.data();
    const double* ry = ref->y.data();
    const double* rz = ref->z.data();
    RawV best = Dist2<M>(x.v, y.v, z.v, rx[0], ry[0], rz[0]);
    RawV best_k = RawV{}, kv = RawV{};
    for (int k = 1; k < n; ++k) {
      kv = kv + one;  // == k exactly
      RawV d = Dist2<M>(x.v, y.v, z.v, rx[k], ry[k], rz[k]);
      // Strict: ties keep the lowest index. Bitwise selects (plain SSE2;
      // the ?: form is split into scalar branches without AVX).
      RawM lt = d < best;
      best = reinterpret_cast<RawV>((reinterpret_cast<RawM>(d) & lt) |
                                    (reinterpret_cast<RawM>(best) & ~lt));
      best_k = reinterpret_cast<RawV>((reinterpret_cast<RawM>(kv) & lt) |
                                      (reinterpret_cast<RawM>(best_k) & ~lt));
    }
    for (int l = 0; l < kLanes; ++l)
      near[static_cast<size_t>(l) * n + j] = static_cast<int>(best_k[l]);
  }
}

template <unsigned M>
void RunSystem(const System& sys, IntegratorKind integrator, double h, const State* ics, int skip,
               int n, const RefSoA* ref, State* traj, int* near) {
  const auto& q = sys.params;
  if (sys.kind == SystemKind::kLorenz) {
    RunLanes<M>(LorenzV{V(q[0]), V(q[1]), V(q[2])}, integrator, h, ics, skip, n, ref, traj, near);
  } else {
    RunLanes<M>(RosslerV{V(q[0]), V(q[1]), V(q[2])}, integrator, h, ics, skip, n, ref, traj, near);
  }
}

// Dispatches on the mask (a template argument, so the distance has no branches).
void RunMasked(DimMask mask, const System& sys, IntegratorKind integrator, double h,
               const State* ics, int skip, int n, const RefSoA* ref, State* traj, int* near) {
  switch (mask) {
    case 1:
      return RunSystem<1>(sys, integrator, h, ics, skip, n, ref, traj, near);
    case 2:
      return RunSystem<2>(sys, integrator, h, ics, skip, n, ref, traj, near);
    case 3:
      return RunSystem<3>(sys, integrator, h, ics, skip, n, ref, traj, near);
    case 4:
      return RunSystem<4>(sys, integrator, h, ics, skip, n, ref, traj, near);
    case 5:
      return RunSystem<5>(sys, integrator, h, ics, skip, n, ref, traj, near);
    case 6:
      return RunSystem<6>(sys, integrator, h, ics, skip, n, ref, traj, near);
    default:
      return RunSystem<7>(sys, integrator, h, ics, skip, n, ref, traj, near);
  }
}

bool Finite(const State& s) {
  return std::isfinite(s[0]) && std::isfinite(s[1]) && std::isfinite(s[2]);
}

std::string IcText(const State& s) {
  std::string out = "(";
  out += FormatDouble(s[0], 17);
  out += ", ";
  out += FormatDouble(s[1], 17);
  out += ", ";
  out += FormatDouble(s[2], 17);
  return out + ")";
}

constexpr uint32_t kDiverged = 1u << 31;

}  // namespace

Result<SearchPlane> ParseSearchPlane(std::string_view s) {
  std::string l = ToLower(s);
  if (l == "xy") return SearchPlane::kXY;
  if (l == "xz") return SearchPlane::kXZ;
  if (l == "yz") return SearchPlane::kYZ;
  if (l == "cube") return SearchPlane::kCube;
  return Status::InvalidInput("search-plane: unknown value \"" + std::string(s) +
                              "\" (xy, xz, yz or cube)");
}

const char* SearchPlaneName(SearchPlane p) {
  switch (p) {
    case SearchPlane::kXY:
      return "xy";
    case SearchPlane::kXZ:
      return "xz";
    case SearchPlane::kYZ:
      return "yz";
    case SearchPlane::kCube:
      return "cube";
  }
  return "?";
}

Status SearchGrid::Validate() const {
  if (!(std::isfinite(spacing) && spacing > 0)) {
    return Status::InvalidInput("search-spacing: must be a finite number > 0");
  }
  if (radius < 0) return Status::InvalidInput("search-radius: must be >= 0");
  double side = 2.0 * radius + 1.0;
  double box = plane == SearchPlane::kCube ? side * side * side : side * side;
  if (box > static_cast<double>(kMaxSearchBox)) {
    return Status::InvalidInput("search-radius: " + std::to_string(radius) + " spans " +
                                std::to_string(static_cast<uint64_t>(box)) +
                                " grid points, more than " + std::to_string(kMaxSearchBox) +
                                " (lower the radius or raise the spacing)");
  }
  return Status::Ok();
}

std::vector<std::array<int, 3>> SearchOffsets(const SearchGrid& grid) {
  int axes[3] = {0, 1, 2};
  int dims = 3;
  switch (grid.plane) {
    case SearchPlane::kXY:
      axes[0] = 0, axes[1] = 1, dims = 2;
      break;
    case SearchPlane::kXZ:
      axes[0] = 0, axes[1] = 2, dims = 2;
      break;
    case SearchPlane::kYZ:
      axes[0] = 1, axes[1] = 2, dims = 2;
      break;
    case SearchPlane::kCube:
      break;
  }
  const int r = grid.radius;
  const long r2 = static_cast<long>(r) * r;
  std::vector<std::array<int, 3>> out;
  int u[3] = {-r, -r, dims == 3 ? -r : 0};
  const int wmax = dims == 3 ? r : 0;
  for (u[2] = dims == 3 ? -r : 0; u[2] <= wmax; ++u[2]) {
    for (u[1] = -r; u[1] <= r; ++u[1]) {
      for (u[0] = -r; u[0] <= r; ++u[0]) {
        long d2 = static_cast<long>(u[0]) * u[0] + static_cast<long>(u[1]) * u[1] +
                  static_cast<long>(u[2]) * u[2];
        if (d2 > r2) continue;
        std::array<int, 3> o = {0, 0, 0};
        for (int d = 0; d < dims; ++d) o[axes[d]] = u[d];
        out.push_back(o);
      }
    }
  }
  auto norm2 = [](const std::array<int, 3>& o) {
    return static_cast<long>(o[0]) * o[0] + static_cast<long>(o[1]) * o[1] +
           static_cast<long>(o[2]) * o[2];
  };
  std::sort(out.begin(), out.end(), [&](const auto& a, const auto& b) {
    long na = norm2(a), nb = norm2(b);
    return na != nb ? na < nb : a < b;
  });
  return out;
}

// ---------------------------------------------------------------------------

struct IcEvaluator::Impl {
  VaryParams params;
  int n = 0;
  std::vector<State> reference;
  std::unique_ptr<NearestIndex> index;  // Euclidean mapping only
  RefSoA ref_soa;                       // filled when the lane pass is used
  bool lane_nearest = false;            // Euclidean and n <= kLaneBruteForceMax
  std::vector<int> move_class;          // for max_repeat (empty when off)
  std::unique_ptr<ConstraintChecker> checker;

  // One lane's mapping, exactly as MapTrajectory (Euclidean branch with the
  // shared index; Dabby through MapTrajectory itself). `near`, when given,
  // holds each point's nearest reference index already.
  void Map(const State* var, const int* near, int* k) const;
};

void IcEvaluator::Impl::Map(const State* var, const int* near, int* k) const {
  const MappingOptions& o = params.mapping;
  if (o.kind != MappingKind::kEuclidean) {
    std::vector<State> v(var, var + n);
    std::vector<int> m = MapTrajectory(reference, v, o, move_class);
    std::copy(m.begin(), m.end(), k);
    return;
  }
  auto nearest = [&](int j) { return near ? near[j] : index->Nearest(var[j]); };
  if (o.max_repeat <= 0) {
    for (int j = 0; j < n; ++j) k[j] = nearest(j);
    return;
  }
  auto cls = [&](int i) { return move_class.empty() ? i : move_class[i]; };
  int run_class = -1, run_len = 0;
  auto allowed = [&](int cand) { return cls(cand) != run_class || run_len < o.max_repeat; };
  for (int j = 0; j < n; ++j) {
    int best = nearest(j);
    if (!allowed(best) && near) {
      // Brute force: the first allowed candidate in (distance, index) order,
      // which is what the widening KNearest below finds.
      const DimMask mask = o.mask;
      int chosen = -1;
      double chosen_d = 0;
      for (int c = 0; c < n; ++c) {
        if (!allowed(c)) continue;
        double d = MaskedDist2(var[j], reference[c], mask);
        if (chosen < 0 || d < chosen_d) {
          chosen = c;
          chosen_d = d;
        }
      }
      if (chosen >= 0) best = chosen;
    } else if (!allowed(best)) {
      int chosen = best;
      for (int want = 8;; want *= 4) {
        std::vector<int> cands = index->KNearest(var[j], want);
        auto it = std::find_if(cands.begin(), cands.end(), allowed);
        if (it != cands.end()) {
          chosen = *it;
          break;
        }
        if (cands.size() >= reference.size()) break;
      }
      best = chosen;
    }
    k[j] = best;
    if (cls(best) == run_class) {
      ++run_len;
    } else {
      run_class = cls(best);
      run_len = 1;
    }
  }
}

IcEvaluator::IcEvaluator() : impl_(std::make_unique<Impl>()) {}
IcEvaluator::IcEvaluator(IcEvaluator&&) noexcept = default;
IcEvaluator& IcEvaluator::operator=(IcEvaluator&&) noexcept = default;
IcEvaluator::~IcEvaluator() = default;

Result<IcEvaluator> IcEvaluator::Make(const std::vector<InputRoute>& inputs,
                                      const VaryParams& params, const MoveFacts& facts,
                                      const Constraints& constraints,
                                      const std::vector<bool>& is_match) {
  SB_RETURN_IF_ERROR(params.Validate());
  SB_RETURN_IF_ERROR(CheckInputKinds(inputs));
  std::vector<VariedMove> prepared = PrepareMoves(inputs, is_match);
  if (prepared.empty()) return Status::InvalidInput("no moves to vary");
  if (!is_match.empty() && is_match.size() != prepared.size()) {
    return Status::InvalidInput("match flags: one per input move expected");
  }
  auto checker =
      ConstraintChecker::Make(prepared, inputs, facts, constraints, params.mapping.max_repeat);
  if (!checker.ok()) return checker.status();
  IcEvaluator e;
  Impl& m = *e.impl_;
  m.params = params;
  m.n = static_cast<int>(prepared.size());
  m.reference =
      Trajectory(params.system, params.integrator, params.step, params.ref_ic, params.skip, m.n);
  for (const State& s : m.reference) {
    if (!Finite(s)) {
      return Status::InvalidInput(
          "the reference trajectory diverged (non-finite state); choose a smaller step, other "
          "parameters or initial conditions");
    }
  }
  if (params.mapping.kind == MappingKind::kEuclidean) {
    m.index = std::make_unique<NearestIndex>(m.reference, params.mapping.mask);
    m.lane_nearest =
        m.n <= kLaneBruteForceMax && params.mapping.mask >= 1 && params.mapping.mask <= 7;
    if (m.lane_nearest) {
      for (const State& s : m.reference) {
        m.ref_soa.x.push_back(s[0]);
        m.ref_soa.y.push_back(s[1]);
        m.ref_soa.z.push_back(s[2]);
      }
    }
  }
  if (params.mapping.max_repeat > 0) m.move_class = RepeatClasses(prepared, AreTokens(inputs));
  m.checker = std::make_unique<ConstraintChecker>(std::move(*checker));
  return e;
}

const ConstraintChecker& IcEvaluator::checker() const { return *impl_->checker; }
int IcEvaluator::size() const { return impl_->n; }

void IcEvaluator::Evaluate(const State* ics, size_t count, uint32_t* failures, int* k_out) const {
  const Impl& m = *impl_;
  const int n = m.n;
  const VaryParams& p = m.params;
  std::vector<State> traj(static_cast<size_t>(kLanes) * n);
  std::vector<int> near(m.lane_nearest ? static_cast<size_t>(kLanes) * n : 0);
  std::vector<int> k(n);
  const uint32_t all = m.checker->requested() ? m.checker->requested() : kDiverged;
  for (size_t base = 0; base < count; base += kLanes) {
    State lane_ics[kLanes];
    const size_t lanes = std::min<size_t>(kLanes, count - base);
    // Lanes past the end repeat the last IC; their results are dropped.
    for (size_t l = 0; l < kLanes; ++l) lane_ics[l] = ics[base + std::min(l, lanes - 1)];
    RunMasked(p.mapping.mask, p.system, p.integrator, p.step, lane_ics, p.skip, n,
              m.lane_nearest ? &m.ref_soa : nullptr, traj.data(), near.data());
    for (size_t l = 0; l < lanes; ++l) {
      const State* var = traj.data() + l * n;
      int* kk = k_out ? k_out + (base + l) * n : k.data();
      bool finite = Finite(ics[base + l]);
      for (int j = 0; j < n && finite; ++j) finite = Finite(var[j]);
      if (!finite) {
        failures[base + l] = all;
        std::fill(kk, kk + n, -1);
        continue;
      }
      m.Map(var, m.lane_nearest ? near.data() + l * n : nullptr, kk);
      failures[base + l] = m.checker->Failures(kk);
    }
  }
}

void IcEvaluator::EvaluateParallel(const State* ics, size_t count, uint32_t* failures,
                                   int threads) const {
  // Below a few lane groups per thread, starting threads costs more than it saves.
  constexpr size_t kMinPerThread = 16;
  size_t t = std::max(1, threads);
  t = std::min(t, std::max<size_t>(1, count / kMinPerThread));
  if (t <= 1) {
    Evaluate(ics, count, failures);
    return;
  }
  // Slices of whole lane groups.
  size_t per = (count + t - 1) / t;
  per = (per + kLanes - 1) / kLanes * kLanes;
  std::vector<std::thread> pool;
  for (size_t i = 1; i < t; ++i) {
    size_t b = std::min(count, i * per), e = std::min(count, (i + 1) * per);
    if (b < e) pool.emplace_back([=, this] { Evaluate(ics + b, e - b, failures + b); });
  }
  Evaluate(ics, std::min(count, per), failures);
  for (std::thread& th : pool) th.join();
}

// ---------------------------------------------------------------------------

namespace {

int ThreadCount(const SearchOptions& o) {
  int t = o.threads > 0 ? o.threads : static_cast<int>(std::thread::hardware_concurrency());
  return std::clamp(t, 1, 8);
}

State IcAt(const State& base, const std::array<int, 3>& o, double spacing) {
  State s = base;
  for (int a = 0; a < 3; ++a) {
    if (o[a] != 0) s[a] = base[a] + static_cast<double>(o[a]) * spacing;
  }
  return s;
}

}  // namespace

Result<SearchResult> SearchVariation(const std::vector<InputRoute>& inputs,
                                     const VaryParams& params, const MoveFacts& facts,
                                     const Constraints& constraints, const SearchGrid& grid,
                                     const std::vector<bool>& is_match,
                                     const SearchOptions& options) {
  SB_RETURN_IF_ERROR(grid.Validate());
  auto ev = IcEvaluator::Make(inputs, params, facts, constraints, is_match);
  if (!ev.ok()) return ev.status();
  const uint32_t requested = ev->requested();
  const uint32_t alt = ConstraintBit(Constraint::kAlternateHands);
  const std::vector<std::array<int, 3>> offsets = SearchOffsets(grid);
  const int threads = ThreadCount(options);

  // Batches grow from 64 candidates (the IC asked for and its neighbours
  // usually decide it) to 4096 (a full search amortises thread start-up).
  constexpr size_t kFirstBatch = 64, kMaxBatch = 4096;
  std::vector<State> ics;
  std::vector<uint32_t> fails;
  long found = -1, fallback = -1;  // offset indices
  std::array<long, kConstraintCount + 1> fail_count{};
  size_t evaluated = 0;
  for (size_t begin = 0, batch = kFirstBatch; begin < offsets.size() && found < 0;
       begin += batch, batch = std::min(batch * 2, kMaxBatch)) {
    const size_t end = std::min(offsets.size(), begin + batch);
    ics.resize(end - begin);
    fails.resize(end - begin);
    for (size_t i = begin; i < end; ++i)
      ics[i - begin] = IcAt(params.var_ic, offsets[i], grid.spacing);
    ev->EvaluateParallel(ics.data(), ics.size(), fails.data(), threads);
    for (size_t i = 0; i < ics.size(); ++i) {
      const uint32_t f = fails[i];
      ++evaluated;
      if (f == 0) {
        found = static_cast<long>(begin + i);
        break;
      }
      if (fallback < 0 && (requested & alt) && (f & ~alt) == 0) {
        fallback = static_cast<long>(begin + i);
      }
      for (int c = 0; c < kConstraintCount; ++c) fail_count[c] += (f >> c) & 1u;
      fail_count[kConstraintCount] += (f & kDiverged) != 0;
    }
  }

  const bool swap_hands = found < 0 && fallback >= 0;
  if (found < 0 && !swap_hands) {
    // The constraint failing most often; alternate-hands (which has the
    // hand-swap fallback) only when nothing else failed.
    int worst = -1;
    for (int c = 0; c < kConstraintCount; ++c) {
      if (!(requested & (1u << c)) || fail_count[c] == 0) continue;
      if ((1u << c) == alt) continue;
      if (worst < 0 || fail_count[c] > fail_count[worst]) worst = c;
    }
    if (worst < 0 && (requested & alt) &&
        fail_count[static_cast<int>(Constraint::kAlternateHands)]) {
      worst = static_cast<int>(Constraint::kAlternateHands);
    }
    char head[256];
    std::snprintf(head, sizeof head,
                  "no variation IC within %d grid steps (spacing %g, plane %s) of ", grid.radius,
                  grid.spacing, SearchPlaneName(grid.plane));
    std::string msg = head + IcText(params.var_ic);
    if (worst < 0) {
      msg += " has a finite trajectory";
      return Status::NotFound(msg);
    }
    msg += " meets every constraint: ";
    msg += ConstraintName(static_cast<Constraint>(worst));
    msg += " could not be met (failed most often";
    for (int c = 0; c < kConstraintCount; ++c) {
      if (!(requested & (1u << c))) continue;
      char part[96];
      std::snprintf(part, sizeof part, "; %s failed at %ld of %zu ICs",
                    ConstraintName(static_cast<Constraint>(c)), fail_count[c], evaluated);
      msg += part;
    }
    msg += ")";
    return Status::NotFound(msg);
  }

  const long chosen = found >= 0 ? found : fallback;
  SearchResult r;
  r.requested_ic = params.var_ic;
  r.offset = offsets[chosen];
  r.used_ic = IcAt(params.var_ic, r.offset, grid.spacing);
  double d2 = 0;
  for (int a = 0; a < 3; ++a)
    d2 += (r.used_ic[a] - r.requested_ic[a]) * (r.used_ic[a] - r.requested_ic[a]);
  r.distance = std::sqrt(d2);
  r.evaluated = static_cast<int>(evaluated);
  VaryParams used = params;
  used.var_ic = r.used_ic;
  auto v = Vary(inputs, used, is_match);
  if (!v.ok()) return v.status();
  r.variation = std::move(*v);
  int same_hand_at = -1;  // the one same-hand pair the kept ends' parity demands
  if (swap_hands) {
    r.hands_swapped = AlternateHands(&r.variation.moves, constraints.keep_start,
                                     constraints.keep_finish, &same_hand_at);
  }
  r.outcomes = ev->checker().Report(r.variation);
  auto swapped = [&](int j) {
    const std::vector<std::string>& notes = r.variation.moves[j].notes;
    return std::find(notes.begin(), notes.end(), "(hand swapped)") != notes.end();
  };
  for (ConstraintOutcome& o : r.outcomes) {
    // Both ends kept, of different parity: the one same-hand pair is the
    // price of keeping both (AlternateHands); not held, and said so.
    if (!o.held && o.constraint == Constraint::kAlternateHands && same_hand_at > 0) {
      o.detail += " only (the kept start's and finish's hands demand one same-hand pair)";
    } else if (!o.held) {
      return Status::Internal(std::string("search: the variation at the IC found fails ") +
                              ConstraintName(o.constraint) + " (" + o.detail + ")");
    }
    // An input's start or finish move with its hand swapped is not that
    // move any more (issue 22): not held, and the report says why.
    const int n = static_cast<int>(r.variation.moves.size());
    const int at = o.constraint == Constraint::kKeepStart    ? 0
                   : o.constraint == Constraint::kKeepFinish ? n - 1
                                                             : -1;
    if (at >= 0 && n > 0 && swapped(at)) {
      o.held = false;
      o.detail += ", but its hand was swapped to alternate hands";
    }
    if (o.constraint == Constraint::kAlternateHands && r.hands_swapped > 0) {
      o.detail += " after " + std::to_string(r.hands_swapped) + " hand swap" +
                  (r.hands_swapped > 1 ? "s" : "") +
                  " (no IC within the radius alternated by itself)";
    }
  }
  return r;
}

}  // namespace sb::chaos
