// Internal: the scan kernel for AVX2 (compiled with -mavx2, no FMA).
#ifdef SB_HAVE_AVX2_KERNEL
#define SB_KERNEL_LANES 4
#define SB_KERNEL_GROUPS 3
#define SB_KERNEL_ENTRY Avx2Kernel
#include "landscape/kernel_impl.inc"
#else
#include "landscape/kernel.h"
namespace sb::landscape::internal {
KernelFn Avx2Kernel() { return nullptr; }
}  // namespace sb::landscape::internal
#endif
