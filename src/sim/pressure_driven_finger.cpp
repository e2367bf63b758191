// The finger in MuJoCo, its springs rewritten from the twin at each step's pressure (pressure_driven_finger.hpp).
#include "pneumatic_finger/sim/pressure_driven_finger.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "pneumatic_finger/description/finger_urdf.hpp"
#include "pneumatic_finger/sim/joint_springs.hpp"

namespace pneumatic_finger {

PressureDrivenFinger::PressureDrivenFinger(const FingerModel& twin, mjModel* model, const std::string& prefix)
    : twin_(twin), model_(model), gauge_pa_(std::numeric_limits<double>::quiet_NaN()) {
  const int n = twin.chamberCount();
  for (int j = 1; j <= n; ++j) {
    const std::string name = jointName(prefix, j);
    const int id = mj_name2id(model, mjOBJ_JOINT, name.c_str());
    if (id < 0) throw ParameterError("the MuJoCo model has no joint '" + name + "' (finger_urdf --mjcf names them)");
    const double k = model->jnt_stiffness[id], c = model->dof_damping[model->jnt_dofadr[id]];
    if (!(k > 0.0)) throw ParameterError("joint '" + name + "' has no stiffness: not a finger_urdf --mjcf finger");
    joint_ids_.push_back(id);
    inertia_beyond_.push_back(c * c / (4.0 * k));
  }
  for (auto* v : {&angle_, &moment_, &since_, &held_moment_}) v->resize(static_cast<std::size_t>(n));
}

bool PressureDrivenFinger::freeShape(double gauge_pa, std::string& why) {
  const double p = gauge_pa < 0.0 ? 0.0 : gauge_pa;  // a vacuum: the straight finger (the model has none)
  if (!std::isfinite(p) || !twin_.jointAnglesAt(p, angle_.data())) {
    why = "the twin has no free shape at " + formatMessage(gauge_pa) +
          " Pa gauge (not finite, or at or beyond the wall's limit point); the springs stay at " +
          formatMessage(gauge_pa_) + " Pa";
    return false;
  }
  twin_.straightJointMomentsNm(p, moment_.data());
  return true;
}

void PressureDrivenFinger::writeSpring(std::size_t j, double k) {
  const int id = joint_ids_[j];
  model_->jnt_stiffness[id] = k;
  model_->qpos_spring[model_->jnt_qposadr[id]] = angle_[j];
  model_->dof_damping[model_->jnt_dofadr[id]] = 2.0 * std::sqrt(k * inertia_beyond_[j]);
}

bool PressureDrivenFinger::applyPressure(double gauge_pa, std::string& why) {
  if (!freeShape(gauge_pa, why)) return false;
  for (std::size_t j = 0; j < joint_ids_.size(); ++j) {
    writeSpring(j, springStiffnessNmPerRad(twin_.parameters(), static_cast<int>(j), angle_[j], moment_[j]));
  }
  gauge_pa_ = gauge_pa;
  return true;
}

bool PressureDrivenFinger::applyPressureWithHeldMoments(double gauge_pa, const mjData& data, std::string& why) {
  if (!freeShape(gauge_pa, why)) return false;
  const double p = gauge_pa < 0.0 ? 0.0 : gauge_pa;
  const std::size_t n = joint_ids_.size();
  // Each joint held short of its rest angle: the pressure at which the free walls stand at its angle (each of its
  // walls turns it by theta per unit compliance weight), from which its walls' plane is held. NaN: not held.
  for (std::size_t j = 0; j < n; ++j) {
    const double q = data.qpos[model_->jnt_qposadr[joint_ids_[j]]];
    const double half_angle = q / twin_.jointComplianceWeight(static_cast<int>(j));
    double since = std::numeric_limits<double>::quiet_NaN();
    if (angle_[j] > 0.0 && q < angle_[j]) {
      if (!(half_angle > 0.0)) {
        since = 0.0;  // held straight or bent back past it: the plane at the gap c, the straight joint's moment
      } else if (twin_.gaugeForHalfAngle(half_angle, since)) {
        since = std::min(since, p);
      }
    }
    since_[j] = since;
  }
  twin_.heldJointMomentsNm(p, since_.data(), held_moment_.data());
  for (std::size_t j = 0; j < n; ++j) {
    const double q = data.qpos[model_->jnt_qposadr[joint_ids_[j]]];
    const double held_k = held_moment_[j] / (angle_[j] - q);
    const bool held = !std::isnan(since_[j]) && held_moment_[j] > 0.0 && std::isfinite(held_k);
    writeSpring(j, held ? held_k : springStiffnessNmPerRad(twin_.parameters(), static_cast<int>(j), angle_[j],
                                                           moment_[j]));
  }
  gauge_pa_ = gauge_pa;
  return true;
}

}  // namespace pneumatic_finger
