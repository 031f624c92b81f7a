#include "chaos/mapping.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <thread>

#include "base/text.h"

namespace sb::chaos {

Result<DimMask> ParseMask(std::string_view s) {
  if (s.size() != 3 || s.find_first_not_of("01") != std::string_view::npos) {
    return Status::InvalidInput("mask \"" + std::string(s) +
                                "\" must be three 0/1 digits for x, y, z (e.g. 101)");
  }
  DimMask m = 0;
  for (int i = 0; i < 3; ++i) {
    if (s[i] == '1') m |= 1u << i;
  }
  if (m == 0) return Status::InvalidInput("mask \"000\" selects no dimension");
  return m;
}

std::string MaskString(DimMask m) {
  std::string s = "000";
  for (int i = 0; i < 3; ++i) {
    if (m & (1u << i)) s[i] = '1';
  }
  return s;
}

Result<MappingKind> ParseMappingKind(std::string_view s) {
  std::string l = ToLower(s);
  if (l == "euclidean") return MappingKind::kEuclidean;
  if (l == "dabby") return MappingKind::kDabby;
  return Status::InvalidInput("unknown mapping \"" + std::string(s) + "\" (euclidean or dabby)");
}

const char* MappingKindName(MappingKind k) {
  return k == MappingKind::kEuclidean ? "euclidean" : "dabby";
}

Result<DabbyDirection> ParseDabbyDirection(std::string_view s) {
  std::string l = ToLower(s);
  if (l == "above") return DabbyDirection::kAbove;
  if (l == "below") return DabbyDirection::kBelow;
  return Status::InvalidInput("unknown Dabby direction \"" + std::string(s) +
                              "\" (above or below)");
}

const char* DabbyDirectionName(DabbyDirection d) {
  return d == DabbyDirection::kAbove ? "above" : "below";
}

// ---------------------------------------------------------------------------
// Uniform grid over the masked coordinates: points are bucketed by cell and
// stored cell by cell (good locality for trajectory-ordered queries); a query
// scans cells in rings of growing Chebyshev radius around its own cell and
// stops once no unscanned cell can hold a point as near as the k-th best.

namespace {
constexpr size_t kBruteForceMax = 64;

// A candidate: (squared distance, index), ordered lexicographically.
using Cand = std::pair<double, int>;
}  // namespace

struct NearestIndex::Grid {
  int dims = 0;
  int axis[3] = {0, 0, 0};          // state component of each grid axis
  double lo[3] = {0, 0, 0};         // grid origin
  double cell = 1.0;                // cell edge length
  long g[3] = {1, 1, 1};            // cells per axis
  std::vector<uint32_t> start;      // CSR: points of cell c are [start[c], start[c+1])
  std::vector<int> index;           // original index of each stored point
  std::vector<double> coords;       // stored points' coordinates, dims per point

  long CellOf(int a, double v) const {
    double f = std::floor((v - lo[a]) / cell);
    if (!(f >= 0)) return 0;  // also NaN
    return f >= static_cast<double>(g[a]) ? g[a] - 1 : static_cast<long>(f);
  }
};

NearestIndex::NearestIndex(const std::vector<State>& points, DimMask mask)
    : points_(points), mask_(mask) {
  if (points_.size() <= kBruteForceMax || mask_ == 0) return;
  auto t = std::make_unique<Grid>();
  for (int i = 0; i < 3; ++i) {
    if (mask_ & (1u << i)) t->axis[t->dims++] = i;
  }
  const size_t n = points_.size();
  double hi[3];
  for (int a = 0; a < t->dims; ++a) {
    t->lo[a] = hi[a] = points_[0][t->axis[a]];
    for (const State& p : points_) {
      double v = p[t->axis[a]];
      if (!std::isfinite(v)) return;  // leave brute force to cope with non-finite data
      t->lo[a] = std::min(t->lo[a], v);
      hi[a] = std::max(hi[a], v);
    }
  }
  // About one cell per point over the bounding box (the attractor fills only
  // part of it, so occupied cells hold a few points each), at most 4M cells.
  double extent_max = 0, volume = 1;
  for (int a = 0; a < t->dims; ++a) extent_max = std::max(extent_max, hi[a] - t->lo[a]);
  if (!(extent_max > 0)) return;  // all points equal: brute force handles ties
  for (int a = 0; a < t->dims; ++a) volume *= std::max(hi[a] - t->lo[a], extent_max * 1e-6);
  double target = std::min<double>(static_cast<double>(n), 4e6);
  t->cell = std::pow(volume / target, 1.0 / t->dims);
  long cells = 1;
  for (int a = 0; a < t->dims; ++a) {
    t->g[a] = std::max(1L, static_cast<long>(std::ceil((hi[a] - t->lo[a]) / t->cell)) + 1);
    cells *= t->g[a];
  }
  auto cell_id = [&](const State& p) {
    long c = 0;
    for (int a = t->dims - 1; a >= 0; --a) c = c * t->g[a] + t->CellOf(a, p[t->axis[a]]);
    return c;
  };
  t->start.assign(cells + 1, 0);
  std::vector<long> ids(n);
  for (size_t i = 0; i < n; ++i) {
    ids[i] = cell_id(points_[i]);
    ++t->start[ids[i] + 1];
  }
  for (long c = 0; c < cells; ++c) t->start[c + 1] += t->start[c];
  std::vector<uint32_t> fill(t->start.begin(), t->start.end() - 1);
  t->index.resize(n);
  t->coords.resize(n * t->dims);
  for (size_t i = 0; i < n; ++i) {  // ascending i: each cell lists indices in order
    uint32_t slot = fill[ids[i]]++;
    t->index[slot] = static_cast<int>(i);
    for (int a = 0; a < t->dims; ++a) t->coords[slot * t->dims + a] = points_[i][t->axis[a]];
  }
  grid_ = std::move(t);
}

NearestIndex::~NearestIndex() = default;

namespace {

// Keeps the k best candidates in a max-heap ordered by (distance, index).
void Offer(std::vector<Cand>& heap, size_t k, Cand c) {
  if (heap.size() < k) {
    heap.push_back(c);
    std::push_heap(heap.begin(), heap.end());
  } else if (c < heap.front()) {
    std::pop_heap(heap.begin(), heap.end());
    heap.back() = c;
    std::push_heap(heap.begin(), heap.end());
  }
}

}  // namespace

// The k nearest (distance, index) pairs in ascending order.
static std::vector<Cand> GridSearch(const NearestIndex::Grid& t, const std::vector<State>& pts,
                                    DimMask mask, const State& q, size_t k);

std::vector<Cand> GridSearch(const NearestIndex::Grid& t, const std::vector<State>& pts,
                             DimMask mask, const State& q, size_t k) {
  (void)pts;
  (void)mask;
  const int d = t.dims;
  long c[3] = {0, 0, 0};
  double qa[3] = {0, 0, 0};
  for (int a = 0; a < d; ++a) {
    qa[a] = q[t.axis[a]];
    c[a] = t.CellOf(a, qa[a]);
  }
  std::vector<Cand> heap;
  heap.reserve(k + 1);
  Cand best1{std::numeric_limits<double>::infinity(), std::numeric_limits<int>::max()};
  bool have1 = false;
  auto scan_cell = [&](long id) {
    for (uint32_t s = t.start[id], e = t.start[id + 1]; s < e; ++s) {
      // The same sum, in the same order, as MaskedDist2.
      const double* p = &t.coords[static_cast<size_t>(s) * d];
      double dist = 0.0;
      for (int a = 0; a < d; ++a) {
        double diff = qa[a] - p[a];
        dist += diff * diff;
      }
      Cand c{dist, t.index[s]};
      if (k == 1) {  // no heap for the common single-neighbour query
        if (c < best1) best1 = c;
        have1 = true;
      } else {
        Offer(heap, k, c);
      }
    }
  };
  long max_r = 0;
  for (int a = 0; a < d; ++a) max_r = std::max({max_r, c[a], t.g[a] - 1 - c[a]});
  for (long r = 0; r <= max_r; ++r) {
    // Visit every cell at Chebyshev distance exactly r from c (clipped to the grid).
    long lo[3], hi[3];
    for (int a = 0; a < d; ++a) {
      lo[a] = std::max(0L, c[a] - r);
      hi[a] = std::min(t.g[a] - 1, c[a] + r);
    }
    long cur[3] = {lo[0], lo[1], lo[2]};
    for (;;) {
      bool on_ring = false;
      for (int a = 0; a < d; ++a) on_ring |= (cur[a] == c[a] - r || cur[a] == c[a] + r);
      if (on_ring || r == 0) {
        long id = 0;
        for (int a = d - 1; a >= 0; --a) id = id * t.g[a] + cur[a];
        scan_cell(id);
      }
      int a = 0;
      while (a < d && ++cur[a] > hi[a]) {
        cur[a] = lo[a];
        ++a;
      }
      if (a == d) break;
    }
    if (k == 1 ? !have1 : heap.size() < k) continue;
    double kth = k == 1 ? best1.first : heap.front().first;
    // Lower bound on the distance to any cell outside the scanned block.
    double bound = std::numeric_limits<double>::infinity();
    for (int a = 0; a < d; ++a) {
      if (c[a] - r > 0) bound = std::min(bound, qa[a] - (t.lo[a] + (c[a] - r) * t.cell));
      if (c[a] + r < t.g[a] - 1) bound = std::min(bound, t.lo[a] + (c[a] + r + 1) * t.cell - qa[a]);
    }
    if (bound == std::numeric_limits<double>::infinity()) break;  // whole grid scanned
    // A safety margin covers rounding in cell assignment and distances.
    bound -= t.cell * 1e-9 + std::abs(bound) * 1e-12;
    if (bound > 0 && bound * bound > kth) break;
  }
  if (k == 1) return {best1};
  std::sort_heap(heap.begin(), heap.end());
  return heap;
}

int NearestIndex::Nearest(const State& q) const {
  if (points_.empty()) return -1;
  if (!grid_) {
    int best = 0;
    double best_d = MaskedDist2(q, points_[0], mask_);
    for (size_t i = 1; i < points_.size(); ++i) {
      double d = MaskedDist2(q, points_[i], mask_);
      if (d < best_d) {
        best_d = d;
        best = static_cast<int>(i);
      }
    }
    return best;
  }
  return GridSearch(*grid_, points_, mask_, q, 1)[0].second;
}

std::vector<int> NearestIndex::KNearest(const State& q, int k) const {
  size_t want = std::min<size_t>(k > 0 ? k : 0, points_.size());
  if (want == 0) return {};
  std::vector<Cand> cand;
  if (!grid_) {
    for (size_t i = 0; i < points_.size(); ++i) {
      cand.emplace_back(MaskedDist2(q, points_[i], mask_), static_cast<int>(i));
    }
    std::sort(cand.begin(), cand.end());
  } else {
    cand = GridSearch(*grid_, points_, mask_, q, want);
  }
  std::vector<int> out;
  for (size_t i = 0; i < cand.size() && out.size() < want; ++i) out.push_back(cand[i].second);
  return out;
}

// ---------------------------------------------------------------------------
// Mapping.

namespace {

// Candidate references for point v in Dabby's rule, best first, at most `limit`.
// `order` holds reference indices sorted by (x, index).
std::vector<int> DabbyCandidates(const std::vector<State>& ref, const std::vector<int>& order,
                                 double vx, DabbyDirection dir, size_t limit) {
  std::vector<int> out;
  if (dir == DabbyDirection::kAbove) {
    auto it = std::lower_bound(order.begin(), order.end(), vx,
                               [&](int i, double x) { return ref[i][0] < x; });
    for (; it != order.end() && out.size() < limit; ++it) out.push_back(*it);
  } else {
    // Largest x <= vx; among equal x the lowest index first.
    auto it = std::upper_bound(order.begin(), order.end(), vx,
                               [&](double x, int i) { return x < ref[i][0]; });
    while (it != order.begin() && out.size() < limit) {
      auto group_end = it;
      double gx = ref[*(it - 1)][0];
      auto group_begin = it - 1;
      while (group_begin != order.begin() && ref[*(group_begin - 1)][0] == gx) --group_begin;
      for (auto g = group_begin; g != group_end && out.size() < limit; ++g) out.push_back(*g);
      it = group_begin;
    }
  }
  return out;
}

}  // namespace

std::vector<int> MapTrajectory(const std::vector<State>& reference,
                               const std::vector<State>& variation,
                               const MappingOptions& options,
                               const std::vector<int>& move_class) {
  const size_t n = variation.size();
  std::vector<int> k(n, -1);
  if (reference.empty()) return k;
  auto cls = [&](int i) { return move_class.empty() ? i : move_class[i]; };

  // The run of equal classes ending at position j-1, and its class.
  int run_class = -1;
  int run_len = 0;
  auto allowed = [&](int cand) {
    return options.max_repeat <= 0 || cls(cand) != run_class || run_len < options.max_repeat;
  };
  auto accept = [&](int j, int cand) {
    k[j] = cand;
    if (cand < 0) {
      run_class = -1;
      run_len = 0;
    } else if (cls(cand) == run_class) {
      ++run_len;
    } else {
      run_class = cls(cand);
      run_len = 1;
    }
  };

  if (options.kind == MappingKind::kEuclidean) {
    NearestIndex index(reference, options.mask);
    if (options.max_repeat <= 0) {
      // Independent queries: split them across threads for long inputs.
      unsigned threads = n >= 65536 ? std::max(1u, std::thread::hardware_concurrency()) : 1;
      threads = std::min(threads, 8u);
      auto work = [&](size_t begin, size_t end) {
        for (size_t j = begin; j < end; ++j) k[j] = index.Nearest(variation[j]);
      };
      std::vector<std::thread> pool;
      size_t chunk = (n + threads - 1) / threads;
      for (unsigned t = 1; t < threads; ++t) {
        size_t b = std::min(n, t * chunk), e = std::min(n, (t + 1) * chunk);
        pool.emplace_back(work, b, e);
      }
      work(0, std::min(n, chunk));
      for (auto& th : pool) th.join();
      return k;
    }
    for (size_t j = 0; j < n; ++j) {
      int best = index.Nearest(variation[j]);
      if (!allowed(best)) {
        // Next-nearest candidates, widening the search until one is allowed.
        int chosen = best;
        for (int want = 8;; want *= 4) {
          std::vector<int> cands = index.KNearest(variation[j], want);
          auto it = std::find_if(cands.begin(), cands.end(), allowed);
          if (it != cands.end()) {
            chosen = *it;
            break;
          }
          if (cands.size() >= reference.size()) break;  // none allowed: keep the nearest
        }
        best = chosen;
      }
      accept(static_cast<int>(j), best);
    }
    return k;
  }

  std::vector<int> order(reference.size());
  for (size_t i = 0; i < order.size(); ++i) order[i] = static_cast<int>(i);
  std::stable_sort(order.begin(), order.end(),
                   [&](int a, int b) { return reference[a][0] < reference[b][0]; });
  for (size_t j = 0; j < n; ++j) {
    double vx = variation[j][0];
    std::vector<int> cands =
        DabbyCandidates(reference, order, vx, options.dabby_direction, 1);
    int best = cands.empty() ? -1 : cands[0];
    if (best >= 0 && !allowed(best)) {
      std::vector<int> all = DabbyCandidates(reference, order, vx, options.dabby_direction,
                                             reference.size());
      auto it = std::find_if(all.begin(), all.end(), allowed);
      if (it != all.end()) best = *it;
    }
    accept(static_cast<int>(j), best);
  }
  return k;
}

}  // namespace sb::chaos
