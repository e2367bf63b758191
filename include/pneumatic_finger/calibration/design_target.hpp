// Design to spec: from one calibrated actuator (its material and effective keys), the drawing that meets a target
// (docs/DESIGN.md). The drawing's free sizes are searched by NLopt (Subplex, bounded, derivative-free, from the best
// points of a coarse grid in log coordinates); the chamber count, a whole number, by enumeration.
#pragma once

#include <limits>
#include <string>
#include <vector>

#include "pneumatic_finger/core/finger_model.hpp"
#include "pneumatic_finger/core/side_grip.hpp"

namespace pneumatic_finger {

/// What the designer needs: a quantity of the designed actuator equal to a value, or as low as the bounds allow.
struct DesignTarget {
  std::string quantity;  ///< snap_gauge_pa, limit_gauge_pa, contact_gauge_pa (Pa); tip_angle_rad, chord_angle_rad
                         ///< (rad), blocked_tip_force_n (N) at a pressure; gauge_for_tip_angle (Pa) at a tip angle;
                         ///< grip_gauge_pa (Pa): the lowest pressure that holds the part (grip)
  double at = std::numeric_limits<double>::quiet_NaN();  ///< the pressure (Pa) or the angle (rad) after '@'
  double value = 0.0;    ///< what it must equal, in the quantity's unit
  bool minimize = false; ///< "=min" (grip_gauge_pa only): as low as the bounds allow, once the other targets are met
  SideGripTask grip;     ///< grip_gauge_pa's part and gripper (attachGripPart)
  std::string text;      ///< as given ("tip_angle_rad@30000=1.2"), for messages
};

/// "QUANTITY=VALUE" or "QUANTITY@AT=VALUE"; "grip_gauge_pa=min". @throws ParameterError naming the text and what is
/// expected
DesignTarget parseDesignTarget(const std::string& text);

/// Gives each grip_gauge_pa target the part of @p part_text (parseSideGripTask's "mass_kg=..,diameter_m=..") held
/// at most at @p max_gauge_pa (the base file's). @throws ParameterError for a grip target without a part, a part
/// without a grip target, or a part parseSideGripTask refuses
void attachGripPart(std::vector<DesignTarget>& targets, const std::string& part_text, double max_gauge_pa);

/// A drawing size the search may change, within [lo, hi] (m).
struct FreeDrawingKey {
  std::string key;  ///< drawing/KEY, one of the drawing's positive sizes
  double lo = 0.0, hi = 0.0;
};

struct DesignRequest {
  std::vector<DesignTarget> targets;
  std::vector<FreeDrawingKey> free;  ///< a bound of 0 takes the default: a quarter to four times the drawn size
  std::vector<int> chamber_counts;   ///< the counts tried (empty: the drawing's own)
  double castable_m = 1e-3;          ///< the thinnest wall, roof or end wall that can be cast (m)
  /// The body's largest length, width and height (m; the drawing's outline: base, end walls, cavities and walls
  /// along; body width across; floor, cavity and roof up); 0: no limit.
  double max_body_length_m = 0.0, max_body_width_m = 0.0, max_body_height_m = 0.0;
  /// The base file's validated range top (Pa gauge; 0: none given): a target the answer meets above it, or at a
  /// pressure above it, is noted, since the base actuator's data say nothing there.
  double validated_max_gauge_pa = 0.0;
};

/// The designed actuator, or the nearest the bounds allow, and how far it reaches from the base drawing.
struct DesignAnswer {
  FingerParameters parameters;    ///< the base with the drawing's free sizes (and count) replaced
  int chamber_count = 0;
  std::vector<double> values;     ///< each free key's value (m), in the request's order
  std::vector<double> drawn;      ///< each free key's size in the base drawing (m; its default where not given)
  std::vector<double> achieved;   ///< each target's quantity for the design, in the targets' order
  std::vector<double> misses;     ///< each target's relative miss, achieved / value - 1 (achieved where value is 0;
                                  ///< 0 for a target to minimise)
  double miss = 0.0;              ///< the largest |achieved / value - 1| over the targets (|achieved| where value is 0)
  bool met = false;               ///< every target within kDesignTolerance (relative); one to minimise achieved
  std::vector<std::string> at_bound;  ///< "drawing/KEY at its upper bound 0.014 m" for each key that stops the search
  std::vector<std::string> notes;     ///< what else a designer must know (a shape that meets itself at a target)
  double reach = 0.0;             ///< the largest |ln(value / drawn)| over the free keys: how far from the base drawing
  double seconds = 0.0;           ///< the search's wall time
};

/// A target is met within a thousandth of its value: finer than any cast part repeats (the search itself goes on to
/// its numerical limit, so that a single target is met to about 1e-10).
inline constexpr double kDesignTolerance = 1e-3;

/// The target's quantity for the actuator @p p (NaN where it has none: no shape at the pressure, no such pressure).
double designQuantity(const FingerParameters& p, const DesignTarget& target);

/// Searches the drawing of @p base (which must have one) for @p request. @throws ParameterError for a base without a
/// drawing, an unknown or repeated free key, a key that is not a positive drawing size, bounds that do not hold the
/// castable thickness, a free key that moves no target (the same quantities at both ends of its bounds), or no
/// design in the bounds that the model accepts
DesignAnswer designToTarget(const FingerParameters& base, const DesignRequest& request);

/// Targets that pull against each other: the Pareto front of the best chamber count (designToTarget's). The designs
/// minimising weighted sums of the targets' squared relative misses, the weights spread evenly over the simplex
/// (@p points steps along each edge: every weight a multiple of 1 / @p points), each searched locally from the
/// unweighted answer; kept are those no other design misses less on every target, in the order of the first target's
/// miss. @throws ParameterError as designToTarget, and for fewer than two targets, a target to minimise (a front
/// trades values) or @p points below 1
std::vector<DesignAnswer> designParetoFront(const FingerParameters& base, const DesignRequest& request, int points);

/// The answer's parameter file: its parameters, the base's range top with validated_max_gauge_pa 0 (no actuator's
/// data validate a drawing not yet cast: every answer is a zero-shot prediction), and its search as comments.
std::string designParameterYaml(const DesignAnswer& answer, const DesignRequest& request, double max_gauge_pa);

}  // namespace pneumatic_finger
