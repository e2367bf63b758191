// The kernels compiled once per instruction set, and the one place that picks among them at run time. Each of
// batch_generic.cpp, batch_avx2.cpp and batch_avx512.cpp compiles the batch (batch_kernel.hpp) and the table's
// polynomials (table_kernel.hpp) with its own instruction set and exports them as one SimdKernels; the library itself
// stays at the distribution's baseline. Internal header of src/core.
#pragma once

#include <cstddef>

#include "pneumatic_finger/core/evaluation.hpp"

namespace pneumatic_finger {

struct UniformRobustSpec;    // batch_kernel.hpp
struct UniformMembraneSpec;  // membrane_kernel.hpp

/// The robust solver over @p count pressures of a finger of identical chambers, SIMD across pressures.
using BatchKernel = void (*)(const UniformRobustSpec& spec, const double* gauge_pa, std::size_t count,
                             const BatchOutputs& out);

/// The membrane or thick wall law over @p count pressures on the near branch, SIMD across pressures.
using MembraneBatchKernel = void (*)(const UniformMembraneSpec& spec, const double* gauge_pa, std::size_t count,
                                     const BatchOutputs& out);

/// One table row's polynomials at one x, SIMD across functions: out[f] for f < live, where coefficient i of
/// function f is row[i * functions + f] (functions a multiple of kTablePackFunctions, table_kernel.hpp).
using TablePolynomials = void (*)(const double* row, int functions, int live, double x, double* out);

/// An instruction set the kernels are compiled for.
enum class InstructionSet {
  kGeneric,  ///< the baseline (SSE2 on x86-64): packs of 4 as two registers
  kAvx2,     ///< packs of 4 in AVX2 registers
  kAvx512,   ///< packs of 8 in AVX-512 registers
};

/// One instruction set's kernels.
struct SimdKernels {
  BatchKernel batch_uniform_robust;
  TablePolynomials table_polynomials;
};

/// True when this build and this CPU run @p set (kGeneric always).
bool instructionSetAvailable(InstructionSet set);

/// The widest instruction set this build and this CPU run.
InstructionSet widestInstructionSet();

/// @p set's kernels, or nullptr where this build or this CPU lacks @p set.
const SimdKernels* simdKernels(InstructionSet set);

/// @p set's membrane kernel, or nullptr where this build or this CPU lacks @p set. Compiled in translation units of
/// its own (batch_*_membrane.cpp): beside the paper law's kernel, the chain they share would have two callers, and GCC
/// then inlines less of it (batch/avx512 took 7 % longer).
MembraneBatchKernel membraneKernel(InstructionSet set);

}  // namespace pneumatic_finger
