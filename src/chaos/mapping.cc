#include "chaos/mapping.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <nanoflann.hpp>

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
// k-d tree over the masked coordinates (nanoflann).

namespace {
constexpr size_t kBruteForceMax = 64;

struct Cloud {
  std::vector<double> coords;  // dims values per point
  size_t dims = 0;
  size_t kdtree_get_point_count() const { return dims ? coords.size() / dims : 0; }
  double kdtree_get_pt(size_t idx, size_t d) const { return coords[idx * dims + d]; }
  template <class BBox>
  bool kdtree_get_bbox(BBox&) const {
    return false;
  }
};

using KdTree = nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<double, Cloud>,
                                                   Cloud, -1, uint32_t>;
}  // namespace

struct NearestIndex::Tree {
  Cloud cloud;
  std::unique_ptr<KdTree> index;
};

NearestIndex::NearestIndex(const std::vector<State>& points, DimMask mask)
    : points_(points), mask_(mask) {
  if (points_.size() <= kBruteForceMax || mask_ == 0) return;
  tree_ = std::make_unique<Tree>();
  for (int i = 0; i < 3; ++i) {
    if (mask_ & (1u << i)) ++tree_->cloud.dims;
  }
  tree_->cloud.coords.reserve(points_.size() * tree_->cloud.dims);
  for (const State& p : points_) {
    for (int i = 0; i < 3; ++i) {
      if (mask_ & (1u << i)) tree_->cloud.coords.push_back(p[i]);
    }
  }
  tree_->index = std::make_unique<KdTree>(static_cast<int>(tree_->cloud.dims), tree_->cloud,
                                          nanoflann::KDTreeSingleIndexAdaptorParams(16));
}

NearestIndex::~NearestIndex() = default;

namespace {
bool Better(double d, int i, double best_d, int best_i) {
  return d < best_d || (d == best_d && i < best_i);
}
}  // namespace

int NearestIndex::Nearest(const State& q) const {
  if (points_.empty()) return -1;
  if (!tree_) {
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
  double qp[3];
  size_t k = 0;
  for (int i = 0; i < 3; ++i) {
    if (mask_ & (1u << i)) qp[k++] = q[i];
  }
  uint32_t idx[2];
  double dist[2];
  size_t found = tree_->index->knnSearch(qp, 2, idx, dist);
  int best = static_cast<int>(idx[0]);
  double best_d = MaskedDist2(q, points_[best], mask_);
  if (found == 2 && dist[1] <= dist[0]) {
    // An exact tie: collect every point at that distance and take the lowest index.
    std::vector<std::pair<uint32_t, double>> hits;
    double radius = std::nextafter(dist[0], std::numeric_limits<double>::infinity());
    tree_->index->radiusSearch(qp, radius, hits, nanoflann::SearchParams(32, 0, false));
    for (const auto& h : hits) {
      double d = MaskedDist2(q, points_[h.first], mask_);
      if (Better(d, static_cast<int>(h.first), best_d, best)) {
        best_d = d;
        best = static_cast<int>(h.first);
      }
    }
  }
  return best;
}

std::vector<int> NearestIndex::KNearest(const State& q, int k) const {
  std::vector<std::pair<double, int>> cand;
  size_t want = std::min<size_t>(k > 0 ? k : 0, points_.size());
  if (want == 0) return {};
  if (!tree_) {
    for (size_t i = 0; i < points_.size(); ++i) {
      cand.emplace_back(MaskedDist2(q, points_[i], mask_), static_cast<int>(i));
    }
  } else {
    double qp[3];
    size_t d = 0;
    for (int i = 0; i < 3; ++i) {
      if (mask_ & (1u << i)) qp[d++] = q[i];
    }
    std::vector<uint32_t> idx(want);
    std::vector<double> dist(want);
    size_t found = tree_->index->knnSearch(qp, want, idx.data(), dist.data());
    // Include every point tied with the k-th so the (distance, index) order is exact.
    double radius =
        std::nextafter(dist[found - 1], std::numeric_limits<double>::infinity());
    std::vector<std::pair<uint32_t, double>> hits;
    tree_->index->radiusSearch(qp, radius, hits, nanoflann::SearchParams(32, 0, false));
    for (const auto& h : hits) {
      cand.emplace_back(MaskedDist2(q, points_[h.first], mask_), static_cast<int>(h.first));
    }
  }
  std::sort(cand.begin(), cand.end());
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
