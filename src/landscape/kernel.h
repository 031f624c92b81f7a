// Internal: the vectorised scan kernel, compiled once per instruction set
// (kernel_generic.cc, kernel_avx2.cc, kernel_avx512.cc) from kernel_impl.inc.
// Not part of the public API; use landscape.h.
#ifndef SB_LANDSCAPE_KERNEL_H_
#define SB_LANDSCAPE_KERNEL_H_

#include <cstdint>

namespace sb::landscape::internal {

// Plain data so the per-ISA translation units need no library types.
struct KernelArgs {
  int system = 0;      // 0 = Lorenz, 1 = Rössler
  int integrator = 0;  // 0 = RK4, 1 = RKF45
  unsigned mask = 0;   // chaos::DimMask, 1..7
  double p[3] = {0, 0, 0};
  double h = 0, half = 0, sixth = 0;  // h, h/2.0, h/6.0 (as chaos::Step)
  int skip = 0;
  int n = 0;
  const double* ref[3] = {nullptr, nullptr, nullptr};  // reference points, n each
  // IC grid: coordinate tables (grid entries each, Region::Coord) per axis;
  // an unscanned axis has a single entry (its fixed value).
  int grid = 0;
  int dims = 3;
  int axes[3] = {0, 1, 2};
  const double* coord[3] = {nullptr, nullptr, nullptr};
};

// Scans ICs [first, first + count). Returns false when some IC's trajectory
// became non-finite; *bad is then one such IC index.
using KernelFn = bool (*)(const KernelArgs& args, uint64_t first, uint64_t count, uint16_t* effect,
                          uint32_t* displacement, uint64_t* bad);

KernelFn GenericKernel();
KernelFn Avx2Kernel();    // nullptr when not compiled in
KernelFn Avx512Kernel();  // nullptr when not compiled in

}  // namespace sb::landscape::internal

#endif  // SB_LANDSCAPE_KERNEL_H_
