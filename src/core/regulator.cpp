#include "pneumatic_finger/core/regulator.hpp"

#include <algorithm>

namespace pneumatic_finger {

double restVolumeM3(const FingerParameters& p, int finger_count) {
  double v = 0.0;
  for (int i = 0; i < p.chamber_count; ++i) {
    const auto k = static_cast<std::size_t>(i);
    v += p.chamber_height_m[k] * p.chamber_thickness_m[k] * p.chamber_width_m[k];
  }
  return finger_count * v;
}

double fillRatePaPerS(double flow_m3_per_s, double rest_volume_m3, double atmospheric_pa) {
  return atmospheric_pa * flow_m3_per_s / rest_volume_m3;
}

double gripperFillRatePaPerS(double flow_m3_per_s, const FingerParameters& finger, int finger_count) {
  return fillRatePaPerS(flow_m3_per_s, restVolumeM3(finger, finger_count), finger.atmospheric_pressure_pa);
}

double regulatorStep(double gauge_pa, double setpoint_pa, double rate_pa_per_s, double dt_s) {
  const double step = rate_pa_per_s * dt_s;
  return gauge_pa < setpoint_pa ? std::min(gauge_pa + step, setpoint_pa) : std::max(gauge_pa - step, setpoint_pa);
}

}  // namespace pneumatic_finger
