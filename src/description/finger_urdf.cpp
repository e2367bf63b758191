#include "pneumatic_finger/description/finger_urdf.hpp"

#include <tinyxml.h>
#include <urdf_parser/urdf_parser.h>

#include <cctype>
#include <memory>

namespace pneumatic_finger {

std::string segmentLinkName(const std::string& prefix, int n) { return prefix + "segment_" + std::to_string(n); }
std::string jointName(const std::string& prefix, int n) { return prefix + "joint_" + std::to_string(n); }
std::string tipLinkName(const std::string& prefix) { return prefix + "tip"; }

bool isValidNamePrefix(const std::string& prefix, std::string& why) {
  if (prefix.empty()) return true;
  if (!std::isalpha(static_cast<unsigned char>(prefix[0]))) {
    why = "must start with a letter";
    return false;
  }
  for (char c : prefix) {
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '_') {
      why = std::string("contains '") + c + "'; allowed: letters, digits and '_'";
      return false;
    }
  }
  return true;
}

bool isValidFrameId(const std::string& frame, std::string& why) {
  if (frame.empty()) {
    why = "is empty";
    return false;
  }
  if (frame[0] == '/') {
    why = "starts with '/', which tf2 refuses";
    return false;
  }
  for (char c : frame) {
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '_' && c != '/') {
      why = std::string("contains '") + c + "'; allowed: letters, digits, '_' and '/'";
      return false;
    }
  }
  return true;
}

namespace {

urdf::Pose poseXyzRpy(double x, double y, double z, double roll, double pitch, double yaw) {
  urdf::Pose p;
  p.position = urdf::Vector3(x, y, z);
  p.rotation.setFromRPY(roll, pitch, yaw);
  return p;
}

// A segment drawn as what it is: a block of elastomer, length along x, the chamber height toward -y (the
// extensible side; the backbone runs along the strain-limited base layer at y = 0), the width along z.
urdf::LinkSharedPtr segmentLink(const std::string& name, double length, double height, double width,
                                const urdf::MaterialSharedPtr& material) {
  auto link = std::make_shared<urdf::Link>();
  link->name = name;
  auto visual = std::make_shared<urdf::Visual>();
  auto box = std::make_shared<urdf::Box>();
  box->dim = urdf::Vector3(length, height, width);
  visual->geometry = box;
  visual->origin = poseXyzRpy(length / 2, -height / 2, 0, 0, 0, 0);
  visual->material_name = material->name;
  visual->material = material;
  link->visual = visual;
  link->visual_array.push_back(visual);
  return link;
}

urdf::JointSharedPtr joint(const std::string& name, int type, const std::string& parent, const std::string& child,
                           const urdf::Pose& origin) {
  auto j = std::make_shared<urdf::Joint>();
  j->name = name;
  j->type = static_cast<decltype(j->type)>(type);
  j->parent_link_name = parent;
  j->child_link_name = child;
  j->parent_to_joint_origin_transform = origin;
  return j;
}

}  // namespace

urdf::ModelInterface fingerUrdfModel(const FingerParameters& p, const FingerUrdfOptions& o) {
  std::string why;
  if (!isValidNamePrefix(o.prefix, why)) throw ParameterError("frame prefix '" + o.prefix + "' " + why);
  if (!isValidFrameId(o.parent_frame, why)) throw ParameterError("parent frame '" + o.parent_frame + "' " + why);
  const int n = p.chamber_count;
  // Upper joint limits: the model's joint angles at the top of its pressure range (the finger cannot bend further
  // there); lower limits 0: vacuum is outside the model, which then shows the straight finger.
  FingerModel model(p);
  const FingerState& at_max = model.evaluate(o.max_gauge_pa);

  urdf::ModelInterface m;
  m.name_ = o.prefix + "pneumatic_finger";
  auto material = std::make_shared<urdf::Material>();
  material->name = o.prefix + "elastomer";
  material->color.init("0.93 0.55 0.18 1.0");
  m.materials_[material->name] = material;
  auto passive = std::make_shared<urdf::Material>();
  passive->name = o.prefix + "base_segment";
  passive->color.init("0.45 0.45 0.5 1.0");
  m.materials_[passive->name] = passive;

  // The parent is the root and carries no inertial (robot_state_publisher warns about an inertial on the root).
  auto root = std::make_shared<urdf::Link>();
  root->name = o.parent_frame;
  m.links_[root->name] = root;
  const double height0 = p.chamber_height_m[0], width0 = p.chamber_width_m[0];
  m.links_[segmentLinkName(o.prefix, 0)] =
      segmentLink(segmentLinkName(o.prefix, 0), p.base_segment_length_m, height0, width0, passive);
  m.joints_[o.prefix + "mount"] =
      joint(o.prefix + "mount", urdf::Joint::FIXED, o.parent_frame, segmentLinkName(o.prefix, 0),
            poseXyzRpy(o.mount_xyz_m[0], o.mount_xyz_m[1], o.mount_xyz_m[2], o.mount_rpy_rad[0], o.mount_rpy_rad[1],
                       o.mount_rpy_rad[2]));
  for (int i = 1; i <= n; ++i) {
    const auto k = static_cast<std::size_t>(i - 1);
    const std::string child = segmentLinkName(o.prefix, i);
    m.links_[child] = segmentLink(child, p.segment_length_m[k], p.chamber_height_m[k], p.chamber_width_m[k], material);
    const double proximal = i == 1 ? p.base_segment_length_m : p.segment_length_m[k - 1];
    auto j = joint(jointName(o.prefix, i), urdf::Joint::REVOLUTE, segmentLinkName(o.prefix, i - 1), child,
                   poseXyzRpy(proximal, 0, 0, 0, 0, 0));
    j->axis = urdf::Vector3(0, 0, 1);
    j->limits = std::make_shared<urdf::JointLimits>();
    j->limits->lower = 0.0;
    // A revolute joint needs upper > lower even where the walls never touch within the range.
    j->limits->upper = std::max(at_max.joint_angle_rad[i - 1], 1e-6);
    j->limits->effort = 0.0;    // not actuated by torque: the angle follows from the pressure
    j->limits->velocity = 10.0;  // rad/s, above what a regulator fill (about 1 s) produces
    m.joints_[j->name] = j;
  }
  auto tip = std::make_shared<urdf::Link>();
  tip->name = tipLinkName(o.prefix);
  m.links_[tip->name] = tip;
  m.joints_[o.prefix + "tip_joint"] =
      joint(o.prefix + "tip_joint", urdf::Joint::FIXED, segmentLinkName(o.prefix, n), tip->name,
            poseXyzRpy(p.segment_length_m.back(), 0, 0, 0, 0, 0));
  m.root_link_ = root;
  return m;
}

std::string fingerUrdf(const FingerParameters& parameters, const FingerUrdfOptions& options) {
  const urdf::ModelInterface model = fingerUrdfModel(parameters, options);
  std::unique_ptr<TiXmlDocument> doc(urdf::exportURDF(model));
  TiXmlPrinter printer;
  printer.SetIndent("  ");
  doc->Accept(&printer);
  return std::string("<?xml version=\"1.0\"?>\n") + printer.CStr();
}

}  // namespace pneumatic_finger
