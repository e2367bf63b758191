// How far to trust the twin's tip: the calibration's error bar, per pressure (docs/ACCURACY.md, "An error bar").
//
// finger_calibrate writes it into the calibrated parameter file (key tip_uncertainty); finger_node reads it from
// there and publishes it with every state (finger_state) and as a translucent sphere at the tip (rviz).
#pragma once

#include <string>
#include <vector>

namespace pneumatic_finger {

/// At each calibrated gauge pressure: the largest of the fit's error there, the leave-one-out error there (what a
/// pressure the fit has not seen gets) and the fit's residual scatter (the noise it leaves), for the tip angle and for
/// the tip position (tipUncertainty, calibration.hpp).
struct TipUncertainty {
  std::vector<double> gauge_pa;        ///< the calibrated pressures (Pa), ascending, > 0
  std::vector<double> tip_angle_rad;   ///< the tip angle's error bar at each (rad), >= 0; NaN: not measured
  std::vector<double> tip_position_m;  ///< the tip position's error bar at each (m), >= 0; NaN: not measured

  bool empty() const { return gauge_pa.empty(); }

  /// The bar at one pressure.
  struct At {
    double tip_angle_rad;   ///< NaN when empty or not measured
    double tip_position_m;  ///< NaN when empty or not measured
    bool extrapolated;      ///< the pressure lies outside the calibrated ones (below the first, above the last)
  };

  /// The bar at @p pressure_pa (gauge). 0 for P <= 0 (the straight finger needs no calibration); below the first
  /// calibrated pressure, the first bar with extrapolated = true (the calibration saw none of these pressures);
  /// linear in P between calibrated pressures; above the last one, that bar scaled by P / P_last with extrapolated =
  /// true: the calibration says nothing there, and the bar says so instead of pretending (the scaling only keeps it
  /// growing as the finger bends further).
  At at(double pressure_pa) const;

  /// Builds one from its three lists, as read from a parameter file or rosparam.
  /// @throws ParameterError naming @p origin: lists of different lengths, a pressure not finite, not > 0 or not
  ///         ascending, a negative or infinite bar, an entry with neither bar (both NaN)
  static TipUncertainty fromLists(const std::vector<double>& gauge_pa, const std::vector<double>& tip_angle_rad,
                                  const std::vector<double>& tip_position_m, const std::string& origin);
};

/// The parameter file's key for it (a mapping of gauge_pa, tip_angle_rad and tip_position_m lists).
constexpr const char* kTipUncertaintyKey = "tip_uncertainty";

// It is read with the file's keys, from one parse: loadRawParametersFromYamlFile's tip_uncertainty (yaml_parameters.hpp).

/// The parameter file's tip_uncertainty entry, with a comment that says what it is.
std::string tipUncertaintyToYaml(const TipUncertainty& uncertainty);

}  // namespace pneumatic_finger
