// The cell arm's forward kinematics, base -> tool, from the URDF, with KDL (cell_sequencer_node.cpp's).
#pragma once

#include <Eigen/Geometry>
#include <kdl/chainfksolverpos_recursive.hpp>
#include <kdl/tree.hpp>
#include <kdl_parser/kdl_parser.hpp>

#include <algorithm>
#include <stdexcept>
#include <string>
#include <vector>

#include "pneumatic_finger/cell/cell_schedule.hpp"
#include "pneumatic_finger/core/smoothstep.hpp"

namespace pneumatic_finger {

// The arm's forward kinematics base -> tool, from the URDF, with KDL.
class ArmKinematics {
 public:
  ArmKinematics(const std::string& urdf_xml, const std::string& base, const std::string& tool,
                const std::vector<std::string>& joint_names) {
    KDL::Tree tree;
    if (!kdl_parser::treeFromString(urdf_xml, tree)) throw std::runtime_error("'robot_description' does not parse");
    if (!tree.getChain(base, tool, chain_)) {
      throw std::runtime_error("'robot_description' has no chain from '" + base + "' to '" + tool + "'");
    }
    for (const auto& segment : chain_.segments) {
      if (segment.getJoint().getType() == KDL::Joint::None) continue;
      const auto it = std::find(joint_names.begin(), joint_names.end(), segment.getJoint().getName());
      if (it == joint_names.end()) {
        throw std::runtime_error("joint '" + segment.getJoint().getName() + "' of the arm is not in 'arm_joint_names'");
      }
      index_.push_back(static_cast<std::size_t>(it - joint_names.begin()));
    }
  }

  Eigen::Isometry3d toolPose(const ArmJoints& q) const {
    KDL::JntArray joints(static_cast<unsigned>(index_.size()));
    for (std::size_t i = 0; i < index_.size(); ++i) joints(static_cast<unsigned>(i)) = q[index_[i]];
    KDL::Frame frame;
    KDL::ChainFkSolverPos_recursive(chain_).JntToCart(joints, frame);
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    double x, y, z, w;
    frame.M.GetQuaternion(x, y, z, w);
    pose.linear() = Eigen::Quaterniond(w, x, y, z).toRotationMatrix();
    pose.translation() = Eigen::Vector3d(frame.p.x(), frame.p.y(), frame.p.z());
    return pose;
  }

  /// The lift's peak upward acceleration (m/s^2): the schedule's path over the tool's rise from the pick pose to the
  /// pose above it. Its inertia adds to the weight the grip must hold (docs/SIMULATION.md, "Does the grasp rule
  /// hold?"); 0 for a lift that does not rise.
  double liftPeakAccelerationMps2(const CellWaypoints& w, const CellSchedule& schedule) const {
    const double rise_m = (toolPose(w.above_pick).translation() - toolPose(w.pick).translation()).z();
    return std::max(0.0, smoothstepPeakAcceleration(rise_m, schedule.phaseDurationS(CellPhase::kLift)));
  }

 private:
  KDL::Chain chain_;
  std::vector<std::size_t> index_;  // chain joint -> position in arm_joint_names
};

}  // namespace pneumatic_finger
