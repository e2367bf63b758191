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

NodeParameterSpec triple(const char* key, double limit, const char* unit, const char* limit_text,
                         const char* description) {
  return {key, "double[3]", "[0, 0, 0]", 0, 0, false, limit, unit, std::string("finite, |x| <= ") + limit_text,
          description};
}

const std::vector<NodeParameterSpec>& specs() {
  static const FingerUrdfOptions urdf;
  static const std::vector<NodeParameterSpec> table = {
      text("frame_prefix", urdf.prefix, "empty, or a letter then letters, digits, '_'",
           "prepended to every link, joint and frame of this finger, so several fingers coexist"),
      text("parent_frame", urdf.parent_frame, "tf frame id without leading '/'", "frame the finger mounts on"),
      triple("mount_xyz_m", 10.0, "m", "10", "mount position in parent_frame"),
      triple("mount_rpy_rad", 2 * kPi, "rad", "2 pi",
             "mount orientation in parent_frame (roll, pitch, yaw about fixed x, y, z)"),
      text("solver", "robust", "robust, paper, table", "the model's solver (see Solvers)"),
      number("max_rate_hz", 0, 0, false, 1e5, "Hz", "model cycles per second at most; 0 runs the model on every pressure message"),
      number("stale_timeout_s", 1.0, 0, true, 3600, "s", "no pressure for longer than this is reported stale"),
      number("stamp_tolerance_s", 1.0, 0, true, 3600, "s",
             "a pressure stamp that is zero or further than this from the receive time is replaced by the receive time"),
      number("max_gauge_pa", urdf.max_gauge_pa, 0, true, 1e7, "Pa",
             "top of the model's range (3 kg/cm^2): higher pressures are clamped to it; URDF joint upper limits, the "
             "inverse service's limit, the table"),
      number("validated_max_gauge_pa", 196133, 0, true, 1e7, "Pa",
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

double readDouble(const ros::NodeHandle& nh, const std::string& key, double max_override = NAN) {
  const NodeParameterSpec& sp = spec(key);
  const double hi = std::isnan(max_override) ? sp.max_value : max_override;
  XmlRpc::XmlRpcValue v;
  if (!nh.getParam(key, v)) return sp.default_value;
  double x;
  if (!asNumber(v, x)) throw ParameterError("parameter '" + key + "' = " + describe(v) + " is not a number");
  if (!std::isfinite(x) || (sp.min_open ? !(x > sp.min_value) : !(x >= sp.min_value)) || !(x <= hi)) {
    std::ostringstream s;
    s << "parameter '" << key << "' = " << formatExact(x) << " is outside its allowed range " << sp.allowed;
    throw ParameterError(s.str());
  }
  return x;
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
  try {
    s.solver = parseSolverName(readString(nh, "solver"));
  } catch (const ParameterError& e) {
    throw ParameterError(std::string("parameter 'solver': ") + e.what());
  }
  s.max_rate_hz = readDouble(nh, "max_rate_hz");
  s.stale_timeout_s = readDouble(nh, "stale_timeout_s");
  s.stamp_tolerance_s = readDouble(nh, "stamp_tolerance_s");
  s.urdf.max_gauge_pa = readDouble(nh, "max_gauge_pa");
  s.validated_max_gauge_pa = readDouble(nh, "validated_max_gauge_pa", s.urdf.max_gauge_pa);
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

FingerNode::FingerNode(ros::NodeHandle& nh, ros::NodeHandle& private_nh) : settings_(readNodeSettings(private_nh)) {
  ModelOptions options;
  options.solver = settings_.solver;
  options.table_max_gauge_pa = settings_.urdf.max_gauge_pa;
  model_ = std::make_unique<FingerModel>(settings_.finger, options);
  const int n = settings_.finger.chamber_count;
  const std::string& prefix = settings_.urdf.prefix;

  // The URDF, for rviz and for anyone who reads the chain (planners): the same names as joint_states and tf.
  nh.setParam(settings_.description_param, fingerUrdf(settings_.finger, settings_.urdf));

  // Frames: this node is their only publisher. The two fixed ones (mount, tip) go out once, latched on
  // /tf_static; the N joints go on /tf with each pressure. robot_state_publisher must not be run on this URDF.
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
  static_tf_.sendTransform(std::vector<geometry_msgs::TransformStamped>{mount, tip});

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
  diagnostics_.setHardwareID(prefix + "pneumatic_finger");
  diagnostics_.add("pressure input", this, &FingerNode::diagnose);
  diagnostics_timer_ = nh.createTimer(ros::Duration(1.0), [this](const ros::TimerEvent&) { diagnostics_.update(); });
  // Queue of 1 when throttled (only the newest pressure matters); otherwise keep up with bursts.
  pressure_sub_ = nh.subscribe(settings_.pressure_topic, settings_.max_rate_hz > 0 ? 1 : 100, &FingerNode::onPressure,
                               this, ros::TransportHints().tcpNoDelay());
  ROS_INFO("finger_node: %d chambers (%d distinct), solver %s, frames %ssegment_0..%d and %stip on %s; URDF in '%s'",
           n, model_->distinctChamberCount(), solverName(settings_.solver), prefix.c_str(), n, prefix.c_str(),
           settings_.urdf.parent_frame.c_str(), nh.resolveName(settings_.description_param).c_str());
}

void FingerNode::refuse(long& counter, const std::string& why, const ros::Time& now) {
  ++counter;
  last_problem_ = now;
  last_problem_text_ = why;
  ROS_WARN_THROTTLE(5.0, "finger_node: refused a pressure message: %s; keeping the last state", why.c_str());
}

void FingerNode::onPressure(const sensor_msgs::FluidPressure::ConstPtr& msg) {
  const ros::Time now = ros::Time::now();
  ++received_;
  last_received_ = now;
  recent_.push_back(now);
  while (!recent_.empty() && (now - recent_.front()).toSec() > 1.0) recent_.pop_front();
  if (settings_.max_rate_hz > 0 && !last_processed_.isZero() &&
      (now - last_processed_).toSec() < 1.0 / settings_.max_rate_hz) {
    ++throttled_;
    return;
  }
  // Bad values: refused, the last valid state stays (nothing is published).
  const double absolute = msg->fluid_pressure;
  if (!std::isfinite(absolute)) {
    refuse(refused_not_finite_, "pressure " + formatExact(absolute) + " Pa is not finite", now);
    return;
  }
  if (absolute < 0) {
    refuse(refused_negative_absolute_, "absolute pressure " + formatExact(absolute) + " Pa is negative", now);
    return;
  }
  // Stamps: a zero stamp, or one implausibly far from now (a regulator with no or a wrong clock), is replaced by
  // the receive time; a stamp not newer than the last published one is refused, since tf and the planners
  // downstream must never see time run backwards or the same instant twice.
  ros::Time stamp = msg->header.stamp;
  if (stamp.isZero() || std::fabs((stamp - now).toSec()) > settings_.stamp_tolerance_s) {
    ++stamps_replaced_;
    last_problem_ = now;
    last_problem_text_ = "stamp " + std::to_string(stamp.toSec()) + " s replaced by the receive time";
    ROS_WARN_THROTTLE(5.0, "finger_node: %s", last_problem_text_.c_str());
    stamp = now;
  }
  if (!last_published_stamp_.isZero() && stamp <= last_published_stamp_) {
    refuse(refused_out_of_order_,
           "stamp " + std::to_string(stamp.toSec()) + " s is not newer than the last published " +
               std::to_string(last_published_stamp_.toSec()) + " s",
           now);
    return;
  }
  last_processed_ = now;
  double gauge = absolute - settings_.finger.atmospheric_pressure_pa;
  last_gauge_pa_ = gauge;
  // Above the model's range (a glitching regulator, or a finger driven past its rating): clamp to the top of the
  // range, where the URDF's joint limits are, instead of curling the model toward pi/2 per wall.
  const bool clamped = gauge > settings_.urdf.max_gauge_pa;
  if (clamped) {
    ++clamped_;
    last_problem_ = now;
    last_problem_text_ = "gauge pressure " + formatExact(gauge) + " Pa clamped to max_gauge_pa";
    ROS_WARN_THROTTLE(5.0, "finger_node: %s", last_problem_text_.c_str());
    gauge = settings_.urdf.max_gauge_pa;
  }
  const FingerState& state = model_->evaluate(gauge);
  if (state.status == EvaluationStatus::kVacuum) {
    ++vacuum_;
    last_problem_ = now;
    last_problem_text_ = "gauge pressure " + formatExact(gauge) + " Pa is a vacuum: straight finger published";
    ROS_WARN_THROTTLE(5.0, "finger_node: %s", last_problem_text_.c_str());
  }
  if (gauge > settings_.validated_max_gauge_pa) ++out_of_range_;
  publish(state, stamp, clamped);
}

void FingerNode::publish(const FingerState& state, const ros::Time& stamp, bool clamped) {
  last_published_stamp_ = stamp;
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
  finger_state_.in_validated_range = state.gauge_pa >= 0 && state.gauge_pa <= settings_.validated_max_gauge_pa;
  finger_state_.status = state.status == EvaluationStatus::kVacuum ? FingerModelState::STATUS_VACUUM
                          : clamped                                  ? FingerModelState::STATUS_CLAMPED
                                                                     : FingerModelState::STATUS_OK;
  tf_.sendTransform(transforms_);
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

void FingerNode::diagnose(diagnostic_updater::DiagnosticStatusWrapper& status) {
  const ros::Time now = ros::Time::now();
  while (!recent_.empty() && (now - recent_.front()).toSec() > 1.0) recent_.pop_front();
  const double age = last_received_.isZero() ? -1.0 : (now - last_received_).toSec();
  // A refusal or correction stays on the report for kProblemHoldS, longer than any diagnostics period, so that a
  // single bad message is seen by whoever watches /diagnostics.
  constexpr double kProblemHoldS = 5.0;
  const bool recent_problem = !last_problem_.isZero() && (now - last_problem_).toSec() <= kProblemHoldS;
  if (last_received_.isZero()) {
    status.summary(diagnostic_msgs::DiagnosticStatus::WARN, "no pressure received yet");
  } else if (age > settings_.stale_timeout_s) {
    status.summaryf(diagnostic_msgs::DiagnosticStatus::ERROR, "stale: no pressure for %.1f s; last state kept", age);
  } else if (recent_problem) {
    status.summary(diagnostic_msgs::DiagnosticStatus::WARN, last_problem_text_);
  } else if (last_gauge_pa_ > settings_.validated_max_gauge_pa) {
    status.summaryf(diagnostic_msgs::DiagnosticStatus::WARN, "gauge pressure %.0f Pa above the validated range",
                    last_gauge_pa_);
  } else {
    status.summary(diagnostic_msgs::DiagnosticStatus::OK, "ok");
  }
  status.add("input rate (Hz, last 1 s)", recent_.size());
  status.add("seconds since last pressure", age);
  status.add("last gauge pressure (Pa)", last_gauge_pa_);
  status.add("validated range (Pa gauge)", "0.." + formatExact(settings_.validated_max_gauge_pa));
  status.add("messages received", received_);
  status.add("refused: not finite", refused_not_finite_);
  status.add("refused: negative absolute pressure", refused_negative_absolute_);
  status.add("refused: stamp not newer than the last", refused_out_of_order_);
  status.add("stamps replaced by the receive time", stamps_replaced_);
  status.add("vacuum (straight finger published)", vacuum_);
  status.add("clamped to max_gauge_pa", clamped_);
  status.add("above the validated range", out_of_range_);
  status.add("skipped by max_rate_hz", throttled_);
  status.add("model evaluations (unchanged pressures reuse the last)", model_->computationCount());
  if (!last_problem_text_.empty()) status.add("last problem", last_problem_text_);
}

}  // namespace pneumatic_finger
