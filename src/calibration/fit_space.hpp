// The calibration's search space (solver.cpp) and its uncertainty (calibration_uncertainty.cpp) share: which keys
// may be fitted, over which bracket each is searched, and how a value is set. Internal header of src/core.
#pragma once

#include <algorithm>
#include <cmath>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "pneumatic_finger/core/drawing.hpp"
#include "pneumatic_finger/core/parameters.hpp"

namespace pneumatic_finger {

struct SearchAxis {
  std::string key;
  bool logarithmic;
  double lo, hi;  // in search coordinates (log10 for logarithmic)
  double toValue(double x) const { return logarithmic ? std::pow(10.0, x) : x; }
};

inline constexpr const char* kFittable[] = {"shear_modulus_pa", "chamber_gap_m",   "wall_critical_height_m",
                                            "chamber_height_m", "base_wall_share", "wall_locking_jm",
                                            "dead_volume_m3",   "chamber_growth_ratio", "wall_bulge_share"};

// The drawing's sizes a calibration may fit (drawing/KEY): each a positive length, searched logarithmically from a
// quarter of the drawn value to four times it, within its key's range. The chamber count is a whole number (sweep it
// with finger_design), and the floor, the gap and the base may be 0.
inline constexpr const char* kFittableDrawn[] = {"cavity_height_m",      "cavity_width_m",   "cavity_length_m",
                                                 "wall_thickness_m",     "end_wall_thickness_m", "roof_thickness_m",
                                                 "body_width_m"};

// The drawn value of @p name (without the prefix), its default resolved: the drawing's own rule.
inline double drawnSize(const FingerParameters& base, const std::string& name) {
  const std::optional<ActuatorDrawing> d = drawingFromRaw(base.drawing);
  if (!d) return 0.0;
  return name == "cavity_height_m"        ? d->cavity_height_m
         : name == "cavity_width_m"       ? d->cavity_width_m
         : name == "cavity_length_m"      ? d->cavity_length_m
         : name == "wall_thickness_m"     ? d->wall_thickness_m
         : name == "end_wall_thickness_m" ? d->end_wall_thickness_m
         : name == "roof_thickness_m"     ? d->roof_thickness_m
                                          : d->body_width_m;
}

inline SearchAxis axisFor(const std::string& key, const FingerParameters& base) {
  if (key.rfind(kDrawingPrefix, 0) == 0) {
    const double drawn = drawnSize(base, key.substr(std::string(kDrawingPrefix).size()));
    return {key, true, std::log10(drawn / 4.0), std::log10(std::min(4.0 * drawn, 0.5))};
  }
  // mu: the paper law's effective modulus over [1e5, 1e12] Pa; the membrane's and the thick wall's is a silicone's,
  // 10 kPa to 10 MPa.
  if (key == "shear_modulus_pa") {
    return base.wall_law != WallLaw::kPaper ? SearchAxis{key, true, 4.0, 7.0} : SearchAxis{key, true, 5.0, 12.0};
  }
  if (key == "base_wall_share") return {key, false, 0.0, 1.0};
  // J_m logarithmically over [1, 1e4]: from a wall that locks at lambda = 1.5 to one that behaves as Neo-Hookean.
  if (key == "wall_locking_jm") return {key, true, 0.0, 4.0};
  // The drive's gas linearly over [0, 1 L]: a syringe or cylinder and its tubing, from none (a liquid) to a litre.
  if (key == "dead_volume_m3") return {key, false, 0.0, 1e-3};
  // r_V logarithmically over [1, 100]: from the walls' growth alone to a skin that takes a hundred times it.
  if (key == "chamber_growth_ratio") return {key, true, 0.0, 2.0};
  // kappa logarithmically over [1e-3, 1]: from a wall that tilts by a thousandth of the sphere's bulge to all of it.
  if (key == "wall_bulge_share") return {key, true, -3.0, 0.0};
  const double l = *std::max_element(base.chamber_height_m.begin(), base.chamber_height_m.end());
  if (key == "chamber_gap_m") return {key, false, 0.0, l};
  return {key, false, 1e-3 * l, (key == "chamber_height_m" ? 4.0 : 1.0) * l};
}

// A value's place on its axis: its log10 on a logarithmic one.
inline double coordinateOf(const SearchAxis& axis, double value) { return axis.logarithmic ? std::log10(value) : value; }

// Why @p value of @p axis's key is no minimum: it sits on an end of the search range (within a millionth of it).
// Empty: within.
inline std::string boundWarning(const SearchAxis& axis, double value) {
  const double x = coordinateOf(axis, value), width = axis.hi - axis.lo;
  if (x > axis.lo + 1e-6 * width && x < axis.hi - 1e-6 * width) return "";
  std::ostringstream w;
  w << axis.key << " = " << formatMessage(value) << " sits on the " << (x <= axis.lo + 1e-6 * width ? "lower" : "upper")
    << " end of its search range [" << formatMessage(axis.toValue(axis.lo)) << ", " << formatMessage(axis.toValue(axis.hi))
    << "]: the data want it beyond, so the fit is not a minimum in it";
  return w.str();
}

inline void setKey(FingerParameters& p, const std::string& key, double value) {
  if (key.rfind(kDrawingPrefix, 0) == 0) {  // drawn anew by the rule: the keys it makes follow the drawing
    p = withDrawingSize(p, key, value);  // @throws ParameterError for a drawing the rule refuses
    return;
  }
  if (key == "base_wall_share" || key == "wall_locking_jm" || key == "dead_volume_m3" || key == "chamber_growth_ratio" ||
      key == "wall_bulge_share") {
    (key == "base_wall_share"        ? p.base_wall_share
     : key == "wall_locking_jm"      ? p.wall_locking_jm
     : key == "dead_volume_m3"       ? p.dead_volume_m3
     : key == "wall_bulge_share"     ? p.wall_bulge_share
                                     : p.chamber_growth_ratio) = value;
    return;
  }
  std::vector<double>* target = key == "shear_modulus_pa"       ? &p.shear_modulus_pa
                                : key == "chamber_gap_m"          ? &p.chamber_gap_m
                                : key == "wall_critical_height_m" ? &p.wall_critical_height_m
                                                                  : &p.chamber_height_m;
  std::fill(target->begin(), target->end(), value);
}

}  // namespace pneumatic_finger
