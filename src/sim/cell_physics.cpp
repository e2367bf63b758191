// The cell as physics (cell_physics.hpp).
#include "pneumatic_finger/sim/cell_physics.hpp"

#include <cmath>
#include <string>
#include <vector>

namespace pneumatic_finger {

CellPhysics::CellPhysics(const std::string& arm_urdf_xml, const std::vector<GripperFinger>& fingers,
                         const std::vector<std::string>& arm_joint_names, const std::vector<double>& pick_joints_rad,
                         const GraspScene& scene, const MjcfOptions& mjcf, const std::vector<double>& place_joints_rad)
    : model_(loadMjcfText(cellSceneMjcf(arm_urdf_xml, fingers, arm_joint_names, pick_joints_rad, scene, mjcf,
                                        place_joints_rad))),
      data_(mj_makeData(model_.get())) {
  mjModel* m = model_.get();
  for (const std::string& name : arm_joint_names) {
    arm_joints_.push_back(mj_name2id(m, mjOBJ_JOINT, name.c_str()));
    arm_qpos_.push_back(m->jnt_qposadr[arm_joints_.back()]);
    arm_actuators_.push_back(mj_name2id(m, mjOBJ_ACTUATOR, name.c_str()));
  }
  for (std::size_t j = 0; j < arm_qpos_.size(); ++j) data_->qpos[arm_qpos_[j]] = pick_joints_rad[j];
  setArmTargets(pick_joints_rad);
  dampArm();
  part_body_ = mj_name2id(m, mjOBJ_BODY, kSceneObjectName);
  part_geom_ = mj_name2id(m, mjOBJ_GEOM, kSceneObjectName);
  gripper_ = std::make_unique<DrivenGripper>(fingers, m, part_geom_);
  tool_body_ = mj_name2id(m, mjOBJ_BODY, kSceneToolName);
  const int part_joint = m->body_jntadr[part_body_];
  part_qpos_ = m->jnt_qposadr[part_joint];
  part_dof_ = m->jnt_dofadr[part_joint];
  for (int k = 0; k < 7; ++k) part_rest_[k] = data_->qpos[part_qpos_ + k];
  mj_forward(m, data_.get());
}

// Each arm joint's servo critically damped for the inertia it moves at the pick pose, c = 2 sqrt(kp M_jj): the file's
// is critical at the zero pose, where the arm's links reach elsewhere.
void CellPhysics::dampArm() {
  mjModel* m = model_.get();
  mj_forward(m, data_.get());
  for (std::size_t j = 0; j < arm_joints_.size(); ++j) {
    const int dof = m->jnt_dofadr[arm_joints_[j]];
    const double kp = m->actuator_gainprm[arm_actuators_[j] * mjNGAIN];
    m->dof_damping[dof] = 2.0 * std::sqrt(kp * data_->qM[m->dof_Madr[dof]]);
  }
}

void CellPhysics::resetPart() {
  for (int k = 0; k < 7; ++k) data_->qpos[part_qpos_ + k] = part_rest_[k];
  for (int k = 0; k < 6; ++k) data_->qvel[part_dof_ + k] = 0.0;
  mj_forward(model_.get(), data_.get());
}

void CellPhysics::jointStates(std::vector<std::string>& names, std::vector<double>& angles_rad) const {
  names.clear();
  angles_rad.clear();
  for (std::size_t j = 0; j < arm_joints_.size(); ++j) {
    names.emplace_back(mj_id2name(model_.get(), mjOBJ_JOINT, arm_joints_[j]));
    angles_rad.push_back(data_->qpos[arm_qpos_[j]]);
  }
  for (const PressureDrivenFinger& f : gripper_->fingers()) {
    for (int id : f.jointIds()) {
      names.emplace_back(mj_id2name(model_.get(), mjOBJ_JOINT, id));
      angles_rad.push_back(data_->qpos[model_->jnt_qposadr[id]]);
    }
  }
}

void CellPhysics::placeArm(const std::vector<double>& joints_rad) {
  setArmTargets(joints_rad);
  for (std::size_t j = 0; j < joints_rad.size(); ++j) {
    data_->qpos[arm_qpos_[j]] = joints_rad[j];
    data_->qvel[model_->jnt_dofadr[arm_joints_[j]]] = 0.0;
  }
  mj_forward(model_.get(), data_.get());
}

void CellPhysics::setArmTargets(const std::vector<double>& joints_rad) {
  if (joints_rad.size() != arm_actuators_.size()) {
    throw ParameterError("the arm has " + std::to_string(arm_actuators_.size()) + " joints, the targets " +
                         std::to_string(joints_rad.size()));
  }
  for (std::size_t j = 0; j < joints_rad.size(); ++j) data_->ctrl[arm_actuators_[j]] = joints_rad[j];
}

bool CellPhysics::step(double gauge_pa, std::string& why) {
  if (!gripper_->apply(gauge_pa, *data_, true, why)) return false;
  mj_step(model_.get(), data_.get());
  if (!stateIsFinite(*model_, *data_)) {
    why = "the simulation's state is not finite at " + formatMessage(data_->time) + " s";
    return false;
  }
  return true;
}

std::vector<int> CellPhysics::fingerContacts() const { return gripper_->partContacts(*data_); }

int CellPhysics::warnings() const { return mujocoWarnings(*data_); }

Eigen::Isometry3d CellPhysics::pose(int body) const {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  const double* q = data_->xquat + 4 * body;
  pose.linear() = Eigen::Quaterniond(q[0], q[1], q[2], q[3]).toRotationMatrix();
  pose.translation() = Eigen::Vector3d(data_->xpos[3 * body], data_->xpos[3 * body + 1], data_->xpos[3 * body + 2]);
  return pose;
}

}  // namespace pneumatic_finger
