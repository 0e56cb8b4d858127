// The network kernels compiled with -mavx2 -mfma (libsysid/CMakeLists.txt sets the flags for
// this file only, on x86-64), used when the CPU has both (mlp_kernels.cpp checks at start-up).
// Eigen's namespace is renamed here so that none of this file's Eigen instantiations, built
// for AVX2, share a symbol with the default-flag instantiations elsewhere in the library.
#ifdef SYSID_HAVE_AVX2_KERNELS
#define Eigen sysid_avx2_Eigen
#define SYSID_KERNEL_NS avx2
#define SYSID_KERNEL_NAME "avx2+fma"
#include "nn/mlp_kernels_impl.inc"
#endif
