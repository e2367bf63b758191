// The batch kernel (batch_kernel.hpp) for the baseline instruction set (SSE2 on x86-64): a pack of 4 is two registers.
#include "batch_kernel.hpp"

namespace pneumatic_finger {

void batchUniformRobustGeneric(const UniformRobustSpec& spec, const double* gauge_pa, std::size_t count,
                           const BatchOutputs& out) {
  uniformRobustBatch<Pack4>(spec, gauge_pa, count, out);
}

}  // namespace pneumatic_finger
