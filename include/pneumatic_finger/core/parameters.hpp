// The actuator's parameters: the one definition of every key (name, symbol, unit, default, allowed range),
// read by the model library, the command-line tools, the ROS node and the generated docs alike.
//
// Keys and symbols follow docs/MODEL.md ("Parameters"). The defaults are the calibrated
// actuator of Sierra & Ordonez-Avila 2022 (see docs/ACCURACY.md and config/finger.yaml, which
// finger_calibrate writes and a test keeps equal to this table).
#pragma once

#include <cstddef>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace pneumatic_finger {

/// The largest chamber_count a parameter file may give (the range of that key; fixed-size scratch uses it).
constexpr int kMaxChamberCount = 64;

/// Thrown when a parameter is missing its form, has a wrong type, or lies outside its allowed range.
/// The message always names the key, the offending value and what is allowed.
class ParameterError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Every key a parameter file may hold: the actuator's, the drawing's (drawing/KEY), the range's, finger_node's own
/// and the error bar's mapping (parameter_keys.cpp).
std::vector<std::string> knownParameterFileKeys();

/// The one refusal of a key that is none of knownParameterFileKeys, the same from every interface: it names the key
/// and, for a typo, the key meant ("did you mean 'roof_thickness_m'?"). @p origin (a file) prefixes it when given.
ParameterError unknownParameterError(const std::string& key, const std::string& origin = "");

/// How a key may be given.
enum class ParameterShape {
  kScalar,         ///< one number
  kScalarInteger,  ///< one whole number
  kPerChamber,     ///< one number for all chambers, or a list of exactly chamber_count numbers
  kChoice,         ///< one name among ParameterSpec::choices, held as its index (0, 1, ...) in a raw value
};

/// The wall law of stages 1-3 (docs/MODEL.md): how a chamber's pressure becomes its wall's bulge.
enum class WallLaw : int {
  kPaper = 0,     ///< the paper's chain: air-spring energy, uniaxial Neo-Hookean strip, elliptical bulge
  kMembrane = 1,  ///< an inflated thin Neo-Hookean (or Gent) membrane: a balloon with a limit point
  kThick = 2,     ///< the membrane's sphere with a wall as thick as it is (a thick incompressible sphere)
};

/// "paper", "membrane" or "thick".
const char* wallLawName(WallLaw law);

/// The thick wall's face whose bulge bends the finger (docs/MODEL.md, "The thick wall"): the two faces of a thin
/// membrane are one, so only the thick wall reads it.
enum class FlexionFace : int {
  kOuter = 0,  ///< the wall's outer face, B (lambda_b - 1): the face that meets the neighbouring wall
  kInner = 1,  ///< the chamber's own face, A (lambda_a - 1): a channel whose own growth lengthens the finger
};

/// The definition of one key: everything the library, the tools, the node and the docs know about it.
struct ParameterSpec {
  const char* key;          ///< YAML / rosparam key
  const char* symbol;       ///< symbol in docs/MODEL.md and the paper
  const char* unit;         ///< SI unit, "-" when dimensionless
  double default_value;     ///< value used when the key is absent
  double min_value;         ///< lower bound of the allowed range
  bool min_inclusive;       ///< whether min_value itself is allowed
  double max_value;         ///< upper bound of the allowed range (always inclusive)
  ParameterShape shape;     ///< scalar, integer or per-chamber
  const char* description;  ///< one line for docs and --help
  const char* choices = nullptr;  ///< kChoice only: the names, separated by '|', in index order
};

/// All keys, in the order of docs/MODEL.md's table.
const std::vector<ParameterSpec>& parameterSpecs();

/// The spec of @p key, or nullptr when no such key exists.
const ParameterSpec* findParameterSpec(const std::string& key);

/// A value as it arrives from YAML, rosparam or the command line, before validation:
/// either one number or a list of numbers.
struct RawParameterValue {
  std::vector<double> values;  ///< one entry for a scalar
  bool is_list = false;        ///< true when given as a list (even of length 1)
};

/// key -> raw value; keys not present take their default.
using RawParameterMap = std::map<std::string, RawParameterValue>;

/// The validated actuator. Per-chamber quantities always have chamber_count entries (a scalar is expanded).
struct FingerParameters {
  int chamber_count = 0;                         ///< N
  std::vector<double> chamber_height_m;          ///< L_n
  std::vector<double> wall_critical_height_m;    ///< b_n
  std::vector<double> chamber_gap_m;             ///< c_n
  std::vector<double> chamber_thickness_m;       ///< d_n
  std::vector<double> chamber_width_m;           ///< e_n
  std::vector<double> segment_length_m;          ///< Z_n, n = 1..N (segment n carries chamber n)
  double base_segment_length_m = 0.0;            ///< Z0
  double base_wall_share = 0.0;                  ///< s0: joint 1's half angle from the base face, theta_0 = s0 theta_1
  std::vector<double> shear_modulus_pa;          ///< mu_n
  double atmospheric_pressure_pa = 0.0;          ///< P_o
  double elastomer_density_kg_m3 = 0.0;          ///< rho (URDF masses only; not in the model)
  WallLaw wall_law = WallLaw::kPaper;            ///< stages 1-3: the paper's chain or the membrane
  std::vector<double> wall_thickness_m;          ///< t_n: the membrane law's wall thickness at rest
  double wall_locking_jm = 0.0;                  ///< J_m: the membrane's Gent locking invariant (0: Neo-Hookean)
  FlexionFace wall_flexion_face = FlexionFace::kOuter;  ///< the thick wall's face whose bulge bends the finger
  double wall_bulge_share = 1.0;                 ///< kappa: the share of that face's bulge that tilts the wall
  double dead_volume_m3 = 0.0;                   ///< V_g: gas at rest in the drive (0: incompressible fluid)
  double chamber_growth_ratio = 1.0;             ///< r_V: a chamber's volume growth over its walls' (1: theirs alone)
  RawParameterMap drawing;  ///< the drawing it was made from, as "drawing/KEY" entries (drawing.hpp); empty: none

  /// The defaults of parameterSpecs() (the calibrated paper actuator).
  static FingerParameters defaults();

  /// Validates @p raw against parameterSpecs() and builds the actuator.
  /// @throws ParameterError naming the key, the value and the allowed range, for an unknown key, a wrong shape,
  ///         a list of the wrong length, a non-finite or out-of-range value, or inconsistent geometry (b > L).
  static FingerParameters fromRaw(const RawParameterMap& raw);

  /// The same actuator as a raw map (lists collapsed to scalars where all entries are equal). A drawn actuator gives
  /// its drawing's entries instead of the model keys the drawing makes (resolveDrawing(toRaw()) has both).
  RawParameterMap toRaw() const;

  /// The finger's length along its straight backbone, mount to tip: Z0 + sum of Z_n (m).
  double lengthM() const;
};

/// Parses "KEY=VALUE" or "KEY=[v1,v2,...]" (as given to --set) into @p raw.
/// @throws ParameterError for a malformed assignment, an unknown key or a value that is not a number.
void parseParameterAssignment(const std::string& assignment, RawParameterMap& raw);

/// Formats a number with 17 significant digits (round-trip exact), as every tool prints numbers.
std::string formatExact(double value);  // NaN as "nan", whatever its sign bit

/// Formats a number with the fewest significant digits (15 to 17) that read back to the same double, as the
/// parameter files are written.
std::string formatShortest(double value);

/// formatShortest in YAML 1.1's float syntax, which rosparam (and PyYAML) read: "1.0e-05", not "1e-05" (a string
/// there), and ".nan", ".inf", "-.inf". Whole numbers stay whole ("90000"): every reader takes an integer for a
/// number. Every parameter file this package writes uses it, so that the node loads what the tools write.
std::string formatYamlNumber(double value);

/// The one number format of messages (errors, warnings, logs, reports): the fewest digits, up to eight, that read back
/// exactly ("294199.5", "-0.1", "3.7e+08"), else six significant digits ("91503.6"), NaN as "nan". Data a program reads back (CSV
/// rows, parameter files) uses formatExact or formatShortest instead.
std::string formatMessage(double value);

/// @p value by a printf format of one number ("%.2f", "%.3g"): a report's fixed columns.
std::string formatNumber(const char* printf_format, double value);

/// @p text as one number (strtod's syntax; blanks after it allowed), or nullopt where it is not one: the one reader of
/// a number typed as text (--set, --target, --part); each caller says what was wrong in its own words.
std::optional<double> readNumber(const std::string& text);

/// The one check of a number against its definition: finite, in range, whole for an integer key. Every reader of
/// parameters (the YAML loader, --set, the ROS nodes' private handles, dynamic_reconfigure) calls it.
/// @throws ParameterError naming the key, the value and the allowed range with its unit
void checkParameterValue(const ParameterSpec& spec, double value);

/// Describes the allowed range of @p spec, e.g. "(0, 1]", "integer in [1, 64]" or "one of paper, membrane".
std::string describeRange(const ParameterSpec& spec);

/// A value written as text (YAML, --set, rosparam, Python): a choice key's name becomes its index; any other key's
/// text must be a number.
/// @throws ParameterError naming the key, the text and what is allowed
double parseParameterText(const ParameterSpec& spec, const std::string& text);

/// A value as it is written back: a choice key's name, else the shortest exact number in YAML 1.1 (formatYamlNumber).
std::string formatParameterValue(const ParameterSpec& spec, double value);

}  // namespace pneumatic_finger
