// What one evaluation reports, and where a batch of them is written. Kept apart from finger_model.hpp (and free of
// Eigen) because the batch kernels, compiled once per instruction set, include it.
#pragma once

#include <cstddef>
#include <cstdint>

namespace pneumatic_finger {

/// Outcome of one evaluation. The one status list: FingerModelState's STATUS_* constants, Python's pf.STATUS (indexed
/// by code) and the tools' words are these codes and evaluationStatusName's names, and tests hold each interface to
/// them (test_finger_node: the message's constants; test_python_api: pf.STATUS). New codes go at the end.
enum class EvaluationStatus : std::uint8_t {
  kOk = 0,        ///< pressure in the model's domain
  kVacuum = 1,    ///< gauge < 0: outside the model; the straight (rest) finger is returned
  kClamped = 2,   ///< above the model's range (pressure_range.hpp): the finger at max_gauge_pa is given. Set by the
                  ///< interfaces that apply the range rule (finger_node, finger_model, Python), never by FingerModel
  kBeyondLimitPoint = 3,  ///< the membrane law's pressure maximum reached or passed: the pressure does not determine
                          ///< the shape, so none is given (evaluate() keeps the previous state; a batch writes NaN)
  kSnappedThrough = 4,  ///< the membrane law: some wall has snapped through its limit point to the far branch, where
                        ///< it stays until the pressure falls to the branch's lower turning point (docs/MODEL.md, "The
                        ///< snap-through"): the shape given is that branch's, and depends on the path
  kNotFinite = 5,     ///< NaN or infinite pressure: refused (evaluate() keeps the previous state; a batch writes NaN)
  kSolverFailure = 6, ///< the solver produced no finite answer (the paper's closed forms can): nothing is computed
  kMeetsItself = 7,   ///< the backbone crosses itself (self_contact.hpp): the shape is the model's, which passes
                      ///< through the finger. Set by the interfaces (finger_node, finger_model, Python), never by
                      ///< FingerModel; it takes the place of kOk, kClamped or kSnappedThrough
};

/// How many codes EvaluationStatus has (0 .. count - 1).
inline constexpr std::uint8_t kEvaluationStatusCount = 8;

/// "ok", "vacuum", "clamped to max_gauge_pa", "beyond limit point", "snapped through", "not finite", "solver
/// failure" or "meets itself": the names tools and Python print.
const char* evaluationStatusName(EvaluationStatus status);

/// Where FingerModel::evaluateMany writes: row-major arrays the caller owns, for `count` pressures. A null pointer
/// is neither written nor, where the batch kernel can leave it out, computed: a tip-angle sweep skips the backbone.
struct BatchOutputs {
  double* stretch = nullptr;          ///< count x N
  double* bulge_m = nullptr;          ///< count x N
  double* half_angle_rad = nullptr;   ///< count x N
  double* joint_angle_rad = nullptr;  ///< count x N
  double* backbone_m = nullptr;       ///< count x (N + 2) x 2: O_0 .. O_{N+1}, each (x, y)
  double* tip_angle_rad = nullptr;    ///< count
  std::uint8_t* status = nullptr;     ///< count: EvaluationStatus as its code
};

/// How FingerModel::evaluateMany runs. Every path writes the same bits; they differ only in speed, and exist side by
/// side so that finger_bench and the tests can compare them in one run.
enum class BatchPath {
  kBest,     ///< the widest pack this CPU runs (robust solver, identical chambers), else kScalar
  kScalar,   ///< one pressure at a time, through the single-evaluation code
  kGeneric,  ///< packs of 4 pressures in the baseline instruction set (SSE2 on x86-64)
  kAvx2,     ///< packs of 4 in AVX2 registers
  kAvx512,   ///< packs of 8 in AVX-512 registers
};

/// "best", "scalar", "generic", "avx2" or "avx512".
const char* batchPathName(BatchPath path);

/// True when this build and this CPU can run @p path (kBest and kScalar always can).
bool batchPathAvailable(BatchPath path);

}  // namespace pneumatic_finger
