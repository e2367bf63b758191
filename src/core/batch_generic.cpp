// The kernels compiled for the baseline instruction set (SSE2 on x86-64), where a pack of 4 is two registers and the
// table takes pairs, exported as one SimdKernels (simd_kernels.hpp picks among the instruction sets).
#include "kernel_set.hpp"

namespace pneumatic_finger {

extern const SimdKernels kGenericKernels;
const SimdKernels kGenericKernels = kernelSet<Pack4, Pack2>();

}  // namespace pneumatic_finger
