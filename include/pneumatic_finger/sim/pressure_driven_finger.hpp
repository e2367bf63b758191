// A finger in MuJoCo driven by its pressure: at each step the twin's joint springs for that step's pressure are
// written into the engine's model (docs/SIMULATION.md). ROS-free; needs Debian's libmujoco-dev.
#pragma once

#include <mujoco/mujoco.h>

#include <string>
#include <vector>

#include "pneumatic_finger/core/finger_model.hpp"

namespace pneumatic_finger {

/// One finger of a MuJoCo model (a file finger_urdf --mjcf wrote, or any model with the finger's joints), and the twin
/// that sets its springs. Holds the model and the twin by reference: both must outlive it.
class PressureDrivenFinger {
 public:
  /// Finds the joints <prefix>joint_1..N in @p model. Each joint's damping is kept as a damping ratio: the file's
  /// damping and stiffness give the inertia beyond the joint (c = 2 zeta sqrt(k J)), and a new stiffness gets the
  /// damping of the same ratio. @throws ParameterError naming a joint the model lacks, or one without stiffness
  PressureDrivenFinger(const FingerModel& twin, mjModel* model, const std::string& prefix);

  /// Writes the springs of @p gauge_pa into the model: each joint's stiffness (m->jnt_stiffness), rest angle
  /// (m->qpos_spring) and damping (m->dof_damping); the next mj_step applies them. @return false, the springs left as
  /// they were, where the twin has no free shape (beyond the membrane law's limit point); @p why says so.
  bool applyPressure(double gauge_pa, std::string& why);

  /// As applyPressure, but a joint that something holds back from its rest angle (an object, a plate) presses as the
  /// force model says a joint held at that angle does: its walls' contact plane where the free walls are at the
  /// joint's angle in @p data, the moment FingerModel::heldJointMomentsNm's. Its spring is the secant from the rest
  /// angle through that angle, rewritten at every step (docs/MODEL.md, "Joint springs"). A joint at or past its rest
  /// angle keeps applyPressure's spring. Needs identical chambers (the angle's pressure in closed form); other fingers
  /// get applyPressure's springs.
  bool applyPressureWithHeldMoments(double gauge_pa, const mjData& data, std::string& why);

  /// The pressure of the springs in the model now (Pa gauge; NaN before the first applyPressure).
  double gaugePa() const { return gauge_pa_; }

  /// The model's joint ids, joint 1 first.
  const std::vector<int>& jointIds() const { return joint_ids_; }

 private:
  const FingerModel& twin_;
  mjModel* model_;
  std::vector<int> joint_ids_;
  std::vector<double> inertia_beyond_;  // J_n (kg m^2) with the file's damping ratio folded in: c = 2 sqrt(k J)
  // The free shape at the pressure into angle_ and the straight joints' moments into moment_; false with why.
  bool freeShape(double gauge_pa, std::string& why);
  void writeSpring(std::size_t joint, double stiffness_nm_per_rad);

  std::vector<double> angle_, moment_, since_, held_moment_;  // scratch, sized once
  double gauge_pa_;
};

}  // namespace pneumatic_finger
