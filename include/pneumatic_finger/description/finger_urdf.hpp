// The finger as a URDF chain, generated with urdfdom from the same parameters as the model. ROS-free.
//
// Links: <prefix>segment_0 (the passive base segment, from the mount to joint 1), <prefix>segment_1..N (segment n
// carries chamber n, from joint n to joint n+1) and <prefix>tip (at O_(N+1)). Joints: <prefix>mount (fixed, the
// parent frame to segment_0 at the mount pose), <prefix>joint_1..N (revolute about +z at the backbone's joint axes,
// positive = flexion toward the strain-limited side, docs/MODEL.md stage 6) and <prefix>tip_joint (fixed).
// Every segment frame has its origin on the backbone at its proximal joint and x along the segment.
#pragma once

#include <array>
#include <string>

#include <urdf_model/model.h>

#include "pneumatic_finger/core/finger_model.hpp"

namespace pneumatic_finger {

struct FingerUrdfOptions {
  std::string prefix = "finger_";               ///< prepended to every link and joint name
  std::string parent_frame = "tool0";           ///< link the finger mounts on (included as the URDF's root)
  std::array<double, 3> mount_xyz_m{{0, 0, 0}};     ///< mount position in the parent frame (m)
  std::array<double, 3> mount_rpy_rad{{0, 0, 0}};   ///< mount orientation in the parent frame (rad, fixed-axis XYZ)
  double max_gauge_pa = 294199.5;               ///< joint upper limits are the joint angles at this pressure
};

std::string segmentLinkName(const std::string& prefix, int n);  ///< <prefix>segment_<n>, n = 0..N
std::string jointName(const std::string& prefix, int n);        ///< <prefix>joint_<n>, n = 1..N
std::string tipLinkName(const std::string& prefix);             ///< <prefix>tip

/// Whether @p prefix makes valid URDF link names and tf frame ids: empty, or a letter followed by letters,
/// digits and underscores. @param[out] why the reason when not
bool isValidNamePrefix(const std::string& prefix, std::string& why);

/// Whether @p frame is a valid tf frame id for the parent: non-empty, no leading '/', letters, digits, '_' and '/'.
bool isValidFrameId(const std::string& frame, std::string& why);

/// The finger's URDF model. @throws ParameterError for an invalid prefix or parent frame.
urdf::ModelInterface fingerUrdfModel(const FingerParameters& parameters, const FingerUrdfOptions& options);

/// The same, as URDF XML text (urdfdom's exporter).
std::string fingerUrdf(const FingerParameters& parameters, const FingerUrdfOptions& options);

}  // namespace pneumatic_finger
