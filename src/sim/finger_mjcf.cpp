// The finger as MJCF (finger_mjcf.hpp): the URDF model walked from its root, each link a body, each finger joint a
// hinge with its spring.
#include "pneumatic_finger/sim/finger_mjcf.hpp"

#include <Eigen/Geometry>

#include <cmath>
#include <map>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include <urdf_parser/urdf_parser.h>

#include "pneumatic_finger/sim/joint_springs.hpp"

namespace pneumatic_finger {

namespace {

std::string num(double v) { return formatShortest(v); }

std::string posQuat(const urdf::Pose& pose) {
  double x = 0, y = 0, z = 0, w = 1;
  pose.rotation.getQuaternion(x, y, z, w);
  return "pos=\"" + num(pose.position.x) + " " + num(pose.position.y) + " " + num(pose.position.z) + "\" quat=\"" +
         num(w) + " " + num(x) + " " + num(y) + " " + num(z) + "\"";
}

// A finger joint's spring and damping, by name.
struct JointDynamics {
  JointSpring spring;
  double damping_nms = 0.0;
  double armature_kgm2 = 0.0;
};

// The rotational inertia (kg m^2) about joint n's axis of every link beyond it, in the straight finger (all joints
// at 0, so each link's frame is the previous one's shifted along x).
double distalInertia(const urdf::ModelInterface& model, const std::string& prefix, int joint, int chambers) {
  double inertia = 0.0, offset = 0.0;
  for (int k = joint; k <= chambers; ++k) {
    const auto link = model.getLink(segmentLinkName(prefix, k));
    if (k > joint) offset += model.getJoint(jointName(prefix, k))->parent_to_joint_origin_transform.position.x;
    if (!link || !link->inertial) continue;
    const urdf::Inertial& in = *link->inertial;
    const double x = offset + in.origin.position.x, y = in.origin.position.y;
    inertia += in.izz + in.mass * (x * x + y * y);
  }
  return inertia;
}

Eigen::Isometry3d isometryOf(const urdf::Pose& pose) {
  double x = 0, y = 0, z = 0, w = 1;
  pose.rotation.getQuaternion(x, y, z, w);
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.linear() = Eigen::Quaterniond(w, x, y, z).normalized().toRotationMatrix();
  t.translation() = Eigen::Vector3d(pose.position.x, pose.position.y, pose.position.z);
  return t;
}

// Every link's pose with all joints at 0 (the file's reference pose), from @p link down; @p pose is @p link's.
void zeroPose(const urdf::LinkConstSharedPtr& link, const Eigen::Isometry3d& pose,
              std::map<std::string, Eigen::Isometry3d>& poses) {
  poses[link->name] = pose;
  for (const auto& child : link->child_links) {
    zeroPose(child, pose * isometryOf(child->parent_joint->parent_to_joint_origin_transform), poses);
  }
}

// M_jj: the inertia about @p joint's axis (kg m^2; the mass, kg, for a prismatic joint) of every link beyond it, the
// robot at its zero pose: what MuJoCo's mass matrix holds on the joint's diagonal there.
double inertiaBeyond(const urdf::ModelInterface& model, const urdf::Joint& joint,
                     const std::map<std::string, Eigen::Isometry3d>& poses) {
  const Eigen::Isometry3d frame = poses.at(joint.parent_link_name) * isometryOf(joint.parent_to_joint_origin_transform);
  const Eigen::Vector3d axis = frame.linear() * Eigen::Vector3d(joint.axis.x, joint.axis.y, joint.axis.z).normalized();
  double sum = 0.0;
  std::vector<urdf::LinkConstSharedPtr> beyond{model.getLink(joint.child_link_name)};
  while (!beyond.empty()) {
    const urdf::LinkConstSharedPtr link = beyond.back();
    beyond.pop_back();
    beyond.insert(beyond.end(), link->child_links.begin(), link->child_links.end());
    if (!link->inertial) continue;
    const urdf::Inertial& in = *link->inertial;
    if (joint.type == urdf::Joint::PRISMATIC) {
      sum += in.mass;
      continue;
    }
    const Eigen::Isometry3d com = poses.at(link->name) * isometryOf(in.origin);
    Eigen::Matrix3d tensor;
    tensor << in.ixx, in.ixy, in.ixz, in.ixy, in.iyy, in.iyz, in.ixz, in.iyz, in.izz;
    const Eigen::Vector3d arm = com.translation() - frame.translation();
    const Eigen::Vector3d off_axis = arm - arm.dot(axis) * axis;
    sum += axis.dot(com.linear() * tensor * com.linear().transpose() * axis) + in.mass * off_axis.squaredNorm();
  }
  return sum;
}

void writeBody(std::ostringstream& out, const urdf::ModelInterface& model, const urdf::LinkConstSharedPtr& link,
               const std::map<std::string, JointDynamics>& dynamics, const std::string& indent);

// The inertial at its position, its tensor turned into the body's axes (MJCF's fullinertia takes no orientation):
// I_body = R I R^T, R the URDF inertial frame's rotation.
void writeInertial(std::ostringstream& out, const urdf::Inertial& i, const std::string& indent) {
  double x = 0, y = 0, z = 0, w = 1;
  i.origin.rotation.getQuaternion(x, y, z, w);
  const double r[3][3] = {{1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)},
                          {2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)},
                          {2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)}};
  const double t[3][3] = {{i.ixx, i.ixy, i.ixz}, {i.ixy, i.iyy, i.iyz}, {i.ixz, i.iyz, i.izz}};
  double b[3][3] = {};
  for (int a = 0; a < 3; ++a) {
    for (int c = 0; c < 3; ++c) {
      for (int k = 0; k < 3; ++k) {
        for (int l = 0; l < 3; ++l) b[a][c] += r[a][k] * t[k][l] * r[c][l];
      }
    }
  }
  const urdf::Vector3& p = i.origin.position;
  out << indent << "<inertial pos=\"" << num(p.x) << " " << num(p.y) << " " << num(p.z) << "\" mass=\"" << num(i.mass)
      << "\" fullinertia=\"" << num(b[0][0]) << " " << num(b[1][1]) << " " << num(b[2][2]) << " " << num(b[0][1]) << " "
      << num(b[0][2]) << " " << num(b[1][2]) << "\"/>\n";
}

void writeJoint(std::ostringstream& out, const urdf::Joint& joint, const std::map<std::string, JointDynamics>& dynamics,
                const std::string& indent) {
  if (joint.type == urdf::Joint::FIXED) return;
  const urdf::Vector3& a = joint.axis;
  out << indent << "<joint name=\"" << joint.name << "\" type=\""
      << (joint.type == urdf::Joint::PRISMATIC ? "slide" : "hinge") << "\" axis=\"" << num(a.x) << " " << num(a.y)
      << " " << num(a.z) << "\"";
  const auto d = dynamics.find(joint.name);
  const bool finger_joint = d != dynamics.end() && d->second.spring.stiffness_nm_per_rad > 0.0;
  // A finger joint is its spring: the URDF's range (the shapes the pressure gives, for planners) would add a limit's
  // force to the force model's statics (a joint held back past straight by a plate, say).
  if (joint.limits && joint.type != urdf::Joint::CONTINUOUS && !finger_joint) {
    out << " limited=\"true\" range=\"" << num(joint.limits->lower) << " " << num(joint.limits->upper) << "\"";
  }
  if (finger_joint) {
    out << " stiffness=\"" << num(d->second.spring.stiffness_nm_per_rad) << "\" springref=\""
        << num(d->second.spring.rest_angle_rad) << "\"";
  }
  if (d != dynamics.end()) out << " damping=\"" << num(d->second.damping_nms) << "\"";
  if (d != dynamics.end() && d->second.armature_kgm2 > 0.0) {
    out << " armature=\"" << num(d->second.armature_kgm2) << "\"";
  }
  out << "/>\n";
}

// The link's visual colour (its URDF material), so that MuJoCo's viewer shows the finger as rviz does.
std::string rgba(const urdf::Link& link) {
  if (!link.visual || !link.visual->material) return "";
  const urdf::Color& c = link.visual->material->color;
  return " rgba=\"" + num(c.r) + " " + num(c.g) + " " + num(c.b) + " " + num(c.a) + "\"";
}

void writeGeoms(std::ostringstream& out, const urdf::Link& link, const std::string& indent) {
  for (const auto& c : link.collision_array) {
    if (!c || !c->geometry) continue;
    std::string type, size;
    if (c->geometry->type == urdf::Geometry::BOX) {
      const urdf::Vector3& s = static_cast<const urdf::Box&>(*c->geometry).dim;
      type = "box", size = num(s.x / 2) + " " + num(s.y / 2) + " " + num(s.z / 2);
    } else if (c->geometry->type == urdf::Geometry::CYLINDER) {
      const auto& cyl = static_cast<const urdf::Cylinder&>(*c->geometry);
      type = "cylinder", size = num(cyl.radius) + " " + num(cyl.length / 2);
    } else if (c->geometry->type == urdf::Geometry::SPHERE) {
      type = "sphere", size = num(static_cast<const urdf::Sphere&>(*c->geometry).radius);
    } else {
      continue;  // meshes: the described robots here have none
    }
    out << indent << "<geom type=\"" << type << "\" size=\"" << size << "\" " << posQuat(c->origin) << rgba(link)
        << "/>\n";
  }
}

void writeBody(std::ostringstream& out, const urdf::ModelInterface& model, const urdf::LinkConstSharedPtr& link,
               const std::map<std::string, JointDynamics>& dynamics, const std::string& indent) {
  const urdf::JointConstSharedPtr& parent = link->parent_joint;
  out << indent << "<body name=\"" << link->name << "\""
      << (parent ? " " + posQuat(parent->parent_to_joint_origin_transform) : std::string()) << ">\n";
  const std::string in = indent + "  ";
  if (parent) writeJoint(out, *parent, dynamics, in);
  if (link->inertial) writeInertial(out, *link->inertial, in);
  writeGeoms(out, *link, in);
  if (link->child_links.empty()) out << in << "<site name=\"" << link->name << "\" size=\"0.0005\"/>\n";
  for (const auto& child : link->child_links) writeBody(out, model, child, dynamics, in);
  out << indent << "</body>\n";
}

}  // namespace

namespace {

// Each finger joint's spring at the pressure, its armature (MjcfOptions::steps_per_period, from its stiffest spring up
// to @p max_gauge_pa) and its damping: critical for the chain beyond it as one rigid body on the spring, with the
// armature, c = 2 zeta sqrt(k (J + A)). @throws ParameterError where the twin has no free shape.
void addFingerDynamics(const urdf::ModelInterface& model, const FingerParameters& parameters, const std::string& prefix,
                       double max_gauge_pa, const MjcfOptions& mjcf, std::map<std::string, JointDynamics>& dynamics) {
  const FingerModel twin(parameters);
  std::string why;
  const std::vector<JointSpring> springs = jointSprings(twin, mjcf.gauge_pa, why);
  if (springs.empty()) throw ParameterError("--mjcf --gauge-pa: " + why);
  const int n = parameters.chamber_count;
  const double period_s = mjcf.steps_per_period * mjcf.timestep_s / (2.0 * M_PI);
  for (int j = 1; j <= n; ++j) {
    JointDynamics d{springs[static_cast<std::size_t>(j - 1)], 0.0, 0.0};
    const double inertia = distalInertia(model, prefix, j, n);
    d.armature_kgm2 = std::max(0.0, stiffestSpringNmPerRad(twin, j - 1, max_gauge_pa) * period_s * period_s - inertia);
    d.damping_nms = 2.0 * mjcf.damping_ratio * std::sqrt(d.spring.stiffness_nm_per_rad * (inertia + d.armature_kgm2));
    dynamics[jointName(prefix, j)] = d;
  }
}

// The MJCF of @p model: the springs of @p dynamics' joints; a position actuator on every other moving joint (the
// robot's), of stiffness kPositionGainPerRad times its effort limit, the joint damped critically for the inertia it
// moves at the zero pose (2 sqrt(kp M_jj));
// contacts between the fingers' neighbouring segments off (@p excluded: pairs of body names).
std::string writeMjcf(const urdf::ModelInterface& model, const std::map<std::string, JointDynamics>& dynamics,
                      const std::vector<std::pair<std::string, std::string>>& excluded, const MjcfOptions& mjcf,
                      const std::string& world_xml);

}  // namespace

std::string fingerMjcf(const FingerParameters& parameters, const FingerUrdfOptions& options, const MjcfOptions& mjcf) {
  const urdf::ModelInterface model = fingerUrdfModel(parameters, options);
  std::map<std::string, JointDynamics> dynamics;
  addFingerDynamics(model, parameters, options.prefix, options.max_gauge_pa, mjcf, dynamics);
  std::vector<std::pair<std::string, std::string>> excluded;
  for (int j = 1; j <= parameters.chamber_count; ++j) {
    excluded.emplace_back(segmentLinkName(options.prefix, j - 1), segmentLinkName(options.prefix, j));
  }
  return writeMjcf(model, dynamics, excluded, mjcf, "");
}

std::string composedMjcf(const std::string& robot_urdf_path, const std::string& gripper_path, const MjcfOptions& mjcf) {
  return composedMjcf(readRobotUrdfFile(robot_urdf_path), loadGripperFile(gripper_path), mjcf, "");
}

std::string composedMjcf(const std::string& robot_urdf_xml, const std::vector<GripperFinger>& fingers,
                         const MjcfOptions& mjcf, const std::string& world_xml) {
  const urdf::ModelInterfaceSharedPtr model = urdf::parseURDF(composeRobotUrdf(robot_urdf_xml, fingers));
  if (!model) throw ParameterError("the composed description does not parse");
  std::map<std::string, JointDynamics> dynamics;
  std::vector<std::pair<std::string, std::string>> excluded;
  for (const GripperFinger& f : fingers) {
    addFingerDynamics(*model, f.parameters, f.mount.prefix, f.mount.max_gauge_pa, mjcf, dynamics);
    for (int j = 1; j <= f.parameters.chamber_count; ++j) {
      excluded.emplace_back(segmentLinkName(f.mount.prefix, j - 1), segmentLinkName(f.mount.prefix, j));
    }
  }
  return writeMjcf(*model, dynamics, excluded, mjcf, world_xml);
}

namespace {

std::string writeMjcf(const urdf::ModelInterface& model, const std::map<std::string, JointDynamics>& dynamics,
                      const std::vector<std::pair<std::string, std::string>>& excluded, const MjcfOptions& mjcf,
                      const std::string& world_xml) {
  // The robot's joints: position-controlled, stiff against their own effort limit.
  std::ostringstream actuators;
  std::map<std::string, double> arm_damping;
  std::map<std::string, Eigen::Isometry3d> poses;
  zeroPose(model.getRoot(), Eigen::Isometry3d::Identity(), poses);
  for (const auto& [name, joint] : model.joints_) {
    if (joint->type == urdf::Joint::FIXED || dynamics.count(name) || !joint->limits) continue;
    const double effort = joint->limits->effort, kp = kPositionGainPerRad * effort;
    arm_damping[name] = 2.0 * std::sqrt(kp * inertiaBeyond(model, *joint, poses));
    actuators << "    <position name=\"" << name << "\" joint=\"" << name << "\" kp=\"" << num(kp)
              << "\" forcelimited=\"true\" forcerange=\"" << num(-effort) << " " << num(effort) << "\"/>\n";
  }
  std::map<std::string, JointDynamics> all = dynamics;
  for (const auto& [name, c] : arm_damping) all[name] = JointDynamics{JointSpring{}, c, 0.0};
  std::ostringstream out;
  out << "<!-- " << model.name_ << " at " << num(mjcf.gauge_pa) << " Pa gauge, written by finger_urdf --mjcf: each "
      << "finger joint a spring whose rest angle is the twin's free angle and whose stiffness holds the twin's "
      << "moment at the straight joint (docs/MODEL.md, Joint springs); each robot joint a position actuator. -->\n"
      << "<mujoco model=\"" << model.name_ << "\">\n"
      << "  <compiler angle=\"radian\"/>\n"
      << "  <!-- Elliptic cones and a high impratio: frictional contacts that hold a grasp without creep. The step is long "
      << "against every finger joint's period: each has an armature (a rotor inertia, no static effect) that gives its "
      << "stiffest spring " << num(mjcf.steps_per_period) << " steps per period. -->\n"
      << "  <option timestep=\"" << num(mjcf.timestep_s) << "\" cone=\"elliptic\" impratio=\"" << num(mjcf.impratio)
      << "\"/>\n"
      << "  <default><geom friction=\"" << num(mjcf.friction) << " 0.005 0.0001\" condim=\"4\"/></default>\n"
      << "  <worldbody>\n"
      << "    <light directional=\"true\" pos=\"0 0 1\" dir=\"0 0 -1\"/>\n";
  // The URDF's root is the world (often named so, which MJCF's world body already is): its geoms and children go
  // into the world body.
  const urdf::LinkConstSharedPtr root = model.getRoot();
  writeGeoms(out, *root, "    ");
  for (const auto& child : root->child_links) writeBody(out, model, child, all, "    ");
  out << world_xml << "  </worldbody>\n"
      << "  <!-- Neighbouring segments' boxes meet at their joint: they bend about it, they do not collide. -->\n"
      << "  <contact>\n";
  for (const auto& [a, b] : excluded) out << "    <exclude body1=\"" << a << "\" body2=\"" << b << "\"/>\n";
  out << "  </contact>\n";
  if (!actuators.str().empty()) out << "  <actuator>\n" << actuators.str() << "  </actuator>\n";
  out << "</mujoco>\n";
  return out.str();
}

}  // namespace

}  // namespace pneumatic_finger
