// The kernels compiled for AVX2 (with -mavx2; run only where the CPU has it): packs of 4, exported as one SimdKernels
// (simd_kernels.hpp picks among the instruction sets).
#include "kernel_set.hpp"

namespace pneumatic_finger {

extern const SimdKernels kAvx2Kernels;
const SimdKernels kAvx2Kernels = kernelSet<Pack4, Pack4>();

}  // namespace pneumatic_finger
