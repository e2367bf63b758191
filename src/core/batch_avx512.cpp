// The kernels of one instruction set, AVX-512 (compiled with -mavx512f; run only where the CPU has it): the batch
// (batch_kernel.hpp) and the table's polynomials (table_kernel.hpp), exported as one SimdKernels (simd_kernels.hpp
// picks among the instruction sets).
#include "batch_kernel.hpp"
#include "simd_kernels.hpp"
#include "table_kernel.hpp"

namespace pneumatic_finger {

extern const SimdKernels kAvx512Kernels;
const SimdKernels kAvx512Kernels{
    [](const UniformRobustSpec& spec, const double* gauge_pa, std::size_t count, const BatchOutputs& out) {
      uniformRobustBatch<Pack8>(spec, gauge_pa, count, out);
    },
    [](const double* row, int functions, int live, double x, double* out) {
      tablePolynomials<Pack8>(row, functions, live, x, out);
    },
};

}  // namespace pneumatic_finger
