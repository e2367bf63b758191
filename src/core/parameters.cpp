#include "pneumatic_finger/core/parameters.hpp"

#include "pneumatic_finger/core/drawing.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <sstream>

#include "pneumatic_finger/core/units.hpp"

namespace pneumatic_finger {

namespace {

// The single table of keys. Ranges are physical plausibility bounds for a finger-sized actuator: wide enough for
// any design a researcher might try, narrow enough that a unit mistake (mm for m, kPa for Pa) is refused.
// shear_modulus_pa, chamber_gap_m and base_wall_share are effective values: the calibrated minimax fit to the paper's
// Table 1 (docs/ACCURACY.md, reproduced by `finger_calibrate`).
const std::vector<ParameterSpec> kSpecs = {
    {"chamber_count", "N", "-", 7, 1, true, kMaxChamberCount, ParameterShape::kScalarInteger,
     "number of pneumatic chambers after the passive base segment"},
    {"chamber_height_m", "L", "m", 0.0115, 0, false, 0.5, ParameterShape::kPerChamber,
     "chamber height (wall length at rest); the wall bulges into an ellipse with one radius L/2"},
    {"wall_critical_height_m", "b", "m", 0.00575, 0, false, 0.5, ParameterShape::kPerChamber,
     "the paper law: height of the wall's thinnest point, in (0, L], L/2 for a uniform wall; the membrane and thick "
     "laws: the lever at which the walls push, the body's top above the bending axis, which may exceed L"},
    {"chamber_gap_m", "c", "m", 4.9640761700127315e-05, 0, true, 0.1, ParameterShape::kPerChamber,
     "effective gap between facing walls of neighbouring chambers (calibrated)"},
    {"chamber_thickness_m", "d", "m", 0.005, 0, false, 0.5, ParameterShape::kPerChamber,
     "chamber size along the finger"},
    {"chamber_width_m", "e", "m", 0.007, 0, false, 0.5, ParameterShape::kPerChamber,
     "chamber size across the finger"},
    {"segment_length_m", "Z", "m", 0.010, 0, false, 0.5, ParameterShape::kPerChamber,
     "joint-to-joint pitch of the segment that carries each chamber"},
    {"base_segment_length_m", "Z0", "m", 0.015, 0, false, 1.0, ParameterShape::kScalar,
     "length of the passive base segment, mount to joint 1"},
    {"base_wall_share", "s0", "-", 0.31406024809366295, 0, true, 1.0, ParameterShape::kScalar,
     "half angle the passive base segment's face adds to joint 1, as a share of chamber 1's: theta_0 = s0 theta_1 "
     "(0: an inert face; 1: a face that turns as a chamber wall does; effective, calibrated)"},
    {"shear_modulus_pa", "mu", "Pa", 223531464.02034336, 0, false, 1e12, ParameterShape::kPerChamber,
     "effective stiffness of the wall in the paper's energy balance (calibrated): a fitted number, not the "
     "elastomer's measured shear modulus (the paper law's fit is about 1000 times a silicone's; the membrane law's is "
     "close to it)"},
    {"atmospheric_pressure_pa", "P_o", "Pa", kStandardAtmospherePa, 1e3, true, 1e6, ParameterShape::kScalar,
     "ambient pressure; gauge = absolute - P_o"},
    // Not in the model: the URDF's masses and inertias. The paper does not name its elastomer; 1070 kg/m^3 is the
    // specific gravity (1.07) that the maker's data sheets give for the silicones PneuNets are usually cast in
    // (Smooth-On Ecoflex 00-30 and Dragon Skin 30: 1.07 and 1.08).
    {"elastomer_density_kg_m3", "rho", "kg/m^3", 1070, 100, false, 3000, ParameterShape::kScalar,
     "density of the elastomer, for the URDF's link masses and inertias (not used by the model)"},
    // The membrane law (docs/MODEL.md, "The membrane law"). Its shear modulus is a real silicone's, 10 kPa to 10 MPa
    // (the key's range stays wide because the paper law's effective mu is 2.2e8 Pa).
    {"wall_law", "-", "-", 0, 0, true, 2, ParameterShape::kChoice,
     "stages 1-3: 'paper' (the paper's air-spring energy and Neo-Hookean strip), 'membrane' (an inflated thin "
     "Neo-Hookean or Gent membrane, with a limit point) or 'thick' (the same sphere with a wall as thick as it is)",
     "paper|membrane|thick"},
    {"wall_thickness_m", "t", "m", 0.002, 0, false, 0.5, ParameterShape::kPerChamber,
     "membrane and thick laws: thickness of a chamber's wall at rest (the paper law does not use it)"},
    {"wall_locking_jm", "J_m", "-", 0, 0, true, 1e4, ParameterShape::kScalar,
     "membrane and thick laws: Gent's locking invariant, the I1 - 3 at which the elastomer locks; 0: no locking "
     "(Neo-Hookean)"},
    // docs/MODEL.md "The thick wall": which face's growth bends the finger. A thin membrane's faces are one.
    {"wall_flexion_face", "-", "-", 0, 0, true, 1, ParameterShape::kChoice,
     "thick law: the face whose bulge bends the finger: 'outer' (the wall's outer face, which meets the neighbouring "
     "wall: chambers in a row) or 'inner' (the chamber's own face, as the thin membrane's: a channel whose own growth "
     "lengthens the finger). The other laws do not use it",
     "outer|inner"},
    // docs/MODEL.md "The thick wall": the laws' sphere moves its face further than a flat wall between box-shaped
    // cavities does; kappa is the share of that bulge which tilts the wall. Effective, calibrated; 1: as derived.
    {"wall_bulge_share", "kappa", "-", 1, 0, false, 1, ParameterShape::kScalar,
     "membrane and thick laws: the share of the bending face's bulge that tilts the wall (Wang's h): 1, the sphere's "
     "whole bulge, as derived; below 1, a wall that moves less than the sphere's face, as a flat wall between "
     "box-shaped cavities does (effective, calibrated; the paper law does not use it)"},
    // docs/MODEL.md "Volume": the gas the supply compresses besides growing the chambers. Up to a cubic metre: a
    // lab's cylinder, tubes and reservoir, with a unit mistake (mL for m^3) refused.
    {"dead_volume_m3", "V_g", "m^3", 0, 0, true, 1.0, ParameterShape::kScalar,
     "gas at rest in the drive (cylinder, tubes and chambers, at P_o) that the supply compresses isothermally "
     "besides growing the chambers; 0: an incompressible fluid. Only the supplied volume depends on it"},
    // docs/MODEL.md "Volume": a chamber whose skin balloons with its walls takes more volume than its walls' bulge
    // gives, without bending the finger more. Up to 100: a skin far larger than the walls that bend the finger.
    {"chamber_growth_ratio", "r_V", "-", 1, 0, false, 100, ParameterShape::kScalar,
     "each chamber's volume growth over what its walls' bulge gives: 1, the walls alone; above 1, the skin around "
     "the chamber balloons with them, taking volume without bending the finger. Only the supplied volume depends on "
     "it"},
};

// The names of a choice key, in index order.
std::vector<std::string> choiceNames(const ParameterSpec& spec) {
  std::vector<std::string> names;
  std::stringstream all(spec.choices ? spec.choices : "");
  std::string name;
  while (std::getline(all, name, '|')) names.push_back(name);
  return names;
}

// " m" after a range; nothing for a dimensionless key.
std::string unitSuffix(const ParameterSpec& spec) {
  return std::string(spec.unit) == "-" ? std::string() : " " + std::string(spec.unit);
}

std::string keyAndValue(const ParameterSpec& spec, double value) {
  std::ostringstream s;
  s << "parameter '" << spec.key << "' = " << formatMessage(value) << " is outside its allowed range "
    << describeRange(spec) << unitSuffix(spec);
  return s.str();
}

}  // namespace

void checkParameterValue(const ParameterSpec& spec, double value) {
  if (spec.shape == ParameterShape::kChoice) {
    if (!(value >= 0 && value < static_cast<double>(choiceNames(spec).size()) && value == std::floor(value))) {
      throw ParameterError(std::string("parameter '") + spec.key + "' = " + formatMessage(value) + " is not " +
                           describeRange(spec));
    }
    return;
  }
  if (!std::isfinite(value)) {
    throw ParameterError(std::string("parameter '") + spec.key + "' = " + formatMessage(value) +
                         " is not a finite number; allowed: " + describeRange(spec) + unitSuffix(spec));
  }
  const bool above_min = spec.min_inclusive ? value >= spec.min_value : value > spec.min_value;
  if (!above_min || value > spec.max_value) throw ParameterError(keyAndValue(spec, value));
  if (spec.shape == ParameterShape::kScalarInteger && value != std::floor(value)) {
    throw ParameterError(std::string("parameter '") + spec.key + "' = " + formatMessage(value) +
                         " is not a whole number; allowed: " + describeRange(spec));
  }
}

namespace {

// Expands a scalar or checks a list against N.
std::vector<double> perChamber(const ParameterSpec& spec, const RawParameterMap& raw, int chamber_count) {
  const auto it = raw.find(spec.key);
  if (it == raw.end()) return std::vector<double>(static_cast<std::size_t>(chamber_count), spec.default_value);
  const RawParameterValue& v = it->second;
  for (double x : v.values) checkParameterValue(spec, x);
  if (!v.is_list) return std::vector<double>(static_cast<std::size_t>(chamber_count), v.values.at(0));
  if (v.values.size() != static_cast<std::size_t>(chamber_count)) {
    std::ostringstream s;
    s << "parameter '" << spec.key << "' is a list of " << v.values.size() << " values but chamber_count is "
      << chamber_count << "; give one value for all chambers or a list of exactly " << chamber_count;
    throw ParameterError(s.str());
  }
  return v.values;
}

double scalar(const ParameterSpec& spec, const RawParameterMap& raw) {
  const auto it = raw.find(spec.key);
  if (it == raw.end()) return spec.default_value;
  if (it->second.is_list || it->second.values.size() != 1) {
    throw ParameterError(std::string("parameter '") + spec.key + "' must be a single number, not a list");
  }
  checkParameterValue(spec, it->second.values[0]);
  return it->second.values[0];
}

const ParameterSpec& spec(const char* key) { return *findParameterSpec(key); }

}  // namespace

const std::vector<ParameterSpec>& parameterSpecs() { return kSpecs; }

const ParameterSpec* findParameterSpec(const std::string& key) {
  for (const auto& s : kSpecs) {
    if (key == s.key) return &s;
  }
  return nullptr;
}

std::string formatExact(double value) {
  if (std::isnan(value)) return "nan";  // printf writes "-nan" for a NaN with its sign bit set, which reads as a number
  char buffer[40];
  std::snprintf(buffer, sizeof(buffer), "%.17g", value);
  return buffer;
}

std::string formatShortest(double value) {
  char buffer[40];
  for (int digits = 15; digits <= 17; ++digits) {
    std::snprintf(buffer, sizeof(buffer), "%.*g", digits, value);
    if (std::strtod(buffer, nullptr) == value) break;
  }
  return buffer;
}

std::string formatYamlNumber(double value) {
  if (std::isnan(value)) return ".nan";
  if (std::isinf(value)) return value > 0 ? ".inf" : "-.inf";
  std::string text = formatShortest(value);
  const std::size_t e = text.find('e');
  // YAML 1.1 reads a float only with a dot in its mantissa: 1e-05 is a string, 1.0e-05 a float.
  if (e != std::string::npos && text.find('.') == std::string::npos) text.insert(e, ".0");
  return text;
}

std::string formatNumber(const char* printf_format, double value) {
  char buffer[64];
  std::snprintf(buffer, sizeof(buffer), printf_format, value);
  return buffer;
}

std::string formatMessage(double value) {
  if (std::isnan(value)) return "nan";
  char buffer[40];
  // A number a person wrote (294199.5, 0.1, 3.7e8) reads back exactly with a few digits: those. A computed one
  // (91503.635757...) gets six.
  for (int digits = 1; digits <= 8; ++digits) {
    std::snprintf(buffer, sizeof(buffer), "%.*g", digits, value);
    if (std::strtod(buffer, nullptr) != value) continue;
    // Whole numbers below 1e7 in full (90000, not 9e+04): a pressure in Pa reads so.
    const int exponent = value == 0 ? 0 : static_cast<int>(std::floor(std::log10(std::fabs(value))));
    if (exponent >= digits && exponent < 7) std::snprintf(buffer, sizeof(buffer), "%.*g", exponent + 1, value);
    return buffer;
  }
  std::snprintf(buffer, sizeof(buffer), "%.6g", value);
  return buffer;
}

std::string describeRange(const ParameterSpec& spec) {
  std::ostringstream s;
  if (spec.shape == ParameterShape::kChoice) {
    const std::vector<std::string> names = choiceNames(spec);
    s << "one of ";
    for (std::size_t i = 0; i < names.size(); ++i) s << (i ? ", " : "") << names[i];
    return s.str();
  }
  if (spec.shape == ParameterShape::kScalarInteger) s << "integer in ";
  s << (spec.min_inclusive ? "[" : "(") << spec.min_value << ", " << spec.max_value << "]";
  return s.str();
}

FingerParameters FingerParameters::defaults() { return fromRaw({}); }

namespace {

FingerParameters fromResolved(const RawParameterMap& raw);
void readDrawnKeys(const RawParameterMap& raw, FingerParameters& p);
void checkPaperLever(const FingerParameters& p);

// A drawn model key out of its range is the drawing's doing, and the user never set it: say where it comes from.
ParameterError forTheDrawing(const ParameterError& e, const RawParameterMap& given) {
  const std::string what = e.what(), opening = "parameter '";
  if (what.rfind(opening, 0) != 0) return e;
  const std::string key = what.substr(opening.size(), what.find('\'', opening.size()) - opening.size());
  const std::vector<std::string>& drawn = drawnModelKeys();
  if (given.count(key) > 0 || std::find(drawn.begin(), drawn.end(), key) == drawn.end()) return e;
  return ParameterError(what + ": the drawing makes " + key + " from its drawing/ keys (docs/DRAWING.md); change "
                        "those");
}

}  // namespace

FingerParameters FingerParameters::fromRaw(const RawParameterMap& given) {
  // A drawing's model keys, put in (docs/DRAWING.md). Its "drawing/" keys sort together: without one, no copy.
  const auto first_drawn = given.lower_bound(kDrawingPrefix);
  const bool drawn = first_drawn != given.end() && first_drawn->first.rfind(kDrawingPrefix, 0) == 0;
  if (!drawn) return fromResolved(given);
  const RawParameterMap resolved = resolveDrawing(given);
  try {
    return fromResolved(resolved);
  } catch (const ParameterError& e) {
    throw forTheDrawing(e, given);
  }
}

namespace {

FingerParameters fromResolved(const RawParameterMap& raw) {
  FingerParameters p;
  for (const auto& entry : raw) {
    if (entry.first.rfind(kDrawingPrefix, 0) == 0) {
      p.drawing[entry.first] = entry.second;
      continue;
    }
    if (findParameterSpec(entry.first) == nullptr) {
      throw unknownParameterError(entry.first);
    }
    if (entry.second.values.empty()) {
      throw ParameterError("parameter '" + entry.first + "' has no value");
    }
  }
  p.chamber_count = static_cast<int>(scalar(spec("chamber_count"), raw));
  const int n = p.chamber_count;
  readDrawnKeys(raw, p);
  p.chamber_gap_m = perChamber(spec("chamber_gap_m"), raw, n);
  p.base_wall_share = scalar(spec("base_wall_share"), raw);
  p.shear_modulus_pa = perChamber(spec("shear_modulus_pa"), raw, n);
  p.atmospheric_pressure_pa = scalar(spec("atmospheric_pressure_pa"), raw);
  p.elastomer_density_kg_m3 = scalar(spec("elastomer_density_kg_m3"), raw);
  p.wall_law = static_cast<WallLaw>(static_cast<int>(scalar(spec("wall_law"), raw)));
  p.wall_locking_jm = scalar(spec("wall_locking_jm"), raw);
  p.wall_bulge_share = scalar(spec("wall_bulge_share"), raw);
  p.dead_volume_m3 = scalar(spec("dead_volume_m3"), raw);
  p.chamber_growth_ratio = scalar(spec("chamber_growth_ratio"), raw);
  checkPaperLever(p);
  return p;
}

// The keys a drawing makes but its count (drawnModelKeys), read from @p raw into @p p for p.chamber_count chambers.
void readDrawnKeys(const RawParameterMap& raw, FingerParameters& p) {
  const int n = p.chamber_count;
  p.chamber_height_m = perChamber(spec("chamber_height_m"), raw, n);
  p.wall_critical_height_m = perChamber(spec("wall_critical_height_m"), raw, n);
  p.chamber_thickness_m = perChamber(spec("chamber_thickness_m"), raw, n);
  p.chamber_width_m = perChamber(spec("chamber_width_m"), raw, n);
  p.segment_length_m = perChamber(spec("segment_length_m"), raw, n);
  p.base_segment_length_m = scalar(spec("base_segment_length_m"), raw);
  p.wall_thickness_m = perChamber(spec("wall_thickness_m"), raw, n);
  p.wall_flexion_face = static_cast<FlexionFace>(static_cast<int>(scalar(spec("wall_flexion_face"), raw)));
}

void checkPaperLever(const FingerParameters& p) {
  // docs/MODEL.md stage 3-4: under the paper law b is a height on the wall, so it cannot exceed the wall (chamber)
  // height L. Under the membrane law b is where the walls push, measured from the bending axis: the chamber need not
  // sit on the base layer, so b may exceed L ("The membrane law").
  for (int i = 0; i < p.chamber_count && p.wall_law == WallLaw::kPaper; ++i) {  // (the thick wall's b is the membrane's)
    const auto k = static_cast<std::size_t>(i);
    if (p.wall_critical_height_m[k] > p.chamber_height_m[k]) {
      std::ostringstream s;
      s << "parameter 'wall_critical_height_m' = " << formatMessage(p.wall_critical_height_m[k]) << " m (chamber "
        << i + 1 << ") exceeds chamber_height_m = " << formatMessage(p.chamber_height_m[k])
        << " m; allowed: (0, chamber_height_m]";
      throw ParameterError(s.str());
    }
  }
}

}  // namespace

FingerParameters withDrawingSize(const FingerParameters& p, const std::string& key, double value) {
  RawParameterMap given = p.drawing;
  given[key] = RawParameterValue{{value}, false};
  const std::optional<ActuatorDrawing> d = drawingFromRaw(given);  // @throws ParameterError naming the key
  if (!d || d->chamber_count != p.chamber_count) {  // a count changes every per-chamber key: the file read again
    RawParameterMap raw = p.toRaw();
    for (const std::string& made : drawnModelKeys()) raw.erase(made);
    raw[key] = RawParameterValue{{value}, false};
    return FingerParameters::fromRaw(raw);
  }
  FingerParameters out = p;
  out.drawing = std::move(given);
  try {
    readDrawnKeys(modelKeysFromDrawing(*d, p.wall_law), out);
    checkPaperLever(out);
  } catch (const ParameterError& e) {
    throw forTheDrawing(e, {});
  }
  return out;
}

RawParameterMap FingerParameters::toRaw() const {
  RawParameterMap raw;
  auto put_list = [&raw](const char* key, const std::vector<double>& v) {
    const bool uniform = std::all_of(v.begin(), v.end(), [&v](double x) { return x == v.front(); });
    raw[key] = uniform ? RawParameterValue{{v.front()}, false} : RawParameterValue{v, true};
  };
  raw["chamber_count"] = {{static_cast<double>(chamber_count)}, false};
  put_list("chamber_height_m", chamber_height_m);
  put_list("wall_critical_height_m", wall_critical_height_m);
  put_list("chamber_gap_m", chamber_gap_m);
  put_list("chamber_thickness_m", chamber_thickness_m);
  put_list("chamber_width_m", chamber_width_m);
  put_list("segment_length_m", segment_length_m);
  raw["base_segment_length_m"] = {{base_segment_length_m}, false};
  raw["base_wall_share"] = {{base_wall_share}, false};
  put_list("shear_modulus_pa", shear_modulus_pa);
  raw["atmospheric_pressure_pa"] = {{atmospheric_pressure_pa}, false};
  raw["elastomer_density_kg_m3"] = {{elastomer_density_kg_m3}, false};
  raw["wall_law"] = {{static_cast<double>(wall_law)}, false};
  put_list("wall_thickness_m", wall_thickness_m);
  raw["wall_locking_jm"] = {{wall_locking_jm}, false};
  raw["wall_flexion_face"] = {{static_cast<double>(wall_flexion_face)}, false};
  raw["wall_bulge_share"] = {{wall_bulge_share}, false};
  raw["dead_volume_m3"] = {{dead_volume_m3}, false};
  raw["chamber_growth_ratio"] = {{chamber_growth_ratio}, false};
  // Drawn, the drawing is what re-creates it: its entries, not the model keys it makes (so that a changed drawing
  // key draws the actuator anew); resolveDrawing(toRaw()) has both.
  if (!drawing.empty()) {
    for (const std::string& key : drawnModelKeys()) raw.erase(key);
    for (const auto& entry : drawing) raw[entry.first] = entry.second;
  }
  return raw;
}

std::optional<double> readNumber(const std::string& text) {
  const char* begin = text.c_str();
  char* end = nullptr;
  const double v = std::strtod(begin, &end);
  while (end != nullptr && (*end == ' ' || *end == '\t')) ++end;
  if (end == begin || end == nullptr || *end != '\0') return std::nullopt;
  return v;
}

namespace {

double parseNumber(const std::string& text, const std::string& key) {
  const std::optional<double> v = readNumber(text);
  if (!v) throw ParameterError("parameter '" + key + "': '" + text + "' is not a number");
  return *v;
}

std::string trim(const std::string& s) {
  const auto first = s.find_first_not_of(" \t");
  if (first == std::string::npos) return "";
  const auto last = s.find_last_not_of(" \t");
  return s.substr(first, last - first + 1);
}

}  // namespace

void parseParameterAssignment(const std::string& assignment, RawParameterMap& raw) {
  const auto eq = assignment.find('=');
  if (eq == std::string::npos) {
    throw ParameterError("--set expects KEY=VALUE, got '" + assignment + "'");
  }
  const std::string key = trim(assignment.substr(0, eq));
  const std::string value = trim(assignment.substr(eq + 1));
  const bool drawn = isDrawingKey(key);  // a drawing's key: one number, checked when drawn
  if (!drawn && findParameterSpec(key) == nullptr) throw unknownParameterError(key);
  RawParameterValue parsed;
  if (!value.empty() && value.front() == '[') {
    if (value.back() != ']') throw ParameterError("parameter '" + key + "': list '" + value + "' lacks ']'");
    parsed.is_list = true;
    std::stringstream items(value.substr(1, value.size() - 2));
    std::string item;
    while (std::getline(items, item, ',')) parsed.values.push_back(parseNumber(trim(item), key));
  } else {
    parsed.values.push_back(drawn ? parseNumber(value, key) : parseParameterText(*findParameterSpec(key), value));
  }
  if (parsed.values.empty()) throw ParameterError("parameter '" + key + "' has no value");
  raw[key] = parsed;
}

double parseParameterText(const ParameterSpec& spec, const std::string& text) {
  if (spec.shape != ParameterShape::kChoice) return parseNumber(trim(text), spec.key);
  const std::vector<std::string> names = choiceNames(spec);
  const auto it = std::find(names.begin(), names.end(), trim(text));
  if (it == names.end()) {
    throw ParameterError(std::string("parameter '") + spec.key + "' = '" + text + "' is not " + describeRange(spec));
  }
  return static_cast<double>(it - names.begin());
}

std::string formatParameterValue(const ParameterSpec& spec, double value) {
  if (spec.shape != ParameterShape::kChoice) return formatYamlNumber(value);
  const std::vector<std::string> names = choiceNames(spec);
  const auto k = static_cast<std::size_t>(value);
  return value >= 0 && k < names.size() ? names[k] : formatExact(value);
}

const char* wallLawName(WallLaw law) {
  return law == WallLaw::kMembrane ? "membrane" : law == WallLaw::kThick ? "thick" : "paper";
}

double FingerParameters::lengthM() const {
  double length_m = base_segment_length_m;
  for (double z : segment_length_m) length_m += z;
  return length_m;
}

}  // namespace pneumatic_finger
