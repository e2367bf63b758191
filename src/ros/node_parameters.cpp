// finger_node's parameters: the one definition of each (nodeParameterSpecs), and their reading and checking from the
// private handle (readNodeSettings), shared by the node's start-up and by dynamic_reconfigure (checkNodeNumber).
#include "pneumatic_finger/ros/node_parameters.hpp"

#include <ros/console.h>

#include <cmath>
#include <sstream>
#include <stdexcept>

#include "pneumatic_finger/core/units.hpp"
#include "pneumatic_finger/core/drawing.hpp"
#include "pneumatic_finger/core/yaml_parameters.hpp"

namespace pneumatic_finger {

namespace {

const std::vector<NodeParameterSpec>& specs() {
  // The defaults are the settings structs' own: each is defined once, there.
  static const FingerUrdfOptions urdf;
  static const PressureInputSettings input;
  static const NodeSettings node;
  static const std::vector<NodeParameterSpec> table = {
      textParameter("frame_prefix", urdf.prefix, "empty, or a letter then letters, digits, '_'",
           "prepended to every link, joint and frame of this finger, so several fingers coexist"),
      textParameter("parent_frame", urdf.parent_frame, "tf frame id without leading '/'", "frame the finger mounts on"),
      tripleParameter("mount_xyz_m", 10.0, "m", "10", "mount position in parent_frame"),
      tripleParameter("mount_rpy_rad", 2 * kPi, "rad", "2 pi",
             "mount orientation in parent_frame (roll, pitch, yaw about fixed x, y, z)"),
      textParameter("gripper_file", "", "empty, or a gripper file (YAML)",
           "take this finger's mount and actuator from the gripper file's entry with frame_prefix, the file the "
           "composed URDF is made from (then parent_frame, the mounts and the actuator keys must not be set)"),
      textParameter("solver", solverName(node.solver), "robust, paper, table", "the model's solver (docs/LIBRARY.md, Solvers)"),
      flagParameter("publish_tf", node.publish_tf,
           "true: this node broadcasts its finger's frames (lowest latency); false: it publishes joint_states only and a "
           "robot_state_publisher on the (composed) description publishes the frames"),
      numberParameter("max_rate_hz", input.max_rate_hz, 0, false, 1e5, "Hz",
             "model cycles per second at most; 0 runs the model on every pressure message"),
      numberParameter("stale_timeout_s", input.stale_timeout_s, 0, true, 3600, "s",
             "no pressure for longer than this is reported stale"),
      numberParameter("stamp_tolerance_s", input.stamp_tolerance_s, 0, true, 3600, "s",
             "a pressure stamp further than this from the receive time is replaced by the receive time (a zero stamp "
             "always is, silently)"),
      numberParameter("time_jump_s", input.time_jump_s, 0, true, 3600, "s",
             "a stamp older than the last by more than this starts a new timeline (a looping bag); smaller steps back "
             "are refused as out of order"),
      coreNumberParameter(rangeParameterSpec("max_gauge_pa"),
             "also the URDF's joint upper limits, the inverse services' limit and the table's (default 3 kg/cm^2)"),
      coreNumberParameter(rangeParameterSpec("validated_max_gauge_pa"),
             "the node's in_validated_range and diagnostics (default: the paper's 2 kg/cm^2)", "[0, max_gauge_pa]"),
      textParameter("description_param", node.description_param, "a ROS name",
           "parameter (resolved in the node's namespace) that receives the generated URDF"),
      textParameter("pressure_topic", node.pressure_topic, "a ROS name", "subscribed sensor_msgs/FluidPressure"),
      textParameter("volume_topic", node.volume_topic, "a ROS name, or empty",
           "volume as the input: when set, subscribed std_msgs/Float64, the volume (m^3) a syringe pump or cylinder "
           "has pushed in (the chambers' growth plus the compression of dead_volume_m3 of gas), instead of the "
           "pressure topic; the pressure is then the model's answer (finger_state.gauge_pa). Empty: driven by "
           "pressure"),
      textParameter("joint_states_topic", node.joint_states_topic, "a ROS name", "published sensor_msgs/JointState"),
      textParameter("finger_state_topic", node.finger_state_topic, "a ROS name", "published pneumatic_finger/FingerModelState"),
      textParameter("grasp_object_topic", node.grasp_object_topic, "a ROS name",
           "subscribed pneumatic_finger/GraspObject (latched): the object the finger closes on"),
      numberParameter("object_rate_hz", node.object_rate_hz, 0, true, 1000, "Hz",
             "while there is a grasp object: how often its pose in the finger's frame is looked up (tf) and, when it "
             "changed (the arm or the object moved), the finger re-solved and re-published"),
      numberParameter("force_arrow_m_per_n", node.force_arrow_m_per_n, 0, true, 10, "m/N",
             "contact_force_markers: each contact's arrow is this long per newton of its normal force"),
      numberParameter("transform_timeout_s", node.transform_timeout_s, 0, false, 3600, "s",
             "the object's transform from tf older than this (its publisher stopped, e.g. robot_state_publisher "
             "died) is no transform: object_status OBJECT_NO_TRANSFORM, the free finger, until it is fresh again; "
             "0: never too old. Frames that only /tf_static relates are never too old"),
  };
  return table;
}

}  // namespace

double checkNodeNumber(const std::string& key, double x) {
  for (const auto& sp : specs()) {
    if (sp.key == key) return checkNumberParameter(sp, x);
  }
  throw std::logic_error("no node parameter '" + key + "'");
}

const std::vector<NodeParameterSpec>& nodeParameterSpecs() { return specs(); }

namespace {

// The node's private namespace as one tree, read by the parameter file's own loader (readParameterTree): the same
// keys, range rule, error bar and refusals as finger_model and Python. diagnostic_updater's own key is its.
ParameterTree readNamespaceTree(const ros::NodeHandle& nh) {
  XmlRpc::XmlRpcValue all;
  if (!nh.getParam(nh.getNamespace(), all) || all.getType() != XmlRpc::XmlRpcValue::TypeStruct) return {};
  YAML::Node tree = parameterTree(all);
  tree.remove("diagnostic_period");
  return readParameterTree(tree, "parameter server " + nh.getNamespace() + "/");
}

// The finger's names and mount: the prefix, the parent frame and the mount pose.
void readMount(const NodeParameterReader& in, NodeSettings& s) {
  s.urdf.prefix = in.text("frame_prefix");
  s.urdf.parent_frame = in.text("parent_frame");
  std::string why;
  if (!isValidNamePrefix(s.urdf.prefix, why)) {
    throw ParameterError("parameter 'frame_prefix' = '" + s.urdf.prefix + "' " + why);
  }
  if (!isValidFrameId(s.urdf.parent_frame, why)) {
    throw ParameterError("parameter 'parent_frame' = '" + s.urdf.parent_frame + "' " + why);
  }
  s.urdf.mount_xyz_m = in.triple("mount_xyz_m");
  s.urdf.mount_rpy_rad = in.triple("mount_rpy_rad");
}

// dynamic_reconfigure keeps the actuator's live keys on the parameter server: it writes them when the node starts and
// at each change. A twin that roslaunch restarts (respawn) finds them there: they are its previous run's live values,
// and it resumes with them over the gripper file's. The server writes a per-chamber list's first value, so a list
// whose first value it holds is unchanged. A changed actuator leaves the calibration's tip error bar behind, as a
// live change does.
void resumeLiveActuatorKeys(const RawParameterMap& live, NodeSettings& s) {
  RawParameterMap raw = s.finger.toRaw();
  std::string changed;
  for (const auto& [key, value] : live) {
    const auto file = raw.find(key);
    if (file != raw.end() && value.values.size() == 1 && !file->second.values.empty() &&
        file->second.values[0] == value.values[0]) {
      continue;
    }
    raw[key] = value;
    changed += (changed.empty() ? "" : ", ") + key + " = " + formatMessage(value.values[0]);
  }
  if (changed.empty()) return;
  s.finger = FingerParameters::fromRaw(raw);
  s.tip_uncertainty = TipUncertainty{};
  s.calibration_error = CalibrationError{};
  ROS_INFO("finger_node: resuming the live values on the parameter server (a previous run's dynamic_reconfigure): "
           "%s, over the gripper file's; the tip error bar no longer applies", changed.c_str());
}

// The finger as the gripper file defines it (one definition for the composed URDF and the node): its mount and its
// actuator. Giving either as a parameter as well would be a second definition, so it is refused.
void readGripperFile(const ros::NodeHandle& nh, const RawParameterMap& actuator_keys, NodeSettings& s) {
  for (const char* key : {"parent_frame", "mount_xyz_m", "mount_rpy_rad"}) {
    if (nh.hasParam(key)) throw ParameterError(std::string("parameter '") + key + "' is set, but gripper_file defines it");
  }
  for (const ParameterSpec& spec : rangeParameterSpecs()) {
    if (nh.hasParam(spec.key)) {
      throw ParameterError(std::string("parameter '") + spec.key + "' is set, but gripper_file defines the actuator "
                           "(its parameter file gives the range)");
    }
  }
  RawParameterMap live;
  for (const auto& [key, value] : actuator_keys) {
    if (!isLiveActuatorKey(key)) {
      throw ParameterError("parameter '" + key + "' is set, but gripper_file defines the actuator");
    }
    live[key] = value;
  }
  for (const GripperFinger& f : loadGripperFile(s.gripper_file)) {
    if (f.mount.prefix != s.urdf.prefix) continue;
    s.urdf = f.mount;
    s.finger = f.parameters;
    s.tip_uncertainty = f.tip_uncertainty;
    s.calibration_error = f.calibration_error;
    s.range = f.range;
    resumeLiveActuatorKeys(live, s);
    return;
  }
  throw ParameterError("gripper file '" + s.gripper_file + "' has no finger with prefix '" + s.urdf.prefix + "'");
}

// The solver, the frame authority, the input rules' settings and the pressure range.
void readModelAndInput(const NodeParameterReader& in, NodeSettings& s) {
  try {
    s.solver = parseSolverName(in.text("solver"));
  } catch (const ParameterError& e) {
    throw ParameterError(std::string("parameter 'solver': ") + e.what());
  }
  s.publish_tf = in.flag("publish_tf");
  s.input.max_rate_hz = in.number("max_rate_hz");
  s.input.stale_timeout_s = in.number("stale_timeout_s");
  s.input.stamp_tolerance_s = in.number("stamp_tolerance_s");
  s.input.time_jump_s = in.number("time_jump_s");
  s.urdf.max_gauge_pa = s.range.max_gauge_pa;  // the parameter file's range, by the loader's one rule
  s.input.max_gauge_pa = s.range.max_gauge_pa;
  s.input.atmospheric_pa = s.finger.atmospheric_pressure_pa;
  s.input.validated_max_gauge_pa = s.range.validated_max_gauge_pa;
  s.object_rate_hz = in.number("object_rate_hz");
  s.transform_timeout_s = in.number("transform_timeout_s");
  s.force_arrow_m_per_n = in.number("force_arrow_m_per_n");
}

// The topics and the description parameter, each a valid ROS name.
void readNames(const NodeParameterReader& in, NodeSettings& s) {
  s.description_param = in.rosName("description_param");
  s.pressure_topic = in.rosName("pressure_topic");
  s.volume_topic = in.rosName("volume_topic");
  s.input.volume_input = !s.volume_topic.empty();
  s.joint_states_topic = in.rosName("joint_states_topic");
  s.finger_state_topic = in.rosName("finger_state_topic");
  s.grasp_object_topic = in.rosName("grasp_object_topic");
}

}  // namespace

NodeSettings readNodeSettings(const ros::NodeHandle& nh) {
  const NodeParameterReader in(nh, specs());
  NodeSettings s;
  const ParameterTree tree = readNamespaceTree(nh);  // refuses a key that is no one's, as every interface does
  s.finger = FingerParameters::fromRaw(tree.raw);
  s.tip_uncertainty = tree.tip_uncertainty;
  s.calibration_error = tree.calibration_error;
  s.range = tree.range;
  readMount(in, s);
  s.gripper_file = in.text("gripper_file");
  if (!s.gripper_file.empty()) {
    if (!tree.tip_uncertainty.empty() || !tree.calibration_error.empty()) {
      throw ParameterError(std::string("parameter '") +
                           (tree.tip_uncertainty.empty() ? "calibration_error" : "tip_uncertainty") +
                           "/*' is set, but gripper_file defines the actuator (and its calibration's record)");
    }
    readGripperFile(nh, tree.raw, s);
  }
  readModelAndInput(in, s);
  readNames(in, s);
  return s;
}

}  // namespace pneumatic_finger
