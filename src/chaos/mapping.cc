#include "chaos/mapping.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
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
  int axis[3] = {0, 0, 0};      // state component of each grid axis
  double lo[3] = {0, 0, 0};     // grid origin
  double cell = 1.0;            // cell edge length
  long g[3] = {1, 1, 1};        // cells per axis
  std::vector<uint32_t> start;  // CSR: points of cell c are [start[c], start[c+1])
  std::vector<int> index;       // original index of each stored point
  std::vector<double> coords;   // stored points' coordinates, dims per point

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
// Nearest point outside one class, for max_repeat: a k-d tree whose nodes
// know when all their points share a class, so a query skips whole subtrees
// of the excluded class. Exact: the answer is the least (MaskedDist2, index)
// among points of another class, as a scan in that order would find it.

namespace {

class ClassNearest {
 public:
  ClassNearest(const std::vector<State>& points, DimMask mask, const std::vector<int>& cls)
      : points_(points), mask_(mask), cls_(cls) {
    for (int i = 0; i < 3; ++i) {
      if (mask & (1u << i)) axis_[dims_++] = i;
    }
    const size_t n = points.size();
    bool finite = n > kBruteForceMax && dims_ > 0;
    for (size_t i = 0; i < n && finite; ++i) {
      for (int a = 0; a < dims_; ++a) finite = finite && std::isfinite(points[i][axis_[a]]);
    }
    if (!finite) return;  // small or non-finite: linear scans
    perm_.resize(n);
    coords_.resize(n * dims_);
    double lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0};
    for (size_t i = 0; i < n; ++i) {
      perm_[i] = static_cast<int>(i);
      for (int a = 0; a < dims_; ++a) {
        double v = points[i][axis_[a]];
        coords_[i * dims_ + a] = v;
        lo[a] = i ? std::min(lo[a], v) : v;
        hi[a] = i ? std::max(hi[a], v) : v;
      }
    }
    nodes_.reserve(2 * n / kLeaf + 2);
    Build(0, n, lo, hi);
  }

  // The point of least (MaskedDist2, index) whose class is not `excluded`;
  // -1 when every point is of that class. Thread-compatible (const).
  int Query(const State& q, int excluded) const {
    std::pair<double, int> best{std::numeric_limits<double>::infinity(),
                                std::numeric_limits<int>::max()};
    bool found = false;
    auto offer = [&](int i) {
      if (cls_[i] == excluded) return;
      std::pair<double, int> c{MaskedDist2(q, points_[i], mask_), i};
      if (!found || c < best) best = c;
      found = true;
    };
    if (nodes_.empty()) {
      for (size_t i = 0; i < points_.size(); ++i) offer(static_cast<int>(i));
      return found ? best.second : -1;
    }
    double qa[3];
    for (int a = 0; a < dims_; ++a) qa[a] = q[axis_[a]];
    std::vector<int> stack{0};
    while (!stack.empty()) {
      const Node& nd = nodes_[stack.back()];
      stack.pop_back();
      if (nd.uniform && nd.cls == excluded) continue;  // the whole subtree is excluded
      // A lower bound of every point's distance, summed like MaskedDist2:
      // rounding is monotone, so it never exceeds a point's computed value.
      if (found && Bound(nd, qa) > best.first) continue;
      if (nd.left < 0) {
        for (uint32_t s = nd.begin; s < nd.end; ++s) {
          int i = perm_[s];
          if (cls_[i] == excluded) continue;
          double d = 0.0;  // the same sum, in the same order, as MaskedDist2
          for (int a = 0; a < dims_; ++a) {
            double t = qa[a] - Coord(i, a);
            d += t * t;
          }
          std::pair<double, int> c{d, i};
          if (!found || c < best) best = c;
          found = true;
        }
        continue;
      }
      const Node& l = nodes_[nd.left];
      const Node& r = nodes_[nd.right];
      // The nearer child is searched first (pushed last).
      bool left_first = Bound(l, qa) <= Bound(r, qa);
      stack.push_back(left_first ? nd.right : nd.left);
      stack.push_back(left_first ? nd.left : nd.right);
    }
    return found ? best.second : -1;
  }

 private:
  static constexpr size_t kLeaf = 8;
  struct Node {
    double lo[3], hi[3];  // bounding box over the masked axes
    uint32_t begin, end;  // perm_ range
    int left = -1, right = -1;
    bool uniform = true;  // every point is of class `cls`
    int cls = 0;
  };

  double Bound(const Node& nd, const double* qa) const {
    double d = 0.0;
    for (int a = 0; a < dims_; ++a) {
      double t = 0.0;
      if (qa[a] < nd.lo[a]) {
        t = nd.lo[a] - qa[a];
      } else if (qa[a] > nd.hi[a]) {
        t = qa[a] - nd.hi[a];
      }
      d += t * t;
    }
    return d;
  }

  double Coord(int i, int a) const { return coords_[static_cast<size_t>(i) * dims_ + a]; }

  // Builds the subtree over perm_[begin, end), whose points lie in the box
  // [lo, hi] (loose: the parent's box cut at its split); returns its node.
  // Splits at the median of the box's widest axis, so the depth is
  // log2(n / kLeaf); a node's own box is the tight one, from its children.
  int Build(size_t begin, size_t end, const double* lo, const double* hi) {
    int id = static_cast<int>(nodes_.size());
    nodes_.emplace_back();
    Node nd;
    nd.begin = static_cast<uint32_t>(begin);
    nd.end = static_cast<uint32_t>(end);
    if (end - begin <= kLeaf) {
      nd.cls = cls_[perm_[begin]];
      for (int a = 0; a < dims_; ++a) nd.lo[a] = nd.hi[a] = Coord(perm_[begin], a);
      for (size_t s = begin; s < end; ++s) {
        for (int a = 0; a < dims_; ++a) {
          nd.lo[a] = std::min(nd.lo[a], Coord(perm_[s], a));
          nd.hi[a] = std::max(nd.hi[a], Coord(perm_[s], a));
        }
        if (cls_[perm_[s]] != nd.cls) nd.uniform = false;
      }
    } else {
      int w = 0;
      for (int a = 1; a < dims_; ++a) {
        if (hi[a] - lo[a] > hi[w] - lo[w]) w = a;
      }
      size_t mid = begin + (end - begin) / 2;
      std::nth_element(perm_.begin() + static_cast<std::ptrdiff_t>(begin),
                       perm_.begin() + static_cast<std::ptrdiff_t>(mid),
                       perm_.begin() + static_cast<std::ptrdiff_t>(end), [&](int x, int y) {
                         double px = Coord(x, w), py = Coord(y, w);
                         return px != py ? px < py : x < y;
                       });
      double left_hi[3] = {hi[0], hi[1], hi[2]}, right_lo[3] = {lo[0], lo[1], lo[2]};
      left_hi[w] = right_lo[w] = Coord(perm_[mid], w);
      nd.left = Build(begin, mid, lo, left_hi);
      nd.right = Build(mid, end, right_lo, hi);
      const Node& l = nodes_[nd.left];
      const Node& r = nodes_[nd.right];
      for (int a = 0; a < dims_; ++a) {
        nd.lo[a] = std::min(l.lo[a], r.lo[a]);
        nd.hi[a] = std::max(l.hi[a], r.hi[a]);
      }
      nd.cls = l.cls;
      nd.uniform = l.uniform && r.uniform && l.cls == r.cls;
    }
    nodes_[id] = nd;
    return id;
  }

  const std::vector<State>& points_;
  DimMask mask_;
  const std::vector<int>& cls_;
  int dims_ = 0;
  int axis_[3] = {0, 0, 0};
  std::vector<double> coords_;  // masked coordinates, dims_ per point, by index
  std::vector<int> perm_;
  std::vector<Node> nodes_;
};

// For sequence `seq` of reference indices: next[i] = the first j > i whose
// class differs from seq[i]'s (seq.size() when none), so "the first entry
// from i on not of seq[i]'s class" is one lookup.
std::vector<size_t> NextOtherClass(const std::vector<int>& seq, const std::vector<int>& cls) {
  std::vector<size_t> next(seq.size());
  for (size_t i = seq.size(); i-- > 0;) {
    if (i + 1 == seq.size()) {
      next[i] = seq.size();
    } else {
      next[i] = cls[seq[i + 1]] != cls[seq[i]] ? i + 1 : next[i + 1];
    }
  }
  return next;
}

}  // namespace

// ---------------------------------------------------------------------------
// Mapping.

std::vector<int> MapTrajectory(const std::vector<State>& reference,
                               const std::vector<State>& variation, const MappingOptions& options,
                               const std::vector<int>& move_class) {
  const size_t n = variation.size();
  std::vector<int> k(n, -1);
  if (reference.empty()) return k;
  std::vector<int> cls = move_class;
  if (cls.empty() && options.max_repeat > 0) {
    cls.resize(reference.size());
    for (size_t i = 0; i < cls.size(); ++i) cls[i] = static_cast<int>(i);
  }

  // The run of equal classes ending at position j-1, and its class. When
  // the nearest candidate would make the run too long, the answer is the
  // first candidate, in the rule's order, of another class (or the nearest
  // when there is none): the next-nearest search the definition describes,
  // found without listing the candidates in between.
  int run_class = -1;
  int run_len = 0;
  auto blocked = [&](int cand) {
    return options.max_repeat > 0 && cand >= 0 && cls[cand] == run_class &&
           run_len >= options.max_repeat;
  };
  auto accept = [&](int j, int cand) {
    k[j] = cand;
    if (options.max_repeat <= 0) return;
    if (cand < 0) {
      run_class = -1;
      run_len = 0;
    } else if (cls[cand] == run_class) {
      ++run_len;
    } else {
      run_class = cls[cand];
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
    // Usually one of the few nearest is of another class; when none of the
    // 64 nearest is (one move repeated over much of the route), the
    // class-aware tree answers (built once, on first need).
    std::optional<ClassNearest> other;
    for (size_t j = 0; j < n; ++j) {
      int best = index.Nearest(variation[j]);
      if (blocked(best)) {
        bool found = false;
        for (int want : {8, 64}) {
          std::vector<int> near = index.KNearest(variation[j], want);
          auto it = std::find_if(near.begin(), near.end(), [&](int c) { return !blocked(c); });
          if (it != near.end()) {
            best = *it;
            found = true;
            break;
          }
          if (near.size() >= reference.size()) break;
        }
        if (!found) {
          if (!other) other.emplace(reference, options.mask, cls);
          int alt = other->Query(variation[j], run_class);
          if (alt >= 0) best = alt;  // none of another class: keep the nearest
        }
      }
      accept(static_cast<int>(j), best);
    }
    return k;
  }

  // Dabby: reference indices sorted by (x, index). Above: candidates are
  // this order from the first x >= v. Below: groups of equal x from the
  // largest x <= v downwards, each in index order; `below` lists the groups
  // in that order and below_start[g] is where group g (ascending) begins.
  std::vector<int> order(reference.size());
  for (size_t i = 0; i < order.size(); ++i) order[i] = static_cast<int>(i);
  std::stable_sort(order.begin(), order.end(),
                   [&](int a, int b) { return reference[a][0] < reference[b][0]; });
  const bool above = options.dabby_direction == DabbyDirection::kAbove;
  std::vector<int> group_of(order.size());
  std::vector<size_t> group_begin;
  for (size_t i = 0; i < order.size(); ++i) {
    if (i == 0 || reference[order[i]][0] != reference[order[i - 1]][0]) group_begin.push_back(i);
    group_of[i] = static_cast<int>(group_begin.size()) - 1;
  }
  std::vector<int> below;
  std::vector<size_t> below_start(group_begin.size());
  if (!above) {
    below.reserve(order.size());
    for (size_t g = group_begin.size(); g-- > 0;) {
      below_start[g] = below.size();
      size_t end = g + 1 < group_begin.size() ? group_begin[g + 1] : order.size();
      below.insert(below.end(), order.begin() + static_cast<std::ptrdiff_t>(group_begin[g]),
                   order.begin() + static_cast<std::ptrdiff_t>(end));
    }
  }
  const std::vector<int>& seq = above ? order : below;
  std::vector<size_t> next;
  if (options.max_repeat > 0) next = NextOtherClass(seq, cls);
  for (size_t j = 0; j < n; ++j) {
    double vx = variation[j][0];
    size_t start = seq.size();  // none
    if (above) {
      start = static_cast<size_t>(
          std::lower_bound(order.begin(), order.end(), vx,
                           [&](int i, double x) { return reference[i][0] < x; }) -
          order.begin());
    } else {
      size_t u = static_cast<size_t>(
          std::upper_bound(order.begin(), order.end(), vx,
                           [&](double x, int i) { return x < reference[i][0]; }) -
          order.begin());
      if (u > 0) start = below_start[group_of[u - 1]];
    }
    int best = start < seq.size() ? seq[start] : -1;
    // seq[start] is of the blocked class: the first entry after it of another.
    if (blocked(best) && next[start] < seq.size()) best = seq[next[start]];
    accept(static_cast<int>(j), best);
  }
  return k;
}

}  // namespace sb::chaos
