#include "pneumatic_finger/ros/finger_node.hpp"

#include <tf2/LinearMath/Quaternion.h>
#include <visualization_msgs/Marker.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <sstream>
#include <stdexcept>

#include "pneumatic_finger/core/units.hpp"

namespace pneumatic_finger {

namespace {

// Numbers: (key, default, min, min excluded, max). The URDF-related defaults are FingerUrdfOptions', shared with
// the finger_urdf tool.
NodeParameterSpec number(const char* key, double def, double lo, bool lo_open, double hi, const char* unit,
                         const char* description, const char* allowed = nullptr) {
  std::ostringstream range;
  range << (lo_open ? "(" : "[") << lo << ", " << hi << "]";
  return {key, "double", formatShortest(def), def, lo, lo_open, hi, unit, allowed ? allowed : range.str(), description};
}

NodeParameterSpec text(const char* key, const std::string& def, const char* allowed, const char* description) {
  return {key, "string", def, 0, 0, false, 0, "-", allowed, description};
}

NodeParameterSpec flag(const char* key, bool def, const char* description) {
  return {key, "bool", def ? "true" : "false", def ? 1.0 : 0.0, 0, false, 1, "-", "true, false", description};
}

NodeParameterSpec triple(const char* key, double limit, const char* unit, const char* limit_text,
                         const char* description) {
  return {key, "double[3]", "[0, 0, 0]", 0, 0, false, limit, unit, std::string("finite, |x| <= ") + limit_text,
          description};
}

const std::vector<NodeParameterSpec>& specs() {
  static const FingerUrdfOptions urdf;
  static const PressureInputSettings input;
  static const std::vector<NodeParameterSpec> table = {
      text("frame_prefix", urdf.prefix, "empty, or a letter then letters, digits, '_'",
           "prepended to every link, joint and frame of this finger, so several fingers coexist"),
      text("parent_frame", urdf.parent_frame, "tf frame id without leading '/'", "frame the finger mounts on"),
      triple("mount_xyz_m", 10.0, "m", "10", "mount position in parent_frame"),
      triple("mount_rpy_rad", 2 * kPi, "rad", "2 pi",
             "mount orientation in parent_frame (roll, pitch, yaw about fixed x, y, z)"),
      text("gripper_file", "", "empty, or a gripper file (YAML)",
           "take this finger's mount and actuator from the gripper file's entry with frame_prefix, the file the "
           "composed URDF is made from (then parent_frame, the mounts and the actuator keys must not be set)"),
      text("solver", "robust", "robust, paper, table", "the model's solver (see Solvers)"),
      flag("publish_tf", true,
           "true: this node broadcasts its finger's frames (lowest latency); false: it publishes joint_states only and a "
           "robot_state_publisher on the (composed) description publishes the frames"),
      number("max_rate_hz", input.max_rate_hz, 0, false, 1e5, "Hz",
             "model cycles per second at most; 0 runs the model on every pressure message"),
      number("stale_timeout_s", input.stale_timeout_s, 0, true, 3600, "s",
             "no pressure for longer than this is reported stale"),
      number("stamp_tolerance_s", input.stamp_tolerance_s, 0, true, 3600, "s",
             "a pressure stamp further than this from the receive time is replaced by the receive time (a zero stamp "
             "always is, silently)"),
      number("time_jump_s", input.time_jump_s, 0, true, 3600, "s",
             "a stamp older than the last by more than this starts a new timeline (a looping bag); smaller steps back "
             "are refused as out of order"),
      number("max_gauge_pa", urdf.max_gauge_pa, 0, true, 1e7, "Pa",
             "top of the model's range (3 kg/cm^2): higher pressures are clamped to it; URDF joint upper limits, the "
             "inverse service's limit, the table"),
      number("validated_max_gauge_pa", input.validated_max_gauge_pa, 0, true, 1e7, "Pa",
             "top of the validated range (the paper: 2 kg/cm^2); above it finger_state says so and diagnostics warn",
             "(0, max_gauge_pa]"),
      text("description_param", "robot_description", "a ROS name",
           "parameter (resolved in the node's namespace) that receives the generated URDF"),
      text("pressure_topic", "pressure", "a ROS name", "subscribed sensor_msgs/FluidPressure"),
      text("joint_states_topic", "joint_states", "a ROS name", "published sensor_msgs/JointState"),
      text("finger_state_topic", "finger_state", "a ROS name", "published pneumatic_finger/FingerModelState"),
      text("grasp_object_topic", "grasp_object", "a ROS name",
           "subscribed pneumatic_finger/GraspObject (latched): the object the finger closes on"),
      number("object_rate_hz", 30.0, 0, true, 1000, "Hz",
             "while there is a grasp object: how often its pose in the finger's frame is looked up (tf) and, when it "
             "changed (the arm or the object moved), the finger re-solved and re-published"),
  };
  return table;
}

const NodeParameterSpec& spec(const std::string& key) {
  for (const auto& s : specs()) {
    if (s.key == key) return s;
  }
  throw std::logic_error("no node parameter '" + key + "'");
}

// The name of a finger_state object status, as diagnostics show it (msg/FingerModelState.msg).
const char* objectStatusName(std::uint8_t status) {
  switch (status) {
    case FingerModelState::OBJECT_NONE: return "none";
    case FingerModelState::OBJECT_OUT_OF_REACH: return "out of reach";
    case FingerModelState::OBJECT_CLEAR: return "clear (in reach, not touched)";
    case FingerModelState::OBJECT_TOUCHING: return "touching";
    case FingerModelState::OBJECT_OVERLAPS_AT_REST: return "overlaps the straight finger";
    case FingerModelState::OBJECT_NO_TRANSFORM: return "no transform to the object's frame";
    default: return "unknown";
  }
}

// A parameter's value as a message shows it: numbers with every digit, lists as [a, b, c], text in quotes.
std::string describe(const XmlRpc::XmlRpcValue& v) {
  auto& x = const_cast<XmlRpc::XmlRpcValue&>(v);
  switch (x.getType()) {
    case XmlRpc::XmlRpcValue::TypeDouble: return formatExact(static_cast<double>(x));
    case XmlRpc::XmlRpcValue::TypeInt: return std::to_string(static_cast<int>(x));
    case XmlRpc::XmlRpcValue::TypeBoolean: return static_cast<bool>(x) ? "true" : "false";
    case XmlRpc::XmlRpcValue::TypeString: return "'" + static_cast<std::string>(x) + "'";
    case XmlRpc::XmlRpcValue::TypeArray: {
      std::string out = "[";
      for (int i = 0; i < x.size(); ++i) out += (i > 0 ? ", " : "") + describe(x[i]);
      return out + "]";
    }
    case XmlRpc::XmlRpcValue::TypeStruct: {
      std::string out = "{";
      for (const auto& entry : x) out += (out.size() > 1 ? ", " : "") + entry.first + ": " + describe(entry.second);
      return out + "}";
    }
    default: return "(" + std::string(x.valid() ? "a value of another type" : "empty") + ")";
  }
}

bool asNumber(const XmlRpc::XmlRpcValue& v, double& out) {
  auto& x = const_cast<XmlRpc::XmlRpcValue&>(v);
  if (x.getType() == XmlRpc::XmlRpcValue::TypeDouble) out = static_cast<double>(x);
  else if (x.getType() == XmlRpc::XmlRpcValue::TypeInt) out = static_cast<int>(x);
  else return false;
  return true;
}

// The entries of a list parameter as numbers. @throws ParameterError naming the key, the value and the entry.
std::vector<double> numbersOf(const XmlRpc::XmlRpcValue& v, const std::string& key) {
  std::vector<double> out;
  for (int i = 0; i < v.size(); ++i) {
    double x;
    if (!asNumber(v[i], x)) {
      throw ParameterError("parameter '" + key + "' = " + describe(v) + ": entry " + std::to_string(i + 1) +
                           " is not a number");
    }
    out.push_back(x);
  }
  return out;
}

// The one range check of a node number: at start-up (rosparam) and live (dynamic_reconfigure).
double checkNumber(const std::string& key, double x, double max_override = NAN) {
  const NodeParameterSpec& sp = spec(key);
  const double hi = std::isnan(max_override) ? sp.max_value : max_override;
  if (!std::isfinite(x) || (sp.min_open ? !(x > sp.min_value) : !(x >= sp.min_value)) || !(x <= hi)) {
    std::ostringstream s;
    s << "parameter '" << key << "' = " << formatExact(x) << " is outside its allowed range " << sp.allowed;
    throw ParameterError(s.str());
  }
  return x;
}

double readDouble(const ros::NodeHandle& nh, const std::string& key, double max_override = NAN) {
  XmlRpc::XmlRpcValue v;
  if (!nh.getParam(key, v)) return spec(key).default_value;
  double x;
  if (!asNumber(v, x)) throw ParameterError("parameter '" + key + "' = " + describe(v) + " is not a number");
  return checkNumber(key, x, max_override);
}

bool readBool(const ros::NodeHandle& nh, const std::string& key) {
  XmlRpc::XmlRpcValue v;
  if (!nh.getParam(key, v)) return spec(key).default_value != 0.0;
  if (v.getType() != XmlRpc::XmlRpcValue::TypeBoolean) {
    throw ParameterError("parameter '" + key + "' = " + describe(v) + " is not true or false");
  }
  return static_cast<bool>(v);
}

std::string readString(const ros::NodeHandle& nh, const std::string& key) {
  XmlRpc::XmlRpcValue v;
  if (!nh.getParam(key, v)) return spec(key).default_text;
  if (v.getType() != XmlRpc::XmlRpcValue::TypeString) {
    throw ParameterError("parameter '" + key + "' = " + describe(v) + " is not a string");
  }
  return static_cast<std::string>(v);
}

std::array<double, 3> readTriple(const ros::NodeHandle& nh, const std::string& key) {
  const double limit = spec(key).max_value;
  XmlRpc::XmlRpcValue v;
  std::array<double, 3> out{{0, 0, 0}};
  if (!nh.getParam(key, v)) return out;
  if (v.getType() != XmlRpc::XmlRpcValue::TypeArray || v.size() != 3) {
    throw ParameterError("parameter '" + key + "' = " + describe(v) + " must be a list of 3 numbers");
  }
  for (int i = 0; i < 3; ++i) {
    const auto k = static_cast<std::size_t>(i);
    if (!asNumber(v[i], out[k]) || !std::isfinite(out[k]) || std::fabs(out[k]) > limit) {
      throw ParameterError("parameter '" + key + "' = " + describe(v) + ": entry " + std::to_string(i + 1) +
                           " is not a number in the allowed range: " + spec(key).allowed);
    }
  }
  return out;
}

// The solid a GraspObject message describes, in its own frame; the reason it is not valid, empty when it is.
std::string solidFromMessage(const GraspObject& msg, SolidObject& solid) {
  const auto& d = msg.shape.dimensions;
  using Prim = shape_msgs::SolidPrimitive;
  if (msg.shape.type == Prim::BOX && d.size() == 3) {
    solid.shape = SolidObject::Shape::kBox;
    solid.box_size_m = Eigen::Vector3d(d[Prim::BOX_X], d[Prim::BOX_Y], d[Prim::BOX_Z]);
  } else if (msg.shape.type == Prim::SPHERE && d.size() == 1) {
    solid.shape = SolidObject::Shape::kSphere;
    solid.radius_m = d[Prim::SPHERE_RADIUS];
  } else if (msg.shape.type == Prim::CYLINDER && d.size() == 2) {
    solid.shape = SolidObject::Shape::kCylinder;
    solid.height_m = d[Prim::CYLINDER_HEIGHT];
    solid.radius_m = d[Prim::CYLINDER_RADIUS];
  } else {
    return "shape type " + std::to_string(msg.shape.type) + " with " + std::to_string(d.size()) +
           " dimensions is not a BOX (3), SPHERE (1) or CYLINDER (2)";
  }
  const auto& o = msg.pose.orientation;
  const Eigen::Quaterniond rotation(o.w, o.x, o.y, o.z);
  if (!(std::fabs(rotation.norm() - 1.0) <= 1e-6)) return "the pose's orientation is not a unit quaternion";
  solid.pose = Eigen::Translation3d(msg.pose.position.x, msg.pose.position.y, msg.pose.position.z) *
               rotation.normalized();
  return solid.problem();
}

void checkName(const std::string& key, const std::string& name) {
  std::string error;
  if (!ros::names::validate(name, error)) {
    throw ParameterError("parameter '" + key + "' = '" + name + "' is not a valid ROS name: " + error);
  }
}

}  // namespace

const std::vector<NodeParameterSpec>& nodeParameterSpecs() { return specs(); }

NodeSettings readNodeSettings(const ros::NodeHandle& nh) {
  NodeSettings s;
  // The actuator: the same keys, ranges and messages as the YAML loader (FingerParameters::fromRaw).
  RawParameterMap raw;
  for (const ParameterSpec& spec : parameterSpecs()) {
    XmlRpc::XmlRpcValue v;
    if (!nh.getParam(spec.key, v)) continue;
    RawParameterValue value;
    if (v.getType() == XmlRpc::XmlRpcValue::TypeArray) {
      value.is_list = true;
      value.values = numbersOf(v, spec.key);
    } else {
      double x;
      if (!asNumber(v, x)) {
        throw ParameterError(std::string("parameter '") + spec.key + "' = " + describe(v) + " is not a number");
      }
      value.values.push_back(x);
    }
    raw[spec.key] = value;
  }
  s.finger = FingerParameters::fromRaw(raw);

  s.urdf.prefix = readString(nh, "frame_prefix");
  s.urdf.parent_frame = readString(nh, "parent_frame");
  std::string why;
  if (!isValidNamePrefix(s.urdf.prefix, why)) {
    throw ParameterError("parameter 'frame_prefix' = '" + s.urdf.prefix + "' " + why);
  }
  if (!isValidFrameId(s.urdf.parent_frame, why)) {
    throw ParameterError("parameter 'parent_frame' = '" + s.urdf.parent_frame + "' " + why);
  }
  s.urdf.mount_xyz_m = readTriple(nh, "mount_xyz_m");
  s.urdf.mount_rpy_rad = readTriple(nh, "mount_rpy_rad");
  s.gripper_file = readString(nh, "gripper_file");
  if (!s.gripper_file.empty()) {
    // The finger as the gripper file defines it (one definition for the composed URDF and the node): its mount and
    // its actuator. Giving either here as well would be a second definition, so it is refused.
    for (const char* key : {"parent_frame", "mount_xyz_m", "mount_rpy_rad"}) {
      if (nh.hasParam(key)) throw ParameterError(std::string("parameter '") + key + "' is set, but gripper_file defines it");
    }
    if (!raw.empty()) {
      throw ParameterError("parameter '" + raw.begin()->first + "' is set, but gripper_file defines the actuator");
    }
    bool found = false;
    for (const GripperFinger& f : loadGripperFile(s.gripper_file)) {
      if (f.mount.prefix != s.urdf.prefix) continue;
      s.urdf = f.mount;  // max_gauge_pa is read below, as for any finger
      s.finger = f.parameters;
      s.tip_uncertainty = f.tip_uncertainty;
      found = true;
    }
    if (!found) {
      throw ParameterError("gripper file '" + s.gripper_file + "' has no finger with prefix '" + s.urdf.prefix + "'");
    }
  }
  // The calibration's error bar: the parameter file's tip_uncertainty mapping, which `rosparam load` puts under
  // ~tip_uncertainty/ (or the gripper file's finger's parameter file). Checked like the file: one rule, one message.
  {
    const std::string base = std::string(kTipUncertaintyKey) + "/";
    std::vector<double> lists[3];
    const char* keys[3] = {"gauge_pa", "tip_angle_rad", "tip_position_m"};
    bool any = false;
    for (int i = 0; i < 3; ++i) {
      if (!nh.hasParam(base + keys[i])) continue;
      any = true;
      XmlRpc::XmlRpcValue v;
      nh.getParam(base + keys[i], v);
      if (v.getType() != XmlRpc::XmlRpcValue::TypeArray) {
        throw ParameterError("parameter '" + base + keys[i] + "' = " + describe(v) + " is not a list of numbers");
      }
      lists[i] = numbersOf(v, base + keys[i]);
    }
    if (any && !s.gripper_file.empty()) {
      throw ParameterError("parameter '" + base + "*' is set, but gripper_file defines the actuator (and its error bar)");
    }
    if (any) s.tip_uncertainty = TipUncertainty::fromLists(lists[0], lists[1], lists[2], "rosparam");
  }
  try {
    s.solver = parseSolverName(readString(nh, "solver"));
  } catch (const ParameterError& e) {
    throw ParameterError(std::string("parameter 'solver': ") + e.what());
  }
  s.publish_tf = readBool(nh, "publish_tf");
  s.input.max_rate_hz = readDouble(nh, "max_rate_hz");
  s.input.stale_timeout_s = readDouble(nh, "stale_timeout_s");
  s.input.stamp_tolerance_s = readDouble(nh, "stamp_tolerance_s");
  s.input.time_jump_s = readDouble(nh, "time_jump_s");
  s.urdf.max_gauge_pa = readDouble(nh, "max_gauge_pa");
  s.input.max_gauge_pa = s.urdf.max_gauge_pa;
  s.input.atmospheric_pa = s.finger.atmospheric_pressure_pa;
  s.input.validated_max_gauge_pa = readDouble(nh, "validated_max_gauge_pa", s.urdf.max_gauge_pa);
  s.description_param = readString(nh, "description_param");
  s.pressure_topic = readString(nh, "pressure_topic");
  s.joint_states_topic = readString(nh, "joint_states_topic");
  s.finger_state_topic = readString(nh, "finger_state_topic");
  s.grasp_object_topic = readString(nh, "grasp_object_topic");
  s.object_rate_hz = readDouble(nh, "object_rate_hz");
  checkName("grasp_object_topic", s.grasp_object_topic);
  checkName("description_param", s.description_param);
  checkName("pressure_topic", s.pressure_topic);
  checkName("joint_states_topic", s.joint_states_topic);
  checkName("finger_state_topic", s.finger_state_topic);
  // Every key the node was given must be one it knows: a typo is an error, not a silent default.
  std::vector<std::string> names;
  nh.getParamNames(names);
  const std::string ns = nh.getNamespace() + "/";
  for (const std::string& full : names) {
    if (full.compare(0, ns.size(), ns) != 0) continue;
    const std::string key = full.substr(ns.size());
    if (key.compare(0, std::strlen(kTipUncertaintyKey) + 1, std::string(kTipUncertaintyKey) + "/") == 0) {
      const std::string sub = key.substr(std::strlen(kTipUncertaintyKey) + 1);
      if (sub != "gauge_pa" && sub != "tip_angle_rad" && sub != "tip_position_m") {
        throw ParameterError("unknown parameter '" + key + "' (in " + ns + "; known: " + kTipUncertaintyKey +
                             "/gauge_pa, tip_angle_rad, tip_position_m)");
      }
      continue;
    }
    if (key.find('/') != std::string::npos) continue;  // nested namespaces belong to others (e.g. diagnostics)
    bool known = findParameterSpec(key) != nullptr || key == "diagnostic_period";
    for (const auto& sp : specs()) known = known || key == sp.key;
    if (!known) throw ParameterError("unknown parameter '" + key + "' (in " + ns + ")");
  }
  return s;
}

void FingerNode::buildModel(ros::NodeHandle& nh) {
  ModelOptions options;
  options.solver = settings_.solver;
  options.table_max_gauge_pa = settings_.urdf.max_gauge_pa;
  model_ = std::make_unique<FingerModel>(settings_.finger, options);
  workspace_ = std::make_unique<FingerWorkspace>(*model_);
  // The URDF, for rviz and for anyone who reads the chain (planners): the same names as joint_states and tf. Its
  // joint limits follow the actuator, so it is republished when the actuator changes.
  nh.setParam(settings_.description_param, fingerUrdf(settings_.finger, settings_.urdf));
  finger_length_m_ = settings_.finger.lengthM();
  // A tracker refers to the model it was made with: the section is cut again for the new one, now (not at the next
  // object tick), so that no pressure in between is published without the object.
  tracker_.reset();
  object_located_ = false;
  updateObject();
}

FingerNode::FingerNode(ros::NodeHandle& nh, ros::NodeHandle& private_nh)
    : settings_(readNodeSettings(private_nh)), input_(settings_.input), nh_(nh) {
  buildModel(nh);
  const int n = settings_.finger.chamber_count;
  const std::string& prefix = settings_.urdf.prefix;

  // Frames, with publish_tf (the default): this node is their only publisher. The two fixed ones (mount, tip) go out
  // once, latched on /tf_static; the N joints go on /tf with each pressure. Without publish_tf, a
  // robot_state_publisher on the (composed) description publishes all of them from joint_states.
  const ros::Time now = ros::Time::now();
  geometry_msgs::TransformStamped mount;
  mount.header.stamp = now;
  mount.header.frame_id = settings_.urdf.parent_frame;
  mount.child_frame_id = segmentLinkName(prefix, 0);
  mount.transform.translation.x = settings_.urdf.mount_xyz_m[0];
  mount.transform.translation.y = settings_.urdf.mount_xyz_m[1];
  mount.transform.translation.z = settings_.urdf.mount_xyz_m[2];
  tf2::Quaternion q;
  q.setRPY(settings_.urdf.mount_rpy_rad[0], settings_.urdf.mount_rpy_rad[1], settings_.urdf.mount_rpy_rad[2]);
  mount.transform.rotation.x = q.x();
  mount.transform.rotation.y = q.y();
  mount.transform.rotation.z = q.z();
  mount.transform.rotation.w = q.w();
  geometry_msgs::TransformStamped tip;
  tip.header.stamp = now;
  tip.header.frame_id = segmentLinkName(prefix, n);
  tip.child_frame_id = tipLinkName(prefix);
  tip.transform.translation.x = settings_.finger.segment_length_m.back();
  tip.transform.rotation.w = 1.0;
  if (settings_.publish_tf) {
    tf_ = std::make_unique<tf2_ros::TransformBroadcaster>();
    static_tf_ = std::make_unique<tf2_ros::StaticTransformBroadcaster>();
    static_tf_->sendTransform(std::vector<geometry_msgs::TransformStamped>{mount, tip});
  }

  // Messages sized once; the per-pressure cycle only writes numbers into them.
  joint_states_.name.resize(static_cast<std::size_t>(n));
  joint_states_.position.resize(static_cast<std::size_t>(n));
  transforms_.resize(static_cast<std::size_t>(n));
  for (int i = 1; i <= n; ++i) {
    const auto k = static_cast<std::size_t>(i - 1);
    joint_states_.name[k] = jointName(prefix, i);
    transforms_[k].header.frame_id = segmentLinkName(prefix, i - 1);
    transforms_[k].child_frame_id = segmentLinkName(prefix, i);
    transforms_[k].transform.translation.x =
        i == 1 ? settings_.finger.base_segment_length_m : settings_.finger.segment_length_m[k - 1];
  }
  finger_state_.header.frame_id = segmentLinkName(prefix, 0);
  finger_state_.stretch.resize(static_cast<std::size_t>(n));
  finger_state_.bulge_m.resize(static_cast<std::size_t>(n));
  finger_state_.half_angle_rad.resize(static_cast<std::size_t>(n));
  finger_state_.joint_angle_rad.resize(static_cast<std::size_t>(n));
  finger_state_.backbone.resize(static_cast<std::size_t>(n + 2));
  finger_state_.held_by_contact.resize(static_cast<std::size_t>(n));
  finger_state_.first_touch_gauge_pa = NAN;
  finger_state_.touch_gauge_pa = NAN;

  joint_states_pub_ = nh.advertise<sensor_msgs::JointState>(settings_.joint_states_topic, 10);
  finger_state_pub_ = nh.advertise<FingerModelState>(settings_.finger_state_topic, 10);
  tip_uncertainty_ = settings_.tip_uncertainty;
  // Latched: rviz, started later, still gets the sphere the finger has now.
  tip_marker_pub_ = nh.advertise<visualization_msgs::Marker>("tip_uncertainty_marker", 1, true);
  tip_marker_.header.frame_id = tipLinkName(prefix);
  tip_marker_.header.stamp = ros::Time(0);  // "latest"
  tip_marker_.frame_locked = true;  // rviz re-transforms it every frame: the sphere rides on the tip as the finger moves
  tip_marker_.ns = prefix + "tip_uncertainty";
  tip_marker_.type = visualization_msgs::Marker::SPHERE;
  tip_marker_.pose.orientation.w = 1.0;
  if (tip_uncertainty_.empty()) {
    ROS_INFO("finger_node: the parameters have no tip_uncertainty (finger_calibrate writes it): the tip's error bar "
             "is published as NaN");
  }
  inverse_srv_ = nh.advertiseService("pressure_for_tip_angle", &FingerNode::onInverse, this);
  reconfigure_ = std::make_unique<dynamic_reconfigure::Server<FingerNodeConfig>>(private_nh);
  reconfigure_->setCallback([this](FingerNodeConfig& config, uint32_t level) { onReconfigure(config, level); });
  diagnostics_.setHardwareID(prefix + "pneumatic_finger");
  diagnostics_.add("pressure input", this, &FingerNode::diagnose);
  // Wall time, and force_update: under simulated time that jumps back (a looping bag, a reset) a ROS-time timer,
  // and the updater's own rate limit, would both wait until the clock caught up again, and diagnostics would stop.
  diagnostics_timer_ = nh.createWallTimer(ros::WallDuration(1.0),
                                          [this](const ros::WallTimerEvent&) { diagnostics_.force_update(); });
  object_sub_ = nh.subscribe(settings_.grasp_object_topic, 1, &FingerNode::onGraspObject, this);
  // Queue of 1 when throttled (only the newest pressure matters); otherwise keep up with bursts.
  pressure_sub_ = nh.subscribe(settings_.pressure_topic, settings_.input.max_rate_hz > 0 ? 1 : 100, &FingerNode::onPressure,
                               this, ros::TransportHints().tcpNoDelay());
  ROS_INFO("finger_node: %d chambers (%d distinct), solver %s, frames %s..%s and %s on %s; URDF in '%s'", n,
           model_->distinctChamberCount(), solverName(settings_.solver), segmentLinkName(prefix, 0).c_str(),
           segmentLinkName(prefix, n).c_str(), tipLinkName(prefix).c_str(), settings_.urdf.parent_frame.c_str(),
           nh.resolveName(settings_.description_param).c_str());
}

void FingerNode::onPressure(const sensor_msgs::FluidPressure::ConstPtr& msg) {
  // The rules are the core's (PressureInputPolicy); this only forwards the message and acts on the verdict.
  const ros::Time now = ros::Time::now();
  const InputDecision d = input_.onMessage(msg->fluid_pressure, msg->header.stamp.toSec(), now.toSec());
  if (d.time_jumped) ROS_WARN("finger_node: %s", d.problem.c_str());  // once per jump
  switch (d.verdict) {
    case InputVerdict::kThrottled:
      return;
    case InputVerdict::kRefusedNotFinite:
    case InputVerdict::kRefusedNegativeAbsolute:
    case InputVerdict::kRefusedOutOfOrder:
      ROS_WARN_THROTTLE(5.0, "finger_node: refused a pressure message: %s; keeping the last state", d.problem.c_str());
      return;
    case InputVerdict::kAccept:
      break;
  }
  if (!d.time_jumped && !d.problem.empty()) ROS_WARN_THROTTLE(5.0, "finger_node: %s", d.problem.c_str());
  // The message's own stamp to the nanosecond (the policy compares seconds as doubles), or the receive time.
  publishAt(d.gauge_pa, d.stamp_replaced ? now : msg->header.stamp, d.clamped);
}

bool FingerNode::publishAt(double gauge_pa, const ros::Time& stamp, bool clamped) {
  const ros::Time now = ros::Time::now();
  const FingerState& state = model_->evaluate(gauge_pa, *workspace_);
  ContactState contact;
  bool failed = state.status == EvaluationStatus::kSolverFailure;
  // The contact rule only with a section within reach: otherwise the free finger is the answer, at no extra cost.
  const bool with_contact = !failed && tracker_ && !tracker_->outOfReach();
  if (with_contact) {
    contact = tracker_->solve(state.gauge_pa);
    failed = contact.status == ContactState::Status::kSolverFailure;
  }
  if (failed) {
    // Nothing non-finite is ever published: the last state stays, and diagnostics say why.
    input_.noteSolverFailure(std::string("solver '") + solverName(settings_.solver) + "' found no finite answer at " +
                                 formatExact(gauge_pa) + " Pa gauge" + (with_contact ? " (with the grasp object)" : "") +
                                 "; last state kept",
                             now.toSec());
    ROS_WARN_THROTTLE(5.0, "finger_node: %s", input_.lastProblem().c_str());
    return false;
  }
  if (state.status == EvaluationStatus::kVacuum) {
    input_.noteVacuum(gauge_pa, now.toSec());
    ROS_WARN_THROTTLE(5.0, "finger_node: %s", input_.lastProblem().c_str());
  }
  have_pressure_ = true;
  last_gauge_pa_ = gauge_pa;
  last_clamped_ = clamped;
  publish(state, with_contact ? &contact : nullptr, stamp, clamped);
  return true;
}

void FingerNode::publish(const FingerState& state, const ContactState* contact, const ros::Time& stamp, bool clamped) {
  const int n = settings_.finger.chamber_count;
  // With contact the joints, backbone and tip are the contact rule's; stretch, bulge and half angle stay the free
  // chambers' (they depend on the pressure alone).
  const double* q_rad = contact ? contact->joint_angle_rad.data() : state.joint_angle_rad.data();
  const Eigen::Ref<const Eigen::Matrix2Xd> backbone = contact ? Eigen::Ref<const Eigen::Matrix2Xd>(contact->backbone_m)
                                                               : Eigen::Ref<const Eigen::Matrix2Xd>(state.backbone_m);
  double tip_angle_rad = 0.0;
  joint_states_.header.stamp = stamp;
  for (int i = 0; i < n; ++i) {
    const auto k = static_cast<std::size_t>(i);
    const double q = q_rad[i];
    tip_angle_rad += q;
    joint_states_.position[k] = q;
    auto& t = transforms_[k];
    t.header.stamp = stamp;
    t.transform.rotation.z = std::sin(0.5 * q);  // rotation q about +z
    t.transform.rotation.w = std::cos(0.5 * q);
    finger_state_.stretch[k] = state.stretch[i];
    finger_state_.bulge_m[k] = state.bulge_m[i];
    finger_state_.half_angle_rad[k] = state.half_angle_rad[i];
    finger_state_.joint_angle_rad[k] = q;
    finger_state_.held_by_contact[k] = contact && contact->held[k];
  }
  if (!contact) tip_angle_rad = state.tip_angle_rad;  // the model's own sum, bit for bit
  for (int i = 0; i < n + 2; ++i) {
    auto& p = finger_state_.backbone[static_cast<std::size_t>(i)];
    p.x = backbone(0, i);
    p.y = backbone(1, i);
  }
  finger_state_.header.stamp = stamp;
  finger_state_.gauge_pa = state.gauge_pa;
  finger_state_.tip.position = finger_state_.backbone.back();
  finger_state_.tip.orientation.z = std::sin(0.5 * tip_angle_rad);
  finger_state_.tip.orientation.w = std::cos(0.5 * tip_angle_rad);
  finger_state_.tip_angle_rad = tip_angle_rad;
  finger_state_.walls_in_contact = state.walls_in_contact;
  finger_state_.in_validated_range = state.gauge_pa >= 0 && state.gauge_pa <= settings_.input.validated_max_gauge_pa;
  finger_state_.status = state.status == EvaluationStatus::kVacuum ? FingerModelState::STATUS_VACUUM
                          : clamped                                  ? FingerModelState::STATUS_CLAMPED
                                                                     : FingerModelState::STATUS_OK;
  finger_state_.object_id = object_ ? object_->id : std::string();
  finger_state_.object_status = object_status_;
  finger_state_.touch_gauge_pa = touch_gauge_pa_;
  finger_state_.first_touch_gauge_pa = NAN;
  finger_state_.contact_points.clear();
  if (contact) {
    using Status = ContactState::Status;
    finger_state_.object_status = contact->status == Status::kInContact       ? FingerModelState::OBJECT_TOUCHING
                                  : contact->status == Status::kOverlapsAtRest ? FingerModelState::OBJECT_OVERLAPS_AT_REST
                                                                               : FingerModelState::OBJECT_CLEAR;
    finger_state_.first_touch_gauge_pa = contact->first_touch_gauge_pa;
    for (const Eigen::Vector2d& c : contact->contact_points_m) {
      geometry_msgs::Point p;
      p.x = c.x();
      p.y = c.y();
      finger_state_.contact_points.push_back(p);
    }
  }
  // The error bar of the free model at this pressure (vacuum: the rest shape, 0).
  const TipUncertainty::At bar = tip_uncertainty_.at(state.gauge_pa);
  finger_state_.tip_angle_uncertainty_rad = bar.tip_angle_rad;
  finger_state_.tip_position_uncertainty_m = bar.tip_position_m;
  finger_state_.tip_uncertainty_extrapolated = bar.extrapolated;
  const double variance = bar.tip_position_m * bar.tip_position_m;
  finger_state_.tip_position_covariance = {variance, 0.0, 0.0, 0.0, variance, 0.0, 0.0, 0.0, 0.0};
  if (tf_) tf_->sendTransform(transforms_);
  joint_states_pub_.publish(joint_states_);
  finger_state_pub_.publish(finger_state_);
  publishTipMarker(bar);
}

void FingerNode::publishTipMarker(const TipUncertainty::At& bar) {
  // Nothing to show without an error bar; no traffic while the bar keeps its size (the sphere rides on the tip frame).
  if (!std::isfinite(bar.tip_position_m)) return;
  const bool same = marker_bar_m_ >= 0.0 && bar.extrapolated == marker_extrapolated_ &&
                    std::fabs(bar.tip_position_m - marker_bar_m_) <= 0.01 * marker_bar_m_;
  if (same) return;
  marker_bar_m_ = bar.tip_position_m;
  marker_extrapolated_ = bar.extrapolated;
  visualization_msgs::Marker& m = tip_marker_;  // frame, namespace and shape were set once, in the constructor
  m.action = visualization_msgs::Marker::ADD;
  // The sphere's radius is the bar: the tip is somewhere inside it, as far as the calibration can tell. At least
  // 0.1 mm across, so that it stays visible at rest.
  m.scale.x = m.scale.y = m.scale.z = std::max(2.0 * bar.tip_position_m, 1e-4);
  // Cyan inside the calibrated pressures; orange above them, where the bar is a guess. Half transparent: the tip
  // stays visible inside it.
  m.color.r = bar.extrapolated ? 1.0f : 0.0f;
  m.color.g = bar.extrapolated ? 0.55f : 0.85f;
  m.color.b = bar.extrapolated ? 0.0f : 1.0f;
  m.color.a = 0.5f;
  tip_marker_pub_.publish(m);
}

void FingerNode::onGraspObject(const GraspObject::ConstPtr& msg) {
  object_located_ = false;
  tracker_.reset();
  touch_gauge_pa_ = NAN;
  object_problem_.clear();
  if (msg->id.empty()) {
    object_.reset();
    object_timer_.stop();
    object_status_ = FingerModelState::OBJECT_NONE;
    ROS_INFO("finger_node: grasp object cleared");
  } else {
    // Validate before use: a bad object is refused by name and the finger stays free.
    std::string why = solidFromMessage(*msg, object_in_frame_);
    if (why.empty() && msg->header.frame_id.empty()) why = "header.frame_id is empty";
    if (!why.empty()) {
      ROS_ERROR("finger_node: grasp object '%s' refused: %s; the finger stays free", msg->id.c_str(), why.c_str());
      object_.reset();
      object_timer_.stop();
      object_status_ = FingerModelState::OBJECT_NONE;
      object_problem_ = "grasp object '" + msg->id + "' refused: " + why;
      if (have_pressure_) publishAt(last_gauge_pa_, ros::Time::now(), last_clamped_);
      return;
    }
    object_ = msg;
    const std::string finger_frame = segmentLinkName(settings_.urdf.prefix, 0);
    if (msg->header.frame_id != finger_frame && msg->header.frame_id != settings_.urdf.parent_frame && !tf_buffer_) {
      tf_buffer_ = std::make_unique<tf2_ros::Buffer>();
      tf_listener_ = std::make_unique<tf2_ros::TransformListener>(*tf_buffer_);
    }
    if (!object_timer_.isValid()) {
      object_timer_ = nh_.createTimer(ros::Duration(1.0 / settings_.object_rate_hz), &FingerNode::onObjectTimer, this);
    }
    object_timer_.start();
    ROS_INFO("finger_node: grasp object '%s' in '%s'", msg->id.c_str(), msg->header.frame_id.c_str());
  }
  updateObject();
  if (have_pressure_) publishAt(last_gauge_pa_, ros::Time::now(), last_clamped_);
}

void FingerNode::onObjectTimer(const ros::TimerEvent&) {
  if (updateObject() && have_pressure_) publishAt(last_gauge_pa_, ros::Time::now(), last_clamped_);
}

bool FingerNode::updateObject() {
  if (!object_) return false;
  const std::string finger_frame = segmentLinkName(settings_.urdf.prefix, 0);
  const std::string& parent_frame = settings_.urdf.parent_frame;
  // The object's pose in this finger's frame: the finger's own mount (known here, not looked up: it does not depend
  // on who publishes the finger's frames) after tf's latest parent_frame <- object frame.
  const auto& xyz = settings_.urdf.mount_xyz_m;
  const auto& rpy = settings_.urdf.mount_rpy_rad;
  const Eigen::Isometry3d parent_from_finger =
      Eigen::Translation3d(xyz[0], xyz[1], xyz[2]) * Eigen::AngleAxisd(rpy[2], Eigen::Vector3d::UnitZ()) *
      Eigen::AngleAxisd(rpy[1], Eigen::Vector3d::UnitY()) * Eigen::AngleAxisd(rpy[0], Eigen::Vector3d::UnitX());
  Eigen::Isometry3d finger_from_frame = Eigen::Isometry3d::Identity();
  if (object_->header.frame_id != finger_frame) {
    Eigen::Isometry3d parent_from_frame = Eigen::Isometry3d::Identity();
    if (object_->header.frame_id != parent_frame) {
      try {
        const auto t = tf_buffer_->lookupTransform(parent_frame, object_->header.frame_id, ros::Time(0)).transform;
        parent_from_frame = Eigen::Translation3d(t.translation.x, t.translation.y, t.translation.z) *
                            Eigen::Quaterniond(t.rotation.w, t.rotation.x, t.rotation.y, t.rotation.z);
      } catch (const tf2::TransformException& e) {
        ++transform_failures_;
        object_problem_ = "no transform from '" + object_->header.frame_id + "' to '" + parent_frame + "': " + e.what();
        ROS_WARN_THROTTLE(5.0, "finger_node: grasp object '%s': %s", object_->id.c_str(), object_problem_.c_str());
        const bool changed = object_status_ != FingerModelState::OBJECT_NO_TRANSFORM;
        object_status_ = FingerModelState::OBJECT_NO_TRANSFORM;
        tracker_.reset();
        object_located_ = false;
        return changed;
      }
    }
    finger_from_frame = parent_from_finger.inverse() * parent_from_frame;
  }
  SolidObject solid = object_in_frame_;
  solid.pose = finger_from_frame * object_in_frame_.pose;
  // Unchanged pose relative to the finger (a still arm and object): the tracker and its touch events stay.
  if (object_located_ && solid.pose.matrix() == object_in_finger_.pose.matrix()) return false;
  object_in_finger_ = solid;
  object_located_ = true;
  object_problem_.clear();
  tracker_.reset();
  touch_gauge_pa_ = NAN;
  // Out of reach (the bounding sphere beyond the finger's length, or off its plane): no section, no contact work.
  const Eigen::Vector3d c = solid.pose.translation();
  const double r = solid.boundingRadius();
  std::optional<Obstacle> section;
  if (c.norm() - r <= finger_length_m_ && std::fabs(c.z()) < r) section = sectionByFingerPlane(solid);
  if (!section || section->distanceFromOrigin() > finger_length_m_) {
    object_status_ = FingerModelState::OBJECT_OUT_OF_REACH;
    return true;
  }
  ++sections_cut_;
  tracker_ = std::make_unique<ContactTracker>(*model_, *section);
  // The whole range at once: the first touch is then known for the gripper action, and every pressure after this
  // is answered from the kept events.
  const ContactState full = tracker_->solve(settings_.urdf.max_gauge_pa);
  touch_gauge_pa_ = full.first_touch_gauge_pa;
  object_status_ = full.status == ContactState::Status::kOverlapsAtRest ? FingerModelState::OBJECT_OVERLAPS_AT_REST
                                                                         : FingerModelState::OBJECT_CLEAR;
  if (full.status == ContactState::Status::kOverlapsAtRest) {
    object_problem_ = "grasp object '" + object_->id + "' overlaps the straight finger: reported, not solved";
    ROS_WARN_THROTTLE(5.0, "finger_node: %s", object_problem_.c_str());
  }
  return true;
}

bool FingerNode::onInverse(PressureForTipAngle::Request& req, PressureForTipAngle::Response& res) {
  std::string why;
  double gauge = 0;
  res.success = model_->gaugeForTipAngle(req.tip_angle_rad, settings_.urdf.max_gauge_pa, gauge, why);
  res.gauge_pa = res.success ? gauge : 0.0;
  res.absolute_pa = res.success ? gauge + settings_.finger.atmospheric_pressure_pa : 0.0;
  res.message = res.success ? "" : why;
  return true;  // a refused request is an answer, not a transport failure
}

FingerNodeConfig FingerNode::currentConfig() const {
  FingerNodeConfig c;
  c.shear_modulus_pa = settings_.finger.shear_modulus_pa[0];
  c.chamber_gap_m = settings_.finger.chamber_gap_m[0];
  c.base_wall_share = settings_.finger.base_wall_share;
  c.max_rate_hz = settings_.input.max_rate_hz;
  c.stale_timeout_s = settings_.input.stale_timeout_s;
  return c;
}

void FingerNode::onReconfigure(FingerNodeConfig& config, uint32_t /*level*/) {
  const FingerNodeConfig now = currentConfig();
  if (!reconfigure_synced_) {
    // The server's first call carries what it read from the parameter server (or its own defaults, for a
    // per-chamber list it cannot read): the node's actual values win.
    reconfigure_synced_ = true;
    config = now;
    return;
  }
  try {
    NodeSettings next = settings_;
    const bool actuator = config.shear_modulus_pa != now.shear_modulus_pa ||
                          config.chamber_gap_m != now.chamber_gap_m || config.base_wall_share != now.base_wall_share;
    if (actuator) {
      // The same validation as a parameter file or a rosparam: fromRaw refuses, naming the key and the range.
      RawParameterMap raw = settings_.finger.toRaw();
      if (config.shear_modulus_pa != now.shear_modulus_pa) raw["shear_modulus_pa"] = {{config.shear_modulus_pa}, false};
      if (config.chamber_gap_m != now.chamber_gap_m) raw["chamber_gap_m"] = {{config.chamber_gap_m}, false};
      if (config.base_wall_share != now.base_wall_share) raw["base_wall_share"] = {{config.base_wall_share}, false};
      next.finger = FingerParameters::fromRaw(raw);
    }
    next.input.max_rate_hz = checkNumber("max_rate_hz", config.max_rate_hz);
    next.input.stale_timeout_s = checkNumber("stale_timeout_s", config.stale_timeout_s);
    settings_ = next;
    input_.updateSettings(settings_.input);
    if (actuator) {
      if (!tip_uncertainty_.empty()) {
        ROS_WARN("finger_node: the actuator was reconfigured: the calibration's tip error bar no longer applies, "
                 "finger_state publishes it as NaN");
        tip_uncertainty_ = TipUncertainty{};
        tip_marker_.action = visualization_msgs::Marker::DELETE;
        tip_marker_pub_.publish(tip_marker_);
        marker_bar_m_ = -1.0;
      }
      buildModel(nh_);
      ROS_INFO("finger_node: reconfigured: shear_modulus_pa %s Pa, chamber_gap_m %s m, base_wall_share %s; URDF "
               "republished", formatExact(config.shear_modulus_pa).c_str(), formatExact(config.chamber_gap_m).c_str(),
               formatExact(config.base_wall_share).c_str());
    }
  } catch (const ParameterError& e) {
    ROS_ERROR("finger_node: reconfigure refused: %s; keeping the previous values", e.what());
    config = now;
  }
}

void FingerNode::diagnose(diagnostic_updater::DiagnosticStatusWrapper& status) {
  const InputReport r = input_.report(ros::Time::now().toSec());
  status.summary(static_cast<unsigned char>(r.level), r.message);
  const InputCounters& c = input_.counters();
  status.add("input rate (Hz, last 1 s)", r.rate_hz);
  status.add("seconds since last pressure", r.age_s);
  status.add("last gauge pressure (Pa)", input_.lastGaugePa());
  status.add("validated range (Pa gauge)", "0.." + formatExact(settings_.input.validated_max_gauge_pa));
  status.add("messages received", c.received);
  status.add("refused: not finite", c.refused_not_finite);
  status.add("refused: negative absolute pressure", c.refused_negative_absolute);
  status.add("refused: stamp not newer than the last", c.refused_out_of_order);
  status.add("zero stamps (receive time used)", c.zero_stamps);
  status.add("stamps replaced by the receive time", c.far_stamps);
  status.add("time jumps (new timeline)", c.time_jumps);
  status.add("vacuum (straight finger published)", c.vacuum);
  status.add("clamped to max_gauge_pa", c.clamped);
  status.add("above the validated range", c.out_of_range);
  status.add("solver failures (last state kept)", c.solver_failures);
  status.add("skipped by max_rate_hz or same instant", c.throttled);
  status.add("model evaluations (unchanged pressures reuse the last)", workspace_->computationCount());
  if (!input_.lastProblem().empty()) status.add("last problem", input_.lastProblem());
  status.add("tip error bar", tip_uncertainty_.empty()
                                   ? std::string("none (NaN in finger_state)")
                                   : "calibrated at " + std::to_string(tip_uncertainty_.gauge_pa.size()) +
                                         " pressures up to " + formatExact(tip_uncertainty_.gauge_pa.back()) +
                                         " Pa gauge; above: extrapolated");
  status.add("grasp object", object_ ? object_->id : std::string("(none)"));
  status.add("grasp object status", objectStatusName(object_status_));
  status.add("predicted first touch (Pa gauge)", touch_gauge_pa_);
  status.add("object sections cut (pose changed)", sections_cut_);
  status.add("object transform failures", transform_failures_);
  if (!object_problem_.empty()) {
    status.mergeSummary(diagnostic_msgs::DiagnosticStatus::WARN, object_problem_);
    status.add("grasp object problem", object_problem_);
  }
}

}  // namespace pneumatic_finger
