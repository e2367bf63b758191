// The membrane kernel (membrane_kernel.hpp) compiled for the baseline instruction set (SSE2 on x86-64), where a pack of 4 is two registers; simd_kernels.hpp says why it
// has a translation unit of its own.
#include "membrane_kernel.hpp"
#include "simd_kernels.hpp"

namespace pneumatic_finger {

extern const MembraneBatchKernel kGenericMembraneKernel;
const MembraneBatchKernel kGenericMembraneKernel = &uniformMembraneBatch<Pack4>;

}  // namespace pneumatic_finger
