// The inverse model: the gauge pressure for a bulge, a half angle or a tip direction. Every stage inverts in closed
// form for identical chambers; unequal chambers bisect on the (non-decreasing) tip direction.
#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <string>

#include "pneumatic_finger/core/finger_model.hpp"
#include "pneumatic_finger/core/units.hpp"

namespace pneumatic_finger {

double gaugeForBulge(double bulge_m, double chamber_height_m, double shear_modulus_pa, double atmospheric_pa) {
  if (!(bulge_m > 0.0)) return 0.0;
  // Stage 3 inverted: sqrt(2 lambda^2 - 1) = 1 + x with x = 2h/L, so lambda^2 - 1 = x (2 + x)/2.
  const double x = 2.0 * bulge_m / chamber_height_m;
  const double lambda_sq_m1 = 0.5 * x * (2.0 + x);
  const double delta = lambda_sq_m1 / (std::sqrt(1.0 + lambda_sq_m1) + 1.0);
  // Stage 2 inverted: g = delta^2 (3 + delta)/(1 + delta).
  const double g = delta * delta * (3.0 + delta) / (1.0 + delta);
  // Stage 1 inverted: P^2 + 2 P_o P - g P_o mu = 0, positive root without cancellation.
  const double gpm = g * atmospheric_pa * shear_modulus_pa;
  return gpm / (atmospheric_pa + std::sqrt(atmospheric_pa * atmospheric_pa + gpm));
}

double contactGaugePa(double chamber_height_m, double chamber_gap_m, double shear_modulus_pa,
                      double atmospheric_pa) {
  return gaugeForBulge(chamber_gap_m, chamber_height_m, shear_modulus_pa, atmospheric_pa);
}

bool FingerModel::gaugeForTipAngle(double tip_angle_rad, double max_gauge_pa, double& gauge_pa,
                                   std::string& message) const {
  std::ostringstream why;
  if (!std::isfinite(tip_angle_rad) || tip_angle_rad < 0.0) {
    why << "tip angle " << formatMessage(tip_angle_rad) << " rad is not a finite angle >= 0 (flexion is positive)";
    message = why.str();
    return false;
  }
  const int n = parameters_.chamber_count;
  // Every half angle stays below pi/2, so Theta_N < (2N - 1 + s0) pi/2.
  const double turns = 2 * n - 1 + parameters_.base_wall_share;
  const double limit = turns * kHalfPi;
  if (tip_angle_rad >= limit) {
    why << "tip angle " << formatMessage(tip_angle_rad) << " rad is beyond the model's limit (2N-1+s0) pi/2 = "
        << formatMessage(limit) << " rad, which no finite pressure reaches";
    message = why.str();
    return false;
  }
  if (tip_angle_rad == 0.0) {
    gauge_pa = 0.0;
    return true;
  }
  if (std::isfinite(limit_gauge_pa_) && tip_angle_rad >= tipAngleBelowLimit() && std::isfinite(far_turning_gauge_pa_) &&
      groups_.size() == 1) {
    return gaugeOnFarBranch(tip_angle_rad / turns, tip_angle_rad, max_gauge_pa, gauge_pa, message);
  }
  if (std::isfinite(limit_gauge_pa_) && tip_angle_rad >= tipAngleBelowLimit()) {
    why << "tip angle " << formatMessage(tip_angle_rad) << " rad lies beyond the wall's limit point: the largest the "
        << "membrane law holds is " << formatMessage(tipAngleBelowLimit()) << " rad, just below "
        << formatMessage(limit_gauge_pa_) << " Pa, and there the pressure no longer determines the shape";
    message = why.str();
    return false;
  }
  const double answer = gaugeOnNearBranch(tip_angle_rad, turns, max_gauge_pa);
  if (!(answer <= max_gauge_pa)) {
    why << "tip angle " << formatMessage(tip_angle_rad) << " rad needs more than the allowed " << formatMessage(max_gauge_pa)
        << " Pa gauge";
    if (std::isfinite(answer)) why << " (" << formatMessage(answer) << " Pa)";
    message = why.str();
    return false;
  }
  gauge_pa = answer;
  return true;
}

// The pressure for a tip angle on the near branch (inf where none up to @p max_gauge_pa).
double FingerModel::gaugeOnNearBranch(double tip_angle_rad, double turns, double max_gauge_pa) const {
  double answer;
  if (groups_.size() == 1) {
    // Identical chambers: Theta_N = (2N - 1 + s0) theta, and every stage inverts in closed form.
    if (!gaugeForHalfAngle(tip_angle_rad / turns, answer)) answer = std::numeric_limits<double>::infinity();
    return answer;
  }
  // Unequal chambers: Theta_N(P) is non-decreasing, so bisect on [0, max] (below the limit point).
  const double top = std::min(max_gauge_pa, belowLimitGaugePa());
  if (tipAngleAt(top) < tip_angle_rad) return std::numeric_limits<double>::infinity();
  double lo = 0.0, hi = top;
  for (int i = 0; i < 200 && hi - lo > 1e-12 * hi; ++i) {
    const double mid = 0.5 * (lo + hi);
    (tipAngleAt(mid) < tip_angle_rad ? lo : hi) = mid;
  }
  return hi;
}

// A tip angle past the near branch's, for identical chambers whose walls have a far branch (docs/MODEL.md, "The
// snap-through"): Wang's relation inverted gives the bulge, the membrane's stretch follows, and the law its pressure.
// The far branch holds it at that pressure once the walls have snapped (the message says how); the part of the law
// between the branches holds no state under pressure control.
bool FingerModel::gaugeOnFarBranch(double half_angle_rad, double tip_angle_rad, double max_gauge_pa, double& gauge_pa,
                                   std::string& message) const {
  const ChamberGroup& g = groups_[0];
  const MembraneWall& w = g.membrane;
  const double delta = membraneStretchForBulge(w, bulgeForHalfAngle(half_angle_rad, g.chamber_gap_m,
                                                                     g.wall_critical_height_m));
  std::ostringstream why;
  why << "tip angle " << formatMessage(tip_angle_rad) << " rad ";
  if (!(delta > w.far_turning_stretch_excess)) {
    why << "lies between the walls' branches, past the limit point (" << formatMessage(limit_gauge_pa_)
        << " Pa) and short of the far branch's turning point: no pressure holds it; the finger snaps past it";
    message = why.str();
    return false;
  }
  const double p = delta < w.locking_stretch_excess ? membraneGaugeForStretchExcess(w, delta)
                                                    : std::numeric_limits<double>::infinity();
  if (!(p <= max_gauge_pa) || !(limit_gauge_pa_ <= max_gauge_pa)) {
    why << "lies on the far branch and needs more than the allowed " << formatMessage(max_gauge_pa) << " Pa gauge ("
        << formatMessage(std::max(p, limit_gauge_pa_)) << " Pa, with the snap at " << formatMessage(limit_gauge_pa_)
        << " Pa)";
    message = why.str();
    return false;
  }
  gauge_pa = p;
  why << "lies on the far branch: raise the pressure to at least " << formatMessage(limit_gauge_pa_)
      << " Pa (the snap-through), then set " << formatMessage(p) << " Pa";
  message = why.str();
  return true;
}

bool FingerModel::volumeForTipAngle(double tip_angle_rad, double max_volume_m3, double& volume_m3,
                                    std::string& message) const {
  const double turns = 2 * parameters_.chamber_count - 1 + parameters_.base_wall_share;
  double v = 0.0;
  if (!volume_by_stretch_ || !(tip_angle_rad > 0.0) || !(tip_angle_rad < turns * kHalfPi)) {
    double gauge = 0.0;  // the pressure's inverse refuses what no state holds, with its reason
    if (!gaugeForTipAngle(tip_angle_rad, std::numeric_limits<double>::infinity(), gauge, message)) return false;
    v = suppliedVolumeAt(gauge);
  } else {
    // Identical membrane chambers: Wang's relation inverted gives the bulge, the wall its stretch, and the stretch
    // the volume, on either side of the limit point.
    const ChamberGroup& g = groups_[0];
    const double h = bulgeForHalfAngle(tip_angle_rad / turns, g.chamber_gap_m, g.wall_critical_height_m);
    const double delta = membraneStretchForBulge(g.membrane, h);
    if (!(delta < volume_limit_stretch_excess_)) {
      message = "tip angle " + formatMessage(tip_angle_rad) + " rad lies beyond what volume control follows: the " +
                "most is " + formatMessage(volumeLimitM3()) + " m^3, past which the finger snaps (or the wall locks)";
      return false;
    }
    v = suppliedVolumeAtStretch(delta);
  }
  if (!(v <= max_volume_m3)) {
    message = "tip angle " + formatMessage(tip_angle_rad) + " rad needs " + formatMessage(v) + " m^3, more than the " +
              "allowed " + formatMessage(max_volume_m3) + " m^3";
    return false;
  }
  volume_m3 = v;
  message.clear();
  return true;
}

double FingerModel::belowLimitGaugePa() const {
  return std::isfinite(limit_gauge_pa_) ? std::nextafter(limit_gauge_pa_, 0.0) : limit_gauge_pa_;
}

double FingerModel::tipAngleBelowLimit() const {
  return std::isfinite(limit_gauge_pa_) ? tipAngleAt(belowLimitGaugePa()) : std::numeric_limits<double>::infinity();
}

bool FingerModel::gaugeForHalfAngle(double half_angle_rad, double& gauge_pa) const {
  if (groups_.size() != 1 || !(half_angle_rad > 0) || !(half_angle_rad < kHalfPi)) return false;
  const ChamberGroup& g = groups_[0];
  const double h = bulgeForHalfAngle(half_angle_rad, g.chamber_gap_m, g.wall_critical_height_m);
  // Under the membrane law a bulge beyond the limit point has no pressure: NaN, refused below.
  const double p = membrane_ ? membraneGaugeForBulge(g.membrane, h)
                             : gaugeForBulge(h, g.chamber_height_m, g.shear_modulus_pa, parameters_.atmospheric_pressure_pa);
  if (!std::isfinite(p)) return false;
  gauge_pa = p;
  return true;
}

}  // namespace pneumatic_finger
