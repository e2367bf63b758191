#include "pneumatic_finger/core/grasp_plan.hpp"

#include "pneumatic_finger/core/parameters.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace pneumatic_finger {

GripperPlan planGripperCommand(const std::vector<FingerGoalAnswer>& fingers, double goal_position_rad,
                               double limit_pa, double squeeze_margin_pa, bool object_present) {
  GripperPlan plan;
  std::ostringstream why;
  if (fingers.empty()) {
    plan.message = "no fingers";
    return plan;
  }
  // The pressure every finger needs is the largest any one needs; one finger that cannot is enough to rule it out.
  auto slowest = [&](double FingerGoalAnswer::*field, std::string& culprit) -> double {
    double worst = 0;
    for (const FingerGoalAnswer& f : fingers) {
      const double p = f.*field;
      if (!(p >= 0 && p <= limit_pa)) {
        culprit = f.name;
        return NAN;
      }
      if (p >= worst) worst = p, culprit = f.name;
    }
    return worst;
  };
  std::string free_by, touch_by;
  const double free_pa = slowest(&FingerGoalAnswer::free_gauge_pa, free_by);
  const double touch_pa = object_present ? slowest(&FingerGoalAnswer::touch_gauge_pa, touch_by) : NAN;
  if (!std::isnan(touch_pa) && (std::isnan(free_pa) || touch_pa <= free_pa)) {
    plan.kind = GripperPlan::Kind::kGrasp;
    plan.gauge_pa = std::min(touch_pa + squeeze_margin_pa, limit_pa);
    why << "grasp: every finger touches the object by " << formatMessage(touch_pa) << " Pa (" << touch_by
        << " last), before the " << formatMessage(goal_position_rad) << " rad goal; commanding "
        << formatMessage(plan.gauge_pa) << " Pa";
    if (plan.gauge_pa < touch_pa + squeeze_margin_pa) why << " (the limit; the margin would ask for more)";
  } else if (!std::isnan(free_pa) && free_pa == 0) {
    // Every finger is at its goal unpressurised: an opening, which no finger "needs the most" and no object delays.
    plan.kind = GripperPlan::Kind::kClose;
    plan.gauge_pa = 0;
    why << "open: vent to 0 Pa, where every finger is at the " << formatMessage(goal_position_rad) << " rad goal";
  } else if (!std::isnan(free_pa)) {
    plan.kind = GripperPlan::Kind::kClose;
    plan.gauge_pa = free_pa;
    why << "close to " << formatMessage(goal_position_rad) << " rad at " << formatMessage(free_pa) << " Pa (" << free_by
        << " needs the most)";
    if (object_present) {
      why << (std::isnan(touch_pa) ? "; " + touch_by + " does not touch the object up to the limit"
                                   : "; the goal comes before every finger touches the object");
    }
  } else {
    plan.kind = GripperPlan::Kind::kUnreachable;
    why << "no gauge pressure up to " << formatMessage(limit_pa) << " Pa brings " << free_by << "'s tip to "
        << formatMessage(goal_position_rad) << " rad";
    if (object_present) why << ", and " << touch_by << " does not touch the object up to it";
  }
  plan.message = why.str();
  return plan;
}

}  // namespace pneumatic_finger
