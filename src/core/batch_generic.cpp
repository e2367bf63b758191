// The kernels of one instruction set, the baseline instruction set (SSE2 on x86-64): a pack of 4 is two registers: the batch
// (batch_kernel.hpp) and the table's polynomials (table_kernel.hpp).
#include "batch_kernel.hpp"
#include "table_kernel.hpp"

namespace pneumatic_finger {

void batchUniformRobustGeneric(const UniformRobustSpec& spec, const double* gauge_pa, std::size_t count,
                           const BatchOutputs& out) {
  uniformRobustBatch<Pack4>(spec, gauge_pa, count, out);
}

void tablePolynomialsGeneric(const double* row, int functions, int live, double x, double* out) {
  tablePolynomials<Pack2>(row, functions, live, x, out);
}

}  // namespace pneumatic_finger
