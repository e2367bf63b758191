// The actuator as drawn (docs/DRAWING.md): the drawing's sizes, and the one rule that maps them to the model's keys
// for every wall law. A parameter file's `drawing:` mapping (rosparam ~drawing/KEY, --set drawing/KEY=VALUE, Python
// overrides {"drawing/KEY": value}) reaches the model through FingerParameters::fromRaw, so every interface reads it.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "pneumatic_finger/core/parameters.hpp"

namespace pneumatic_finger {

/// The prefix of a drawing's keys in a RawParameterMap ("drawing/cavity_height_m"), as rosparam names them.
constexpr const char* kDrawingPrefix = "drawing/";

/// A PneuNet as drawn: N cavities in a row on a strain-limiting layer, each a box; the elastomer between and around
/// them. Lengths in m, along the finger unless named otherwise.
struct ActuatorDrawing {
  int chamber_count = 0;
  double cavity_height_m = 0.0;       ///< from the cavity's floor up, away from the strain-limiting layer
  double cavity_width_m = 0.0;        ///< across the finger
  double cavity_length_m = 0.0;       ///< along the finger
  double wall_thickness_m = 0.0;      ///< elastomer between neighbouring cavities (an air gap in it included)
  double end_wall_thickness_m = 0.0;  ///< elastomer at each end of the row (default: wall_thickness_m)
  double roof_thickness_m = 0.0;      ///< elastomer above the cavities (default: wall_thickness_m)
  double floor_height_m = 0.0;        ///< the cavities' floor above the bending axis, the strain-limiting layer (0)
  double gap_m = 0.0;                 ///< air gap splitting each wall between cavities in two (0: one solid wall)
  double base_length_m = 0.0;         ///< solid passive base from the mount to the first end wall (0)
  double body_width_m = 0.0;          ///< across the finger (default: the cavity and two walls)
  double layer_thickness_m = 0.0;     ///< the strain-limiting layer under the body (0: not drawn); the model bends
                                      ///< about its top and does not use it; the body's mesh does
};

/// The body's length along the finger (m): the base, the two end walls, the cavities and the walls between them.
double bodyLengthM(const ActuatorDrawing& drawing);
/// The body's top above the bending axis (m): the cavities' floor, their height and the roof.
double bodyTopM(const ActuatorDrawing& drawing);

/// The drawing's keys: their one definition (names without the prefix; NaN default: required).
const std::vector<ParameterSpec>& drawingParameterSpecs();

/// Whether @p key is one of the drawing's, with its prefix ("drawing/cavity_height_m").
bool isDrawingKey(const std::string& key);

/// The model's keys a drawing sets (chamber_count, chamber_height_m, ...): a file with a drawing may repeat one only
/// with the drawing's own value. The effective keys (shear_modulus_pa, chamber_gap_m, base_wall_share,
/// wall_locking_jm) are not among them: a drawing gives them a start (chamber_gap_m = gap_m, base_wall_share = 1),
/// and a calibration may replace it.
const std::vector<std::string>& drawnModelKeys();

/// The drawing in @p raw's "drawing/KEY" entries, checked; nullopt when there is none.
/// @throws ParameterError naming the key (unknown, missing, out of range) or the sizes that do not fit (a wall the
///         gap leaves no elastomer in, a body narrower than its cavities, end walls too short for the base's joint).
std::optional<ActuatorDrawing> drawingFromRaw(const RawParameterMap& raw);

/// The model's keys for @p drawing under @p law (docs/DRAWING.md, "The rule"): L, d, e from the cavity; the pitch
/// Z = d + wall; Z0 so that Z0 + N Z is the body's length; the wall t (the wall between cavities, or each half of a
/// split one; the roof where one cavity bends by its own face); b (the paper law: the wall's middle, L/2; the
/// membrane and thick laws: the body's top above the bending axis); the face (outer for N > 1, inner for N = 1).
RawParameterMap modelKeysFromDrawing(const ActuatorDrawing& drawing, WallLaw law);

/// @p p with its drawing's entry @p key ("drawing/NAME") set to @p value and the model keys the drawing makes drawn
/// anew, the other keys as they were: what FingerParameters::fromRaw gives for p.toRaw() so changed, without the
/// drawn keys. Only the drawn keys are read again (a fit sets a drawing's size at each of its steps), but for a
/// changed chamber count, which changes every per-chamber key.
/// @throws ParameterError as fromRaw does (a drawing the rule refuses, a drawn key out of its range)
FingerParameters withDrawingSize(const FingerParameters& p, const std::string& key, double value);

/// @p raw with its drawing resolved: the drawing's model keys put in (a key also given with another value is refused,
/// naming both), the effective keys started where not given, the "drawing/" entries kept as given (a default is not
/// written out, so that it follows the key it comes from). Without a drawing, @p raw.
RawParameterMap resolveDrawing(const RawParameterMap& raw);

}  // namespace pneumatic_finger
