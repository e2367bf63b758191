// The batch kernel (batch_kernel.hpp) for AVX-512F (compiled with -mavx512f; run only where the CPU has it).
#include "batch_kernel.hpp"

namespace pneumatic_finger {

void batchUniformRobustAvx512(const UniformRobustSpec& spec, const double* gauge_pa, std::size_t count,
                           const BatchOutputs& out) {
  uniformRobustBatch<Pack8>(spec, gauge_pa, count, out);
}

}  // namespace pneumatic_finger
