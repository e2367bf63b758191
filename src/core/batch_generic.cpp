// The kernels of one instruction set, the baseline instruction set (SSE2 on x86-64), where a pack of 4 is two
// registers: the batch (batch_kernel.hpp) and the table's polynomials (table_kernel.hpp), exported as one SimdKernels
// (simd_kernels.hpp picks among the instruction sets).
#include "batch_kernel.hpp"
#include "simd_kernels.hpp"
#include "table_kernel.hpp"

namespace pneumatic_finger {

extern const SimdKernels kGenericKernels;
const SimdKernels kGenericKernels{
    [](const UniformRobustSpec& spec, const double* gauge_pa, std::size_t count, const BatchOutputs& out) {
      uniformRobustBatch<Pack4>(spec, gauge_pa, count, out);
    },
    [](const double* row, int functions, int live, double x, double* out) {
      tablePolynomials<Pack2>(row, functions, live, x, out);
    },
};

}  // namespace pneumatic_finger
