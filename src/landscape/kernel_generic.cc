// Internal: the scan kernel for the baseline instruction set (SSE2 on x86-64).
#define SB_KERNEL_LANES 2
#define SB_KERNEL_GROUPS 4
#define SB_KERNEL_ENTRY GenericKernel
#include "landscape/kernel_impl.inc"
