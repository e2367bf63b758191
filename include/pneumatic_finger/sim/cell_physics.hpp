// The pick-and-place cell as physics (docs/SIMULATION.md): the arm follows joint targets through its position
// actuators, every finger's springs follow the regulator's pressure with the held moments, and the part is a free
// body on its table, carried, slipped or dropped by MuJoCo. ROS-free; what a node or a test steps.
#pragma once

#include <Eigen/Geometry>

#include <memory>
#include <string>
#include <vector>

#include "pneumatic_finger/core/finger_model.hpp"
#include "pneumatic_finger/sim/cell_scene.hpp"
#include "pneumatic_finger/sim/driven_gripper.hpp"
#include "pneumatic_finger/sim/mjcf_text.hpp"
#include "pneumatic_finger/sim/pressure_driven_finger.hpp"

namespace pneumatic_finger {

class CellPhysics {
 public:
  /// The cell of cellSceneMjcf (with a place table at @p place_joints_rad, when given), the arm at @p pick_joints_rad
  /// and held there. Each arm joint's servo is critically
  /// damped for the inertia it moves at that pose (the file's damping is for a joint held still, and would slow a
  /// moving one to 0.2 rad/s). @throws ParameterError as cellSceneMjcf
  CellPhysics(const std::string& arm_urdf_xml, const std::vector<GripperFinger>& fingers,
              const std::vector<std::string>& arm_joint_names, const std::vector<double>& pick_joints_rad,
              const GraspScene& scene, const MjcfOptions& mjcf, const std::vector<double>& place_joints_rad = {});

  /// A new part on the pick table, at rest where the scene put the first (the next cycle's part).
  void resetPart();

  /// Puts the arm at @p joints_rad at rest, its targets there too (where the cell starts). @throws ParameterError for
  /// another count
  void placeArm(const std::vector<double>& joints_rad);

  /// The arm's joint targets (rad, in arm_joint_names' order). @throws ParameterError for another count
  void setArmTargets(const std::vector<double>& joints_rad);

  /// One engine step (the file's) with every finger's springs at @p gauge_pa. false, nothing stepped, with @p why,
  /// where the twin has no shape at the pressure or the state is no longer finite.
  bool step(double gauge_pa, std::string& why);

  /// The part's pose and tool0's, in the world (the arm's base) frame; the simulated time (s).
  Eigen::Isometry3d partPose() const { return pose(part_body_); }
  Eigen::Isometry3d toolPose() const { return pose(tool_body_); }
  double timeS() const { return data_->time; }
  /// How many contacts the part has with each finger now.
  std::vector<int> fingerContacts() const;
  /// MuJoCo's warnings so far.
  int warnings() const;
  /// Every arm and finger joint's name and angle (rad): the simulated robot's joint states.
  void jointStates(std::vector<std::string>& names, std::vector<double>& angles_rad) const;

  const mjModel& model() const { return *model_; }
  const mjData& data() const { return *data_; }

 private:
  Eigen::Isometry3d pose(int body) const;
  void dampArm();

  MujocoModelPtr model_;
  MujocoDataPtr data_;
  std::unique_ptr<DrivenGripper> gripper_;
  std::vector<int> arm_joints_, arm_qpos_, arm_actuators_;
  int part_body_ = -1, part_geom_ = -1, tool_body_ = -1, part_qpos_ = -1, part_dof_ = -1;
  double part_rest_[7] = {};  // the part's free joint at the start: position and quaternion
};

}  // namespace pneumatic_finger
