// The kernels compiled for AVX-512 (with -mavx512f; run only where the CPU has it): packs of 8, exported as one
// SimdKernels (simd_kernels.hpp picks among the instruction sets).
#include "kernel_set.hpp"

namespace pneumatic_finger {

extern const SimdKernels kAvx512Kernels;
const SimdKernels kAvx512Kernels = kernelSet<Pack8, Pack8>();

}  // namespace pneumatic_finger
