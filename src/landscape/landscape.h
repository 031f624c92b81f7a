// The initial-condition landscape (paper section 7): for every variation IC on
// a grid around the reference IC, how many moves a variation changes (effect)
// and how far they move on average (change).
//
// Typical use (CLI, web app):
//
//   landscape::ScanParams params;            // system, integrator, step, ref IC,
//   params.length = 30;                      // skip, n, mask
//   landscape::Region region = landscape::Region::Around(params.ref_ic, 100, 0.01,
//                                                        landscape::Plane::kXY);
//   Result<landscape::LandscapeMap> map = landscape::Scan(params, region);
//   // map->effect[i], map->Change(i), map->IcAt(i) for i in [0, map->size())
//
// Definitions (exact, float64): a variation IC's trajectory is integrated as
// chaos::Trajectory does (skip steps, then n points); each point j maps to the
// reference point k(j) of least chaos::MaskedDist2, ties to the lowest index.
// effect = #{j : k(j) != j}; displacement = sum |k(j) - j|; change =
// displacement / effect (0 when effect is 0). The scan is vectorised across
// ICs and gives bit-identical results to that scalar definition.
#ifndef SB_LANDSCAPE_LANDSCAPE_H_
#define SB_LANDSCAPE_LANDSCAPE_H_

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "base/status.h"
#include "chaos/mapping.h"
#include "chaos/ode.h"
#include "chaos/variation.h"

namespace sb::landscape {

// Everything that defines the trajectories and the mapping, i.e. all of a
// variation's parameters except the variation IC. Value type.
struct ScanParams {
  chaos::System system = chaos::System::Lorenz();
  chaos::IntegratorKind integrator = chaos::IntegratorKind::kRk4;
  double step = 0.015;
  chaos::State ref_ic = {-13.0, -12.0, 52.0};
  int skip = 0;
  int length = 30;  // n, the number of moves (trajectory points)
  chaos::DimMask mask = chaos::kMaskX | chaos::kMaskZ;

  // The scan parameters of a variation (Euclidean mapping only) with n moves.
  static ScanParams FromVary(const chaos::VaryParams& vary, int length);
  // Checks ranges: finite step > 0, finite params, ref IC within
  // kMaxAbsCoordinate, 0 <= skip <= chaos::kMaxSkip, 1 <= length <= kMaxLength,
  // non-empty mask within "111". Errors are kInvalidInput naming the field.
  Status Validate() const;
};

// Limits of scans, regions and map files (docs/landscape.md, "Limits"),
// checked by ScanParams::Validate, Region::Validate and ValidateScan before
// any work or allocation; map files are held to the same.
//
// The largest supported n (effect is stored in 16 bits).
inline constexpr int kMaxLength = 65535;
// Grid points per axis: a plane of kMaxGrid^2 ICs is kMaxIcs.
inline constexpr int kMaxGrid = 32768;
// ICs in one region: the whole map is held in memory at 6 bytes per IC
// (6 GiB at the limit, by the scanning process or MPI rank 0 and by readers).
inline constexpr uint64_t kMaxIcs = uint64_t{1} << 30;
// |coordinate| of the reference IC, the grid centre and every grid point.
// The attractors live within |x| < 100; beyond 10^6 grid coordinates and
// axis ticks lose the precision that tells neighbouring points apart.
inline constexpr double kMaxAbsCoordinate = 1e6;
// spacing >= kMinRelativeSpacing * max(1, largest |grid coordinate|): keeps
// neighbouring grid points (and axis ticks) at least ~2^22 float64 steps
// apart, and rules out zero and denormal spacings.
inline constexpr double kMinRelativeSpacing = 1e-9;
// Work of one scan, ICs x (skip + n + n^2) (integration steps plus distance
// evaluations): 2^50 is about 4.6 core-days on the project's machine, an
// hour on the paper's 128-CPU cluster; more is never going to finish.
inline constexpr uint64_t kMaxScanWork = uint64_t{1} << 50;

// Which ICs a scan covers: the full N^3 cube, or the N x N slice through
// `center` parallel to a coordinate plane.
enum class Plane { kCube = 0, kXY = 1, kXZ = 2, kYZ = 3 };

// "cube", "xy", "xz", "yz" (case-insensitive). Errors name the value.
Result<Plane> ParsePlane(std::string_view s);
const char* PlaneName(Plane p);

// A grid of variation ICs. Axis a's coordinate i (0-based) is
// center[a] + (i - floor(N/2)) * spacing (see Coord). ICs are numbered with
// the first scanned axis fastest: cube index = (iz*N + iy)*N + ix; plane xy
// index = iy*N + ix; xz = iz*N + ix; yz = iz*N + iy. Unscanned axes stay at
// center. Value type.
struct Region {
  int grid = 100;         // N, points per axis
  double spacing = 0.01;  // s
  Plane plane = Plane::kCube;
  chaos::State center = {-13.0, -12.0, 52.0};

  // The region of the issue/paper: centred on the reference IC.
  static Region Around(const chaos::State& center, int grid, double spacing,
                       Plane plane = Plane::kCube);
  // Checks 1 <= N <= kMaxGrid, at most kMaxIcs ICs, every grid coordinate
  // within kMaxAbsCoordinate, spacing finite and at least kMinRelativeSpacing
  // x max(1, largest |coordinate|), a valid plane. Errors are kInvalidInput
  // naming the field.
  Status Validate() const;
  // Number of scanned axes (3 or 2) and which they are (0 = x, 1 = y, 2 = z),
  // fastest first; axes()[dims()..] are unused.
  int dims() const { return plane == Plane::kCube ? 3 : 2; }
  std::array<int, 3> axes() const;
  // Number of ICs: N^dims.
  uint64_t size() const;
  // Coordinate of grid point i on axis a. The one definition used by scans,
  // pickers, renderers and tests.
  double Coord(int axis, int i) const {
    return center[axis] + static_cast<double>(i - grid / 2) * spacing;
  }
  // Grid indices (per axis x, y, z; unscanned axes -1) of IC number `index`.
  std::array<int, 3> GridIndex(uint64_t index) const;
  // The variation IC number `index` (< size()).
  chaos::State IcAt(uint64_t index) const;
};

// The result of a scan: per IC, its effect and total displacement, in Region
// index order. Value type; thread-compatible.
struct LandscapeMap {
  ScanParams params;
  Region region;
  std::vector<uint16_t> effect;        // size() entries, each in 0..n
  std::vector<uint32_t> displacement;  // sum over j of |k(j) - j|

  uint64_t size() const { return effect.size(); }
  // change = displacement / effect, 0 when effect is 0.
  double Change(uint64_t index) const {
    return effect[index] ? static_cast<double>(displacement[index]) / effect[index] : 0.0;
  }
  chaos::State IcAt(uint64_t index) const { return region.IcAt(index); }
};

// Which instruction set the scan kernel uses. kAuto picks the widest the CPU
// supports; the others exist for tests (all give identical results).
enum class Isa { kAuto, kGeneric, kAvx2, kAvx512 };
// Whether this CPU can run `isa` (kAuto and kGeneric: always).
bool IsaSupported(Isa isa);
const char* IsaName(Isa isa);

struct ScanOptions {
  int threads = 0;  // worker threads; 0 = std::thread::hardware_concurrency()
  Isa isa = Isa::kAuto;
  // Called about every 0.1 s from the calling thread with ICs done and total;
  // may be empty. Not called from workers.
  std::function<void(uint64_t done, uint64_t total)> progress;
};

// ScanParams::Validate, Region::Validate, and the scan's work within
// kMaxScanWork. Errors are kInvalidInput naming the field. Pure.
Status ValidateScan(const ScanParams& params, const Region& region);

// Scans every IC of `region`. Errors: kInvalidInput for bad parameters or
// region, or when a trajectory (reference or variation) becomes non-finite
// (the message names the IC). Uses options.threads threads; allocation is
// O(size) for the result only. Thread-safe (concurrent scans are
// independent).
Result<LandscapeMap> Scan(const ScanParams& params, const Region& region,
                          const ScanOptions& options = {});

// Scans ICs [first, first + count) of `region` into effect[0..count) and
// displacement[0..count) (caller-owned). The building block of Scan and the
// MPI driver. Same errors as Scan (parameters are validated here too).
Status ScanRange(const ScanParams& params, const Region& region, uint64_t first, uint64_t count,
                 uint16_t* effect, uint32_t* displacement, const ScanOptions& options = {});

// The result for one IC, by the plain scalar definition (chaos::Trajectory +
// chaos::MapTrajectory). For pickers, spot checks and tests.
struct IcResult {
  int effect = 0;
  uint32_t displacement = 0;
  double change = 0.0;
};
Result<IcResult> EvaluateIc(const ScanParams& params, const chaos::State& ic);

// --summary numbers: histogram[e] = number of ICs with effect e (e = 0..n),
// mean_change = mean over all ICs of Change(i), summed in index order.
struct Summary {
  std::vector<uint64_t> histogram;
  double mean_change = 0.0;
};
Summary Summarize(const LandscapeMap& map);
// "effect_histogram c0 c1 ... cn\nmean_change X\n" with X as %.9f.
std::string FormatSummary(const Summary& summary);

}  // namespace sb::landscape

#endif  // SB_LANDSCAPE_LANDSCAPE_H_
