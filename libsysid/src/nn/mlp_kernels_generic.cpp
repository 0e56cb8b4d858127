// The network kernels compiled with the build's default flags (any x86-64, or any other CPU).
#define SYSID_KERNEL_NS generic
#define SYSID_KERNEL_NAME "generic"
#include "nn/mlp_kernels_impl.inc"
