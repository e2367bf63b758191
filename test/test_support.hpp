// Helpers shared by the core tests: the reference's view of a parameter set, and finger-vs-reference errors.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "pneumatic_finger/core/finger_model.hpp"
#include "pneumatic_finger/core/yaml_parameters.hpp"
#include "reference_quad.hpp"

namespace pf_test {

/// The parameters of a YAML text (the defaults for every key it leaves out). @throws ParameterError as the node would
inline pneumatic_finger::FingerParameters fingerFromYaml(const std::string& yaml) {
  pneumatic_finger::RawParameterMap raw;
  pneumatic_finger::loadRawParametersFromYamlText(yaml, "test", raw);
  return pneumatic_finger::FingerParameters::fromRaw(raw);
}

/// The membrane tests' silicone finger: mu = 20 kPa, t = 2 mm (L = 11.5 mm, d = 5 mm, e = 7 mm, N = 7 by default),
/// Gent's locking J_m = @p jm (0: Neo-Hookean), then @p extra keys.
inline pneumatic_finger::FingerParameters membraneFinger(double jm, const std::string& extra = "") {
  return fingerFromYaml("wall_law: membrane\nshear_modulus_pa: 2e4\nwall_thickness_m: 0.002\nwall_locking_jm: " +
                        std::to_string(jm) + "\n" + extra);
}

inline std::vector<reference::ChamberGeometry> chambersOf(const pneumatic_finger::FingerParameters& p) {
  std::vector<reference::ChamberGeometry> out;
  for (int i = 0; i < p.chamber_count; ++i) {
    const auto k = static_cast<std::size_t>(i);
    out.push_back({p.chamber_height_m[k], p.wall_critical_height_m[k], p.chamber_gap_m[k], p.shear_modulus_pa[k]});
  }
  return out;
}

inline reference::Finger referenceFinger(const pneumatic_finger::FingerParameters& p, double gauge_pa) {
  return reference::finger(gauge_pa, p.atmospheric_pressure_pa, chambersOf(p), p.segment_length_m,
                           p.base_segment_length_m, p.base_wall_share);
}

/// Largest errors of one evaluation against the reference.
struct FingerError {
  double half_angle_rad = 0, joint_angle_rad = 0, point_m = 0, tip_angle_rad = 0;
  bool finite = true;
  void merge(const FingerError& o) {
    half_angle_rad = std::max(half_angle_rad, o.half_angle_rad);
    joint_angle_rad = std::max(joint_angle_rad, o.joint_angle_rad);
    point_m = std::max(point_m, o.point_m);
    tip_angle_rad = std::max(tip_angle_rad, o.tip_angle_rad);
    finite = finite && o.finite;
  }
};

// NaN counts as an infinite error (std::max would drop it).
inline double absError(double got, double want) {
  const double e = std::fabs(got - want);
  return std::isnan(e) ? INFINITY : e;
}

inline FingerError fingerError(const pneumatic_finger::FingerState& s, const reference::Finger& r) {
  FingerError e;
  if (s.status == pneumatic_finger::EvaluationStatus::kSolverFailure) {  // no answer: an infinite error
    e.half_angle_rad = e.joint_angle_rad = e.point_m = e.tip_angle_rad = INFINITY;
    e.finite = false;
    return e;
  }
  for (int i = 0; i < s.half_angle_rad.size(); ++i) {
    const auto k = static_cast<std::size_t>(i);
    e.half_angle_rad = std::max(e.half_angle_rad, absError(s.half_angle_rad[i], r.half_angle_rad[k]));
    e.joint_angle_rad = std::max(e.joint_angle_rad, absError(s.joint_angle_rad[i], r.joint_angle_rad[k]));
  }
  for (int i = 0; i < s.backbone_m.cols(); ++i) {
    const auto k = static_cast<std::size_t>(i);
    e.point_m = std::max({e.point_m, absError(s.backbone_m(0, i), r.x_m[k]), absError(s.backbone_m(1, i), r.y_m[k])});
  }
  e.tip_angle_rad = absError(s.tip_angle_rad, r.tip_angle_rad);
  e.finite = s.backbone_m.allFinite() && s.joint_angle_rad.allFinite();
  return e;
}

/// Pressures from 0 to @p max_pa: @p linear evenly spaced points plus a log sweep from 1e-3 Pa.
inline std::vector<double> pressureSweep(double max_pa, int linear, int per_decade) {
  std::vector<double> out;
  for (int i = 0; i <= linear; ++i) out.push_back(max_pa * i / linear);
  for (double e = -3; e <= std::log10(max_pa); e += 1.0 / per_decade) out.push_back(std::pow(10.0, e));
  std::sort(out.begin(), out.end());
  return out;
}

/// A measured error for RecordProperty, in a form that shows it (std::to_string prints 1e-17 as "0.000000").
inline std::string scientific(double x) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3e", x);
  return text;
}

/// The accuracy the default solver promises (the README: "exact to 1e-12").
constexpr double kAngleTolerance = 1e-12;  // rad
constexpr double kPointTolerance = 1e-12;  // m

}  // namespace pf_test
