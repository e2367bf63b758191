// The kernels of the instruction set a translation unit is compiled for, as one SimdKernels: the batch
// (batch_kernel.hpp) over packs of BatchPack, and the table's polynomials (table_kernel.hpp) over packs of TablePack.
// Included only by batch_generic.cpp, batch_avx2.cpp and batch_avx512.cpp. Internal header of src/core.
#pragma once

#include "batch_kernel.hpp"
#include "simd_kernels.hpp"
#include "table_kernel.hpp"

namespace pneumatic_finger {
namespace {  // NOLINT(build/namespaces): internal linkage per instruction set (simd_math.hpp)

template <class BatchPack, class TablePack>
constexpr SimdKernels kernelSet() {
  return {&uniformRobustBatch<BatchPack>, &tablePolynomials<TablePack>};
}

}  // namespace
}  // namespace pneumatic_finger
