// The actuator as drawn, and the one rule from its drawing to the model's keys (drawing.hpp, docs/DRAWING.md).
#include "pneumatic_finger/core/drawing.hpp"

#include <cmath>
#include <limits>
#include <sstream>

namespace pneumatic_finger {

namespace {

constexpr double kRequired = std::numeric_limits<double>::quiet_NaN();

const ParameterSpec& drawingSpec(const std::string& key) {
  for (const ParameterSpec& spec : drawingParameterSpecs()) {
    if (key == spec.key) return spec;
  }
  throw unknownParameterError(kDrawingPrefix + key);
}

// The drawing's value for @p key: given (checked against its range), else its default (NaN: required, refused).
double drawn(const RawParameterMap& raw, const std::string& key, double fallback = kRequired) {
  const ParameterSpec& spec = drawingSpec(key);
  const auto it = raw.find(kDrawingPrefix + key);
  if (it == raw.end()) {
    if (std::isnan(fallback)) {
      throw ParameterError("parameter '" + std::string(kDrawingPrefix) + key + "' is missing: a drawing gives " +
                           spec.description);
    }
    return fallback;
  }
  if (it->second.is_list || it->second.values.size() != 1) {
    throw ParameterError("parameter '" + std::string(kDrawingPrefix) + key + "' must be one number (every cavity "
                         "of a drawing is the same)");
  }
  // The range check's own words, the key named as the file and --set name it (drawing/KEY).
  const std::string full_key = kDrawingPrefix + key;
  ParameterSpec named = spec;
  named.key = full_key.c_str();
  checkParameterValue(named, it->second.values[0]);
  return it->second.values[0];
}

std::string mm(double m) { return formatMessage(1e3 * m) + " mm"; }

// The sizes that must fit together, each refusal naming them.
void checkFits(const ActuatorDrawing& d) {
  if (!(d.gap_m < d.wall_thickness_m)) {
    throw ParameterError("drawing: the gap " + mm(d.gap_m) + " leaves no elastomer in the " + mm(d.wall_thickness_m) +
                         " wall between cavities: a wall must be thicker than its gap");
  }
  if (!(d.body_width_m > d.cavity_width_m)) {
    throw ParameterError("drawing: the cavities (" + mm(d.cavity_width_m) + " wide) do not fit the body (" +
                         mm(d.body_width_m) + " wide): body_width_m must exceed cavity_width_m");
  }
  if (!(d.floor_height_m + d.cavity_height_m > 0.0)) {
    throw ParameterError("drawing: the cavities' floor " + mm(d.floor_height_m) + " lies more than their height " +
                         mm(d.cavity_height_m) + " below the bending axis: the cavities would sit on the far side");
  }
  if (!(d.base_length_m + 2.0 * d.end_wall_thickness_m > d.wall_thickness_m)) {
    throw ParameterError("drawing: the base and the end walls (" + mm(d.base_length_m + 2.0 * d.end_wall_thickness_m) +
                         ") must be longer than one wall between cavities (" + mm(d.wall_thickness_m) +
                         "): the base segment, mount to joint 1, would have no length");
  }
}

}  // namespace

const std::vector<ParameterSpec>& drawingParameterSpecs() {
  static const std::vector<ParameterSpec> specs = {
      {"chamber_count", "N", "-", kRequired, 1, true, kMaxChamberCount, ParameterShape::kScalarInteger,
       "the number of cavities in the row"},
      {"cavity_height_m", "-", "m", kRequired, 0, false, 0.5, ParameterShape::kScalar,
       "each cavity's height, from its floor up, away from the strain-limiting layer"},
      {"cavity_width_m", "-", "m", kRequired, 0, false, 0.5, ParameterShape::kScalar, "each cavity's width, across"},
      {"cavity_length_m", "-", "m", kRequired, 0, false, 0.5, ParameterShape::kScalar,
       "each cavity's length, along the finger"},
      {"wall_thickness_m", "-", "m", kRequired, 0, false, 0.5, ParameterShape::kScalar,
       "the elastomer between neighbouring cavities, along the finger (an air gap in it included)"},
      {"end_wall_thickness_m", "-", "m", kRequired, 0, false, 0.5, ParameterShape::kScalar,
       "the elastomer at each end of the row (default: wall_thickness_m)"},
      {"roof_thickness_m", "-", "m", kRequired, 0, false, 0.5, ParameterShape::kScalar,
       "the elastomer above the cavities (default: wall_thickness_m)"},
      {"floor_height_m", "-", "m", 0.0, -0.5, true, 0.5, ParameterShape::kScalar,
       "the cavities' floor above the bending axis, the strain-limiting layer (default 0; below 0: a cavity that "
       "reaches across the axis)"},
      {"gap_m", "-", "m", 0.0, 0, true, 0.5, ParameterShape::kScalar,
       "an air gap splitting each wall between cavities into two (default 0: one solid wall)"},
      {"base_length_m", "-", "m", 0.0, 0, true, 1.0, ParameterShape::kScalar,
       "the solid passive base from the mount to the first end wall (default 0)"},
      {"body_width_m", "-", "m", kRequired, 0, false, 1.0, ParameterShape::kScalar,
       "the body's width, across (default: the cavity and a wall each side)"},
      {"layer_thickness_m", "-", "m", 0.0, 0, true, 0.5, ParameterShape::kScalar,
       "the strain-limiting layer under the body, below the bending axis (default 0: not drawn). The model bends "
       "about its top and does not use it; the body's mesh (finger_urdf --stl) does"},
  };
  return specs;
}

bool isDrawingKey(const std::string& key) {
  if (key.rfind(kDrawingPrefix, 0) != 0) return false;
  const std::string name = key.substr(std::string(kDrawingPrefix).size());
  for (const ParameterSpec& spec : drawingParameterSpecs()) {
    if (name == spec.key) return true;
  }
  return false;
}

const std::vector<std::string>& drawnModelKeys() {
  static const std::vector<std::string> keys = {
      "chamber_count",     "chamber_height_m",      "chamber_thickness_m", "chamber_width_m",
      "segment_length_m",  "base_segment_length_m", "wall_thickness_m",    "wall_critical_height_m",
      "wall_flexion_face"};
  return keys;
}

std::optional<ActuatorDrawing> drawingFromRaw(const RawParameterMap& raw) {
  bool any = false;
  for (const auto& entry : raw) {
    if (entry.first.rfind(kDrawingPrefix, 0) != 0) continue;
    drawingSpec(entry.first.substr(std::string(kDrawingPrefix).size()));  // refuses an unknown key
    any = true;
  }
  if (!any) return std::nullopt;
  ActuatorDrawing d;
  d.chamber_count = static_cast<int>(drawn(raw, "chamber_count"));
  d.cavity_height_m = drawn(raw, "cavity_height_m");
  d.cavity_width_m = drawn(raw, "cavity_width_m");
  d.cavity_length_m = drawn(raw, "cavity_length_m");
  d.wall_thickness_m = drawn(raw, "wall_thickness_m");
  d.end_wall_thickness_m = drawn(raw, "end_wall_thickness_m", d.wall_thickness_m);
  d.roof_thickness_m = drawn(raw, "roof_thickness_m", d.wall_thickness_m);
  d.floor_height_m = drawn(raw, "floor_height_m", 0.0);
  d.gap_m = drawn(raw, "gap_m", 0.0);
  d.base_length_m = drawn(raw, "base_length_m", 0.0);
  d.body_width_m = drawn(raw, "body_width_m", d.cavity_width_m + 2.0 * d.wall_thickness_m);
  d.layer_thickness_m = drawn(raw, "layer_thickness_m", 0.0);
  checkFits(d);
  return d;
}

double bodyLengthM(const ActuatorDrawing& d) {
  return d.base_length_m + 2.0 * d.end_wall_thickness_m + d.chamber_count * d.cavity_length_m +
         (d.chamber_count - 1) * d.wall_thickness_m;
}

double bodyTopM(const ActuatorDrawing& d) { return d.floor_height_m + d.cavity_height_m + d.roof_thickness_m; }

RawParameterMap modelKeysFromDrawing(const ActuatorDrawing& d, WallLaw law) {
  const int n = d.chamber_count;
  const bool own_face = n == 1;  // one cavity has no neighbour to press: its own face lengthens the side
  // A solid wall is shared: both cavities push on all of it. A split wall gives each cavity its half.
  const double between = d.gap_m > 0.0 ? 0.5 * (d.wall_thickness_m - d.gap_m) : d.wall_thickness_m;
  const double pitch = d.cavity_length_m + d.wall_thickness_m;
  const double length = bodyLengthM(d), top = bodyTopM(d);
  RawParameterMap keys;
  auto put = [&keys](const char* key, double v) { keys[key] = RawParameterValue{{v}, false}; };
  put("chamber_count", n);
  put("chamber_height_m", d.cavity_height_m);
  put("chamber_thickness_m", d.cavity_length_m);
  put("chamber_width_m", d.cavity_width_m);
  put("segment_length_m", pitch);
  put("base_segment_length_m", length - n * pitch);
  put("wall_thickness_m", own_face ? d.roof_thickness_m : between);
  // The paper law's b is a point on its wall, the uniform wall's middle; the membrane and thick laws' is the lever
  // where the walls push, the body's top above the bending axis.
  put("wall_critical_height_m", law == WallLaw::kPaper ? 0.5 * d.cavity_height_m : top);
  put("wall_flexion_face", static_cast<double>(own_face ? FlexionFace::kInner : FlexionFace::kOuter));
  return keys;
}

RawParameterMap resolveDrawing(const RawParameterMap& raw) {
  const std::optional<ActuatorDrawing> drawing = drawingFromRaw(raw);
  if (!drawing) return raw;
  const auto law_entry = raw.find("wall_law");
  const WallLaw law = law_entry == raw.end() ? static_cast<WallLaw>(static_cast<int>(findParameterSpec("wall_law")->default_value))
                                             : static_cast<WallLaw>(static_cast<int>(law_entry->second.values.at(0)));
  RawParameterMap out = raw;
  for (const auto& [key, value] : modelKeysFromDrawing(*drawing, law)) {
    const auto given = raw.find(key);
    if (given != raw.end()) {
      for (double v : given->second.values) {
        if (v == value.values[0]) continue;
        throw ParameterError("parameter '" + key + "' = " + formatMessage(v) + " contradicts the drawing, which makes it " +
                             formatMessage(value.values[0]) + " (docs/DRAWING.md): give the drawing or the key, not both");
      }
    }
    out[key] = value;
  }
  if (!raw.count("chamber_gap_m")) out["chamber_gap_m"] = {{drawing->gap_m}, false};
  if (!raw.count("base_wall_share")) out["base_wall_share"] = {{1.0}, false};  // the end wall bends as the others
  return out;  // the drawing's entries as given: a default follows the keys it comes from when they change
}

}  // namespace pneumatic_finger
