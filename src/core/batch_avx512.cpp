// The kernels of one instruction set, AVX-512F (compiled with -mavx512f; run only where the CPU has it): the batch
// (batch_kernel.hpp) and the table's polynomials (table_kernel.hpp).
#include "batch_kernel.hpp"
#include "table_kernel.hpp"

namespace pneumatic_finger {

void batchUniformRobustAvx512(const UniformRobustSpec& spec, const double* gauge_pa, std::size_t count,
                           const BatchOutputs& out) {
  uniformRobustBatch<Pack8>(spec, gauge_pa, count, out);
}

void tablePolynomialsAvx512(const double* row, int functions, int live, double x, double* out) {
  tablePolynomials<Pack8>(row, functions, live, x, out);
}

}  // namespace pneumatic_finger
