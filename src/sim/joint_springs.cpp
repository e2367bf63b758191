// The joint springs (docs/MODEL.md, "Joint springs"): the twin's free angles and the force model's moments.
#include "pneumatic_finger/sim/joint_springs.hpp"

#include <algorithm>
#include <cmath>
#include <string>

namespace pneumatic_finger {

double straightBendingStiffnessNmPerRad(const FingerParameters& p, int joint) {
  const auto k = static_cast<std::size_t>(joint);
  const double height_m = p.chamber_height_m[k], width_m = p.chamber_width_m[k];
  const double segment_m = joint == 0 ? p.base_segment_length_m : p.segment_length_m[k - 1];
  return kStraightFingerYoungsModulusPa * width_m * height_m * height_m * height_m / 12.0 / segment_m;
}

double springStiffnessNmPerRad(const FingerParameters& parameters, int joint, double rest_angle_rad, double moment_nm) {
  // In contact the joint held straight presses with M: k q0 = M. Before it, the elastomer alone.
  return rest_angle_rad > 0.0 && moment_nm > 0.0 ? moment_nm / rest_angle_rad
                                                 : straightBendingStiffnessNmPerRad(parameters, joint);
}

double stiffestSpringNmPerRad(const FingerModel& model, int joint, double max_gauge_pa) {
  const double top = std::min(max_gauge_pa, model.belowLimitGaugePa());
  double stiffest = straightBendingStiffnessNmPerRad(model.parameters(), joint);
  std::string why;
  for (int i = 1; i <= 64; ++i) {
    const std::vector<JointSpring> springs = jointSprings(model, top * i / 64.0, why);
    if (!springs.empty()) stiffest = std::max(stiffest, springs[static_cast<std::size_t>(joint)].stiffness_nm_per_rad);
  }
  return stiffest;
}

namespace {

// The twin's free angles at @p gauge_pa as every interface gives them from rest (finger_model, Python, the node): the
// near branch, or past a Gent wall's snap the far branch it jumps to. false where there is no shape (not finite, a
// Neo-Hookean wall at or beyond its limit point).
bool freeJointAngles(const FingerModel& model, double gauge_pa, std::vector<double>& q) {
  if (!std::isfinite(gauge_pa)) return false;
  if (model.jointAnglesAt(gauge_pa, q.data())) return true;
  FingerWorkspace workspace(model);
  const FingerState& state = model.evaluate(gauge_pa, workspace);
  if (state.status != EvaluationStatus::kSnappedThrough) return false;
  for (std::size_t j = 0; j < q.size(); ++j) q[j] = state.joint_angle_rad[static_cast<Eigen::Index>(j)];
  return true;
}

}  // namespace

std::vector<JointSpring> jointSprings(const FingerModel& model, double gauge_pa, std::string& why) {
  const int n = model.chamberCount();
  std::vector<double> q(static_cast<std::size_t>(n)), moment(static_cast<std::size_t>(n));
  const double p = gauge_pa < 0.0 ? 0.0 : gauge_pa;  // a vacuum: the straight finger (the model has none)
  if (!freeJointAngles(model, p, q)) {
    why = "the twin has no free shape at " + formatMessage(gauge_pa) +
          " Pa gauge (not finite, or at or beyond the wall's limit point)";
    return {};
  }
  model.straightJointMomentsNm(p, moment.data());
  std::vector<JointSpring> springs(static_cast<std::size_t>(n));
  for (std::size_t j = 0; j < springs.size(); ++j) {
    JointSpring& s = springs[j];
    s.rest_angle_rad = q[j];
    s.pressure_moment_nm = moment[j];
    s.stiffness_nm_per_rad = springStiffnessNmPerRad(model.parameters(), static_cast<int>(j), q[j], moment[j]);
  }
  return springs;
}

}  // namespace pneumatic_finger
