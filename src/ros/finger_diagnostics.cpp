// finger_node's report on /diagnostics (task "pressure input"): the input rules' verdict and counters, the model's
// work and the walls' branch, the tip's error bar and the grasp object; and the log line of a snap-through.
#include <string>
#include <utility>

#include "pneumatic_finger/ros/finger_node.hpp"

namespace pneumatic_finger {

void FingerNode::diagnose(diagnostic_updater::DiagnosticStatusWrapper& status) {
  const InputReport r = input_.report(ros::Time::now().toSec());
  status.summary(static_cast<unsigned char>(r.level), r.message);
  const InputCounters& c = input_.counters();
  status.add("input rate (Hz, last 1 s)", r.rate_hz);
  status.add("seconds since last pressure", r.age_s);
  status.add("last gauge pressure (Pa)", input_.lastGaugePa());
  const double validated = settings_.input.validated_max_gauge_pa;
  status.add("validated range (Pa gauge)",
             validated > 0 ? "0.." + formatMessage(validated) : "none: a zero-shot prediction (no actuator's data)");
  // The input rules' counters, each with the name diagnostics give it, in three groups: what arrived and when, what
  // was refused, and what the accepted messages gave.
  using Counted = std::pair<const char*, long>;
  const Counted arrived[] = {{"messages received", c.received},
                             {"zero stamps (receive time used)", c.zero_stamps},
                             {"stamps replaced by the receive time", c.far_stamps},
                             {"time jumps (new timeline)", c.time_jumps},
                             {"skipped by max_rate_hz or same instant", c.throttled}};
  const Counted refused[] = {{"refused: not finite", c.refused_not_finite},
                             {"refused: negative absolute pressure", c.refused_negative_absolute},
                             {"refused: stamp not newer than the last", c.refused_out_of_order}};
  const Counted gave[] = {{"vacuum (straight finger published)", c.vacuum},
                          {"clamped to max_gauge_pa", c.clamped},
                          {"above the validated range", c.out_of_range},
                          {"solver failures (last state kept)", c.solver_failures},
                          {"beyond the limit point (last state kept)", c.beyond_limit_point}};
  auto add = [&status](const auto& group) {
    for (const auto& [name, count] : group) status.add(name, count);
  };
  add(arrived);
  add(refused);
  add(gave);
  status.add("model evaluations (unchanged pressures reuse the last)", workspace_->computationCount());
  // The snap-through (membrane law, a Gent wall): which branch the walls are on, and how often they jumped.
  status.add("wall branch", on_far_branch_ ? "far (snapped through; back at or below " +
                                                 formatMessage(model_->farTurningGaugePa()) + " Pa gauge)"
                                           : std::string("near"));
  status.add("snaps through (near to far branch)", snaps_through_);
  status.add("snaps back (far to near branch)", snaps_back_);
  // Where a rising pressure bends the finger fastest: its limit point, or where a wall that does not fold is softest.
  status.add("snap pressure (Pa gauge)", formatMessage(model_->snapGaugePa()));
  if (!input_.lastProblem().empty()) status.add("last problem", input_.lastProblem());
  diagnoseCalibration(status);
  status.add("grasp object", object_ ? object_->id : std::string("(none)"));
  status.add("grasp object status", graspObjectStatusName(grasp_->status()));
  status.add("predicted first touch (Pa gauge)", grasp_->touchGaugePa());
  status.add("object sections cut (pose changed)", grasp_->sectionsCut());
  status.add("object transform failures", grasp_->transformFailures());
  const std::string problem = !object_refused_.empty()  ? object_refused_
                              : grasp_->problem().empty() ? std::string()
                                                          : "grasp object '" + object_->id + "': " + grasp_->problem();
  if (!problem.empty()) {
    status.mergeSummary(diagnostic_msgs::DiagnosticStatus::WARN, problem);
    status.add("grasp object problem", problem);
  }
}

// What the parameter file says of its calibration: the tip's error bar, and how well the fit followed its data; a
// fit that does not is a warning, since every shape this node publishes comes from it.
void FingerNode::diagnoseCalibration(diagnostic_updater::DiagnosticStatusWrapper& status) {
  status.add("tip error bar", tip_uncertainty_.empty()
                                   ? std::string("none (NaN in finger_state)")
                                   : "calibrated at " + std::to_string(tip_uncertainty_.gauge_pa.size()) +
                                         " pressures up to " + formatMessage(tip_uncertainty_.gauge_pa.back()) +
                                         " Pa gauge; above: extrapolated");
  const CalibrationError& e = settings_.calibration_error;
  status.add("calibration", e.describe());
  if (!e.empty() && !e.follows_data) {
    status.mergeSummary(diagnostic_msgs::DiagnosticStatus::WARN,
                        "the parameter file's calibration does not follow its data (" + e.describe() + ")");
  }
}

// The snap-through (docs/MODEL.md): a jump between the walls' branches is logged once and counted for diagnostics.
void FingerNode::noteBranch(double gauge_pa) {
  const bool far = workspace_->snappedThrough();
  if (far == on_far_branch_) return;
  on_far_branch_ = far;
  if (far) {
    ++snaps_through_;
    ROS_INFO("%s: snapped through at %s Pa gauge: the walls jumped past their limit point (%s Pa) to the far branch, "
             "where they hold until the pressure falls to %s Pa",
             log_name_.c_str(), formatMessage(gauge_pa).c_str(), formatMessage(model_->limitGaugePa()).c_str(),
             formatMessage(model_->farTurningGaugePa()).c_str());
  } else {
    ++snaps_back_;
    ROS_INFO("%s: snapped back at %s Pa gauge: the walls are on the near branch again", log_name_.c_str(),
             formatMessage(gauge_pa).c_str());
  }
}

}  // namespace pneumatic_finger
