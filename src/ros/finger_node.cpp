#include "pneumatic_finger/ros/finger_node.hpp"

#include <tf2/LinearMath/Quaternion.h>

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
  };
  return table;
}

const NodeParameterSpec& spec(const std::string& key) {
  for (const auto& s : specs()) {
    if (s.key == key) return s;
  }
  throw std::logic_error("no node parameter '" + key + "'");
}

std::string describe(const XmlRpc::XmlRpcValue& v) {
  std::string text = const_cast<XmlRpc::XmlRpcValue&>(v).toXml();
  // Strip the XML-RPC wrapping for a readable message: <value><double>3</double></value> -> 3
  std::string out;
  bool in_tag = false;
  for (char c : text) {
    if (c == '<') in_tag = true;
    else if (c == '>') in_tag = false;
    else if (!in_tag) out += c;
  }
  return out.empty() ? "(empty)" : out;
}

bool asNumber(const XmlRpc::XmlRpcValue& v, double& out) {
  auto& x = const_cast<XmlRpc::XmlRpcValue&>(v);
  if (x.getType() == XmlRpc::XmlRpcValue::TypeDouble) out = static_cast<double>(x);
  else if (x.getType() == XmlRpc::XmlRpcValue::TypeInt) out = static_cast<int>(x);
  else return false;
  return true;
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
      for (int i = 0; i < v.size(); ++i) {
        double x;
        if (!asNumber(v[i], x)) {
          throw ParameterError(std::string("parameter '") + spec.key + "' = " + describe(v) + ": entry " +
                               std::to_string(i + 1) + " is not a number");
        }
        value.values.push_back(x);
      }
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
      found = true;
    }
    if (!found) {
      throw ParameterError("gripper file '" + s.gripper_file + "' has no finger with prefix '" + s.urdf.prefix + "'");
    }
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
  // The URDF, for rviz and for anyone who reads the chain (planners): the same names as joint_states and tf. Its
  // joint limits follow the actuator, so it is republished when the actuator changes.
  nh.setParam(settings_.description_param, fingerUrdf(settings_.finger, settings_.urdf));
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

  joint_states_pub_ = nh.advertise<sensor_msgs::JointState>(settings_.joint_states_topic, 10);
  finger_state_pub_ = nh.advertise<FingerModelState>(settings_.finger_state_topic, 10);
  inverse_srv_ = nh.advertiseService("pressure_for_tip_angle", &FingerNode::onInverse, this);
  reconfigure_ = std::make_unique<dynamic_reconfigure::Server<FingerNodeConfig>>(private_nh);
  reconfigure_->setCallback([this](FingerNodeConfig& config, uint32_t level) { onReconfigure(config, level); });
  diagnostics_.setHardwareID(prefix + "pneumatic_finger");
  diagnostics_.add("pressure input", this, &FingerNode::diagnose);
  // Wall time, and force_update: under simulated time that jumps back (a looping bag, a reset) a ROS-time timer,
  // and the updater's own rate limit, would both wait until the clock caught up again, and diagnostics would stop.
  diagnostics_timer_ = nh.createWallTimer(ros::WallDuration(1.0),
                                          [this](const ros::WallTimerEvent&) { diagnostics_.force_update(); });
  // Queue of 1 when throttled (only the newest pressure matters); otherwise keep up with bursts.
  pressure_sub_ = nh.subscribe(settings_.pressure_topic, settings_.input.max_rate_hz > 0 ? 1 : 100, &FingerNode::onPressure,
                               this, ros::TransportHints().tcpNoDelay());
  ROS_INFO("finger_node: %d chambers (%d distinct), solver %s, frames %ssegment_0..%d and %stip on %s; URDF in '%s'",
           n, model_->distinctChamberCount(), solverName(settings_.solver), prefix.c_str(), n, prefix.c_str(),
           settings_.urdf.parent_frame.c_str(), nh.resolveName(settings_.description_param).c_str());
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
  const FingerState& state = model_->evaluate(d.gauge_pa);
  if (state.status == EvaluationStatus::kSolverFailure) {
    // Nothing non-finite is ever published: the last state stays, and diagnostics say why.
    input_.noteSolverFailure(std::string("solver '") + solverName(settings_.solver) + "' found no finite answer at " +
                                 formatExact(d.gauge_pa) + " Pa gauge; last state kept",
                             now.toSec());
    ROS_WARN_THROTTLE(5.0, "finger_node: %s", input_.lastProblem().c_str());
    return;
  }
  if (state.status == EvaluationStatus::kVacuum) {
    input_.noteVacuum(d.gauge_pa, now.toSec());
    ROS_WARN_THROTTLE(5.0, "finger_node: %s", input_.lastProblem().c_str());
  }
  // The message's own stamp to the nanosecond (the policy compares seconds as doubles), or the receive time.
  publish(state, d.stamp_replaced ? now : msg->header.stamp, d.clamped);
}

void FingerNode::publish(const FingerState& state, const ros::Time& stamp, bool clamped) {
  const int n = settings_.finger.chamber_count;
  joint_states_.header.stamp = stamp;
  for (int i = 0; i < n; ++i) {
    const auto k = static_cast<std::size_t>(i);
    const double q = state.joint_angle_rad[i];
    joint_states_.position[k] = q;
    auto& t = transforms_[k];
    t.header.stamp = stamp;
    t.transform.rotation.z = std::sin(0.5 * q);  // rotation q about +z
    t.transform.rotation.w = std::cos(0.5 * q);
    finger_state_.stretch[k] = state.stretch[i];
    finger_state_.bulge_m[k] = state.bulge_m[i];
    finger_state_.half_angle_rad[k] = state.half_angle_rad[i];
    finger_state_.joint_angle_rad[k] = q;
  }
  for (int i = 0; i < n + 2; ++i) {
    auto& p = finger_state_.backbone[static_cast<std::size_t>(i)];
    p.x = state.backbone_m(0, i);
    p.y = state.backbone_m(1, i);
  }
  finger_state_.header.stamp = stamp;
  finger_state_.gauge_pa = state.gauge_pa;
  finger_state_.tip.position = finger_state_.backbone.back();
  finger_state_.tip.orientation.z = std::sin(0.5 * state.tip_angle_rad);
  finger_state_.tip.orientation.w = std::cos(0.5 * state.tip_angle_rad);
  finger_state_.tip_angle_rad = state.tip_angle_rad;
  finger_state_.in_contact = state.in_contact;
  finger_state_.in_validated_range = state.gauge_pa >= 0 && state.gauge_pa <= settings_.input.validated_max_gauge_pa;
  finger_state_.status = state.status == EvaluationStatus::kVacuum ? FingerModelState::STATUS_VACUUM
                          : clamped                                  ? FingerModelState::STATUS_CLAMPED
                                                                     : FingerModelState::STATUS_OK;
  if (tf_) tf_->sendTransform(transforms_);
  joint_states_pub_.publish(joint_states_);
  finger_state_pub_.publish(finger_state_);
}

bool FingerNode::onInverse(PressureForTipAngle::Request& req, PressureForTipAngle::Response& res) {
  std::string why;
  double gauge = 0;
  res.success = model_->gaugeForTipAngle(req.tip_angle_rad, settings_.urdf.max_gauge_pa, gauge, why);
  res.gauge_pa = res.success ? gauge : 0.0;
  res.absolute_pa = res.success ? gauge + settings_.finger.atmospheric_pressure_pa : 0.0;
  res.message = res.success ? "" : why + " (max_gauge_pa)";
  return true;  // a refused request is an answer, not a transport failure
}

FingerNodeConfig FingerNode::currentConfig() const {
  FingerNodeConfig c;
  c.shear_modulus_pa = settings_.finger.shear_modulus_pa[0];
  c.chamber_gap_m = settings_.finger.chamber_gap_m[0];
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
    const bool actuator = config.shear_modulus_pa != now.shear_modulus_pa || config.chamber_gap_m != now.chamber_gap_m;
    if (actuator) {
      // The same validation as a parameter file or a rosparam: fromRaw refuses, naming the key and the range.
      RawParameterMap raw = settings_.finger.toRaw();
      if (config.shear_modulus_pa != now.shear_modulus_pa) raw["shear_modulus_pa"] = {{config.shear_modulus_pa}, false};
      if (config.chamber_gap_m != now.chamber_gap_m) raw["chamber_gap_m"] = {{config.chamber_gap_m}, false};
      next.finger = FingerParameters::fromRaw(raw);
    }
    next.input.max_rate_hz = checkNumber("max_rate_hz", config.max_rate_hz);
    next.input.stale_timeout_s = checkNumber("stale_timeout_s", config.stale_timeout_s);
    settings_ = next;
    input_.updateSettings(settings_.input);
    if (actuator) {
      buildModel(nh_);
      ROS_INFO("finger_node: reconfigured: shear_modulus_pa %s Pa, chamber_gap_m %s m; URDF republished",
               formatExact(config.shear_modulus_pa).c_str(), formatExact(config.chamber_gap_m).c_str());
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
  status.add("model evaluations (unchanged pressures reuse the last)", model_->computationCount());
  if (!input_.lastProblem().empty()) status.add("last problem", input_.lastProblem());
}

}  // namespace pneumatic_finger
