// The grasp-and-lift scene: the gripper's fingers on a lift (a carriage on a vertical slide, the tool frame pointing
// down as on the cell's arm) and the cell's cylinder as a free body with its mass, held where the cell holds it
// (docs/SIMULATION.md, "Does the grasp rule hold?"). ROS-free and MuJoCo-free: it writes text.
#pragma once

#include <string>
#include <vector>

#include "pneumatic_finger/description/finger_urdf.hpp"
#include "pneumatic_finger/sim/finger_mjcf.hpp"

namespace pneumatic_finger {

/// The names the scene gives its lift joint, its tool body and its object (body and geom).
constexpr const char* kLiftJointName = "lift";
constexpr const char* kSceneToolName = "tool0";
constexpr const char* kSceneObjectName = "object";

/// The object and where it is held. The defaults are the cell's part (config/cell.yaml).
struct GraspScene {
  double object_radius_m = 0.016;       ///< the cylinder's radius (m)
  double object_height_m = 0.035;       ///< its height (m)
  double object_mass_kg = 0.01;         ///< its mass (kg), spread uniformly
  double object_centre_depth_m = 0.0;   ///< its centre along tool z from the tool frame (m): sideGraspDepth's
};

/// The scene's MJCF: @p fingers mounted on tool0 (their mounts' parent must be tool0), tool0 on a carriage that the
/// slide joint kLiftJointName moves along world z (tool z pointing down), and the object, a free cylinder standing on
/// tool z at the depth @p scene gives, with the carriage at 0. Every finger's springs at @p mjcf.gauge_pa. The
/// object's contacts are stiffer than MuJoCo's default (a 2 ms time constant, 20 steps of the file's 0.1 ms), so that
/// the fingers do not sink into it. @throws ParameterError for a size or mass that is not finite and > 0, a finger
/// not on tool0, and as composedMjcf
std::string graspSceneMjcf(const std::vector<GripperFinger>& fingers, const GraspScene& scene, const MjcfOptions& mjcf);

/// The part alone as an MJCF body of the world (kSceneObjectName), its centre at @p pos and its axis along the z axis
/// of the rotation @p quat (MJCF's "x y z" and "w x y z" text): what graspSceneMjcf and cellSceneMjcf add.
std::string partBodyMjcf(const GraspScene& scene, const std::string& pos, const std::string& quat);

}  // namespace pneumatic_finger
