#include "landscape/landscape.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cinttypes>
#include <cmath>
#include <cstdio>
#include <new>
#include <thread>

#include "base/number.h"
#include "base/text.h"
#include "landscape/kernel.h"

namespace sb::landscape {

namespace {

bool Finite3(const chaos::State& s) {
  return std::isfinite(s[0]) && std::isfinite(s[1]) && std::isfinite(s[2]);
}

std::string Fmt(double v) { return FormatDouble(v, 17); }

std::string IcString(const chaos::State& s) {
  std::string out = "(";
  out += Fmt(s[0]);
  out += ", ";
  out += Fmt(s[1]);
  out += ", ";
  out += Fmt(s[2]);
  out += ")";
  return out;
}

internal::KernelFn PickKernel(Isa isa) {
  switch (isa) {
    case Isa::kGeneric:
      return internal::GenericKernel();
    case Isa::kAvx2:
      return IsaSupported(Isa::kAvx2) ? internal::Avx2Kernel() : nullptr;
    case Isa::kAvx512:
      return IsaSupported(Isa::kAvx512) ? internal::Avx512Kernel() : nullptr;
    case Isa::kAuto:
      break;
  }
  if (IsaSupported(Isa::kAvx512)) return internal::Avx512Kernel();
  if (IsaSupported(Isa::kAvx2)) return internal::Avx2Kernel();
  return internal::GenericKernel();
}

}  // namespace

ScanParams ScanParams::FromVary(const chaos::VaryParams& vary, int length) {
  ScanParams p;
  p.system = vary.system;
  p.integrator = vary.integrator;
  p.step = vary.step;
  p.ref_ic = vary.ref_ic;
  p.skip = vary.skip;
  p.length = length;
  p.mask = vary.mapping.mask;
  return p;
}

Status ScanParams::Validate() const {
  if (!(std::isfinite(step) && step > 0)) {
    return Status::InvalidInput("step: must be a finite number > 0, got " + Fmt(step));
  }
  for (double p : system.params) {
    if (!std::isfinite(p)) return Status::InvalidInput("params: must be finite numbers");
  }
  if (!Finite3(ref_ic)) return Status::InvalidInput("ref-ic: must be finite numbers");
  for (double v : ref_ic) {
    if (std::fabs(v) > kMaxAbsCoordinate) {
      return Status::InvalidInput("ref-ic: " + Fmt(v) + " is outside [-1e6, 1e6]");
    }
  }
  if (skip < 0 || skip > chaos::kMaxSkip) {  // the one skip limit (chaos/variation.h)
    return Status::InvalidInput("skip: must be in 0.." + std::to_string(chaos::kMaxSkip) +
                                ", got " + std::to_string(skip));
  }
  if (length < 1 || length > kMaxLength) {
    return Status::InvalidInput("length: must be in 1.." + std::to_string(kMaxLength) + ", got " +
                                std::to_string(length));
  }
  if (mask == 0 || mask > 7) return Status::InvalidInput("mask: must be a non-empty xyz mask");
  return Status::Ok();
}

Result<Plane> ParsePlane(std::string_view s) {
  std::string l = ToLower(s);
  if (l == "cube") return Plane::kCube;
  if (l == "xy") return Plane::kXY;
  if (l == "xz") return Plane::kXZ;
  if (l == "yz") return Plane::kYZ;
  return Status::InvalidInput("plane: unknown value \"" + std::string(s) +
                              "\" (cube, xy, xz or yz)");
}

const char* PlaneName(Plane p) {
  switch (p) {
    case Plane::kCube:
      return "cube";
    case Plane::kXY:
      return "xy";
    case Plane::kXZ:
      return "xz";
    case Plane::kYZ:
      return "yz";
  }
  return "?";
}

Region Region::Around(const chaos::State& center, int grid, double spacing, Plane plane) {
  Region r;
  r.center = center;
  r.grid = grid;
  r.spacing = spacing;
  r.plane = plane;
  return r;
}

Status Region::Validate() const {
  if (grid < 1 || grid > kMaxGrid) {
    return Status::InvalidInput("grid: must be in 1.." + std::to_string(kMaxGrid) + ", got " +
                                std::to_string(grid));
  }
  if (static_cast<int>(plane) < 0 || static_cast<int>(plane) > 3) {
    return Status::InvalidInput("plane: invalid");
  }
  if (size() > kMaxIcs) {
    return Status::InvalidInput("grid: " + std::to_string(grid) + "^" + std::to_string(dims()) +
                                " = " + std::to_string(size()) + " ICs is more than 2^30 (" +
                                std::to_string(kMaxIcs) + ")");
  }
  if (!Finite3(center)) return Status::InvalidInput("center: must be finite numbers");
  if (!(std::isfinite(spacing) && spacing > 0)) {
    return Status::InvalidInput("spacing: must be a finite number > 0, got " + Fmt(spacing));
  }
  // The largest |coordinate| of any grid point (unscanned axes: the centre).
  double largest = 0;
  std::array<int, 3> ax = axes();
  for (int a = 0; a < 3; ++a) {
    bool scanned = a == ax[0] || a == ax[1] || (dims() == 3 && a == ax[2]);
    double lo = scanned ? Coord(a, 0) : center[a], hi = scanned ? Coord(a, grid - 1) : center[a];
    largest = std::max({largest, std::fabs(lo), std::fabs(hi)});
  }
  if (!(largest <= kMaxAbsCoordinate)) {
    return Status::InvalidInput("center: the grid reaches " + Fmt(largest) +
                                ", outside [-1e6, 1e6] (centre +- grid/2 x spacing)");
  }
  double min_spacing = kMinRelativeSpacing * std::max(1.0, largest);
  if (spacing < min_spacing) {
    return Status::InvalidInput("spacing: " + Fmt(spacing) + " is below " + Fmt(min_spacing) +
                                " (1e-9 x the largest |coordinate|, at least 1e-9)");
  }
  return Status::Ok();
}

Status ValidateScan(const ScanParams& params, const Region& region) {
  SB_RETURN_IF_ERROR(params.Validate());
  SB_RETURN_IF_ERROR(region.Validate());
  const double n = params.length;
  double work = static_cast<double>(region.size()) * (params.skip + n + n * n);
  if (work > static_cast<double>(kMaxScanWork)) {
    return Status::InvalidInput("grid: " + std::to_string(region.size()) + " ICs x (skip " +
                                std::to_string(params.skip) + " + n " +
                                std::to_string(params.length) +
                                " + n^2) is more than 2^50 steps and distances (" +
                                std::to_string(kMaxScanWork) + "); scan a smaller grid or plane");
  }
  return Status::Ok();
}

std::array<int, 3> Region::axes() const {
  switch (plane) {
    case Plane::kXY:
      return {0, 1, -1};
    case Plane::kXZ:
      return {0, 2, -1};
    case Plane::kYZ:
      return {1, 2, -1};
    case Plane::kCube:
      break;
  }
  return {0, 1, 2};
}

uint64_t Region::size() const {
  uint64_t n = 1;
  for (int d = 0; d < dims(); ++d) n *= static_cast<uint64_t>(grid);
  return n;
}

std::array<int, 3> Region::GridIndex(uint64_t index) const {
  std::array<int, 3> g = {-1, -1, -1};
  std::array<int, 3> ax = axes();
  for (int d = 0; d < dims(); ++d) {
    g[ax[d]] = static_cast<int>(index % static_cast<uint64_t>(grid));
    index /= static_cast<uint64_t>(grid);
  }
  return g;
}

chaos::State Region::IcAt(uint64_t index) const {
  chaos::State s = center;
  std::array<int, 3> g = GridIndex(index);
  for (int a = 0; a < 3; ++a) {
    if (g[a] >= 0) s[a] = Coord(a, g[a]);
  }
  return s;
}

bool IsaSupported(Isa isa) {
  switch (isa) {
    case Isa::kAuto:
    case Isa::kGeneric:
      return true;
    case Isa::kAvx2:
#if defined(__x86_64__)
      return internal::Avx2Kernel() != nullptr && __builtin_cpu_supports("avx2");
#else
      return false;
#endif
    case Isa::kAvx512:
#if defined(__x86_64__)
      return internal::Avx512Kernel() != nullptr && __builtin_cpu_supports("avx512f");
#else
      return false;
#endif
  }
  return false;
}

const char* IsaName(Isa isa) {
  switch (isa) {
    case Isa::kAuto:
      return "auto";
    case Isa::kGeneric:
      return "generic";
    case Isa::kAvx2:
      return "avx2";
    case Isa::kAvx512:
      return "avx512";
  }
  return "?";
}

Status ScanRange(const ScanParams& params, const Region& region, uint64_t first, uint64_t count,
                 uint16_t* effect, uint32_t* displacement, const ScanOptions& options) {
  SB_RETURN_IF_ERROR(ValidateScan(params, region));
  const uint64_t total = region.size();
  if (first > total || count > total - first) {
    return Status::InvalidInput("scan range [" + std::to_string(first) + ", " +
                                std::to_string(first + count) + ") is outside the " +
                                std::to_string(total) + " ICs of the region");
  }
  internal::KernelFn kernel = PickKernel(options.isa);
  if (kernel == nullptr) {
    return Status::InvalidInput(std::string("isa: ") + IsaName(options.isa) +
                                " is not supported on this CPU or build");
  }
  if (count == 0) return Status::Ok();

  // The reference trajectory, exactly as vary computes it.
  std::vector<chaos::State> ref = chaos::Trajectory(params.system, params.integrator, params.step,
                                                    params.ref_ic, params.skip, params.length);
  std::vector<double> rxyz[3];
  for (int a = 0; a < 3; ++a) {
    rxyz[a].resize(ref.size());
    for (size_t k = 0; k < ref.size(); ++k) rxyz[a][k] = ref[k][a];
  }
  for (const chaos::State& r : ref) {
    if (!Finite3(r)) {
      return Status::InvalidInput("the reference trajectory from " + IcString(params.ref_ic) +
                                  " becomes non-finite");
    }
  }
  // Coordinate tables: the single definition Region::Coord.
  std::vector<double> coords[3];
  std::array<int, 3> axes = region.axes();
  for (int a = 0; a < 3; ++a) coords[a] = {region.center[a]};
  for (int d = 0; d < region.dims(); ++d) {
    int a = axes[d];
    coords[a].resize(region.grid);
    for (int i = 0; i < region.grid; ++i) coords[a][i] = region.Coord(a, i);
  }

  internal::KernelArgs args;
  args.system = params.system.kind == chaos::SystemKind::kLorenz ? 0 : 1;
  args.integrator = params.integrator == chaos::IntegratorKind::kRk4 ? 0 : 1;
  args.mask = params.mask;
  for (int i = 0; i < 3; ++i) args.p[i] = params.system.params[i];
  args.h = params.step;
  args.half = params.step / 2.0;
  args.sixth = params.step / 6.0;
  args.skip = params.skip;
  args.n = params.length;
  for (int a = 0; a < 3; ++a) {
    args.ref[a] = rxyz[a].data();
    args.coord[a] = coords[a].data();
  }
  args.grid = region.grid;
  args.dims = region.dims();
  for (int d = 0; d < 3; ++d) args.axes[d] = axes[d] < 0 ? 0 : axes[d];

  int threads =
      options.threads > 0 ? options.threads : static_cast<int>(std::thread::hardware_concurrency());
  if (threads < 1) threads = 1;
  // Chunks of a multiple of every kernel's lane count; dynamic scheduling
  // (results do not depend on which thread scans which chunk).
  const uint64_t chunk = 3072;
  const uint64_t chunks = (count + chunk - 1) / chunk;
  if (static_cast<uint64_t>(threads) > chunks) threads = static_cast<int>(chunks);
  std::atomic<uint64_t> next{0}, done{0};
  std::atomic<bool> failed{false};
  std::atomic<uint64_t> bad_index{UINT64_MAX};
  auto worker = [&]() {
    for (;;) {
      uint64_t c = next.fetch_add(1, std::memory_order_relaxed);
      if (c >= chunks) break;
      uint64_t lo = c * chunk, len = std::min(chunk, count - lo);
      uint64_t bad = 0;
      if (!kernel(args, first + lo, len, effect + lo, displacement + lo, &bad)) {
        failed.store(true);
        uint64_t cur = bad_index.load();
        while (bad < cur && !bad_index.compare_exchange_weak(cur, bad)) {
        }
      }
      done.fetch_add(len, std::memory_order_relaxed);
    }
  };
  std::vector<std::thread> pool;
  if (options.progress) {
    // All workers in the pool; the calling thread reports progress.
    for (int t = 0; t < threads; ++t) pool.emplace_back(worker);
    auto last_report = std::chrono::steady_clock::now();
    options.progress(0, count);
    while (done.load() < count && !failed.load()) {
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
      auto now = std::chrono::steady_clock::now();
      if (now - last_report >= std::chrono::milliseconds(100)) {
        options.progress(done.load(), count);
        last_report = now;
      }
    }
  } else {
    for (int t = 1; t < threads; ++t) pool.emplace_back(worker);
    worker();
  }
  for (std::thread& t : pool) t.join();
  if (options.progress) options.progress(done.load(), count);
  if (failed.load()) {
    uint64_t b = bad_index.load();
    return Status::InvalidInput("the trajectory from IC " + IcString(region.IcAt(b)) + " (index " +
                                std::to_string(b) + ") becomes non-finite");
  }
  return Status::Ok();
}

Result<LandscapeMap> Scan(const ScanParams& params, const Region& region,
                          const ScanOptions& options) {
  SB_RETURN_IF_ERROR(ValidateScan(params, region));
  LandscapeMap map;
  map.params = params;
  map.region = region;
  try {
    map.effect.resize(region.size());
    map.displacement.resize(region.size());
  } catch (const std::bad_alloc&) {
    return Status::InvalidInput("grid: " + std::to_string(region.size()) +
                                " ICs need more memory than is available (6 bytes per IC)");
  }
  SB_RETURN_IF_ERROR(ScanRange(params, region, 0, region.size(), map.effect.data(),
                               map.displacement.data(), options));
  return map;
}

Result<IcResult> EvaluateIc(const ScanParams& params, const chaos::State& ic) {
  SB_RETURN_IF_ERROR(params.Validate());
  if (!Finite3(ic)) return Status::InvalidInput("ic: must be finite numbers");
  std::vector<chaos::State> ref = chaos::Trajectory(params.system, params.integrator, params.step,
                                                    params.ref_ic, params.skip, params.length);
  std::vector<chaos::State> var = chaos::Trajectory(params.system, params.integrator, params.step,
                                                    ic, params.skip, params.length);
  for (size_t j = 0; j < var.size(); ++j) {
    if (!Finite3(var[j]) || !Finite3(ref[j])) {
      return Status::InvalidInput("the trajectory from IC " + IcString(ic) + " becomes non-finite");
    }
  }
  chaos::MappingOptions mo;
  mo.kind = chaos::MappingKind::kEuclidean;
  mo.mask = params.mask;
  std::vector<int> k = chaos::MapTrajectory(ref, var, mo);
  IcResult r;
  for (size_t j = 0; j < k.size(); ++j) {
    int d = k[j] - static_cast<int>(j);
    if (d != 0) {
      ++r.effect;
      r.displacement += static_cast<uint32_t>(d < 0 ? -d : d);
    }
  }
  r.change = r.effect ? static_cast<double>(r.displacement) / r.effect : 0.0;
  return r;
}

Summary Summarize(const LandscapeMap& map) {
  Summary s;
  s.histogram.assign(static_cast<size_t>(map.params.length) + 1, 0);
  double sum = 0.0;
  for (uint64_t i = 0; i < map.size(); ++i) {
    uint16_t e = map.effect[i];
    if (e < s.histogram.size()) ++s.histogram[e];
    sum += map.Change(i);
  }
  s.mean_change = map.size() ? sum / static_cast<double>(map.size()) : 0.0;
  return s;
}

std::string FormatSummary(const Summary& summary) {
  std::string out = "effect_histogram";
  for (uint64_t c : summary.histogram) {
    out += ' ';
    out += std::to_string(c);
  }
  char buf[64];
  std::snprintf(buf, sizeof buf, "\nmean_change %.9f\n", summary.mean_change);
  out += buf;
  return out;
}

}  // namespace sb::landscape
