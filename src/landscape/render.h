// Drawing landscape maps: 2-D slices as figure-4-style heatmaps (PNG, cairo)
// and as CSV.
#ifndef SB_LANDSCAPE_RENDER_H_
#define SB_LANDSCAPE_RENDER_H_

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "base/status.h"
#include "landscape/landscape.h"

namespace sb::landscape {

enum class Metric { kEffect, kChange };
// "effect" / "change". Errors name the value.
Result<Metric> ParseMetric(std::string_view s);
const char* MetricName(Metric m);

// One N x N slice of a map. Cells are row-major with row 0 at the lowest v
// coordinate: cell (iu, iv) is at iv * size + iu. Value type.
struct Slice {
  Plane plane = Plane::kXY;    // which axes: u = first, v = second
  int u_axis = 0, v_axis = 1;  // 0 = x, 1 = y, 2 = z
  int fixed_axis = 2;
  double fixed_value = 0.0;  // coordinate of the fixed axis
  int size = 0;              // N
  double spacing = 0.0;
  std::vector<double> u, v;     // coordinates of the columns / rows
  std::vector<uint64_t> index;  // map IC number per cell
  std::vector<int> effect;
  std::vector<double> change;
  ScanParams params;  // the map's, for captions
};

// The widest slice ExtractSlice takes: a slice holds 20 bytes per cell and
// its PNG at least one pixel per cell (4096^2 cells: 335 MB + a 75 MB image).
// Larger maps (only MPI scans make them) are read by info and pick.
inline constexpr int kMaxSliceGrid = 4096;

// The slice of `map` in `plane` (default: the map's own plane, or xy for a
// cube) at fixed coordinate `at` (default: the region centre's). `at` selects
// the nearest grid layer and must lie within half a spacing of one. Errors
// (kInvalidInput): a plane other than the map's for a slice map, `at`
// outside the map (the message gives the valid range), or a grid wider than
// kMaxSliceGrid. Pure; thread-safe.
Result<Slice> ExtractSlice(const LandscapeMap& map, std::optional<Plane> plane,
                           std::optional<double> at);

// The slice as a PNG heatmap in the style of the paper's figure 4: hot colours
// (red) for little variation through yellow to cold (blue, purple) for the
// most; effect on the scale 0..n, change on 0..max over the slice. Axis ticks
// in state-space coordinates, a colour bar, the reference IC marked (a ring;
// dashed when it lies off the slice's plane). Returns the PNG bytes. Errors:
// kInternal when cairo fails. Thread-safe.
Result<std::string> RenderPng(const Slice& slice, Metric metric);

// The slice as CSV: header "x,y,z,effect,change", then one row per cell in
// cell order; coordinates and change printed with %.17g. Pure.
std::string SliceCsv(const Slice& slice);

}  // namespace sb::landscape

#endif  // SB_LANDSCAPE_RENDER_H_
