// The membrane kernel (membrane_kernel.hpp) compiled for AVX2 (with -mavx2; run only where the CPU has it): packs of 4; simd_kernels.hpp says why it
// has a translation unit of its own.
#include "membrane_kernel.hpp"
#include "simd_kernels.hpp"

namespace pneumatic_finger {

extern const MembraneBatchKernel kAvx2MembraneKernel;
const MembraneBatchKernel kAvx2MembraneKernel = &uniformMembraneBatch<Pack4>;

}  // namespace pneumatic_finger
