#include "pneumatic_finger/description/finger_urdf.hpp"

#include <tinyxml.h>
#include <urdf_parser/urdf_parser.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <fstream>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <sstream>

#include "pneumatic_finger/core/drawing.hpp"
#include "pneumatic_finger/core/tip_uncertainty.hpp"
#include "pneumatic_finger/core/yaml_parameters.hpp"

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

// Principal moments of a uniform box of mass m and sides (x, y, z) about its centre.
urdf::Vector3 boxInertia(double m, double x, double y, double z) {
  return urdf::Vector3(m * (y * y + z * z) / 12, m * (x * x + z * z) / 12, m * (x * x + y * y) / 12);
}

// A segment's block and its cavity (m): the block's height (from the backbone) and width; the cavity's height and
// width. From the model's keys the block is the chamber (L x e) and the cavity spans it, the walls having no thickness
// across the finger; from a drawing (docs/DRAWING.md) the block is the body, up to its top and as wide as drawn, and
// the cavity the drawn one inside it.
struct BlockSize {
  double height = 0, width = 0, cavity_height = 0, cavity_width = 0;
};

BlockSize blockSize(const FingerParameters& p, std::size_t k) {
  BlockSize b{p.chamber_height_m[k], p.chamber_width_m[k], p.chamber_height_m[k], p.chamber_width_m[k]};
  const std::optional<ActuatorDrawing> d = drawingFromRaw(p.drawing);
  if (!d) return b;
  b.height = std::max(d->floor_height_m + d->cavity_height_m + d->roof_thickness_m, d->cavity_height_m);
  b.width = d->body_width_m;
  return b;
}

// A segment drawn as what it is: a block of elastomer, length along x, its height toward -y (the extensible side;
// the backbone runs along the strain-limited base layer at y = 0), the width along z. The collision shape is the
// same box (simple shapes, no meshes). The inertial: the block minus its cavity, of @p cavity_length along x (0 for
// the passive base segment), centred in it. Inertia: the block's minus the cavity's, both about the common centre
// (exact for that shape).
urdf::LinkSharedPtr segmentLink(const std::string& name, double length, const BlockSize& size, double cavity_length,
                                double density, const urdf::MaterialSharedPtr& material) {
  const double height = size.height, width = size.width;
  auto link = std::make_shared<urdf::Link>();
  link->name = name;
  auto box = std::make_shared<urdf::Box>();
  box->dim = urdf::Vector3(length, height, width);
  const urdf::Pose centre = poseXyzRpy(length / 2, -height / 2, 0, 0, 0, 0);
  auto visual = std::make_shared<urdf::Visual>();
  visual->geometry = box;
  visual->origin = centre;
  visual->material_name = material->name;
  visual->material = material;
  link->visual = visual;
  link->visual_array.push_back(visual);
  auto collision = std::make_shared<urdf::Collision>();
  collision->geometry = box;
  collision->origin = centre;
  link->collision = collision;
  link->collision_array.push_back(collision);
  const double block_mass = density * length * height * width;
  const double cavity_mass = density * cavity_length * size.cavity_height * size.cavity_width;
  const urdf::Vector3 block = boxInertia(block_mass, length, height, width);
  const urdf::Vector3 cavity = boxInertia(cavity_mass, cavity_length, size.cavity_height, size.cavity_width);
  auto inertial = std::make_shared<urdf::Inertial>();
  inertial->origin = centre;
  inertial->mass = block_mass - cavity_mass;
  inertial->ixx = block.x - cavity.x;
  inertial->iyy = block.y - cavity.y;
  inertial->izz = block.z - cavity.z;
  inertial->ixy = inertial->ixz = inertial->iyz = 0.0;
  link->inertial = inertial;
  return link;
}

// Sets what urdfdom's parser sets: each link's parent joint and parent link, each link's children, the root.
void wireTree(urdf::ModelInterface& m) {
  std::map<std::string, std::string> parent_of;
  for (auto& l : m.links_) {
    l.second->child_joints.clear();
    l.second->child_links.clear();
  }
  m.initTree(parent_of);
  m.initRoot(parent_of);
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

// Upper joint limits: the model's joint angles at the top of its pressure range (the finger cannot bend further
// there); the lower limits are 0: vacuum is outside the model, which then shows the straight finger.
std::vector<double> upperJointLimits(const FingerParameters& p, double max_gauge_pa) {
  FingerModel model(p);
  FingerWorkspace ws(model);
  // Under the membrane law the limit point may come first. Where the walls have a far branch they snap to it and bend
  // on up to the range's top; otherwise the joints reach the most the model holds just below the limit.
  const bool far = std::isfinite(model.farTurningGaugePa()) && max_gauge_pa >= model.limitGaugePa();
  model.startBranch(ws, far);
  const double top_pa = far ? max_gauge_pa : std::min(max_gauge_pa, model.belowLimitGaugePa());
  const FingerState* at_max = &model.evaluate(top_pa, ws);
  if (at_max->status == EvaluationStatus::kBeyondLimitPoint) {  // a group without a far branch passed its limit
    model.startBranch(ws, false);
    at_max = &model.evaluate(model.belowLimitGaugePa(), ws);
  }
  return std::vector<double>(at_max->joint_angle_rad.data(), at_max->joint_angle_rad.data() + p.chamber_count);
}

}  // namespace

urdf::ModelInterface fingerUrdfModel(const FingerParameters& p, const FingerUrdfOptions& o) {
  std::string why;
  if (!isValidNamePrefix(o.prefix, why)) throw ParameterError("frame prefix '" + o.prefix + "' " + why);
  if (!isValidFrameId(o.parent_frame, why)) throw ParameterError("parent frame '" + o.parent_frame + "' " + why);
  const int n = p.chamber_count;
  const std::vector<double> upper_rad = upperJointLimits(p, o.max_gauge_pa);
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
  m.links_[segmentLinkName(o.prefix, 0)] = segmentLink(segmentLinkName(o.prefix, 0), p.base_segment_length_m,
                                                       blockSize(p, 0), 0.0, p.elastomer_density_kg_m3, passive);
  m.joints_[o.prefix + "mount"] =
      joint(o.prefix + "mount", urdf::Joint::FIXED, o.parent_frame, segmentLinkName(o.prefix, 0),
            poseXyzRpy(o.mount_xyz_m[0], o.mount_xyz_m[1], o.mount_xyz_m[2], o.mount_rpy_rad[0], o.mount_rpy_rad[1],
                       o.mount_rpy_rad[2]));
  for (int i = 1; i <= n; ++i) {
    const auto k = static_cast<std::size_t>(i - 1);
    const std::string child = segmentLinkName(o.prefix, i);
    m.links_[child] = segmentLink(child, p.segment_length_m[k], blockSize(p, k),
                                  std::min(p.chamber_thickness_m[k], p.segment_length_m[k]), p.elastomer_density_kg_m3,
                                  material);
    const double proximal = i == 1 ? p.base_segment_length_m : p.segment_length_m[k - 1];
    auto j = joint(jointName(o.prefix, i), urdf::Joint::REVOLUTE, segmentLinkName(o.prefix, i - 1), child,
                   poseXyzRpy(proximal, 0, 0, 0, 0, 0));
    j->axis = urdf::Vector3(0, 0, 1);
    j->limits = std::make_shared<urdf::JointLimits>();
    j->limits->lower = 0.0;
    // A revolute joint needs upper > lower even where the walls never touch within the range.
    j->limits->upper = std::max(upper_rad[k], 1e-6);
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
  wireTree(m);
  return m;
}

namespace {

std::string triple(double a, double b, double c) {
  return formatExact(a) + " " + formatExact(b) + " " + formatExact(c);
}

// urdfdom's exporter writes numbers with 6 significant digits: a mount roll of pi/3 would come back 4e-6 rad off,
// and robot_state_publisher on this URDF would disagree with the node that far. The mount joint's origin is
// rewritten from the options it was made from (not from urdfdom's quaternion, whose RPY is ill-conditioned at
// pitch +-pi/2, where the cell's fingers are), and every joint limit, with every digit (17 significant).
std::string exportFingerXml(const urdf::ModelInterface& model, const FingerUrdfOptions& o) {
  std::unique_ptr<TiXmlDocument> doc(urdf::exportURDF(model));
  for (TiXmlElement* j = doc->RootElement()->FirstChildElement("joint"); j; j = j->NextSiblingElement("joint")) {
    const urdf::JointConstSharedPtr joint = model.getJoint(j->Attribute("name"));
    if (!joint) continue;
    TiXmlElement* origin = j->FirstChildElement("origin");
    if (origin && joint->name == o.prefix + "mount") {
      origin->SetAttribute("xyz", triple(o.mount_xyz_m[0], o.mount_xyz_m[1], o.mount_xyz_m[2]));
      origin->SetAttribute("rpy", triple(o.mount_rpy_rad[0], o.mount_rpy_rad[1], o.mount_rpy_rad[2]));
    } else if (origin) {  // the finger's own joints: a translation along x, no rotation
      const urdf::Vector3& t = joint->parent_to_joint_origin_transform.position;
      origin->SetAttribute("xyz", triple(t.x, t.y, t.z));
    }
    if (TiXmlElement* limit = j->FirstChildElement("limit"); limit && joint->limits) {
      limit->SetAttribute("lower", formatExact(joint->limits->lower));
      limit->SetAttribute("upper", formatExact(joint->limits->upper));
    }
  }
  TiXmlPrinter printer;
  printer.SetIndent("  ");
  doc->Accept(&printer);
  return std::string("<?xml version=\"1.0\"?>\n") + printer.CStr();
}

std::array<double, 3> readTriple(const YAML::Node& node, const std::string& where) {
  if (!node) return {0, 0, 0};
  if (!node.IsSequence() || node.size() != 3) throw ParameterError(where + " must be a list of 3 numbers");
  std::array<double, 3> v{};
  for (std::size_t i = 0; i < 3; ++i) {
    try {
      v[i] = node[i].as<double>();
    } catch (const YAML::Exception&) {
      throw ParameterError(where + ": entry " + std::to_string(i + 1) + " is not a number");
    }
    if (!std::isfinite(v[i])) throw ParameterError(where + ": entry " + std::to_string(i + 1) + " is not finite");
  }
  return v;
}

}  // namespace

std::string fingerUrdf(const FingerParameters& parameters, const FingerUrdfOptions& options) {
  return exportFingerXml(fingerUrdfModel(parameters, options), options);
}

std::vector<GripperFinger> loadGripperFile(const std::string& path) {
  YAML::Node root;
  try {
    root = YAML::LoadFile(path);
  } catch (const YAML::Exception& e) {
    throw ParameterError("gripper file '" + path + "': " + e.what());
  }
  const YAML::Node list = root["fingers"];
  if (!list || !list.IsSequence() || list.size() == 0) {
    throw ParameterError("gripper file '" + path + "' needs 'fingers:', a list of {prefix, parent, xyz, rpy, config}");
  }
  const std::string folder = path.find('/') == std::string::npos ? "." : path.substr(0, path.rfind('/'));
  std::vector<GripperFinger> fingers;
  for (std::size_t i = 0; i < list.size(); ++i) {
    const YAML::Node f = list[i];
    const std::string where = "gripper file '" + path + "', finger " + std::to_string(i + 1);
    for (const auto& kv : f) {
      const std::string key = kv.first.as<std::string>();
      if (key != "prefix" && key != "parent" && key != "xyz" && key != "rpy" && key != "config") {
        throw ParameterError(where + ": unknown key '" + key + "' (known: prefix, parent, xyz, rpy, config)");
      }
    }
    GripperFinger g;
    if (!f["prefix"] || !f["parent"]) throw ParameterError(where + " needs 'prefix' and 'parent'");
    g.mount.prefix = f["prefix"].as<std::string>();
    g.mount.parent_frame = f["parent"].as<std::string>();
    g.mount.mount_xyz_m = readTriple(f["xyz"], where + " 'xyz'");
    g.mount.mount_rpy_rad = readTriple(f["rpy"], where + " 'rpy'");
    RawParameterMap raw;
    if (f["config"]) {
      const std::string config = f["config"].as<std::string>();
      g.config_path = !config.empty() && config[0] == '/' ? config : folder + "/" + config;
      loadRawParametersFromYamlFile(g.config_path, raw, &g.tip_uncertainty, &g.range, &g.calibration_error);
    }
    g.mount.max_gauge_pa = g.range.max_gauge_pa;  // the joint limits at the top of its own range
    try {
      g.parameters = FingerParameters::fromRaw(raw);
    } catch (const ParameterError& e) {
      throw ParameterError(where + ": " + e.what());
    }
    fingers.push_back(g);
  }
  return fingers;
}

std::string composeRobotUrdf(const std::string& robot_urdf_xml, const std::vector<GripperFinger>& fingers) {
  // urdfdom checks the robot and the names; the fingers are then added to the robot's own XML, so that the robot's
  // numbers stay exactly as written (urdfdom's exporter would round them to 6 digits).
  const urdf::ModelInterfaceSharedPtr robot = urdf::parseURDF(robot_urdf_xml);
  if (!robot) throw ParameterError("the robot's URDF does not parse (urdfdom refused it)");
  TiXmlDocument doc;
  doc.Parse(robot_urdf_xml.c_str());
  if (doc.Error() || !doc.RootElement()) throw ParameterError("the robot's URDF is not XML that TinyXML reads");
  std::set<std::string> prefixes, links, joints, materials;
  for (const auto& l : robot->links_) links.insert(l.first);
  for (const auto& j : robot->joints_) joints.insert(j.first);
  for (const auto& m : robot->materials_) materials.insert(m.first);
  for (const GripperFinger& f : fingers) {
    const std::string& prefix = f.mount.prefix;
    if (!prefixes.insert(prefix).second) throw ParameterError("finger prefix '" + prefix + "' is used twice");
    if (!robot->getLink(f.mount.parent_frame)) {
      throw ParameterError("finger '" + prefix + "': the robot has no link '" + f.mount.parent_frame +
                           "' to mount it on");
    }
    const urdf::ModelInterface finger = fingerUrdfModel(f.parameters, f.mount);
    for (const auto& l : finger.links_) {
      if (l.first == f.mount.parent_frame) continue;  // the mount link is the robot's own
      if (!links.insert(l.first).second) {
        throw ParameterError("finger '" + prefix + "': link '" + l.first + "' already exists in the robot");
      }
    }
    for (const auto& j : finger.joints_) {
      if (!joints.insert(j.first).second) {
        throw ParameterError("finger '" + prefix + "': joint '" + j.first + "' already exists in the robot");
      }
    }
    TiXmlDocument finger_doc;
    finger_doc.Parse(exportFingerXml(finger, f.mount).c_str());
    for (const TiXmlElement* e = finger_doc.RootElement()->FirstChildElement(); e; e = e->NextSiblingElement()) {
      const std::string kind = e->Value(), name = e->Attribute("name") ? e->Attribute("name") : "";
      if (kind == "link" && name == f.mount.parent_frame) continue;
      if (kind == "material" && !materials.insert(name).second) continue;
      doc.RootElement()->InsertEndChild(*e);
    }
  }
  TiXmlPrinter printer;
  printer.SetIndent("  ");
  doc.Accept(&printer);
  const std::string xml = printer.CStr();
  if (!urdf::parseURDF(xml)) throw ParameterError("the composed URDF does not parse (urdfdom refused it)");
  return xml;
}

std::string readRobotUrdfFile(const std::string& robot_urdf_path) {
  std::ifstream in(robot_urdf_path);
  if (!in) throw ParameterError("cannot read the robot's URDF '" + robot_urdf_path + "'");
  std::stringstream xml;
  xml << in.rdbuf();
  return xml.str();
}

std::string composeRobotUrdfFiles(const std::string& robot_urdf_path, const std::string& gripper_path) {
  return composeRobotUrdf(readRobotUrdfFile(robot_urdf_path), loadGripperFile(gripper_path));
}

}  // namespace pneumatic_finger
