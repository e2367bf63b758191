#include "simd_kernels.hpp"

namespace pneumatic_finger {

// Defined by the translation unit compiled for each instruction set.
extern const SimdKernels kGenericKernels;
extern const MembraneBatchKernel kGenericMembraneKernel;
#if defined(__x86_64__)
extern const SimdKernels kAvx2Kernels;
extern const SimdKernels kAvx512Kernels;
extern const MembraneBatchKernel kAvx2MembraneKernel;
extern const MembraneBatchKernel kAvx512MembraneKernel;
#endif

bool instructionSetAvailable(InstructionSet set) {
  switch (set) {
    case InstructionSet::kGeneric: return true;
#if defined(__x86_64__)
    case InstructionSet::kAvx2: return __builtin_cpu_supports("avx2");
    case InstructionSet::kAvx512: return __builtin_cpu_supports("avx512f");
#else
    case InstructionSet::kAvx2:
    case InstructionSet::kAvx512:
      return false;
#endif
  }
  return false;
}

InstructionSet widestInstructionSet() {
  if (instructionSetAvailable(InstructionSet::kAvx512)) return InstructionSet::kAvx512;
  if (instructionSetAvailable(InstructionSet::kAvx2)) return InstructionSet::kAvx2;
  return InstructionSet::kGeneric;
}

const SimdKernels* simdKernels(InstructionSet set) {
  if (!instructionSetAvailable(set)) return nullptr;
#if defined(__x86_64__)
  if (set == InstructionSet::kAvx512) return &kAvx512Kernels;
  if (set == InstructionSet::kAvx2) return &kAvx2Kernels;
#endif
  return &kGenericKernels;
}

MembraneBatchKernel membraneKernel(InstructionSet set) {
  if (!instructionSetAvailable(set)) return nullptr;
#if defined(__x86_64__)
  if (set == InstructionSet::kAvx512) return kAvx512MembraneKernel;
  if (set == InstructionSet::kAvx2) return kAvx2MembraneKernel;
#endif
  return kGenericMembraneKernel;
}

}  // namespace pneumatic_finger
