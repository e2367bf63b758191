// The finger as a URDF chain, generated with urdfdom from the same parameters as the model. ROS-free.
//
// Links: <prefix>segment_0 (the passive base segment, from the mount to joint 1), <prefix>segment_1..N (segment n
// carries chamber n, from joint n to joint n+1) and <prefix>tip (at O_(N+1)). Joints: <prefix>mount (fixed, the
// parent frame to segment_0 at the mount pose), <prefix>joint_1..N (revolute about +z at the backbone's joint axes,
// positive = flexion toward the strain-limited side, docs/MODEL.md stage 6) and <prefix>tip_joint (fixed).
// Every segment frame has its origin on the backbone at its proximal joint and x along the segment.
// Each segment link has the same box as visual and collision, and an inertial: the elastomer block minus its
// chamber (elastomer_density_kg_m3), with the box-minus-cavity inertia about the block's centre.
#pragma once

#include <array>
#include <string>
#include <vector>

#include <urdf_model/model.h>

#include "pneumatic_finger/core/finger_model.hpp"
#include "pneumatic_finger/core/pressure_range.hpp"
#include "pneumatic_finger/core/calibration_error.hpp"
#include "pneumatic_finger/core/tip_uncertainty.hpp"

namespace pneumatic_finger {

struct FingerUrdfOptions {
  std::string prefix = "finger_";               ///< prepended to every link and joint name
  std::string parent_frame = "tool0";           ///< link the finger mounts on (included as the URDF's root)
  std::array<double, 3> mount_xyz_m{{0, 0, 0}};     ///< mount position in the parent frame (m)
  std::array<double, 3> mount_rpy_rad{{0, 0, 0}};   ///< mount orientation in the parent frame (rad, fixed-axis XYZ)
  double max_gauge_pa = kModelMaxGaugePa;             ///< joint upper limits are the joint angles at this pressure
};

std::string segmentLinkName(const std::string& prefix, int n);  ///< <prefix>segment_<n>, n = 0..N
std::string jointName(const std::string& prefix, int n);        ///< <prefix>joint_<n>, n = 1..N
std::string tipLinkName(const std::string& prefix);             ///< <prefix>tip

/// Whether @p prefix makes valid URDF link names and tf frame ids: empty, or a letter followed by letters,
/// digits and underscores. @param[out] why the reason when not
bool isValidNamePrefix(const std::string& prefix, std::string& why);

/// Whether @p frame is a valid tf frame id for the parent: non-empty, no leading '/', letters, digits, '_' and '/'.
bool isValidFrameId(const std::string& frame, std::string& why);

/// The finger's URDF model, wired like a parsed one (every link's parent joint and children, the root set), so it can
/// be used with urdfdom and KDL directly. @throws ParameterError for an invalid prefix or parent frame.
urdf::ModelInterface fingerUrdfModel(const FingerParameters& parameters, const FingerUrdfOptions& options);

/// One finger of a gripper: where it mounts and which actuator it is.
struct GripperFinger {
  FingerUrdfOptions mount;      ///< prefix, parent link, mount pose, max_gauge_pa
  FingerParameters parameters;  ///< the actuator
  std::string config_path;      ///< the parameter file it was read from (for messages)
  TipUncertainty tip_uncertainty;  ///< that file's error bar (empty when it has none)
  CalibrationError calibration_error;  ///< how well that file's calibration followed its data (empty: none)
  PressureRange range;             ///< that file's range (max_gauge_pa, validated_max_gauge_pa); mount.max_gauge_pa
};

/// Reads a gripper file (YAML): `fingers:` a list of {prefix, parent, xyz, rpy, config}, config a parameter file
/// path, relative to the gripper file's folder unless absolute. @throws ParameterError naming the file and entry.
std::vector<GripperFinger> loadGripperFile(const std::string& path);

/// The robot's URDF with every finger attached at its mount, as one model (exported as XML text).
/// @throws ParameterError, naming it, for a robot that does not parse, a parent link the robot lacks, a prefix
/// used twice, or a finger link or joint whose name the robot (or another finger) already has.
std::string composeRobotUrdf(const std::string& robot_urdf_xml, const std::vector<GripperFinger>& fingers);

/// The text of a robot's URDF file. @throws ParameterError naming a file that cannot be read
std::string readRobotUrdfFile(const std::string& robot_urdf_path);

/// The same from files: the robot's URDF and a gripper file.
std::string composeRobotUrdfFiles(const std::string& robot_urdf_path, const std::string& gripper_path);

/// The same, as URDF XML text (urdfdom's exporter).
std::string fingerUrdf(const FingerParameters& parameters, const FingerUrdfOptions& options);

}  // namespace pneumatic_finger
