// The batch kernel (batch_kernel.hpp) for AVX2 (compiled with -mavx2; run only where the CPU has it).
#include "batch_kernel.hpp"

namespace pneumatic_finger {

void batchUniformRobustAvx2(const UniformRobustSpec& spec, const double* gauge_pa, std::size_t count,
                            const BatchOutputs& out) {
  uniformRobustBatch<Pack4>(spec, gauge_pa, count, out);
}

}  // namespace pneumatic_finger
