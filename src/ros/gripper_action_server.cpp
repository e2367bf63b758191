// gripper_action_server: the gripper's actionlib interface (pneumatic_finger/GripperCommand, MoveIt's fields). It
// gathers each finger's answers (the pressure for the goal's tip angle from its pressure_for_tip_angle service, the
// predicted first touch of the grasp object from its finger_state), lets the core plan the pressure
// (planGripperCommand), commands the regulator and follows the fingers until the pressure settles.
#include <actionlib/server/simple_action_server.h>
#include <ros/ros.h>
#include <sensor_msgs/FluidPressure.h>
#include <std_msgs/Float64.h>

#include <algorithm>
#include <cstdio>
#include <cmath>
#include <map>
#include <mutex>
#include <sstream>
#include <string>
#include <vector>

#include "pneumatic_finger/FingerModelState.h"
#include "pneumatic_finger/GripperCommandAction.h"
#include "pneumatic_finger/PressureForContactForce.h"
#include "pneumatic_finger/PressureForTipAngle.h"
#include "pneumatic_finger/core/grasp_plan.hpp"
#include "pneumatic_finger/core/units.hpp"
#include "pneumatic_finger/ros/node_main.hpp"
#include "pneumatic_finger/ros/parameter_reader.hpp"

namespace pf = pneumatic_finger;

namespace {

// The server's parameters: their one definition (`gripper_action_server --parameters` prints it for docs/).
const std::vector<pf::NodeParameterSpec>& parameterSpecs() {
  static const std::vector<pf::NodeParameterSpec> table = {
      pf::listParameter("finger_namespaces", "string[]", "-", "each finger_node's namespace",
                        "the fingers the action drives (their pressure_for_tip_angle service and finger_state)"),
      pf::numberParameter("squeeze_margin_pa", pf::kDefaultSqueezeMarginPa, 0, false, 1e6, "Pa",
                          "a grasp's pressure beyond the last finger's touch (0.1 kg/cm^2)"),
      pf::numberParameter("goal_tolerance_rad", 0.01, 1e-6, false, 1.0, "rad", "`reached_goal` tolerance"),
      pf::numberParameter("settle_tolerance_pa", 200.0, 1e-3, false, 1e5, "Pa",
                          "settled: every finger's pressure this close to the command"),
      pf::numberParameter("settle_timeout_s", 10.0, 0.1, false, 600, "s", "no settling within this aborts the goal"),
      pf::numberParameter("max_gauge_pa", pf::kModelMaxGaugePa, 1e-3, false, 1e7, "Pa",
                          "the fingers' range (their max_gauge_pa): the highest pressure the action commands"),
      pf::numberParameter("object_settle_s", 0.1, 0, true, 10, "s",
                          "a goal is planned on finger states received this long after it came: time for the fingers "
                          "to see the object where the arm has stopped (3 of their object updates at 30 Hz)"),
      pf::numberParameter("input_timeout_s", 0.5, 0.01, false, 60, "s",
                          "during a goal, a finger whose finger_state, or a regulator whose pressure, is older than "
                          "this is lost: the goal aborts and names it (both come at the regulator's 100 Hz)"),
      pf::textParameter("pressure_topic", "pressure", "-",
                        "the regulator's pressure (sensor_msgs/FluidPressure): watched so that a stale regulator is "
                        "told from a lost finger"),
  };
  return table;
}

class GripperActionServer {
 public:
  GripperActionServer(ros::NodeHandle& nh, ros::NodeHandle& pnh)
      : server_(nh, "gripper_action", [this](const pf::GripperCommandGoalConstPtr& goal) { execute(goal); }, false) {
    const pf::NodeParameterReader in(pnh, parameterSpecs());
    fingers_ = in.texts("finger_namespaces");
    squeeze_margin_pa_ = in.number("squeeze_margin_pa");
    goal_tolerance_rad_ = in.number("goal_tolerance_rad");
    settle_tolerance_pa_ = in.number("settle_tolerance_pa");
    settle_timeout_s_ = in.number("settle_timeout_s");
    max_gauge_pa_ = in.number("max_gauge_pa");
    object_settle_s_ = in.number("object_settle_s");
    input_timeout_s_ = in.number("input_timeout_s");
    const std::string pressure_topic = in.text("pressure_topic");
    in.refuseUnknownKeys();
    pressure_sub_ = nh.subscribe<sensor_msgs::FluidPressure>(pressure_topic, 1, [this](const sensor_msgs::FluidPressure::ConstPtr&) {
      std::lock_guard<std::mutex> lock(mutex_);
      pressure_received_ = ros::Time::now();
    });
    pressure_topic_ = nh.resolveName(pressure_topic);
    for (const std::string& ns : fingers_) {
      subs_.push_back(nh.subscribe<pf::FingerModelState>(
          ros::names::append(ns, "finger_state"), 1,
          [this, ns](const pf::FingerModelState::ConstPtr& m) {
            std::lock_guard<std::mutex> lock(mutex_);
            states_[ns] = {m, ros::Time::now()};
          }));
    }
    setpoint_pub_ = nh.advertise<std_msgs::Float64>("setpoint", 1, true);
    server_.start();
    ROS_INFO("gripper_action_server: %zu fingers, squeeze margin %.0f Pa, action '%s'", fingers_.size(),
             squeeze_margin_pa_, nh.resolveName("gripper_action").c_str());
  }

 private:
  struct Latest {
    pf::FingerModelState::ConstPtr state;
    ros::Time received;
  };

  // Every finger's latest state (received after @p since), or an empty list when one is missing.
  std::vector<Latest> latest(const ros::Time& since) {
    std::lock_guard<std::mutex> lock(mutex_);
    std::vector<Latest> out;
    for (const std::string& ns : fingers_) {
      const auto it = states_.find(ns);
      if (it == states_.end() || it->second.received < since) return {};
      out.push_back(it->second);
    }
    return out;
  }

  void describe(const std::vector<Latest>& states, double goal_rad, pf::GripperCommandResult& r) const {
    r.position = r.gauge_pa = 0;
    r.effort = INFINITY;
    r.stalled = r.reached_goal = true;
    for (const Latest& l : states) {
      r.position += l.state->tip_angle_rad / static_cast<double>(states.size());
      r.gauge_pa += l.state->gauge_pa / static_cast<double>(states.size());
      double force_n = 0.0;  // this finger's total normal force on the object (finger_state's contact forces)
      for (double f : l.state->contact_normal_forces_n) force_n += f;
      r.effort = std::min(r.effort, force_n);
      r.stalled = r.stalled && l.state->object_status == pf::FingerModelState::OBJECT_TOUCHING;
      r.reached_goal = r.reached_goal && std::fabs(l.state->tip_angle_rad - goal_rad) <= goal_tolerance_rad_;
    }
  }

  // What the goal has lost, or empty: the regulator's pressure, or a finger's finger_state, older than
  // input_timeout_s (counted from @p since for one never received since). A dead regulator silences every finger,
  // so it is named first; a dead finger_node is named by its namespace. Planning or settling on the others' states
  // would grasp on a guess.
  std::string lostInput(const ros::Time& since) {
    std::lock_guard<std::mutex> lock(mutex_);
    const ros::Time now = ros::Time::now();
    auto age = [&](const ros::Time& received) { return (now - std::max(received, since)).toSec(); };
    std::ostringstream why;
    why.precision(2);
    why << std::fixed;
    if (!pressure_received_.isZero() && age(pressure_received_) > input_timeout_s_) {
      why << "the regulator's pressure '" << pressure_topic_ << "' is stale: none for " << age(pressure_received_)
          << " s, and the fingers keep their last shape";
      return why.str();
    }
    std::string lost;
    double oldest = 0;
    for (const std::string& ns : fingers_) {
      const auto it = states_.find(ns);
      const double a = age(it == states_.end() ? ros::Time() : it->second.received);
      if (a <= input_timeout_s_) continue;
      lost += (lost.empty() ? "" : ", ") + ns;
      oldest = std::max(oldest, a);
    }
    if (lost.empty()) return {};
    why << "lost " << lost << ": no finger_state for " << oldest << " s (did the finger's node stop?)";
    return why.str();
  }

  // The fingers' states to plan with: received object_settle_s after the goal came, and, while any finger has an
  // object, seen by every finger within reach (up to kObjectWaitS). A goal sent as the arm arrives would otherwise be
  // planned on states from while the arm still moved: the object out of reach, or within reach but where the closing
  // fingers pass it ("does not touch the object up to it"; the 1000-cycle soak of docs/SOAK.md missed 17 grasps so).
  // Empty, with @p lost saying why, when an input is lost (lostInput).
  std::vector<Latest> statesForThePlan(std::string& lost) {
    constexpr double kObjectWaitS = 1.0;
    const ros::Time start = ros::Time::now() + ros::Duration(object_settle_s_);
    std::vector<Latest> states;
    for (ros::Rate wait(100); ros::ok(); wait.sleep()) {
      const double waited = (ros::Time::now() - start).toSec();
      if (waited < 0) continue;
      const std::vector<Latest> now = latest(start);
      if (now.empty()) {
        lost = lostInput(start);
        if (!lost.empty()) return {};
        continue;
      }
      states = now;
      bool object = false, in_reach = true;
      for (const Latest& l : states) {
        object = object || !l.state->object_id.empty();
        in_reach = in_reach && (l.state->object_status == pf::FingerModelState::OBJECT_CLEAR ||
                                l.state->object_status == pf::FingerModelState::OBJECT_TOUCHING);
      }
      if (!object || in_reach || waited > kObjectWaitS) break;
    }
    return states;
  }

  // A grasp with a grip force: the pressure at which every finger presses on the object with @p force_n newtons, the
  // largest any finger needs (each answers from its own model, pressure_for_contact_force). false: a finger cannot
  // (its reason, with the most it gives), and nothing is commanded.
  bool planForce(double force_n, pf::GripperPlan& plan, std::string& why) {
    double needed = 0.0;
    std::string by;
    for (const std::string& ns : fingers_) {
      pf::PressureForContactForce srv;
      srv.request.force_n = force_n;
      const std::string name = ros::names::append(ns, "pressure_for_contact_force");
      if (!ros::service::waitForService(name, ros::Duration(2.0)) || !ros::service::call(name, srv)) {
        why = "service '" + name + "' did not answer";
        return false;
      }
      if (!srv.response.success) {
        why = ns + " cannot grip with " + pf::formatMessage(force_n) + " N: " + srv.response.message;
        return false;
      }
      if (srv.response.gauge_pa >= needed) needed = srv.response.gauge_pa, by = ns;
    }
    // The goal settles within settle_tolerance_pa of the command, from below as the regulator fills: commanding that
    // much more (up to the range) leaves a settled grip no weaker than the force asked.
    const double command = std::min(needed + settle_tolerance_pa_, max_gauge_pa_);
    std::ostringstream s;
    s << "grasp with " << force_n << " N per finger: commanding " << command << " Pa (" << by << " needs the most, "
      << needed << " Pa; the settle tolerance above it)";
    plan.gauge_pa = command;
    plan.message = s.str();
    return true;
  }

  void publishSetpoint(double gauge_pa) {
    std_msgs::Float64 setpoint;
    setpoint.data = gauge_pa;
    setpoint_pub_.publish(setpoint);
  }

  void abort(const std::string& why, const pf::GripperCommandResult& result = {}) {
    ROS_WARN("gripper_action_server: goal aborted: %s", why.c_str());
    server_.setAborted(result, why);
  }

  // The fingers that cannot locate the object (OBJECT_NO_TRANSFORM), in words, or empty: a plan on the free finger
  // would be a guess.
  std::string unlocatedFingers(const std::vector<Latest>& states) const {
    std::string unlocated;
    for (std::size_t i = 0; i < fingers_.size(); ++i) {
      if (states[i].state->object_status != pf::FingerModelState::OBJECT_NO_TRANSFORM) continue;
      unlocated += (unlocated.empty() ? "" : ", ") + fingers_[i];
    }
    if (unlocated.empty()) return unlocated;
    return unlocated + " cannot locate the object '" + states[0].state->object_id +
           "': no fresh transform to its frame (is robot_state_publisher running?)";
  }

  void execute(const pf::GripperCommandGoalConstPtr& goal) {
    // Opening needs no plan (every finger is open at 0 Pa): vent first, so that the gripper lets go even when a finger
    // or the regulator is lost and the goal below aborts.
    if (goal->position <= 0) publishSetpoint(0.0);
    // The fingers' answers: the pressure that brings each free tip to the goal, the predicted touch of the object.
    std::string lost;
    std::vector<Latest> states = statesForThePlan(lost);
    if (states.empty()) return abort(lost.empty() ? "shut down while planning" : lost);
    const std::string unlocated = unlocatedFingers(states);
    if (!unlocated.empty()) return abort(unlocated);
    std::vector<pf::FingerGoalAnswer> answers;
    bool object = false;
    std::string unanswered;
    if (!askFingers(goal->position, states, answers, object, unanswered)) return abort(unanswered);
    // Within the fingers' range (their max_gauge_pa, where they clamp).
    pf::GripperPlan plan = pf::planGripperCommand(answers, goal->position, max_gauge_pa_, squeeze_margin_pa_, object);
    if (plan.kind == pf::GripperPlan::Kind::kUnreachable) return abort(plan.message);
    if (plan.kind == pf::GripperPlan::Kind::kGrasp && goal->max_effort > 0) {
      std::string why;
      if (!planForce(goal->max_effort, plan, why)) return abort(why);
    }
    ROS_INFO("gripper_action_server: %s", plan.message.c_str());

    publishSetpoint(plan.gauge_pa);
    const ros::Time commanded = ros::Time::now();
    pf::GripperCommandResult result;
    pf::GripperCommandFeedback feedback;
    for (ros::Rate rate(20); ros::ok(); rate.sleep()) {
      if (server_.isPreemptRequested()) {
        server_.setPreempted(result, "preempted; the regulator keeps the last setpoint");
        return;
      }
      lost = lostInput(commanded);
      if (!lost.empty()) return abort(lost, result);
      states = latest(commanded);
      if (states.empty()) continue;
      describe(states, goal->position, result);
      feedback.position = result.position, feedback.effort = result.effort, feedback.gauge_pa = result.gauge_pa;
      feedback.stalled = result.stalled, feedback.reached_goal = result.reached_goal;
      server_.publishFeedback(feedback);
      bool settled = true;
      for (const Latest& l : states) settled = settled && std::fabs(l.state->gauge_pa - plan.gauge_pa) <= settle_tolerance_pa_;
      if (settled) break;
      if ((ros::Time::now() - commanded).toSec() > settle_timeout_s_) {
        std::ostringstream s;
        s << "the fingers did not settle at " << plan.gauge_pa << " Pa within " << settle_timeout_s_
          << " s (at " << result.gauge_pa << " Pa)";
        return abort(s.str(), result);
      }
    }
    finish(plan, result);
  }

  // Each finger's pressure for the goal's tip angle (its pressure_for_tip_angle service) and its predicted touch of
  // the object; false with the finger whose service did not answer.
  bool askFingers(double goal_tip_angle_rad, const std::vector<Latest>& states,
                  std::vector<pf::FingerGoalAnswer>& answers, bool& object, std::string& why) {
    for (std::size_t i = 0; i < fingers_.size(); ++i) {
      pf::PressureForTipAngle srv;
      srv.request.tip_angle_rad = std::max(goal_tip_angle_rad, 0.0);  // below 0: open, as 0
      const std::string name = ros::names::append(fingers_[i], "pressure_for_tip_angle");
      if (!ros::service::waitForService(name, ros::Duration(2.0)) || !ros::service::call(name, srv)) {
        why = "service '" + name + "' did not answer";
        return false;
      }
      // The finger's range: the service refuses beyond its max_gauge_pa; the touch is predicted up to it.
      const pf::FingerModelState& s = *states[i].state;
      object = object || !s.object_id.empty();
      answers.push_back({fingers_[i], srv.response.success ? srv.response.gauge_pa : NAN, s.touch_gauge_pa});
      // Expected when the goal lies beyond the object (the touch comes first): the plan below says what it does.
      if (!srv.response.success) ROS_DEBUG("gripper_action_server: %s: %s", name.c_str(), srv.response.message.c_str());
    }
    return true;
  }

  // The settled fingers' verdict: a grasp succeeds when every finger touches, a move when the goal is reached or the
  // object stops it.
  void finish(const pf::GripperPlan& plan, pf::GripperCommandResult& result) {
    std::ostringstream s;
    s << "at " << result.gauge_pa << " Pa: tip angle " << result.position << " rad, grip force " << result.effort
      << " N";
    if (plan.kind == pf::GripperPlan::Kind::kGrasp ? result.stalled : (result.reached_goal || result.stalled)) {
      s << (result.stalled ? ", every finger touches the object" : ", goal reached");
      ROS_INFO("gripper_action_server: goal succeeded %s", s.str().c_str());
      server_.setSucceeded(result, s.str());
    } else {
      s << (plan.kind == pf::GripperPlan::Kind::kGrasp ? ": not every finger touches the object (did it move?)"
                                                       : ": the goal is not reached and the object does not stop it");
      abort(s.str(), result);
    }
  }

  actionlib::SimpleActionServer<pf::GripperCommandAction> server_;
  std::vector<std::string> fingers_;
  std::vector<ros::Subscriber> subs_;
  ros::Subscriber pressure_sub_;
  ros::Publisher setpoint_pub_;
  std::string pressure_topic_;
  ros::Time pressure_received_;
  std::mutex mutex_;
  std::map<std::string, Latest> states_;
  double squeeze_margin_pa_ = 0, goal_tolerance_rad_ = 0, settle_tolerance_pa_ = 0, settle_timeout_s_ = 0;
  double max_gauge_pa_ = 0, object_settle_s_ = 0, input_timeout_s_ = 0;
};

}  // namespace

int main(int argc, char** argv) {
  return pf::runNode<GripperActionServer>(argc, argv, "gripper_action_server", parameterSpecs());
}
