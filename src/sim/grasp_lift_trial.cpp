// A grasp and a lift in MuJoCo (grasp_lift_trial.hpp).
#include "pneumatic_finger/sim/grasp_lift_trial.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "pneumatic_finger/core/smoothstep.hpp"

namespace pneumatic_finger {

namespace {

// The carriage moves on its prescribed path: its slide gets an armature this large (kg), so that a newton from the
// fingers or the object changes its acceleration by 1e-4 m/s^2, and the force that gives the path's acceleration is
// applied; its position and velocity are set to the path's at every step besides, so that nothing drifts.
constexpr double kCarriageArmatureKg = 1e4;

int requireId(const mjModel* m, mjtObj type, const char* name) {
  const int id = mj_name2id(m, type, name);
  if (id < 0) throw ParameterError(std::string("the grasp scene has no '") + name + "'");
  return id;
}

}  // namespace

double LiftMotion::durationS() const { return std::sqrt(6.0 * height_m / peak_acceleration_mps2); }

void LiftMotion::at(double t_s, double& z_m, double& v_mps, double& a_mps2) const {
  const double T = durationS(), u = std::clamp(t_s / T, 0.0, 1.0);
  const bool moving = t_s > 0.0 && t_s < T;
  z_m = height_m * smoothstep(u);
  v_mps = moving ? height_m * smoothstepRate(u) / T : 0.0;
  a_mps2 = moving ? height_m * smoothstepCurvature(u) / (T * T) : 0.0;
}

GraspLiftTrial::GraspLiftTrial(const std::vector<GripperFinger>& fingers, const GraspScene& scene,
                               const MjcfOptions& mjcf)
    : fingers_(fingers), model_(loadMjcfText(graspSceneMjcf(fingers, scene, mjcf))), data_(mj_makeData(model_.get())) {
  if (fingers.empty()) throw ParameterError("the grasp scene needs at least one finger");
  mjModel* m = model_.get();
  const int lift = requireId(m, mjOBJ_JOINT, kLiftJointName);
  lift_dof_ = m->jnt_dofadr[lift];
  lift_qpos_ = m->jnt_qposadr[lift];
  lift_actuator_ = requireId(m, mjOBJ_ACTUATOR, kLiftJointName);
  object_body_ = requireId(m, mjOBJ_BODY, kSceneObjectName);
  object_geom_ = requireId(m, mjOBJ_GEOM, kSceneObjectName);
  gripper_ = std::make_unique<DrivenGripper>(fingers, m, object_geom_);
  m->dof_damping[lift_dof_] = 0.0;
  m->dof_armature[lift_dof_] = kCarriageArmatureKg;
  gravity_z_ = m->opt.gravity[2];
}

bool GraspLiftTrial::step(double gauge_pa, double z_m, double v_mps, double a_mps2, bool gravity,
                          std::string& problem) {
  mjModel* m = model_.get();
  mjData* d = data_.get();
  if (!gripper_->apply(gauge_pa, *d, held_moments_, problem)) return false;
  m->opt.gravity[2] = gravity ? gravity_z_ : 0.0;
  const int carriage = m->dof_bodyid[lift_dof_];
  d->qpos[lift_qpos_] = z_m;
  d->qvel[lift_dof_] = v_mps;
  d->ctrl[lift_actuator_] = z_m;
  d->qfrc_applied[lift_dof_] = kCarriageArmatureKg * a_mps2 - m->body_subtreemass[carriage] * m->opt.gravity[2];
  mj_step(m, d);
  if (!stateIsFinite(*m, *d)) {
    problem = "the simulation's state is not finite";
    return false;
  }
  return true;
}

GraspTrialOutcome GraspLiftTrial::run(double grasp_gauge_pa, const LiftMotion& lift,
                                      const GraspTrialSettings& settings) {
  GraspTrialOutcome out;
  mjModel* m = model_.get();
  mjData* d = data_.get();
  mj_resetData(m, d);
  held_moments_ = settings.held_moments;
  const double dt = m->opt.timestep;
  const double rate = gripperFillRatePaPerS(settings.flow_m3_per_s, fingers_.front().parameters,
                                            static_cast<int>(fingers_.size()));
  double gauge = 0.0;
  bool ok = true;
  // The fill at the regulator's rate, then the settle: the object floats where the cell would hold it.
  while (ok && gauge < grasp_gauge_pa) {
    gauge = regulatorStep(gauge, grasp_gauge_pa, rate, dt);
    ok = step(gauge, 0, 0, 0, false, out.problem);
  }
  for (double t = 0; ok && t < settings.settle_s; t += dt) ok = step(gauge, 0, 0, 0, false, out.problem);
  for (double t = 0; ok && t < settings.hang_s; t += dt) ok = step(gauge, 0, 0, 0, true, out.problem);
  out.finger_normal_force_n = gripper_->partNormalForcesN(*d);
  const double held_below_m = d->qpos[lift_qpos_] - d->xpos[3 * object_body_ + 2];
  const double T = lift.durationS();
  for (double t = 0; ok && t < T + settings.after_s; t += dt) {
    double z = 0, v = 0, a = 0;
    lift.at(t, z, v, a);
    ok = step(gauge, z, v, a, true, out.problem);
  }
  const int warnings = mujocoWarnings(*d);
  if (ok && warnings > 0) out.problem = "MuJoCo warned " + std::to_string(warnings) + " times";
  out.slip_m = d->qpos[lift_qpos_] - d->xpos[3 * object_body_ + 2] - held_below_m;
  out.carried = out.problem.empty() && out.slip_m < settings.carried_slip_m;
  return out;
}

}  // namespace pneumatic_finger
