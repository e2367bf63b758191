// The parameter definition: defaults, ranges, lists, YAML, --set, and that the shipped file is the definition.
#include <gtest/gtest.h>

#include <fstream>
#include <regex>

#include <cmath>

#include "pneumatic_finger/core/parameters.hpp"
#include "pneumatic_finger/core/yaml_parameters.hpp"

namespace pf = pneumatic_finger;

namespace {

std::string refusal(const pf::RawParameterMap& raw) {
  try {
    pf::FingerParameters::fromRaw(raw);
  } catch (const pf::ParameterError& e) {
    return e.what();
  }
  return "";
}

pf::RawParameterMap one(const std::string& key, std::vector<double> v, bool list = false) {
  pf::RawParameterMap raw;
  raw[key] = {std::move(v), list};
  return raw;
}

}  // namespace

TEST(Parameters, EveryKeyOfModelMdIsDefinedOnce) {
  // The keys of docs/MODEL.md's parameter table: its rows that start with a key in backticks.
  std::vector<std::string> model_md;
  std::ifstream doc(std::string(PACKAGE_SOURCE_DIR) + "/docs/MODEL.md");
  bool in_table = false;
  for (std::string line; std::getline(doc, line);) {
    if (line.rfind("| key (YAML", 0) == 0) in_table = true;
    else if (in_table && line.rfind("| `", 0) != 0 && line.rfind("|---", 0) != 0) break;
    else if (in_table && line.rfind("| `", 0) == 0) model_md.push_back(line.substr(3, line.find('`', 3) - 3));
  }
  ASSERT_EQ(pf::parameterSpecs().size(), model_md.size());
  for (const auto& key : model_md) EXPECT_NE(pf::findParameterSpec(key), nullptr) << key;
  for (const auto& spec : pf::parameterSpecs()) {
    // Every default lies in its own allowed range: the defaults pass the same validation as user input.
    pf::RawParameterMap raw = one(spec.key, {spec.default_value});
    EXPECT_EQ(refusal(raw), "") << spec.key;
  }
}

TEST(Parameters, DefaultsAreThePaperActuator) {
  const auto p = pf::FingerParameters::defaults();
  EXPECT_EQ(p.chamber_count, 7);
  EXPECT_EQ(p.chamber_height_m[6], 0.0115);
  EXPECT_EQ(p.wall_critical_height_m[0], 0.00575);
  EXPECT_EQ(p.segment_length_m[3], 0.010);
  EXPECT_EQ(p.base_segment_length_m, 0.015);
  EXPECT_EQ(p.atmospheric_pressure_pa, 101325);
}

TEST(Parameters, ShippedParameterFileEqualsTheDefinition) {
  // config/finger.yaml is what the node and the tools load; it must say what parameterSpecs() says.
  pf::RawParameterMap raw;
  pf::loadRawParametersFromYamlFile(std::string(PACKAGE_SOURCE_DIR) + "/config/finger.yaml", raw);
  for (const auto& spec : pf::parameterSpecs()) {
    ASSERT_TRUE(raw.count(spec.key)) << "config/finger.yaml lacks " << spec.key;
    EXPECT_EQ(raw[spec.key].values, std::vector<double>{spec.default_value}) << spec.key;
  }
}

TEST(Parameters, OutOfRangeNamesKeyValueAndRange) {
  const std::string msg = refusal(one("shear_modulus_pa", {-3}));
  EXPECT_NE(msg.find("shear_modulus_pa"), std::string::npos) << msg;
  EXPECT_NE(msg.find("-3"), std::string::npos) << msg;
  EXPECT_NE(msg.find("(0, 1e+12]"), std::string::npos) << msg;
}

TEST(Parameters, NonFiniteValuesAreRefused) {
  for (double bad : {NAN, INFINITY, -INFINITY}) {
    const std::string msg = refusal(one("chamber_gap_m", {bad}));
    EXPECT_NE(msg.find("chamber_gap_m"), std::string::npos) << msg;
    EXPECT_NE(msg.find("not a finite number"), std::string::npos) << msg;
  }
}

TEST(Parameters, ChamberCountMustBeAWholeNumberInRange) {
  EXPECT_NE(refusal(one("chamber_count", {2.5})).find("not a whole number"), std::string::npos);
  EXPECT_NE(refusal(one("chamber_count", {0})).find("chamber_count"), std::string::npos);
  EXPECT_NE(refusal(one("chamber_count", {65})).find("integer in [1, 64]"), std::string::npos);
}

TEST(Parameters, PerChamberListsMustHaveLengthN) {
  const std::string msg = refusal(one("chamber_gap_m", {1e-5, 2e-5}, true));
  EXPECT_NE(msg.find("chamber_gap_m"), std::string::npos) << msg;
  EXPECT_NE(msg.find("list of 2 values but chamber_count is 7"), std::string::npos) << msg;
  // A list for a key that has no per-chamber form is refused too.
  EXPECT_NE(refusal(one("base_segment_length_m", {0.01, 0.02}, true)).find("single number"), std::string::npos);
}

TEST(Parameters, WallCriticalHeightCannotExceedChamberHeight) {
  pf::RawParameterMap raw;
  raw["chamber_height_m"] = {{0.01}, false};
  raw["wall_critical_height_m"] = {{0.006, 0.006, 0.006, 0.011, 0.006, 0.006, 0.006}, true};
  const std::string msg = refusal(raw);
  EXPECT_NE(msg.find("wall_critical_height_m"), std::string::npos) << msg;
  EXPECT_NE(msg.find("chamber 4"), std::string::npos) << msg;
}

TEST(Parameters, UnknownKeyIsRefused) {
  EXPECT_NE(refusal(one("chamber_hieght_m", {0.01})).find("unknown parameter 'chamber_hieght_m'"), std::string::npos);
}

TEST(Parameters, YamlListsScalarsAndErrorsNameTheOrigin) {
  pf::RawParameterMap raw;
  pf::loadRawParametersFromYamlText("chamber_count: 3\nchamber_gap_m: [1e-5, 2e-5, 3e-5]\n", "inline", raw);
  const auto p = pf::FingerParameters::fromRaw(raw);
  EXPECT_EQ(p.chamber_gap_m, (std::vector<double>{1e-5, 2e-5, 3e-5}));
  EXPECT_EQ(p.chamber_height_m.size(), 3u);
  auto yamlError = [](const std::string& text) {
    pf::RawParameterMap r;
    try {
      pf::loadRawParametersFromYamlText(text, "bad.yaml", r);
    } catch (const pf::ParameterError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_NE(yamlError("chamber_gap_m: wide\n").find("bad.yaml: parameter 'chamber_gap_m' = 'wide' is not a number"),
            std::string::npos);
  EXPECT_NE(yamlError("chamber_gap_m: [1, [2]]\n").find("chamber_gap_m"), std::string::npos);
  EXPECT_NE(yamlError("- a\n- b\n").find("expected a mapping"), std::string::npos);
  EXPECT_NE(yamlError("a: [\n").find("not valid YAML"), std::string::npos);
  EXPECT_NE(yamlError("shear: 1\n").find("unknown parameter 'shear'"), std::string::npos);
  EXPECT_NE(yamlError("chamber_gap_m: []\n").find("empty list"), std::string::npos);
}

TEST(Parameters, YamlRoundTripIsExact) {
  pf::RawParameterMap raw;
  raw["chamber_gap_m"] = {{1e-5, 2e-5, 3e-5, 4e-5, 5e-5, 6e-5, 0.1 / 3}, true};
  raw["shear_modulus_pa"] = {{1.0 / 3 * 1e9}, false};
  const auto p = pf::FingerParameters::fromRaw(raw);
  pf::RawParameterMap back;
  pf::loadRawParametersFromYamlText(pf::parametersToYaml(p), "written", back);
  const auto q = pf::FingerParameters::fromRaw(back);
  EXPECT_EQ(q.chamber_gap_m, p.chamber_gap_m);
  EXPECT_EQ(q.shear_modulus_pa, p.shear_modulus_pa);
}

TEST(Parameters, SetAssignmentsParse) {
  pf::RawParameterMap raw;
  pf::parseParameterAssignment("chamber_count=3", raw);
  pf::parseParameterAssignment("chamber_gap_m=[1e-5, 2e-5,3e-5]", raw);
  EXPECT_EQ(pf::FingerParameters::fromRaw(raw).chamber_gap_m[1], 2e-5);
  EXPECT_THROW(pf::parseParameterAssignment("chamber_count", raw), pf::ParameterError);
  EXPECT_THROW(pf::parseParameterAssignment("chamber_count=seven", raw), pf::ParameterError);
  EXPECT_THROW(pf::parseParameterAssignment("nonsense=1", raw), pf::ParameterError);
  EXPECT_THROW(pf::parseParameterAssignment("chamber_gap_m=[1e-5", raw), pf::ParameterError);
}

// Every key of the definition, each way it can be wrong, through the YAML loader that finger_model,
// finger_calibrate and the node's config file share: refused, with the key named.
TEST(Parameters, EveryKeyRefusesEveryKindOfBadValueNamingTheKey) {
  for (const auto& spec : pf::parameterSpecs()) {
    const std::string key = spec.key;
    std::vector<std::string> bad = {
        key + ": wide",                                        // wrong type
        key + ": [1, two]",                                    // wrong type inside a list
        key + ": " + pf::formatExact(spec.max_value * 10),     // above the range
        key + ": " + pf::formatExact(spec.min_value - 1),      // below the range
        key + ": .nan",                                        // not finite
        key + ": {a: 1}",                                      // a mapping
    };
    if (spec.shape == pf::ParameterShape::kPerChamber) {
      bad.push_back(key + ": [" + pf::formatExact(spec.default_value) + ", " + pf::formatExact(spec.default_value) + "]");
    } else {
      bad.push_back(key + ": [" + pf::formatExact(spec.default_value) + "]");  // a list where one number is due
    }
    for (const std::string& text : bad) {
      std::string message;
      try {
        pf::RawParameterMap raw;
        pf::loadRawParametersFromYamlText(text, "test.yaml", raw);
        pf::FingerParameters::fromRaw(raw);
      } catch (const pf::ParameterError& e) {
        message = e.what();
      }
      EXPECT_NE(message.find(key), std::string::npos) << "'" << text << "' gave: '" << message << "'";
    }
  }
}

// A written file must read as numbers under YAML 1.1, which rosparam and PyYAML's safe_load use.
// The reference is YAML 1.1's own float and int patterns (yaml.org/type/float.html, /int.html, decimal forms):
// "1e-05" matches neither, so rosparam read it as a string and finger_node refused the file.
TEST(Parameters, WrittenNumbersAreYaml11NumbersThatReadBackExactly) {
  const std::regex yaml11_float(R"([-+]?([0-9][0-9_]*)?\.[0-9.]*([eE][-+][0-9]+)?)");
  const std::regex yaml11_int(R"([-+]?(0|[1-9][0-9_]*))");
  for (double v : {1e-05, 1e-20, 3e+20, -2.5e-7, 0.1, 90000.0, 0.0, 223531464.01998678, 4.9640761700248786e-05,
                   1e300, 5e-324, -1.0}) {
    const std::string text = pf::formatYamlNumber(v);
    EXPECT_TRUE(std::regex_match(text, yaml11_float) || std::regex_match(text, yaml11_int)) << text;
    EXPECT_EQ(std::strtod(text.c_str(), nullptr), v) << text;
  }
  EXPECT_EQ(pf::formatYamlNumber(1e-05), "1.0e-05");
  EXPECT_EQ(pf::formatYamlNumber(std::nan("")), ".nan");
  EXPECT_EQ(pf::formatYamlNumber(-INFINITY), "-.inf");
  // The whole file: dead_volume_m3 and chamber_gap_m are the keys that were refused.
  pf::FingerParameters p = pf::FingerParameters::defaults();
  p.dead_volume_m3 = 1e-05;
  p.chamber_gap_m.assign(p.chamber_gap_m.size(), 1e-05);
  const std::string yaml = pf::parametersToYaml(p);
  EXPECT_NE(yaml.find("\ndead_volume_m3: 1.0e-05\n"), std::string::npos) << yaml;
  EXPECT_NE(yaml.find("\nchamber_gap_m: 1.0e-05"), std::string::npos) << yaml;
}
