// finger_node's parameters: the one definition of each (nodeParameterSpecs), and their reading and checking from the
// private handle (readNodeSettings), shared by the node's start-up and by dynamic_reconfigure (checkNodeNumber).
#include "pneumatic_finger/ros/node_parameters.hpp"

#include <ros/names.h>

#include <cmath>
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
  // The defaults are the settings structs' own: each is defined once, there.
  static const FingerUrdfOptions urdf;
  static const PressureInputSettings input;
  static const NodeSettings node;
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
      text("solver", solverName(node.solver), "robust, paper, table", "the model's solver (docs/LIBRARY.md, Solvers)"),
      flag("publish_tf", node.publish_tf,
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
      text("description_param", node.description_param, "a ROS name",
           "parameter (resolved in the node's namespace) that receives the generated URDF"),
      text("pressure_topic", node.pressure_topic, "a ROS name", "subscribed sensor_msgs/FluidPressure"),
      text("joint_states_topic", node.joint_states_topic, "a ROS name", "published sensor_msgs/JointState"),
      text("finger_state_topic", node.finger_state_topic, "a ROS name", "published pneumatic_finger/FingerModelState"),
      text("grasp_object_topic", node.grasp_object_topic, "a ROS name",
           "subscribed pneumatic_finger/GraspObject (latched): the object the finger closes on"),
      number("object_rate_hz", node.object_rate_hz, 0, true, 1000, "Hz",
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

void checkName(const std::string& key, const std::string& name) {
  std::string error;
  if (!ros::names::validate(name, error)) {
    throw ParameterError("parameter '" + key + "' = '" + name + "' is not a valid ROS name: " + error);
  }
}


}  // namespace

double checkNodeNumber(const std::string& key, double x) { return checkNumber(key, x); }

const std::vector<NodeParameterSpec>& nodeParameterSpecs() { return specs(); }

namespace {

// The actuator: the same keys, ranges and messages as the YAML loader (FingerParameters::fromRaw). Returns the keys
// given, which a gripper file then must not repeat.
RawParameterMap readActuatorKeys(const ros::NodeHandle& nh) {
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
  return raw;
}

// The finger's names and mount: the prefix, the parent frame and the mount pose.
void readMount(const ros::NodeHandle& nh, NodeSettings& s) {
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
}

// The finger as the gripper file defines it (one definition for the composed URDF and the node): its mount and its
// actuator. Giving either as a parameter as well would be a second definition, so it is refused.
void readGripperFile(const ros::NodeHandle& nh, const RawParameterMap& actuator_keys, NodeSettings& s) {
  for (const char* key : {"parent_frame", "mount_xyz_m", "mount_rpy_rad"}) {
    if (nh.hasParam(key)) throw ParameterError(std::string("parameter '") + key + "' is set, but gripper_file defines it");
  }
  if (!actuator_keys.empty()) {
    throw ParameterError("parameter '" + actuator_keys.begin()->first + "' is set, but gripper_file defines the actuator");
  }
  for (const GripperFinger& f : loadGripperFile(s.gripper_file)) {
    if (f.mount.prefix != s.urdf.prefix) continue;
    s.urdf = f.mount;  // max_gauge_pa is read later, as for any finger
    s.finger = f.parameters;
    s.tip_uncertainty = f.tip_uncertainty;
    return;
  }
  throw ParameterError("gripper file '" + s.gripper_file + "' has no finger with prefix '" + s.urdf.prefix + "'");
}

// The calibration's error bar: the parameter file's tip_uncertainty mapping, which `rosparam load` puts under
// ~tip_uncertainty/ (or the gripper file's finger's parameter file). Checked like the file: one rule, one message.
void readTipUncertainty(const ros::NodeHandle& nh, NodeSettings& s) {
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

// The solver, the frame authority, the input rules' settings and the pressure range.
void readModelAndInput(const ros::NodeHandle& nh, NodeSettings& s) {
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
  s.object_rate_hz = readDouble(nh, "object_rate_hz");
}

// The topics and the description parameter, each a valid ROS name.
void readNames(const ros::NodeHandle& nh, NodeSettings& s) {
  const std::pair<const char*, std::string*> names[] = {
      {"description_param", &s.description_param}, {"pressure_topic", &s.pressure_topic},
      {"joint_states_topic", &s.joint_states_topic}, {"finger_state_topic", &s.finger_state_topic},
      {"grasp_object_topic", &s.grasp_object_topic}};
  for (const auto& [key, value] : names) *value = readString(nh, key);
  for (const auto& [key, value] : names) checkName(key, *value);
}

// Every key the node was given must be one it knows: a typo is an error, not a silent default.
void refuseUnknownKeys(const ros::NodeHandle& nh) {
  std::vector<std::string> names;
  nh.getParamNames(names);
  const std::string ns = nh.getNamespace() + "/";
  const std::string tip = std::string(kTipUncertaintyKey) + "/";
  for (const std::string& full : names) {
    if (full.compare(0, ns.size(), ns) != 0) continue;
    const std::string key = full.substr(ns.size());
    if (key.compare(0, tip.size(), tip) == 0) {
      const std::string sub = key.substr(tip.size());
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
}

}  // namespace

NodeSettings readNodeSettings(const ros::NodeHandle& nh) {
  NodeSettings s;
  const RawParameterMap actuator_keys = readActuatorKeys(nh);
  s.finger = FingerParameters::fromRaw(actuator_keys);
  readMount(nh, s);
  s.gripper_file = readString(nh, "gripper_file");
  if (!s.gripper_file.empty()) readGripperFile(nh, actuator_keys, s);
  readTipUncertainty(nh, s);
  readModelAndInput(nh, s);
  readNames(nh, s);
  refuseUnknownKeys(nh);
  return s;
}

}  // namespace pneumatic_finger
