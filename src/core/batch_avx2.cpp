// The kernels of one instruction set, AVX2 (compiled with -mavx2; run only where the CPU has it): the batch
// (batch_kernel.hpp) and the table's polynomials (table_kernel.hpp).
#include "batch_kernel.hpp"
#include "table_kernel.hpp"

namespace pneumatic_finger {

void batchUniformRobustAvx2(const UniformRobustSpec& spec, const double* gauge_pa, std::size_t count,
                            const BatchOutputs& out) {
  uniformRobustBatch<Pack4>(spec, gauge_pa, count, out);
}

void tablePolynomialsAvx2(const double* row, int functions, int live, double x, double* out) {
  tablePolynomials<Pack4>(row, functions, live, x, out);
}

}  // namespace pneumatic_finger
