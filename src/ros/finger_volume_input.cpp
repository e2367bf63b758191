// finger_node's input (pressure or volume), and finger_node driven by volume (~volume_topic; docs/MODEL.md "Volume"): a syringe pump's or a cylinder's supplied
// volume in, the finger's state and the pressure it makes out. The input rules are the pressure's (rate, staleness,
// refusals: PressureInputPolicy); the model answers with FingerModel::evaluateVolume.
#include <string>

#include "pneumatic_finger/ros/finger_node.hpp"

namespace pneumatic_finger {

void FingerNode::subscribeInput(ros::NodeHandle& nh) {
  // Queue of 1 when throttled (only the newest pressure matters); otherwise keep up with bursts. One input drives the
  // finger: the volume when ~volume_topic is set, else the pressure.
  const int queue = settings_.input.max_rate_hz > 0 ? 1 : 100;
  if (settings_.volume_topic.empty()) {
    pressure_sub_ = nh.subscribe(settings_.pressure_topic, queue, &FingerNode::onPressure, this,
                                 ros::TransportHints().tcpNoDelay());
    return;
  }
  volume_sub_ = nh.subscribe(settings_.volume_topic, queue, &FingerNode::onVolume, this,
                             ros::TransportHints().tcpNoDelay());
  ROS_INFO("%s: driven by the supplied volume on %s (m^3), not by pressure", log_name_.c_str(),
           nh.resolveName(settings_.volume_topic).c_str());
}

// The last input again, with the object as it is now.
void FingerNode::republish() {
  if (!have_pressure_) return;
  if (settings_.volume_topic.empty()) {
    publishAt(last_gauge_pa_, ros::Time::now(), last_clamped_);
  } else {
    followVolume(last_volume_m3_, ros::Time::now());
  }
}

void FingerNode::onVolume(const std_msgs::Float64::ConstPtr& msg) {
  const ros::Time now = ros::Time::now();
  const double volume_m3 = msg->data;
  const InputDecision d = input_.onVolumeMessage(volume_m3, now.toSec());
  if (d.time_jumped) ROS_WARN("%s: %s", log_name_.c_str(), d.problem.c_str());
  if (d.verdict == InputVerdict::kThrottled) return;
  if (d.verdict != InputVerdict::kAccept) {
    ROS_WARN_THROTTLE(5.0, "%s: refused a volume message: %s; keeping the last state", log_name_.c_str(),
                      d.problem.c_str());
    return;
  }
  followVolume(volume_m3, now);
}

void FingerNode::followVolume(double volume_m3, const ros::Time& now) {
  last_volume_m3_ = volume_m3;
  // An object within reach holds the walls it touches, which then take less volume: the contact rule's own volume.
  if (volume_m3 >= 0.0 && grasp_->inReach()) return followVolumeInContact(volume_m3, now);
  // The range rule of every interface (pressure_range.hpp): above the volume that makes max_gauge_pa, the finger there.
  const VolumeCheck in_range = checkVolumeRange(volume_m3, max_volume_m3_);
  if (in_range.clamped) {
    input_.noteVolumeClamped(volumeClampedMessage(volume_m3, max_volume_m3_, input_.range()), now.toSec());
    ROS_WARN_THROTTLE(5.0, "%s: %s", log_name_.c_str(), input_.lastProblem().c_str());
  }
  const FingerState& state = model_->evaluateVolume(in_range.volume_m3, *workspace_);
  if (state.status == EvaluationStatus::kBeyondLimitPoint || state.status == EvaluationStatus::kSolverFailure) {
    // No invented shape: finger_state repeats the last one and says why; joint_states and tf stay as they were.
    const std::string why = volumeNotFollowedMessage(volume_m3, state.status == EvaluationStatus::kSolverFailure,
                                                     model_->volumeLimitM3()) +
                            "; last state kept";
    input_.noteVolumeNotFollowed(why, now.toSec());
    ROS_WARN_THROTTLE(5.0, "%s: %s", log_name_.c_str(), why.c_str());
    if (have_pressure_) {
      finger_state_.header.stamp = now;
      finger_state_.status = FingerModelState::STATUS_BEYOND_LIMIT_POINT;
      finger_state_.status_flags = 0;  // the core's report of a volume not followed (no pressure, so nothing else holds)
      finger_state_pub_.publish(finger_state_);
    }
    return;
  }
  if (state.status == EvaluationStatus::kVacuum) {  // the straight finger, as Python and finger_model give it
    input_.noteVacuum(state.gauge_pa, now.toSec());
    ROS_WARN_THROTTLE(5.0, "%s: %s", log_name_.c_str(), input_.lastProblem().c_str());
  }
  // Past the limit point the pressure falls while the volume grows: a valid state under volume control, said so.
  input_.noteGaugeFromVolume(state.gauge_pa, volume_m3 > model_->limitPointVolumeM3());
  have_pressure_ = true;
  last_gauge_pa_ = state.gauge_pa;
  last_clamped_ = in_range.clamped;
  publish(state, nullptr, now, in_range.clamped, in_range.volume_m3);
}

// The pressure at which the finger closing on the object has taken the volume (gaugeForVolumeInContact), then the
// pressure's own path: the state, the contact rule and its forces. More than the finger takes on the object up to the
// top of its range is clamped there, as a pressure would be; up to its limit point, kept as beyond it.
void FingerNode::followVolumeInContact(double volume_m3, const ros::Time& now) {
  double gauge_pa = 0.0;
  std::string why;
  const auto contact_at = [this](double p) { return grasp_->solve(p); };
  const double top_pa = settings_.urdf.max_gauge_pa;
  if (gaugeForVolumeInContact(*model_, contact_at, volume_m3, top_pa, gauge_pa, why)) {
    input_.noteGaugeFromVolume(gauge_pa, false);
    publishAt(gauge_pa, now, false);
    return;
  }
  const std::string problem = why + " (closing on grasp object '" + object_->id + "')";
  if (model_->belowLimitGaugePa() >= top_pa) {
    input_.noteVolumeNotFollowed(problem + ": clamped to the top of the range", now.toSec());
    ROS_WARN_THROTTLE(5.0, "%s: %s", log_name_.c_str(), input_.lastProblem().c_str());
    input_.noteGaugeFromVolume(top_pa, false);
    publishAt(top_pa, now, true);
    return;
  }
  input_.noteVolumeNotFollowed(problem + "; last state kept", now.toSec());
  ROS_WARN_THROTTLE(5.0, "%s: %s", log_name_.c_str(), input_.lastProblem().c_str());
  if (have_pressure_) {
    finger_state_.header.stamp = now;
    finger_state_.status = FingerModelState::STATUS_BEYOND_LIMIT_POINT;
    finger_state_.status_flags = 0;
    finger_state_pub_.publish(finger_state_);
  }
}

}  // namespace pneumatic_finger
