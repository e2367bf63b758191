// The kernels of one instruction set, AVX2 (compiled with -mavx2; run only where the CPU has it): the batch
// (batch_kernel.hpp) and the table's polynomials (table_kernel.hpp), exported as one SimdKernels (simd_kernels.hpp
// picks among the instruction sets).
#include "batch_kernel.hpp"
#include "simd_kernels.hpp"
#include "table_kernel.hpp"

namespace pneumatic_finger {

extern const SimdKernels kAvx2Kernels;
const SimdKernels kAvx2Kernels{
    [](const UniformRobustSpec& spec, const double* gauge_pa, std::size_t count, const BatchOutputs& out) {
      uniformRobustBatch<Pack4>(spec, gauge_pa, count, out);
    },
    [](const double* row, int functions, int live, double x, double* out) {
      tablePolynomials<Pack4>(row, functions, live, x, out);
    },
};

}  // namespace pneumatic_finger
