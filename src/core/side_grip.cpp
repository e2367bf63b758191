// A part held by its side (side_grip.hpp).
#include "pneumatic_finger/core/side_grip.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <vector>

#include "pneumatic_finger/core/contact.hpp"
#include "pneumatic_finger/core/parameters.hpp"

namespace pneumatic_finger {

namespace {

// One number of a grip's text. @throws ParameterError naming the key
double gripNumber(const std::string& text, const std::string& key, const std::string& value) {
  const std::optional<double> v = readNumber(value);
  if (!v || !std::isfinite(*v)) {
    throw ParameterError("part '" + text + "': " + key + " '" + value + "' is not a finite number");
  }
  return *v;
}

}  // namespace

SideGripTask parseSideGripTask(const std::string& text) {
  SideGripTask task;
  bool mass = false, diameter = false;
  std::stringstream items(text);
  std::string item;
  while (std::getline(items, item, ',')) {
    const auto eq = item.find('=');
    const std::string key = item.substr(0, eq), value = eq == std::string::npos ? "" : item.substr(eq + 1);
    const double v = gripNumber(text, key, value);
    if (key == "mass_kg") task.mass_kg = v, mass = true;
    else if (key == "diameter_m") task.diameter_m = v, diameter = true;
    else if (key == "lift_mps2") task.lift_acceleration_mps2 = v;
    else if (key == "fingers") {
      if (v != std::floor(v) || std::fabs(v) > 1e6) {
        throw ParameterError("part '" + text + "': fingers is a whole number");
      }
      task.finger_count = static_cast<int>(v);
    }
    else if (key == "mount_radius_m") task.mount_radius_m = v;
    else if (key == "friction") task.friction_coefficient = v;
    else if (key == "margin") task.hold_margin = v;
    else if (key == "limit_share") task.limit_share = v;
    else {
      throw ParameterError("part '" + text + "': '" + item + "' is not a part's or gripper's key (mass_kg, "
                           "diameter_m, lift_mps2, fingers, mount_radius_m, friction, margin, limit_share)");
    }
  }
  if (!mass || !diameter) throw ParameterError("part '" + text + "': mass_kg and diameter_m are needed");
  checkSideGripTask(task);
  return task;
}

void checkSideGripTask(const SideGripTask& t) {
  const auto refuse = [](const std::string& what) { throw ParameterError("the part to grip: " + what); };
  if (!(t.mass_kg > 0.0)) refuse("mass_kg " + formatMessage(t.mass_kg) + " is not a mass > 0 (kg)");
  if (!(t.diameter_m > 0.0)) refuse("diameter_m " + formatMessage(t.diameter_m) + " is not a size > 0 (m)");
  if (!(t.lift_acceleration_mps2 >= 0.0)) refuse("lift_mps2 must be >= 0 (m/s^2, upward)");
  if (t.finger_count < 1) refuse("fingers must be at least 1");
  if (!(t.mount_radius_m > 0.5 * t.diameter_m)) {
    refuse("diameter_m " + formatMessage(t.diameter_m) + " does not fit between the fingers' bases (mount_radius_m " +
           formatMessage(t.mount_radius_m) + ": a diameter below " + formatMessage(2.0 * t.mount_radius_m) + " m)");
  }
  if (!(t.friction_coefficient > 0.0)) refuse("friction must be > 0");
  if (!(t.hold_margin >= 1.0)) refuse("margin must be at least 1");
  if (!(t.limit_share > 0.0 && t.limit_share <= 1.0)) refuse("limit_share must be in (0, 1]");
}

Obstacle partSideInFingerPlane(const FingerModel& model, const SideGripTask& task) {
  const double near_m = task.mount_radius_m - 0.5 * task.diameter_m, far_m = task.mount_radius_m + 0.5 * task.diameter_m;
  const double reach_m = 2.0 * model.parameters().lengthM();  // past the tip however the finger bends
  return Obstacle::polygon({{-reach_m, near_m}, {reach_m, near_m}, {reach_m, far_m}, {-reach_m, far_m}});
}

double holdingGaugePa(const FingerModel& model, const SideGripTask& task, std::string* why) {
  checkSideGripTask(task);
  if (!(task.max_gauge_pa > 0.0) || !std::isfinite(task.max_gauge_pa)) {
    throw ParameterError("the part to grip: the highest pressure to hold it at, " + formatMessage(task.max_gauge_pa) +
                         " Pa, is not a finite pressure > 0");
  }
  const double need_n = requiredFingerForceN(task.finger_count, task.mass_kg, task.friction_coefficient,
                                             task.hold_margin, task.lift_acceleration_mps2);
  ContactTracker tracker(model, partSideInFingerPlane(model, task));
  // Past the walls' limit point the chambers balloon and no grip is defined; the search stops short of it by the
  // task's share (and a hair, where the share is 1).
  const double limit_pa = model.limitGaugePa();
  const double top_pa = std::min(task.max_gauge_pa, limit_pa * std::min(task.limit_share, 1.0 - 1e-9));
  double gauge_pa = 0.0;
  std::string reason;
  if (gaugeForContactForce(model, [&tracker](double p) { return tracker.solve(p); }, need_n, top_pa, gauge_pa,
                           reason)) {
    return gauge_pa;
  }
  if (why) {
    *why = "each finger must press with " + formatMessage(need_n) + " N; it " + reason +
           (top_pa < task.max_gauge_pa ? " (limit_share " + formatMessage(task.limit_share) + " of the limit point " +
                                             formatMessage(limit_pa) + " Pa)" : std::string());
  }
  return std::numeric_limits<double>::quiet_NaN();
}

}  // namespace pneumatic_finger
