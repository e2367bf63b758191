// finger_node's services: the inverse model (the pressure for a tip angle) and the grasp's force (the pressure for a
// contact force on the grasp object), both answered by the core.
#include <string>

#include "pneumatic_finger/ros/finger_node.hpp"

namespace pneumatic_finger {

bool FingerNode::onInverse(PressureForTipAngle::Request& req, PressureForTipAngle::Response& res) {
  std::string why;
  double gauge = 0;
  res.success = model_->gaugeForTipAngle(req.tip_angle_rad, settings_.urdf.max_gauge_pa, gauge, why);
  res.gauge_pa = res.success ? gauge : 0.0;
  res.absolute_pa = res.success ? gauge + settings_.finger.atmospheric_pressure_pa : 0.0;
  res.message = why;  // empty, or why not, or (a target on the far branch) how to reach it
  return true;  // a refused request is an answer, not a transport failure
}

// The pressure at which this finger presses on its grasp object with the requested total normal force: the core's
// search on the finger's own contact tracker (the object as the finger sees it now).
bool FingerNode::onContactForce(PressureForContactForce::Request& req, PressureForContactForce::Response& res) {
  std::string why;
  double gauge = 0;
  if (!object_ || !grasp_->inReach()) {
    why = "no grasp object within reach of this finger";
  } else {
    res.success = gaugeForContactForce(*model_, [this](double p) { return grasp_->solve(p); }, req.force_n,
                                       settings_.urdf.max_gauge_pa, gauge, why);
  }
  res.gauge_pa = res.success ? gauge : 0.0;
  res.absolute_pa = res.success ? gauge + settings_.finger.atmospheric_pressure_pa : 0.0;
  res.message = res.success ? "" : why;
  return true;  // a refused request is an answer, not a transport failure
}

}  // namespace pneumatic_finger
