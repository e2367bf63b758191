#include "pneumatic_finger/ros/finger_node.hpp"

#include <tf2/LinearMath/Quaternion.h>
#include <visualization_msgs/Marker.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <sstream>
#include <stdexcept>
#include <utility>

#include "pneumatic_finger/core/units.hpp"
#include "pneumatic_finger/core/self_contact.hpp"
#include "pneumatic_finger/ros/conversions.hpp"

namespace pneumatic_finger {

void FingerNode::buildModel(ros::NodeHandle& nh) {
  ModelOptions options;
  options.solver = settings_.solver;
  options.table_max_gauge_pa = settings_.urdf.max_gauge_pa;
  model_ = std::make_unique<FingerModel>(settings_.finger, options);
  workspace_ = std::make_unique<FingerWorkspace>(*model_);
  max_volume_m3_ = maxSuppliedVolumeM3(*model_, input_.range());  // the range rule for ~volume_topic
  // The URDF, for rviz and for anyone who reads the chain (planners): the same names as joint_states and tf. Its
  // joint limits follow the actuator, so it is republished when the actuator changes.
  nh.setParam(settings_.description_param, fingerUrdf(settings_.finger, settings_.urdf));
  // A tracker refers to the model it was made with: the section is cut again for the new one, now (not at the next
  // object tick), so that no pressure in between is published without the object.
  grasp_ = std::make_unique<GraspObjectTracker>(*model_, settings_.urdf.max_gauge_pa);
  if (object_) grasp_->setObject(object_in_frame_);
  updateObject();
}

FingerNode::FingerNode(ros::NodeHandle& nh, ros::NodeHandle& private_nh)
    : settings_(readNodeSettings(private_nh)), input_(settings_.input), nh_(nh) {
  // Its own name in every line it logs: the cell runs three, whose lines must be told apart ("/finger_a/finger_node").
  log_name_ = private_nh.getNamespace();
  buildModel(nh);
  if (settings_.publish_tf) publishStaticFrames();
  sizeMessages();
  setUpTipMarker(nh);
  inverse_srv_ = nh.advertiseService("pressure_for_tip_angle", &FingerNode::onInverse, this);
  force_srv_ = nh.advertiseService("pressure_for_contact_force", &FingerNode::onContactForce, this);
  reconfigure_ = std::make_unique<dynamic_reconfigure::Server<FingerNodeConfig>>(private_nh);
  reconfigure_->setCallback([this](FingerNodeConfig& config, uint32_t level) { onReconfigure(config, level); });
  diagnostics_.setHardwareID(settings_.urdf.prefix + "pneumatic_finger");
  diagnostics_.add("pressure input", this, &FingerNode::diagnose);
  // Wall time, and force_update: under simulated time that jumps back (a looping bag, a reset) a ROS-time timer,
  // and the updater's own rate limit, would both wait until the clock caught up again, and diagnostics would stop.
  diagnostics_timer_ = nh.createWallTimer(ros::WallDuration(1.0),
                                          [this](const ros::WallTimerEvent&) { diagnostics_.force_update(); });
  object_sub_ = nh.subscribe(settings_.grasp_object_topic, 1, &FingerNode::onGraspObject, this);
  subscribeInput(nh);
  const int n = settings_.finger.chamber_count;
  const std::string& prefix = settings_.urdf.prefix;
  ROS_INFO("%s: %d chambers (%d distinct), solver %s, frames %s..%s and %s on %s; URDF in '%s'", log_name_.c_str(), n,
           model_->distinctChamberCount(), solverName(settings_.solver), segmentLinkName(prefix, 0).c_str(),
           segmentLinkName(prefix, n).c_str(), tipLinkName(prefix).c_str(), settings_.urdf.parent_frame.c_str(),
           nh.resolveName(settings_.description_param).c_str());
}

// With publish_tf (the default) this node is the frames' only publisher. The two fixed ones (mount, tip) go out once,
// latched on /tf_static; the N joints go on /tf with each pressure. Without publish_tf, a robot_state_publisher on the
// (composed) description publishes all of them from joint_states, and the node does not even advertise /tf.
void FingerNode::publishStaticFrames() {
  const std::string& prefix = settings_.urdf.prefix;
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
  tip.header.frame_id = segmentLinkName(prefix, settings_.finger.chamber_count);
  tip.child_frame_id = tipLinkName(prefix);
  tip.transform.translation.x = settings_.finger.segment_length_m.back();
  tip.transform.rotation.w = 1.0;
  tf_ = std::make_unique<tf2_ros::TransformBroadcaster>();
  static_tf_ = std::make_unique<tf2_ros::StaticTransformBroadcaster>();
  static_tf_->sendTransform(std::vector<geometry_msgs::TransformStamped>{mount, tip});
}

// Messages sized once; the per-pressure cycle only writes numbers into them.
void FingerNode::sizeMessages() {
  const int n = settings_.finger.chamber_count;
  const auto un = static_cast<std::size_t>(n);
  const std::string& prefix = settings_.urdf.prefix;
  joint_states_.name.resize(un);
  joint_states_.position.resize(un);
  joint_states_.effort.resize(un);
  finger_state_.joint_moment_nm.resize(un);
  transforms_.resize(un);
  for (int i = 1; i <= n; ++i) {
    const auto k = static_cast<std::size_t>(i - 1);
    joint_states_.name[k] = jointName(prefix, i);
    transforms_[k].header.frame_id = segmentLinkName(prefix, i - 1);
    transforms_[k].child_frame_id = segmentLinkName(prefix, i);
    transforms_[k].transform.translation.x =
        i == 1 ? settings_.finger.base_segment_length_m : settings_.finger.segment_length_m[k - 1];
  }
  finger_state_.header.frame_id = segmentLinkName(prefix, 0);
  for (auto* v : {&finger_state_.stretch, &finger_state_.bulge_m, &finger_state_.half_angle_rad,
                  &finger_state_.joint_angle_rad}) {
    v->resize(un);
  }
  finger_state_.backbone.resize(un + 2);
  finger_state_.held_by_contact.resize(un);
  finger_state_.snapped_through.resize(un);
  finger_state_.first_touch_gauge_pa = NAN;
  finger_state_.touch_gauge_pa = NAN;
  joint_states_pub_ = nh_.advertise<sensor_msgs::JointState>(settings_.joint_states_topic, 10);
  finger_state_pub_ = nh_.advertise<FingerModelState>(settings_.finger_state_topic, 10);
}

// The tip's error bar as a sphere riding on the tip frame, latched: rviz, started later, still gets the one the finger
// has now.
void FingerNode::setUpTipMarker(ros::NodeHandle& nh) {
  const std::string& prefix = settings_.urdf.prefix;
  tip_uncertainty_ = settings_.tip_uncertainty;
  tip_marker_pub_ = nh.advertise<visualization_msgs::Marker>("tip_uncertainty_marker", 1, true);
  force_marker_pub_ = nh.advertise<visualization_msgs::MarkerArray>("contact_force_markers", 1);
  tip_marker_.header.frame_id = tipLinkName(prefix);
  tip_marker_.header.stamp = ros::Time(0);  // "latest"
  tip_marker_.frame_locked = true;  // rviz re-transforms it every frame: the sphere rides on the tip as the finger moves
  tip_marker_.ns = prefix + "tip_uncertainty";
  tip_marker_.type = visualization_msgs::Marker::SPHERE;
  tip_marker_.pose.orientation.w = 1.0;
  if (tip_uncertainty_.empty()) {
    ROS_INFO("%s: the parameters have no tip_uncertainty (finger_calibrate writes it): the tip's error bar "
             "is published as NaN", log_name_.c_str());
  }
}

void FingerNode::onPressure(const sensor_msgs::FluidPressure::ConstPtr& msg) {
  // The rules are the core's (PressureInputPolicy); this only forwards the message and acts on the verdict.
  const ros::Time now = ros::Time::now();
  const InputDecision d = input_.onMessage(msg->fluid_pressure, msg->header.stamp.toSec(), now.toSec());
  if (d.time_jumped) ROS_WARN("%s: %s", log_name_.c_str(), d.problem.c_str());  // once per jump
  switch (d.verdict) {
    case InputVerdict::kThrottled:
      return;
    case InputVerdict::kRefusedNotFinite:
    case InputVerdict::kRefusedNegativeAbsolute:
    case InputVerdict::kRefusedOutOfOrder:
      ROS_WARN_THROTTLE(5.0, "%s: refused a pressure message: %s; keeping the last state", log_name_.c_str(), d.problem.c_str());
      return;
    case InputVerdict::kAccept:
      break;
  }
  if (!d.time_jumped && !d.problem.empty()) ROS_WARN_THROTTLE(5.0, "%s: %s", log_name_.c_str(), d.problem.c_str());
  // The message's own stamp to the nanosecond (the policy compares seconds as doubles), or the receive time.
  publishAt(d.gauge_pa, d.stamp_replaced ? now : msg->header.stamp, d.clamped);
}

bool FingerNode::publishAt(double gauge_pa, const ros::Time& stamp, bool clamped) {
  const ros::Time now = ros::Time::now();
  const FingerState& state = model_->evaluate(gauge_pa, *workspace_);
  if (state.status == EvaluationStatus::kBeyondLimitPoint) {
    // No invented shape: finger_state repeats the last one and says why; joint_states and tf stay as they were.
    input_.noteBeyondLimitPoint(gauge_pa, model_->limitGaugePa(), now.toSec());
    ROS_WARN_THROTTLE(5.0, "%s: %s", log_name_.c_str(), input_.lastProblem().c_str());
    if (have_pressure_) {  // before any shape there is none to repeat: diagnostics alone say why
      finger_state_.header.stamp = stamp;
      // What else holds, by the core's one rule, as Python and finger_model report it.
      const RangeCheck range = checkedInput(gauge_pa, clamped, settings_.input.validated_max_gauge_pa);
      finger_state_.status = FingerModelState::STATUS_BEYOND_LIMIT_POINT;
      finger_state_.status_flags = reportEvaluation(state.status, range, false).flags;
      finger_state_pub_.publish(finger_state_);
    }
    return false;
  }
  ContactState contact;
  bool failed = state.status == EvaluationStatus::kSolverFailure;
  // The contact rule only with a section within reach: otherwise the free finger is the answer, at no extra cost.
  const bool with_contact = !failed && grasp_->inReach();
  if (with_contact) {
    contact = grasp_->solve(state.gauge_pa);
    failed = contact.status == ContactState::Status::kSolverFailure;
  }
  if (failed) {
    // Nothing non-finite is ever published: the last state stays, and diagnostics say why.
    input_.noteSolverFailure(std::string("solver '") + solverName(settings_.solver) + "' found no finite answer at " +
                                 formatMessage(gauge_pa) + " Pa gauge" + (with_contact ? " (with the grasp object)" : "") +
                                 "; last state kept",
                             now.toSec());
    ROS_WARN_THROTTLE(5.0, "%s: %s", log_name_.c_str(), input_.lastProblem().c_str());
    return false;
  }
  if (state.status == EvaluationStatus::kVacuum) {
    input_.noteVacuum(gauge_pa, now.toSec());
    ROS_WARN_THROTTLE(5.0, "%s: %s", log_name_.c_str(), input_.lastProblem().c_str());
  }
  noteBranch(gauge_pa);
  have_pressure_ = true;
  last_gauge_pa_ = gauge_pa;
  last_clamped_ = clamped;
  publish(state, with_contact ? &contact : nullptr, stamp, clamped);
  return true;
}

void FingerNode::publish(const FingerState& state, const ContactState* contact, const ros::Time& stamp, bool clamped,
                         double supplied_volume_m3) {
  // With contact the joints, backbone and tip are the contact rule's; stretch, bulge and half angle stay the free
  // chambers' (they depend on the pressure alone).
  const double* q_rad = contact ? contact->joint_angle_rad.data() : state.joint_angle_rad.data();
  const Eigen::Ref<const Eigen::Matrix2Xd> backbone = contact ? Eigen::Ref<const Eigen::Matrix2Xd>(contact->backbone_m)
                                                               : Eigen::Ref<const Eigen::Matrix2Xd>(state.backbone_m);
  double tip_angle_rad = writeJoints(state, contact, q_rad, stamp);
  if (!contact) tip_angle_rad = state.tip_angle_rad;  // the model's own sum, bit for bit
  writeShape(state, backbone, tip_angle_rad, stamp);
  const bool held = contact && std::any_of(contact->held.begin(), contact->held.end(), [](bool h) { return h; });
  // Held, the walls' bulges the state already holds (the free ones) are reused; only the held walls' are solved.
  if (held) {
    finger_state_.supplied_volume_m3 = suppliedVolumeInContact(*model_, *contact, state.gauge_pa, state.bulge_m.data());
  } else {
    finger_state_.supplied_volume_m3 =
        std::isnan(supplied_volume_m3) ? model_->suppliedVolumeOf(state) : supplied_volume_m3;
  }
  finger_state_.walls_in_contact = state.walls_in_contact;
  finger_state_.in_validated_range = state.gauge_pa >= 0 && state.gauge_pa <= settings_.input.validated_max_gauge_pa;
  const bool meets_itself = backboneMeetsItself(backbone, q_rad);  // said, and published with its status
  if (meets_itself) ROS_WARN_THROTTLE(5.0, "%s: %s", log_name_.c_str(), selfContactMessage(tip_angle_rad).c_str());
  // The input's check, as the input policy made it (a clamped volume is a clamped pressure).
  const RangeCheck range = checkedInput(state.gauge_pa, clamped, settings_.input.validated_max_gauge_pa);
  const EvaluationReport report = reportEvaluation(state.status, range, meets_itself);  // the core's one rule
  finger_state_.status = static_cast<std::uint8_t>(report.status);
  finger_state_.status_flags = report.flags;
  writeObject(contact);
  writeForces(state.gauge_pa, contact);
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

double FingerNode::writeJoints(const FingerState& state, const ContactState* contact, const double* q_rad,
                               const ros::Time& stamp) {
  double tip_angle_rad = 0.0;
  joint_states_.header.stamp = stamp;
  for (int i = 0; i < settings_.finger.chamber_count; ++i) {
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
    finger_state_.snapped_through[k] = workspace_->onFarBranch(model_->groupOfChamber(i));
  }
  return tip_angle_rad;
}

void FingerNode::writeShape(const FingerState& state, const Eigen::Ref<const Eigen::Matrix2Xd>& backbone,
                            double tip_angle_rad, const ros::Time& stamp) {
  for (int i = 0; i < settings_.finger.chamber_count + 2; ++i) {
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
  finger_state_.chord_angle_rad =
      chordAngleRad(finger_state_.tip.position.x, finger_state_.tip.position.y, tip_angle_rad);
}

void FingerNode::writeObject(const ContactState* contact) {
  finger_state_.object_id = object_ ? object_->id : std::string();
  finger_state_.object_status = toMessage(contact ? grasp_->statusWith(*contact) : grasp_->status());
  finger_state_.touch_gauge_pa = grasp_->touchGaugePa();
  finger_state_.first_touch_gauge_pa = NAN;
  finger_state_.contact_points.clear();
  if (!contact) return;
  finger_state_.first_touch_gauge_pa = contact->first_touch_gauge_pa;
  for (const Eigen::Vector2d& c : contact->contact_points_m) {
    geometry_msgs::Point p;
    p.x = c.x();
    p.y = c.y();
    finger_state_.contact_points.push_back(p);
  }
}

// The force model only where there is contact (a scene that needs it): the held joints' moments, into finger_state
// and joint_states.effort, and the normal force at each contact point. A free finger's joints carry no moment: its
// walls are at their free bulge, so the zeros are the model's answer, not a stand-in.
void FingerNode::writeForces(double gauge_pa, const ContactState* contact) {
  const auto n = static_cast<std::size_t>(settings_.finger.chamber_count);
  std::fill(finger_state_.joint_moment_nm.begin(), finger_state_.joint_moment_nm.end(), 0.0);
  finger_state_.contact_normal_forces_n.clear();
  const bool in_contact = contact && contact->status == ContactState::Status::kInContact;
  if (in_contact) {
    model_->heldJointMomentsNm(gauge_pa, contact->held_since_gauge_pa.data(), finger_state_.joint_moment_nm.data());
    contactNormalForcesN(*model_, gauge_pa, *contact, finger_state_.contact_normal_forces_n);
  }
  // The arrows only for someone who looks, and once more when the contact ends (to clear them).
  if ((in_contact || arrows_shown_) && force_marker_pub_.getNumSubscribers() > 0) {
    force_marker_pub_.publish(contactForceArrows(in_contact ? *contact : ContactState(),
                                                 finger_state_.contact_normal_forces_n, finger_state_.header.frame_id,
                                                 settings_.urdf.prefix + "contact_force", settings_.force_arrow_m_per_n,
                                                 0.5 * settings_.finger.chamber_width_m[0] + 0.003));
  }
  arrows_shown_ = in_contact;
  std::copy(finger_state_.joint_moment_nm.begin(), finger_state_.joint_moment_nm.begin() + static_cast<long>(n),
            joint_states_.effort.begin());
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

FingerNodeConfig FingerNode::currentConfig() const {
  FingerNodeConfig c;
  c.shear_modulus_pa = settings_.finger.shear_modulus_pa[0];
  c.chamber_gap_m = settings_.finger.chamber_gap_m[0];
  c.base_wall_share = settings_.finger.base_wall_share;
  c.wall_locking_jm = settings_.finger.wall_locking_jm;
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
    // The actuator's live keys: the same validation as a parameter file or a rosparam (fromRaw refuses, naming the
    // key and the range).
    const std::pair<const char*, double FingerNodeConfig::*> live[] = {
        {"shear_modulus_pa", &FingerNodeConfig::shear_modulus_pa},
        {"chamber_gap_m", &FingerNodeConfig::chamber_gap_m},
        {"base_wall_share", &FingerNodeConfig::base_wall_share},
        {"wall_locking_jm", &FingerNodeConfig::wall_locking_jm}};
    RawParameterMap raw = settings_.finger.toRaw();
    bool actuator = false;
    for (const auto& [key, member] : live) {
      if (config.*member == now.*member) continue;
      raw[key] = {{config.*member}, false};
      actuator = true;
    }
    if (actuator) next.finger = FingerParameters::fromRaw(raw);
    next.input.max_rate_hz = checkNodeNumber("max_rate_hz", config.max_rate_hz);
    next.input.stale_timeout_s = checkNodeNumber("stale_timeout_s", config.stale_timeout_s);
    settings_ = next;
    input_.updateSettings(settings_.input);
    if (actuator) {
      if (!tip_uncertainty_.empty()) {
        ROS_WARN("%s: the actuator was reconfigured: the calibration's tip error bar no longer applies, "
                 "finger_state publishes it as NaN", log_name_.c_str());
        tip_uncertainty_ = TipUncertainty{};
        tip_marker_.action = visualization_msgs::Marker::DELETE;
        tip_marker_pub_.publish(tip_marker_);
        marker_bar_m_ = -1.0;
      }
      settings_.calibration_error = CalibrationError{};  // nor does the record of how well it followed its data
      buildModel(nh_);
      ROS_INFO("%s: reconfigured: shear_modulus_pa %s Pa, chamber_gap_m %s m, base_wall_share %s, "
               "wall_locking_jm %s; URDF republished", log_name_.c_str(), formatMessage(config.shear_modulus_pa).c_str(),
               formatMessage(config.chamber_gap_m).c_str(), formatMessage(config.base_wall_share).c_str(),
               formatMessage(config.wall_locking_jm).c_str());
    }
  } catch (const ParameterError& e) {
    ROS_ERROR("%s: reconfigure refused: %s; keeping the previous values", log_name_.c_str(), e.what());
    config = now;
  }
}

}  // namespace pneumatic_finger
