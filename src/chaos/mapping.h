// Nearest-neighbour mapping from variation points to reference points
// (paper section 6, equation 2), and Dabby's one-dimensional rule.
#ifndef SB_CHAOS_MAPPING_H_
#define SB_CHAOS_MAPPING_H_

#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "base/status.h"
#include "chaos/ode.h"

namespace sb::chaos {

// Which of x, y, z enter the distance: bit 0 = x, bit 1 = y, bit 2 = z.
// Written as three digits "xyz", e.g. "101" = x and z.
using DimMask = unsigned;
inline constexpr DimMask kMaskX = 1, kMaskY = 2, kMaskZ = 4;

// Parses "101"-style masks; errors for anything but three 0/1 digits or "000".
Result<DimMask> ParseMask(std::string_view s);
std::string MaskString(DimMask m);

enum class MappingKind { kEuclidean, kDabby };
// Dabby's rule: kAbove = the reference point with the smallest x >= the
// variation point's x; kBelow = the largest x <= it. Ties: lowest index.
enum class DabbyDirection { kAbove, kBelow };

Result<MappingKind> ParseMappingKind(std::string_view s);
const char* MappingKindName(MappingKind k);
Result<DabbyDirection> ParseDabbyDirection(std::string_view s);
const char* DabbyDirectionName(DabbyDirection d);

struct MappingOptions {
  MappingKind kind = MappingKind::kEuclidean;
  DimMask mask = kMaskX | kMaskZ;
  DabbyDirection dabby_direction = DabbyDirection::kAbove;
  // 0 = off. Otherwise no run of the same source move longer than max_repeat:
  // a point that would extend the run takes its next-nearest candidate.
  int max_repeat = 0;
};

// Squared masked Euclidean distance, summed over x, y, z in that order.
inline double MaskedDist2(const State& a, const State& b, DimMask mask) {
  double d = 0.0;
  for (int i = 0; i < 3; ++i) {
    if (mask & (1u << i)) {
      double t = a[i] - b[i];
      d += t * t;
    }
  }
  return d;
}

// Nearest-neighbour index over a fixed set of reference points. Exact: the
// answer is the point of least MaskedDist2, ties to the lowest index. Large
// sets are bucketed in a uniform grid over the masked coordinates (about one
// cell per point), so a query near the points scans O(1) cells on average. Immutable after
// construction; queries are thread-safe. Holds its own copy of the points.
class NearestIndex {
 public:
  NearestIndex(const std::vector<State>& points, DimMask mask);
  ~NearestIndex();
  NearestIndex(const NearestIndex&) = delete;
  NearestIndex& operator=(const NearestIndex&) = delete;

  // Index of the nearest point; -1 when there are no points.
  int Nearest(const State& q) const;
  // The k nearest indices ordered by (distance, index); fewer when k > size.
  std::vector<int> KNearest(const State& q, int k) const;
  size_t size() const { return points_.size(); }

  struct Grid;  // the bucket grid (implementation detail)

 private:
  std::vector<State> points_;
  DimMask mask_;
  std::unique_ptr<Grid> grid_;  // null for small sets (brute force)
};

// Maps each variation point j to a reference index k(j), or -1 for a blank
// (Dabby's rule with no qualifying point). `move_class[k]` says which
// reference indices count as "the same move" for max_repeat (equal ids);
// empty means every index is its own class. Pure; thread-safe.
std::vector<int> MapTrajectory(const std::vector<State>& reference,
                               const std::vector<State>& variation,
                               const MappingOptions& options,
                               const std::vector<int>& move_class = {});

}  // namespace sb::chaos

#endif  // SB_CHAOS_MAPPING_H_
