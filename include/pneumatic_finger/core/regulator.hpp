// The pressure source of the paper (section 3.1, eq 2-4): a constant volumetric air flow Q into chambers whose air
// behaves as an ideal spring, V/V_o = P_abs/P_o. Then P_abs(t) = P_o (V_o + Q t)/V_o: the gauge pressure rises
// linearly at P_o Q / V_o, and the stored energy is eq 4, W = P_o/(2 V_o) ((V_o + Q t)^2 - V_o^2). ROS-free.
#pragma once

#include "pneumatic_finger/core/parameters.hpp"

namespace pneumatic_finger {

/// The cell's source: a constant flow of about 1 L/min, which fills three fingers to 2 kg/cm^2 in about 1 s (m^3/s).
constexpr double kCellRegulatorFlowM3PerS = 1.6e-5;

/// Air volume of @p finger_count fingers at rest: V_o = finger_count * sum_n L_n d_n e_n (m^3).
double restVolumeM3(const FingerParameters& parameters, int finger_count);

/// Gauge pressure rise rate of a constant flow (Pa/s): dP/dt = P_o Q / V_o (ideal spring).
double fillRatePaPerS(double flow_m3_per_s, double rest_volume_m3, double atmospheric_pa);

/// The rate at which @p flow_m3_per_s fills @p finger_count fingers of @p finger's parameters (Pa/s): fillRatePaPerS
/// over their restVolumeM3, at the finger's atmospheric pressure.
double gripperFillRatePaPerS(double flow_m3_per_s, const FingerParameters& finger, int finger_count);

/// One step of a regulator that fills (or vents) at @p rate_pa_per_s toward @p setpoint_pa and then holds it.
double regulatorStep(double gauge_pa, double setpoint_pa, double rate_pa_per_s, double dt_s);

}  // namespace pneumatic_finger
