// Internal: the scan kernel for AVX-512F (compiled with -mavx512f, no FMA).
#ifdef SB_HAVE_AVX512_KERNEL
#define SB_KERNEL_LANES 8
#define SB_KERNEL_GROUPS 3
#define SB_KERNEL_ENTRY Avx512Kernel
#include "landscape/kernel_impl.inc"
#else
#include "landscape/kernel.h"
namespace sb::landscape::internal {
KernelFn Avx512Kernel() { return nullptr; }
}  // namespace sb::landscape::internal
#endif
