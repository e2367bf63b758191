// The actuator as drawn (src/core/drawing.cpp, docs/DRAWING.md): the rule from a drawing to the model's keys, checked
// by hand on the EPFL actuator and against the package's own mappings in prose (its three key files), a drawing that
// survives writing and reading, and drawings refused with the reason.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "pneumatic_finger/core/drawing.hpp"
#include "pneumatic_finger/core/finger_model.hpp"
#include "pneumatic_finger/core/yaml_parameters.hpp"

namespace pf = pneumatic_finger;

namespace {

pf::RawParameterMap load(const std::string& file) {
  pf::RawParameterMap raw;
  pf::loadRawParametersFromYamlFile(std::string(PACKAGE_SOURCE_DIR) + "/config/" + file, raw);
  return raw;
}

pf::RawParameterMap epfl() {
  pf::RawParameterMap raw;
  pf::loadRawParametersFromYamlText("wall_law: thick\ndrawing: {chamber_count: 7, cavity_height_m: 0.008, "
                                    "cavity_width_m: 0.008, cavity_length_m: 0.002, wall_thickness_m: 0.007}\n",
                                    "epfl", raw);
  return raw;
}

std::string refusal(pf::RawParameterMap raw) {
  try {
    pf::FingerParameters::fromRaw(raw);
  } catch (const pf::ParameterError& e) {
    return e.what();
  }
  return "(accepted)";
}

void expectSameGeometry(const pf::FingerParameters& a, const pf::FingerParameters& b, const std::string& what) {
  EXPECT_EQ(a.chamber_count, b.chamber_count) << what;
  for (int i = 0; i < a.chamber_count; ++i) {
    const auto k = static_cast<std::size_t>(i);
    EXPECT_NEAR(a.chamber_height_m[k], b.chamber_height_m[k], 1e-15) << what;
    EXPECT_NEAR(a.chamber_thickness_m[k], b.chamber_thickness_m[k], 1e-15) << what;
    EXPECT_NEAR(a.chamber_width_m[k], b.chamber_width_m[k], 1e-15) << what;
    EXPECT_NEAR(a.segment_length_m[k], b.segment_length_m[k], 1e-15) << what;
    EXPECT_NEAR(a.wall_critical_height_m[k], b.wall_critical_height_m[k], 1e-15) << what;
  }
  EXPECT_NEAR(a.base_segment_length_m, b.base_segment_length_m, 1e-15) << what;
  EXPECT_EQ(a.wall_flexion_face, b.wall_flexion_face) << what;
  EXPECT_EQ(a.base_wall_share, b.base_wall_share) << what;
}

}  // namespace

// The EPFL 7-chamber actuator by hand: cavities 8 x 8 x 2 mm, 7 mm walls. The pitch is 2 + 7 = 9 mm, and Z0 + 7 Z is
// the 70 mm body its maker states (7 * 2 + 8 * 7); the thick law's lever is the top, 8 + 7 mm above the layer.
TEST(Drawing, TheRuleByHandOnTheEpflActuator) {
  const pf::FingerParameters p = pf::FingerParameters::fromRaw(epfl());
  EXPECT_EQ(p.chamber_count, 7);
  EXPECT_EQ(p.chamber_height_m[0], 0.008);
  EXPECT_EQ(p.chamber_width_m[0], 0.008);
  EXPECT_EQ(p.chamber_thickness_m[0], 0.002);
  EXPECT_NEAR(p.segment_length_m[0], 0.009, 1e-17);
  EXPECT_NEAR(p.base_segment_length_m + 7 * p.segment_length_m[0], 0.070, 1e-16);
  EXPECT_EQ(p.wall_thickness_m[0], 0.007);
  EXPECT_NEAR(p.wall_critical_height_m[0], 0.015, 1e-17);
  EXPECT_EQ(p.wall_flexion_face, pf::FlexionFace::kOuter);
  EXPECT_EQ(p.chamber_gap_m[0], 0.0) << "one solid wall: no gap";
  EXPECT_EQ(p.base_wall_share, 1.0) << "the end wall bends as the others, until calibrated";
  pf::RawParameterMap paper = epfl();
  paper["wall_law"] = {{0}, false};
  EXPECT_NEAR(pf::FingerParameters::fromRaw(paper).wall_critical_height_m[0], 0.004, 1e-17)
      << "the paper law's b is the uniform wall's middle";
}

// The package's mappings in prose (docs/ACCURACY.md; the key files) are the rule's: each drawing gives its key
// file's geometry, and the paper's finger as drawn bends as config/finger.yaml does, joint for joint.
TEST(Drawing, TheShippedDrawingsGiveTheShippedKeys) {
  for (const char* name : {"marchese2015_ribbed", "marchese2015_cylindrical"}) {
    expectSameGeometry(pf::FingerParameters::fromRaw(load(std::string(name) + "_drawing.yaml")),
                       pf::FingerParameters::fromRaw(load(std::string(name) + ".yaml")), name);
    EXPECT_NEAR(pf::FingerParameters::fromRaw(load(std::string(name) + "_drawing.yaml")).wall_thickness_m[0],
                pf::FingerParameters::fromRaw(load(std::string(name) + ".yaml")).wall_thickness_m[0], 1e-15) << name;
  }
  const pf::FingerParameters drawn = pf::FingerParameters::fromRaw(load("sierra2022_finger_drawing.yaml"));
  const pf::FingerParameters keys = pf::FingerParameters::fromRaw(load("finger.yaml"));
  expectSameGeometry(drawn, keys, "the paper's finger");
  EXPECT_NEAR(drawn.wall_thickness_m[0], 0.00225, 1e-18) << "(5 - 0.5) / 2 mm: each half of the split wall";
  const pf::FingerModel from_drawing(drawn), from_keys(keys);
  pf::FingerWorkspace a(from_drawing), b(from_keys);
  for (double p : {0.0, 49033.25, 98066.5, 196133.0, 294199.5}) {
    const pf::FingerState& s = from_drawing.evaluate(p, a);
    const pf::FingerState& t = from_keys.evaluate(p, b);
    for (Eigen::Index j = 0; j < s.joint_angle_rad.size(); ++j) {
      EXPECT_NEAR(s.joint_angle_rad[j], t.joint_angle_rad[j], 1e-13) << p << " Pa, joint " << j + 1;
    }
  }
}

// One cavity per side bends by its own face, whose skin is the roof; a split wall gives each cavity its half, and the
// designed gap starts the effective one.
TEST(Drawing, OneCavityBendsByItsRoofAndASplitWallByItsHalves) {
  pf::RawParameterMap one = epfl();
  one["drawing/chamber_count"] = {{1}, false};
  one["drawing/roof_thickness_m"] = {{0.003}, false};
  const pf::FingerParameters p = pf::FingerParameters::fromRaw(one);
  EXPECT_EQ(p.wall_flexion_face, pf::FlexionFace::kInner);
  EXPECT_EQ(p.wall_thickness_m[0], 0.003);
  EXPECT_NEAR(p.wall_critical_height_m[0], 0.011, 1e-17);
  pf::RawParameterMap split = epfl();
  split["drawing/gap_m"] = {{0.001}, false};
  const pf::FingerParameters q = pf::FingerParameters::fromRaw(split);
  EXPECT_EQ(q.wall_thickness_m[0], 0.003);
  EXPECT_EQ(q.chamber_gap_m[0], 0.001);
}

// Written (parametersToYaml) and read back, a drawn actuator is the same, its drawn keys as comments; a changed
// drawing key draws it anew (the sibling check: only chamber_count changed, Z0 + N Z the new body's length).
TEST(Drawing, ADrawnActuatorIsWrittenAsItsDrawingAndDrawsAnew) {
  const pf::FingerParameters p = pf::FingerParameters::fromRaw(epfl());
  const std::string text = pf::parametersToYaml(p);
  EXPECT_NE(text.find("# (from the drawing) chamber_height_m: 0.008"), std::string::npos) << text;
  EXPECT_NE(text.find("drawing:\n"), std::string::npos) << text;
  pf::RawParameterMap raw;
  pf::loadRawParametersFromYamlText(text, "written", raw);
  const pf::FingerParameters q = pf::FingerParameters::fromRaw(raw);
  expectSameGeometry(p, q, "written and read");
  ASSERT_EQ(q.drawing.size(), p.drawing.size());
  for (const auto& [key, value] : p.drawing) EXPECT_EQ(q.drawing.at(key).values, value.values) << key;
  raw["drawing/chamber_count"] = {{5}, false};
  const pf::FingerParameters five = pf::FingerParameters::fromRaw(raw);
  EXPECT_EQ(five.chamber_count, 5);
  EXPECT_NEAR(five.base_segment_length_m + 5 * five.segment_length_m[0], 5 * 0.002 + 6 * 0.007, 1e-16);
  pf::RawParameterMap set = epfl();
  pf::parseParameterAssignment("drawing/wall_thickness_m=0.005", set);
  EXPECT_EQ(pf::FingerParameters::fromRaw(set).wall_thickness_m[0], 0.005);
}

// A drawing and a model key that says otherwise, an unknown or missing drawing key, a wall the gap empties, a body
// narrower than its cavities: each refused with its reason. The same value as the drawing's is accepted.
TEST(Drawing, BadDrawingsAreRefusedWithTheReason) {
  pf::RawParameterMap both = epfl();
  both["chamber_height_m"] = {{0.01}, false};
  EXPECT_NE(refusal(both).find("parameter 'chamber_height_m' = 0.01 contradicts the drawing, which makes it 0.008"),
            std::string::npos) << refusal(both);
  both["chamber_height_m"] = {{0.008}, false};
  EXPECT_EQ(refusal(both), "(accepted)");
  pf::RawParameterMap unknown = epfl();
  unknown["drawing/cavity_depth_m"] = {{0.01}, false};
  EXPECT_NE(refusal(unknown).find("unknown parameter 'drawing/cavity_depth_m'"), std::string::npos);
  pf::RawParameterMap missing = epfl();
  missing.erase("drawing/cavity_width_m");
  EXPECT_NE(refusal(missing).find("parameter 'drawing/cavity_width_m' is missing"), std::string::npos);
  pf::RawParameterMap gap = epfl();
  gap["drawing/gap_m"] = {{0.007}, false};
  EXPECT_NE(refusal(gap).find("leaves no elastomer in the 7 mm wall"), std::string::npos) << refusal(gap);
  pf::RawParameterMap narrow = epfl();
  narrow["drawing/body_width_m"] = {{0.006}, false};
  EXPECT_NE(refusal(narrow).find("the cavities (8 mm wide) do not fit the body (6 mm wide)"), std::string::npos)
      << refusal(narrow);
  pf::RawParameterMap thin = epfl();
  thin["drawing/wall_thickness_m"] = {{0.0}, false};
  EXPECT_NE(refusal(thin).find("parameter 'drawing/wall_thickness_m' = 0 is outside its allowed range"),
            std::string::npos)
      << refusal(thin);
}

// withDrawingSize, which a fit calls at each step, is the file read again with the size changed: every key equal to
// what fromRaw gives, on the shipped drawings under each law, for each size a calibration may fit; a refused drawing
// is refused with fromRaw's message.
TEST(Drawing, ASizeSetIsTheFileReadAgain) {
  const std::vector<std::string> sizes = {"cavity_height_m", "cavity_width_m", "cavity_length_m", "wall_thickness_m",
                                          "end_wall_thickness_m", "roof_thickness_m", "body_width_m", "chamber_count"};
  int accepted = 0, refused = 0;
  for (const char* file : {"epfl_ecoflex30_c7_coupon.yaml", "marchese2015_ribbed_drawing.yaml",
                           "marchese2015_cylindrical_drawing.yaml"}) {
    for (const char* law : {"paper", "membrane", "thick"}) {
      pf::RawParameterMap raw = load(file);
      raw["wall_law"] = pf::RawParameterValue{{static_cast<double>(std::string(law) == "paper"      ? pf::WallLaw::kPaper
                                                                   : std::string(law) == "membrane" ? pf::WallLaw::kMembrane
                                                                                                    : pf::WallLaw::kThick)},
                                              false};
      raw.erase("wall_critical_height_m");
      const pf::FingerParameters p = pf::FingerParameters::fromRaw(raw);
      for (const std::string& size : sizes) {
        const std::string key = std::string(pf::kDrawingPrefix) + size;
        const double value = size == "chamber_count" ? p.chamber_count + 2 : 1.1 * (size == "body_width_m" ? 0.05 : 0.004);
        pf::RawParameterMap again = p.toRaw();
        for (const std::string& made : pf::drawnModelKeys()) again.erase(made);
        again[key] = pf::RawParameterValue{{value}, false};
        const std::string what = std::string(file) + ", " + law + ", " + key;
        std::string expected_refusal, refusal_got;
        pf::RawParameterMap expected, got;
        try {
          expected = pf::FingerParameters::fromRaw(again).toRaw();
        } catch (const pf::ParameterError& e) {
          expected_refusal = e.what();
        }
        try {
          got = pf::withDrawingSize(p, key, value).toRaw();
        } catch (const pf::ParameterError& e) {
          refusal_got = e.what();
        }
        EXPECT_EQ(refusal_got, expected_refusal) << what;
        (expected_refusal.empty() ? accepted : refused) += 1;
        ASSERT_EQ(got.size(), expected.size()) << what;
        for (const auto& [k, v] : expected) {
          ASSERT_EQ(got.count(k), 1u) << what << ": " << k;
          EXPECT_EQ(got.at(k).values, v.values) << what << ": " << k;
          EXPECT_EQ(got.at(k).is_list, v.is_list) << what << ": " << k;
        }
      }
    }
  }
  EXPECT_GT(refused, 0);  // a refusal compared too (a wider cavity than its body, ...)
  EXPECT_GT(accepted, 60);
}
