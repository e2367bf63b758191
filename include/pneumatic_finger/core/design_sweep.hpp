// Many designs at one pressure: the design sweeps of finger_design and Python's pf.sweep_designs. Each design is the
// base actuator with some keys set to new values; each is validated as a parameter file is, and evaluated at one
// gauge pressure into scalar outputs (a swept chamber_count changes the per-chamber shapes, so only per-design
// numbers are written).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "pneumatic_finger/core/finger_model.hpp"
#include "pneumatic_finger/core/pressure_range.hpp"

namespace pneumatic_finger {

/// Where sweepDesigns writes, one entry per design; a null pointer is neither written nor computed.
struct DesignOutputs {
  double* tip_angle_rad = nullptr;     ///< Theta_N at the pressure (rad)
  double* tip_x_m = nullptr;           ///< the tip O_{N+1} at the pressure (m, the finger's frame)
  double* tip_y_m = nullptr;
  double* contact_gauge_pa = nullptr;  ///< the pressure at which the first walls touch (Pa gauge)
  std::uint8_t* status = nullptr;      ///< EvaluationStatus at the pressure
  double* snap_gauge_pa = nullptr;     ///< where a rising pressure bends it fastest (Pa gauge; snapGaugePa)
  double* limit_gauge_pa = nullptr;    ///< its limit point (Pa gauge; inf where no wall folds)
  std::uint8_t* status_flags = nullptr;  ///< StatusFlag bits at the pressure (evaluation_report.hpp)
};

/// A design the parameters refuse: its index and the loader's message. Its outputs are NaN.
struct DesignRefusal {
  std::size_t design;
  std::string message;
};

/// Evaluates @p designs designs at @p gauge_pa: design d is @p base with keys[j] = values[d * keys.size() + j].
/// Each design's status and flags are reported by the one rule (reportEvaluation) every interface reports by, with
/// @p input: how the caller's range rule made @p gauge_pa of the pressure asked for (clamped, above the validated
/// range). @return the refused designs, in order
/// @throws ParameterError for an unknown key (before any design is evaluated)
std::vector<DesignRefusal> sweepDesigns(const FingerParameters& base, const ModelOptions& options,
                                        const std::vector<std::string>& keys, const double* values,
                                        std::size_t designs, double gauge_pa, const DesignOutputs& out,
                                        const RangeCheck& input = {});

}  // namespace pneumatic_finger
