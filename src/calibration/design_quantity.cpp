// A design's targets (design_target.hpp): their text, and each one's quantity for a drawn actuator.
#include "pneumatic_finger/calibration/design_target.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

namespace pneumatic_finger {

namespace {

constexpr const char* kAtPressure[] = {"tip_angle_rad", "chord_angle_rad", "blocked_tip_force_n"};
constexpr const char* kOwn[] = {"snap_gauge_pa", "limit_gauge_pa", "contact_gauge_pa", "grip_gauge_pa"};

bool among(const std::string& q, const char* const* first, const char* const* last) {
  return std::find_if(first, last, [&q](const char* k) { return q == k; }) != last;
}

// A number of a target's text. @throws ParameterError naming the target
double targetNumber(const std::string& text, const std::string& field, const char* what) {
  const std::optional<double> v = readNumber(field);
  if (!v || !std::isfinite(*v)) {
    throw ParameterError("--target " + text + ": '" + field + "' is not a finite number (" + what + ")");
  }
  return *v;
}

}  // namespace

DesignTarget parseDesignTarget(const std::string& text) {
  const auto eq = text.find('=');
  const std::string usage = "; expected QUANTITY=VALUE (snap_gauge_pa, limit_gauge_pa, contact_gauge_pa, "
                            "grip_gauge_pa; grip_gauge_pa=min for the lowest) or QUANTITY@P=VALUE (tip_angle_rad, "
                            "chord_angle_rad, blocked_tip_force_n at P Pa gauge; gauge_for_tip_angle at a tip angle "
                            "in rad)";
  if (eq == std::string::npos) throw ParameterError("--target " + text + ": no '='" + usage);
  DesignTarget t;
  t.text = text;
  std::string left = text.substr(0, eq);
  const auto at = left.find('@');
  t.quantity = left.substr(0, at);
  const bool pressure = among(t.quantity, std::begin(kAtPressure), std::end(kAtPressure));
  const bool angle = t.quantity == "gauge_for_tip_angle";
  if (!pressure && !angle && !among(t.quantity, std::begin(kOwn), std::end(kOwn))) {
    throw ParameterError("--target " + text + ": unknown quantity '" + t.quantity + "'" + usage);
  }
  if ((pressure || angle) != (at != std::string::npos)) {
    throw ParameterError("--target " + text + ": " + t.quantity + (pressure || angle ? " needs" : " takes no") +
                         " '@'" + usage);
  }
  if (at != std::string::npos) t.at = targetNumber(text, left.substr(at + 1), angle ? "rad" : "Pa gauge");
  const std::string value = text.substr(eq + 1);
  t.minimize = value == "min";
  if (t.minimize && t.quantity != "grip_gauge_pa") {
    throw ParameterError("--target " + text + ": only grip_gauge_pa takes 'min' (the lowest pressure that holds the "
                         "part); give a value" + usage);
  }
  if (t.minimize) return t;
  t.value = targetNumber(text, value, "a number in the quantity's unit, Pa, rad or N, with no suffix");
  const bool pressure_value = among(t.quantity, std::begin(kOwn), std::end(kOwn)) || angle;
  if (pressure_value && !(t.value > 0.0)) {
    throw ParameterError("--target " + text + ": a pressure (Pa gauge) above 0 is expected");
  }
  return t;
}

void attachGripPart(std::vector<DesignTarget>& targets, const std::string& part_text, double max_gauge_pa) {
  const auto grip = [](const DesignTarget& t) { return t.quantity == "grip_gauge_pa"; };
  const bool wanted = std::any_of(targets.begin(), targets.end(), grip);
  if (!wanted && !part_text.empty()) {
    throw ParameterError("--part " + part_text + ": no target grips it (--target grip_gauge_pa=min, or =PRESSURE)");
  }
  if (!wanted) return;
  if (part_text.empty()) {
    throw ParameterError("--target grip_gauge_pa needs the part: --part mass_kg=M,diameter_m=D[,lift_mps2=A] "
                         "(docs/DESIGN.md, \"A grip\")");
  }
  SideGripTask part = parseSideGripTask(part_text);
  part.max_gauge_pa = max_gauge_pa;
  for (DesignTarget& t : targets) {
    if (grip(t)) t.grip = part;
  }
}

double designQuantity(const FingerParameters& p, const DesignTarget& t) {
  ModelOptions options;
  options.wall_inverse = false;  // one model per design, asked once or twice
  options.snap_point = t.quantity == "snap_gauge_pa";
  const FingerModel model(p, options);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  if (t.quantity == "snap_gauge_pa") return model.snapGaugePa();
  if (t.quantity == "limit_gauge_pa") return model.limitGaugePa();
  if (t.quantity == "contact_gauge_pa") return model.contactGaugePa();
  if (t.quantity == "blocked_tip_force_n") return model.blockedTipForceN(t.at);
  if (t.quantity == "grip_gauge_pa") return holdingGaugePa(model, t.grip);
  if (t.quantity == "gauge_for_tip_angle") {
    double gauge_pa = nan;
    std::string why;
    return model.gaugeForTipAngle(t.at, std::numeric_limits<double>::infinity(), gauge_pa, why) ? gauge_pa : nan;
  }
  FingerWorkspace ws(model);
  const FingerState& s = model.evaluate(t.at, ws);
  if (s.status != EvaluationStatus::kOk && s.status != EvaluationStatus::kSnappedThrough) return nan;
  return t.quantity == "tip_angle_rad" ? s.tip_angle_rad : s.chordAngle();
}

}  // namespace pneumatic_finger
