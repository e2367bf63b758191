// The finger in MuJoCo, its springs rewritten from the twin at each step's pressure (pressure_driven_finger.hpp).
#include "pneumatic_finger/sim/pressure_driven_finger.hpp"

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
  angle_.resize(static_cast<std::size_t>(n));
  moment_.resize(static_cast<std::size_t>(n));
}

bool PressureDrivenFinger::applyPressure(double gauge_pa, std::string& why) {
  const double p = gauge_pa < 0.0 ? 0.0 : gauge_pa;  // a vacuum: the straight finger (the model has none)
  if (!std::isfinite(p) || !twin_.jointAnglesAt(p, angle_.data())) {
    why = "the twin has no free shape at " + formatMessage(gauge_pa) +
          " Pa gauge (not finite, or at or beyond the wall's limit point); the springs stay at " +
          formatMessage(gauge_pa_) + " Pa";
    return false;
  }
  twin_.straightJointMomentsNm(p, moment_.data());
  for (std::size_t j = 0; j < joint_ids_.size(); ++j) {
    const int id = joint_ids_[j];
    const double k = springStiffnessNmPerRad(twin_.parameters(), static_cast<int>(j), angle_[j], moment_[j]);
    model_->jnt_stiffness[id] = k;
    model_->qpos_spring[model_->jnt_qposadr[id]] = angle_[j];
    model_->dof_damping[model_->jnt_dofadr[id]] = 2.0 * std::sqrt(k * inertia_beyond_[j]);
  }
  gauge_pa_ = gauge_pa;
  return true;
}

}  // namespace pneumatic_finger
