// The finger as a MuJoCo model (MJCF): the URDF's bodies, inertials and collision boxes, with each finger joint's
// spring (joint_springs.hpp) at a pressure, so that MuJoCo's own passive springs hold the twin's shape and another
// program that loads the file gets the same finger (docs/MODEL.md, "Joint springs"; docs/SIMULATION.md). ROS-free and
// MuJoCo-free: it writes text.
#pragma once

#include <string>
#include <vector>

#include "pneumatic_finger/description/finger_urdf.hpp"

namespace pneumatic_finger {

/// The MJCF's settings besides the description. Each is written into the file, with the reason beside it.
struct MjcfOptions {
  double gauge_pa = 0.0;        ///< the pressure whose springs the joints carry (Pa gauge)
  double timestep_s = 1e-3;     ///< the engine's step (s): the armature below makes it short against every period
  /// Each finger joint gets an armature (a rotor inertia, which changes no static shape or force) so that its stiffest
  /// spring over the finger's range, on the chain beyond the joint plus the armature, has a period of at least this
  /// many steps: J + A >= k_max (steps dt / 2 pi)^2. 0: no armature (the chain's own inertia alone).
  double steps_per_period = 60.0;
  double damping_ratio = 1.0;   ///< each joint's damping, as a share of critical for the chain beyond it
  double friction = 1.0;        ///< sliding friction of every geom (silicone on most objects: 1 and more)
  double impratio = 10.0;       ///< elliptic friction cones, frictional constraints this much harder than normal ones
};

/// The robot's joints in a composed MJCF: position actuators whose gain is this many times the joint's effort limit
/// (N m/rad per N m: the rated torque at 10 mrad of error), each joint damped critically for the inertia it moves at
/// the zero pose, 2 sqrt(kp M_jj). Stated, not tuned against the arm.
constexpr double kPositionGainPerRad = 100.0;

/// The MJCF of one finger mounted on @p options.parent_frame (a static body at the world's origin), its joints'
/// springs at @p mjcf.gauge_pa, a site <prefix>tip at the tip. @throws ParameterError as fingerUrdfModel does, and
/// where the twin has no free shape at the pressure (beyond the membrane law's limit point)
std::string fingerMjcf(const FingerParameters& parameters, const FingerUrdfOptions& options, const MjcfOptions& mjcf);

/// The MJCF of a robot with a gripper (finger_urdf --robot --gripper --mjcf): composeRobotUrdfFiles' description,
/// every finger's joints with their springs at @p mjcf.gauge_pa, every other moving joint with a position actuator
/// (kPositionGainPerRad, critically damped at the zero pose) named after it. @throws ParameterError as composeRobotUrdfFiles, and
/// where a finger's twin has no free shape at the pressure
std::string composedMjcf(const std::string& robot_urdf_path, const std::string& gripper_path, const MjcfOptions& mjcf);

/// The same from a robot's URDF text and its fingers, with @p world_xml (MJCF elements: bodies, geoms) added to the
/// world body: the scene around the robot (grasp_scene.hpp). @throws ParameterError as composeRobotUrdf, and where a
/// finger's twin has no free shape at the pressure
std::string composedMjcf(const std::string& robot_urdf_xml, const std::vector<GripperFinger>& fingers,
                         const MjcfOptions& mjcf, const std::string& world_xml);

}  // namespace pneumatic_finger
