// The pick-and-place cell in MuJoCo: the arm with its gripper (composedMjcf), a table at the pick spot and the part
// standing on it where the gripper holds it at the pick pose (docs/SIMULATION.md). ROS-free; needs libmujoco-dev.
#pragma once

#include <string>
#include <vector>

#include "pneumatic_finger/sim/grasp_scene.hpp"

namespace pneumatic_finger {

/// The cell's MJCF. The part (@p scene's size and mass) stands with its centre @p scene.object_centre_depth_m along
/// tool z from tool0 at the pick pose @p pick_joints_rad (the arm's joints @p arm_joint_names), its axis along tool z,
/// on a table whose top meets its base; with @p place_joints_rad, a second table where the part's base is when the
/// gripper holds it at that pose (where the cell puts it down). @throws ParameterError as composedMjcf and
/// graspSceneMjcf, and for a joint name the arm lacks or a pose of another size
std::string cellSceneMjcf(const std::string& arm_urdf_xml, const std::vector<GripperFinger>& fingers,
                          const std::vector<std::string>& arm_joint_names, const std::vector<double>& pick_joints_rad,
                          const GraspScene& scene, const MjcfOptions& mjcf,
                          const std::vector<double>& place_joints_rad = {});

}  // namespace pneumatic_finger
