// The membrane kernel (membrane_kernel.hpp) compiled for AVX-512 (with -mavx512f; run only where the CPU has it): packs of 8; simd_kernels.hpp says why it
// has a translation unit of its own.
#include "membrane_kernel.hpp"
#include "simd_kernels.hpp"

namespace pneumatic_finger {

extern const MembraneBatchKernel kAvx512MembraneKernel;
const MembraneBatchKernel kAvx512MembraneKernel = &uniformMembraneBatch<Pack8>;

}  // namespace pneumatic_finger
