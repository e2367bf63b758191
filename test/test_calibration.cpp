// Calibration: recovers known parameters, reaches the accuracy target on the paper's data, refuses bad files.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <sstream>

#include "pneumatic_finger/calibration/calibration.hpp"
#include "pneumatic_finger/core/yaml_parameters.hpp"
#include "test_support.hpp"
#include "pneumatic_finger/calibration/calibration_run.hpp"

namespace pf = pneumatic_finger;

namespace {

const std::string kTable1 = std::string(PACKAGE_SOURCE_DIR) + "/data/sierra2022_table1.csv";
constexpr double kDeg = 180.0 / M_PI;

double largestError(const std::vector<pf::Residual>& r) {
  double worst = 0;
  for (const auto& x : r) worst = std::max(worst, std::fabs(x.error_rad()));
  return worst;
}

// Measurements made by the model itself at the given parameters.
std::vector<pf::Measurement> synthetic(const pf::FingerParameters& truth, const std::vector<double>& pressures) {
  pf::FingerModel model(truth);
  pf::FingerWorkspace ws(model);
  std::vector<pf::Measurement> out;
  for (double p : pressures) {
    const pf::FingerState& s = model.evaluate(p, ws);
    out.push_back({0, p, std::vector<double>(s.joint_angle_rad.data(), s.joint_angle_rad.data() + 7), NAN});
  }
  return out;
}

std::string refusal(const std::string& csv, std::size_t min_rows = 4) {
  try {
    pf::parseMeasurementsCsv(csv, "m.csv", min_rows);
  } catch (const pf::ParameterError& e) {
    return e.what();
  }
  return "";
}

const char* const kHeader = "gauge_pa,joint_1_rad,joint_2_rad,joint_3_rad,joint_4_rad,joint_5_rad,joint_6_rad,joint_7_rad\n";

}  // namespace

TEST(Calibration, RecoversKnownMuAndGapFromModelData) {
  pf::RawParameterMap raw;
  raw["shear_modulus_pa"] = {{3.7e8}, false};
  raw["chamber_gap_m"] = {{8.5e-5}, false};
  const pf::FingerParameters truth = pf::FingerParameters::fromRaw(raw);
  const auto data = synthetic(truth, {49033.25, 98066.5, 147099.75, 196133.0});
  // Start from parameters far from the truth: the search is global over its brackets.
  for (auto objective : {pf::CalibrationObjective::kMinimax, pf::CalibrationObjective::kLeastSquares}) {
    const auto fit = pf::calibrate(pf::FingerParameters::defaults(), {"shear_modulus_pa", "chamber_gap_m"}, data,
                                   objective);
    EXPECT_NEAR(fit.values[0], 3.7e8, 3.7e8 * 1e-6) << pf::objectiveName(objective);
    EXPECT_NEAR(fit.values[1], 8.5e-5, 8.5e-5 * 1e-6) << pf::objectiveName(objective);
    EXPECT_LT(largestError(fit.residuals), 1e-10);
  }
}

TEST(Calibration, RecoversOneKeyAlone) {
  pf::RawParameterMap raw;
  raw["chamber_gap_m"] = {{2e-5}, false};
  const pf::FingerParameters truth = pf::FingerParameters::fromRaw(raw);
  const auto fit = pf::calibrate(pf::FingerParameters::defaults(), {"chamber_gap_m"},
                                 synthetic(truth, {5e4, 1e5, 2e5}), pf::CalibrationObjective::kMinimax);
  EXPECT_NEAR(fit.values[0], 2e-5, 2e-5 * 1e-6);
}

TEST(Calibration, PaperDataReachesTheTargetAtAMinimaxOptimum) {
  const auto data = pf::readMeasurementsCsv(kTable1, 4);
  ASSERT_EQ(data.size(), 4u);
  const auto fit = pf::calibrate(pf::FingerParameters::defaults(), {"shear_modulus_pa", "chamber_gap_m"}, data,
                                 pf::CalibrationObjective::kMinimax);
  const double worst_deg = largestError(fit.residuals) * kDeg;
  EXPECT_LE(worst_deg, 0.56);  // below the paper's own 0.647 deg with a margin
  // An optimum, checked independently of the search: every small move of either parameter makes it worse.
  for (std::size_t k = 0; k < 2; ++k) {
    for (double f : {0.999, 1.001}) {
      pf::FingerParameters moved = fit.parameters;
      auto& v = k == 0 ? moved.shear_modulus_pa : moved.chamber_gap_m;
      for (double& x : v) x *= f;
      EXPECT_GT(largestError(pf::residuals(moved, data)), largestError(fit.residuals)) << k << " " << f;
    }
  }
  // Minimax equioscillates: at least three of the four errors share the largest magnitude.
  int at_max = 0;
  for (const auto& r : fit.residuals) at_max += std::fabs(std::fabs(r.error_rad()) - largestError(fit.residuals)) < 1e-9;
  EXPECT_GE(at_max, 3);
  // The shipped defaults are this fit.
  EXPECT_DOUBLE_EQ(pf::FingerParameters::defaults().shear_modulus_pa[0], fit.values[0]);
  EXPECT_DOUBLE_EQ(pf::FingerParameters::defaults().chamber_gap_m[0], fit.values[1]);
}

TEST(Calibration, PaperAverageColumnGivesTheReferenceOptimum) {
  // The best minimax fit of the paper's printed averages (which differ from the mean of its printed joints) is
  // near 0.550 deg at mu ~ 2.2e8 Pa, c ~ 0.052 mm.
  const auto data = pf::readMeasurementsCsv(kTable1, 4, "paper_avg_rad");
  const auto fit = pf::calibrate(pf::FingerParameters::defaults(), {"shear_modulus_pa", "chamber_gap_m"}, data,
                                 pf::CalibrationObjective::kMinimax);
  EXPECT_NEAR(largestError(fit.residuals) * kDeg, 0.550, 0.0005);
  EXPECT_NEAR(fit.values[0], 2.2e8, 0.01e8);
  EXPECT_NEAR(fit.values[1], 5.2e-5, 0.1e-5);
}

// A key that cannot be fitted is refused with the list of those that can: a drawing's sizes only where the file has a
// drawing (elsewhere, where they would come from).
TEST(Calibration, AnUnknownKeyIsRefusedWithTheKeysThisFileCanFit) {
  const std::vector<pf::Measurement> data = pf::readMeasurementsCsv(kTable1, 4);
  const auto refused = [&data](const pf::FingerParameters& base) {
    try {
      pf::calibrate(base, {"shear_modulus"}, data, pf::CalibrationObjective::kMinimax);
    } catch (const pf::ParameterError& e) {
      return std::string(e.what());
    }
    return std::string("(fitted)");
  };
  const std::string plain = refused(pf::FingerParameters::defaults());
  EXPECT_NE(plain.find("parameter 'shear_modulus' cannot be fitted; fittable: shear_modulus_pa, "), std::string::npos)
      << plain;
  EXPECT_EQ(plain.find("drawing/cavity_height_m"), std::string::npos) << plain;
  EXPECT_NE(plain.find("(and a drawing's sizes, drawing/KEY, where the file has a drawing"), std::string::npos) << plain;
  pf::RawParameterMap raw;
  pf::loadRawParametersFromYamlFile(std::string(PACKAGE_SOURCE_DIR) + "/config/epfl_ecoflex30_c7_coupon.yaml", raw);
  const std::string drawn = refused(pf::FingerParameters::fromRaw(raw));
  EXPECT_NE(drawn.find(", drawing/roof_thickness_m"), std::string::npos) << drawn;
}

TEST(Calibration, MalformedCsvIsRefusedNamingTheLine) {
  EXPECT_NE(refusal("# c\npressure,joint_1_rad,joint_2_rad\n1,2,3\n").find("m.csv:2: header has no 'gauge_pa'"),
            std::string::npos);
  EXPECT_NE(refusal("gauge_pa,joint_1_rad\n1,2\n").find("m.csv:1: header has joint_1_rad alone"), std::string::npos);
  const std::string bad_number = std::string(kHeader) + "1e5,0.1,0.1,0.1,0.1,0.1,0.1,0.1\n2e5,0.1,0.1,x,0.1,0.1,0.1,0.1\n";
  EXPECT_NE(refusal(bad_number).find("m.csv:3: 'x' in column joint_3_rad is not a finite number"), std::string::npos)
      << refusal(bad_number);
  const std::string short_row = std::string(kHeader) + "1e5,0.1,0.1\n";
  EXPECT_NE(refusal(short_row).find("m.csv:2: has 3 fields, the header 8"), std::string::npos) << refusal(short_row);
  const std::string few = std::string(kHeader) + "1e5,0.1,0.1,0.1,0.1,0.1,0.1,0.1\n";
  EXPECT_NE(refusal(few).find("only 1 data rows; at least 4"), std::string::npos) << refusal(few);
  const std::string nan_row = std::string(kHeader) + "nan,0.1,0.1,0.1,0.1,0.1,0.1,0.1\n";
  EXPECT_NE(refusal(nan_row, 1).find("m.csv:2: 'nan' in column gauge_pa"), std::string::npos);
  EXPECT_NE(refusal("").find("no header"), std::string::npos);
  EXPECT_EQ(refusal(std::string(kHeader) + "1,1,1,1,1,1,1,1\n", 1), "");  // a well-formed file passes
}

TEST(Calibration, RefusesWhatItCannotFit) {
  const auto data = pf::readMeasurementsCsv(kTable1, 4);
  const auto base = pf::FingerParameters::defaults();
  EXPECT_THROW(pf::calibrate(base, {"atmospheric_pressure_pa"}, data, pf::CalibrationObjective::kMinimax),
               pf::ParameterError);
  EXPECT_THROW(pf::calibrate(base, {"chamber_gap_m", "chamber_gap_m"}, data, pf::CalibrationObjective::kMinimax),
               pf::ParameterError);
  EXPECT_THROW(pf::calibrate(base, {"chamber_gap_m", "shear_modulus_pa", "chamber_height_m", "wall_critical_height_m"},
                             data, pf::CalibrationObjective::kMinimax),
               pf::ParameterError);  // four keys
  pf::RawParameterMap raw;
  raw["chamber_count"] = {{5}, false};
  EXPECT_THROW(pf::calibrate(pf::FingerParameters::fromRaw(raw), {"chamber_gap_m"}, data,
                             pf::CalibrationObjective::kMinimax),
               pf::ParameterError);  // 7 measured joints, 5 chambers
  EXPECT_THROW(pf::parseObjective("median"), pf::ParameterError);
}

namespace {

// What a researcher with a camera has: the tip angle or the tip position at each pressure, here made by the model
// itself at known parameters, written as the CSV the tools read and parsed back.
std::vector<pf::Measurement> syntheticTipCsv(const pf::FingerParameters& truth, const std::vector<double>& pressures,
                                             bool position) {
  pf::FingerModel model(truth);
  pf::FingerWorkspace ws(model);
  std::string csv = position ? "# tip in the finger's frame\ngauge_pa,tip_x_m,tip_y_m\n" : "gauge_pa,tip_angle_rad\n";
  for (double p : pressures) {
    const pf::FingerState& s = model.evaluate(p, ws);
    csv += pf::formatExact(p) + "," +
           (position ? pf::formatExact(s.tip().x()) + "," + pf::formatExact(s.tip().y()) : pf::formatExact(s.tip_angle_rad)) +
           "\n";
  }
  return pf::parseMeasurementsCsv(csv, "tip.csv", pressures.size());
}

pf::FingerParameters truthWith(double mu, double gap, double share) {
  pf::RawParameterMap raw;
  raw["shear_modulus_pa"] = {{mu}, false};
  raw["chamber_gap_m"] = {{gap}, false};
  raw["base_wall_share"] = {{share}, false};
  return pf::FingerParameters::fromRaw(raw);
}

const std::vector<double> kPressures = {49033.25, 98066.5, 147099.75, 196133.0};

}  // namespace

TEST(Calibration, RecoversMuGapAndBaseShareFromEveryJoint) {
  const pf::FingerParameters truth = truthWith(3.7e8, 8.5e-5, 0.42);
  const auto data = synthetic(truth, kPressures);
  for (auto objective : {pf::CalibrationObjective::kMinimax, pf::CalibrationObjective::kLeastSquares}) {
    // Start from the shipped parameters, far from the truth: the search is global over its brackets.
    const auto fit = pf::calibrate(pf::FingerParameters::defaults(),
                                   pf::defaultFitKeys(pf::CalibrationQuantity::kEveryJoint), data, objective,
                                   pf::CalibrationQuantity::kEveryJoint);
    ASSERT_EQ(fit.keys, (std::vector<std::string>{"shear_modulus_pa", "chamber_gap_m", "base_wall_share"}));
    EXPECT_NEAR(fit.values[0], 3.7e8, 3.7e8 * 1e-6) << pf::objectiveName(objective);
    EXPECT_NEAR(fit.values[1], 8.5e-5, 8.5e-5 * 1e-6);
    EXPECT_NEAR(fit.values[2], 0.42, 1e-6);
    EXPECT_EQ(fit.parameters.base_wall_share, fit.values[2]);
    for (const auto& r : fit.residuals) {
      for (double e : r.terms(pf::CalibrationQuantity::kEveryJoint)) EXPECT_LT(std::fabs(e), 1e-9);
    }
  }
}

TEST(Calibration, RecoversMuAndGapFromTipAnglesOrTipPositionsAlone) {
  const pf::FingerParameters truth = truthWith(3.7e8, 8.5e-5, pf::FingerParameters::defaults().base_wall_share);
  for (bool position : {false, true}) {
    const auto data = syntheticTipCsv(truth, kPressures, position);
    ASSERT_FALSE(data[0].hasJoints());
    ASSERT_EQ(data[0].hasTipPosition(), position);
    const pf::CalibrationQuantity quantity = pf::defaultQuantity(data);
    EXPECT_EQ(quantity, position ? pf::CalibrationQuantity::kTipPosition : pf::CalibrationQuantity::kTipAngle);
    for (auto objective : {pf::CalibrationObjective::kMinimax, pf::CalibrationObjective::kLeastSquares}) {
      SCOPED_TRACE(std::string(pf::quantityName(quantity)) + ", " + pf::objectiveName(objective));
      const auto fit = pf::calibrate(pf::FingerParameters::defaults(), pf::defaultFitKeys(quantity), data, objective,
                                     quantity);
      EXPECT_NEAR(fit.values[0], 3.7e8, 3.7e8 * 1e-6);
      EXPECT_NEAR(fit.values[1], 8.5e-5, 8.5e-5 * 1e-6);
      for (const auto& r : fit.residuals) {
        EXPECT_LT(std::fabs(position ? r.tip_position_error_m() : r.tip_angle_error_rad()), 1e-10);
        EXPECT_TRUE(std::isnan(r.measured_joint1_rad));  // nothing invented where the file has no joints
      }
    }
  }
  // The base face's share alone is determined by tip data (the chambers held at the truth).
  pf::FingerParameters base = truth;
  base.base_wall_share = 0.0;
  const auto fit = pf::calibrate(base, {"base_wall_share"}, syntheticTipCsv(truth, kPressures, false),
                                 pf::CalibrationObjective::kMinimax, pf::CalibrationQuantity::kTipAngle);
  EXPECT_NEAR(fit.values[0], truth.base_wall_share, 1e-6);
}

// A lab that tracks the tip alone on video measures the chord, base to tip. Written as chord_angle_rad, the fit
// recovers the truth from chords alone, each row's measured chord is the file's, and the model's is the angle of its
// own tip seen from its base (atan2, independent of chordAngleRad's unwrapping at these bends). The same rows as tip
// positions give the same chords.
TEST(Calibration, RecoversMuAndGapFromChordAnglesAlone) {
  const pf::FingerParameters truth = truthWith(3.7e8, 8.5e-5, pf::FingerParameters::defaults().base_wall_share);
  pf::FingerModel model(truth);
  pf::FingerWorkspace ws(model);
  std::string csv = "# one marker on the tip, seen from the base\ngauge_pa,chord_angle_rad\n";
  std::vector<double> chord_rad;
  for (double p : kPressures) {
    const pf::FingerState& s = model.evaluate(p, ws);
    chord_rad.push_back(std::atan2(s.tip().y(), s.tip().x()));
    csv += pf::formatExact(p) + "," + pf::formatExact(chord_rad.back()) + "\n";
  }
  const auto data = pf::parseMeasurementsCsv(csv, "chord.csv", kPressures.size());
  ASSERT_TRUE(data[0].hasChordAngle() && !data[0].hasTipAngle() && !data[0].hasTipPosition());
  const pf::CalibrationQuantity quantity = pf::defaultQuantity(data);
  ASSERT_EQ(quantity, pf::CalibrationQuantity::kChordAngle);
  EXPECT_EQ(pf::parseQuantity("chord_angle"), quantity);
  const auto fit = pf::calibrate(pf::FingerParameters::defaults(), pf::defaultFitKeys(quantity), data,
                                 pf::CalibrationObjective::kMinimax, quantity);
  EXPECT_NEAR(fit.values[0], 3.7e8, 3.7e8 * 1e-6);
  EXPECT_NEAR(fit.values[1], 8.5e-5, 8.5e-5 * 1e-6);
  for (std::size_t i = 0; i < fit.residuals.size(); ++i) {
    const pf::Residual& r = fit.residuals[i];
    EXPECT_EQ(r.measured_chord_angle_rad, chord_rad[i]);
    EXPECT_NEAR(r.model_chord_angle_rad, std::atan2(r.model_tip_y_m, r.model_tip_x_m), 1e-15);
    EXPECT_LT(std::fabs(r.chord_angle_error_rad()), 1e-9);
    EXPECT_TRUE(std::isnan(r.measured_tip_angle_rad));  // nothing invented: a chord is not a tip angle
  }
  for (const pf::Residual& r : pf::residuals(truth, syntheticTipCsv(truth, kPressures, true),
                                             pf::CalibrationQuantity::kChordAngle)) {
    EXPECT_NEAR(r.measured_chord_angle_rad, std::atan2(r.measured_tip_y_m, r.measured_tip_x_m), 1e-15);
  }
  // A chord in degrees is refused as the other angles are; one beyond half a turn cannot be a finger's.
  std::vector<pf::Measurement> degrees = data;
  degrees[1].chord_angle_rad = 30.0;
  try {
    pf::checkMeasurementsPlausible(truth, degrees);
    ADD_FAILURE() << "a chord of 30 rad was accepted";
  } catch (const pf::ParameterError& e) {
    EXPECT_NE(std::string(e.what()).find("chord_angle_rad = 30 rad is beyond pi (half a turn)"), std::string::npos)
        << e.what();
  }
}

TEST(Calibration, RefusesKeysTheDataCannotDetermine) {
  const pf::FingerParameters base = pf::FingerParameters::defaults();
  const auto joints = pf::readMeasurementsCsv(kTable1, 4);
  const auto tips = syntheticTipCsv(base, kPressures, false);
  auto message = [&](const std::vector<std::string>& keys, const std::vector<pf::Measurement>& data,
                     pf::CalibrationQuantity quantity) {
    try {
      pf::calibrate(base, keys, data, pf::CalibrationObjective::kMinimax, quantity);
    } catch (const pf::ParameterError& e) {
      return std::string(e.what());
    }
    return std::string("(accepted)");
  };
  using Q = pf::CalibrationQuantity;
  EXPECT_NE(message({"base_wall_share"}, joints, Q::kOuterAverage).find("moves joint 1 alone"), std::string::npos);
  EXPECT_NE(message({"shear_modulus_pa", "base_wall_share"}, tips, Q::kTipAngle).find("tip data alone"),
            std::string::npos);
  EXPECT_NE(message({"chamber_gap_m"}, joints, Q::kFirstJoint).find("joint 1 alone cannot fit chamber keys"),
            std::string::npos);
  const std::vector<pf::Measurement> two(joints.begin(), joints.begin() + 2);
  EXPECT_NE(message({"shear_modulus_pa", "chamber_gap_m"}, two, Q::kEveryJoint).find("more pressures than"),
            std::string::npos);
  EXPECT_NE(message({"shear_modulus_pa"}, tips, Q::kTipPosition).find("no measurement for 'tip_position'"),
            std::string::npos);
  EXPECT_NE(message({"shear_modulus_pa"}, tips, Q::kEveryJoint).find("no measurement for 'joints'"), std::string::npos);
  EXPECT_NE(message({}, joints, Q::kEveryJoint).find("at least one parameter"), std::string::npos);
  // What the file's header lacks or half-gives is refused when it is read, naming the line.
  EXPECT_NE(refusal("gauge_pa,tip_x_m\n1e5,0.01\n", 1).find("m.csv:1: header has tip_x_m without tip_y_m"),
            std::string::npos);
  EXPECT_NE(refusal("gauge_pa,pressure_kgcm2\n1e5,1\n", 1).find("header has nothing measured"), std::string::npos);
  EXPECT_NE(refusal("gauge_pa,joint_1_rad\n1e5,0.1\n", 1).find("joint_1_rad alone"), std::string::npos);
}

// What a user meets: five tip angles made at mu = 1.8e8 Pa with 0.01 rad of noise. Tip angles barely separate mu from
// c: the fit must say so (a trade-off warning), and its one-sigma bars must cover the truth (within three).
TEST(CalibrationUncertainty, TipAnglesWithNoiseWarnThatMuAndGapTradeOffAndTheBarsCoverTheTruth) {
  const pf::FingerParameters truth = truthWith(1.8e8, 4.9640761700248786e-05, 0.31406024809341682);
  const std::vector<double> pressures = {39226.6, 78453.2, 117679.8, 156906.4, 196133.0};
  std::vector<pf::Measurement> data = syntheticTipCsv(truth, pressures, false);
  const double noise[] = {0.01, -0.01, 0.01, -0.01, 0.01};
  for (std::size_t i = 0; i < data.size(); ++i) data[i].tip_angle_rad += noise[i];
  const pf::CalibrationResult fit = pf::calibrate(pf::FingerParameters::defaults(),
                                                  {"shear_modulus_pa", "chamber_gap_m"}, data,
                                                  pf::CalibrationObjective::kLeastSquares,
                                                  pf::CalibrationQuantity::kTipAngle);
  ASSERT_EQ(fit.uncertainty.size(), 2u);
  EXPECT_LE(std::fabs(fit.values[0] - 1.8e8), 3 * fit.uncertainty[0]) << fit.values[0] << " +- " << fit.uncertainty[0];
  EXPECT_LE(std::fabs(fit.values[1] - truth.chamber_gap_m[0]), 3 * fit.uncertainty[1]);
  EXPECT_GT(fit.uncertainty[0] / fit.values[0], 0.02) << "five noisy tip angles cannot pin mu to 2 %";
  EXPECT_LT(fit.correlation[1], -0.95);
  ASSERT_FALSE(fit.warnings.empty());
  EXPECT_NE(fit.warnings[0].find("shear_modulus_pa and chamber_gap_m trade off"), std::string::npos) << fit.warnings[0];
}

// A key the data push past its search range stops on the range's end: a fit there is no minimum, and it says so.
TEST(CalibrationUncertainty, AKeyOnItsBoundIsNamed) {
  std::vector<pf::Measurement> data;
  for (double p : kPressures) {
    pf::Measurement m = synthetic(pf::FingerParameters::defaults(), {p})[0];
    m.joint_rad[0] = 3.0 * m.joint_rad[1];  // a joint 1 larger than any base share up to 1 makes
    data.push_back(m);
  }
  const pf::CalibrationResult fit = pf::calibrate(pf::FingerParameters::defaults(), {"base_wall_share"}, data,
                                                  pf::CalibrationObjective::kMinimax,
                                                  pf::CalibrationQuantity::kFirstJoint);
  EXPECT_EQ(fit.values[0], 1.0);
  ASSERT_FALSE(fit.warnings.empty());
  EXPECT_NE(fit.warnings[0].find("base_wall_share = 1 sits on the upper end of its search range [0, 1]"),
            std::string::npos)
      << fit.warnings[0];
}

// Keys the data determine well give small bars and no warning: mu alone from exact joints.
TEST(CalibrationUncertainty, AWellDeterminedKeyHasASmallBarAndNoWarning) {
  const pf::FingerParameters truth = truthWith(2e8, 4.9640761700248786e-05, 0.31406024809341682);
  const pf::CalibrationResult fit =
      pf::calibrate(truth, {"shear_modulus_pa"}, synthetic(truth, kPressures), pf::CalibrationObjective::kLeastSquares,
                    pf::CalibrationQuantity::kOuterAverage);
  EXPECT_TRUE(fit.warnings.empty()) << fit.warnings[0];
  EXPECT_LT(fit.uncertainty[0], 1e-6 * fit.values[0]);
}

// A long calibration says where it is: every step it reports names the law, the leave-one-out row and the model
// evaluations so far; the fit is the same with or without someone listening. The printer stays quiet for its first
// seconds, then writes a line per step at most that often.
TEST(Calibration, ALongCalibrationReportsItsProgress) {
  pf::MeasurementSet data;
  data.rows = pf::readMeasurementsCsv(kTable1, 1);
  pf::CalibrationRequest request;
  request.wall_law = "paper";  // with leave-one-out (the default): the fit, then a fit per row
  std::vector<std::string> steps;
  request.progress = [&steps](const std::string& step) { steps.push_back(step); };
  const pf::FingerParameters base = pf::calibrationBase(pf::FingerParameters::defaults().toRaw(), "paper");
  const pf::CalibrationRun heard = pf::runCalibration(base, data, request);
  request.progress = nullptr;
  const pf::CalibrationRun quiet = pf::runCalibration(base, data, request);
  EXPECT_EQ(heard.best().fit.values, quiet.best().fit.values);
  ASSERT_FALSE(steps.empty());
  auto heard_of = [&steps](const std::string& part) {
    return std::any_of(steps.begin(), steps.end(), [&](const std::string& s) { return s.find(part) != std::string::npos; });
  };
  EXPECT_TRUE(heard_of("paper law: the fit: ")) << steps.front();
  EXPECT_TRUE(heard_of("paper law: leave-one-out, row 4 of 4: ")) << steps.back();
  EXPECT_TRUE(heard_of(" model evaluations")) << steps.back();

  std::ostringstream loud, silent;
  pf::CalibrationProgressPrinter now(loud, "finger_calibrate", 0.0), later(silent, "finger_calibrate", 1e9);
  now("paper law: the fit: 64 model evaluations");
  later("paper law: the fit: 64 model evaluations");
  EXPECT_NE(loud.str().find("finger_calibrate: 0.0 s: paper law: the fit: 64 model evaluations\n"), std::string::npos)
      << loud.str();
  EXPECT_EQ(silent.str(), "");
}

// A snap under pressure control: a Gent membrane finger on a pressure ramp through its limit point leaps to its far
// branch. Its bends leap, so the default comparison is the pressure that holds each measured bend (continuous through
// the snap, on both branches); at the truth every such pressure is the measured one, and the fit finds the truth
// again from a start off it.
TEST(Calibration, FitsASnapByThePressureThatHoldsEachBend) {
  const pf::FingerParameters truth = pf_test::membraneFinger(20.0, "chamber_gap_m: 1e-3\n");
  pf::FingerModel model(truth);
  pf::FingerWorkspace ws(model);
  ASSERT_TRUE(std::isfinite(model.limitGaugePa()));
  std::vector<pf::Measurement> rows;
  bool snapped = false;
  for (int k = 1; k <= 19; ++k) {
    pf::Measurement m;
    m.line = k;
    m.gauge_pa = model.limitGaugePa() * (0.5 + 0.05 * (k - 1));  // 0.5 to 1.4 of the limit point
    const pf::FingerState& s = model.evaluate(m.gauge_pa, ws);
    snapped = snapped || s.status == pf::EvaluationStatus::kSnappedThrough;
    ASSERT_TRUE(std::isfinite(s.tip_angle_rad)) << "row " << k;
    m.tip_angle_rad = s.tip_angle_rad;
    rows.push_back(m);
  }
  ASSERT_TRUE(snapped) << "the ramp must pass the snap";
  EXPECT_TRUE(pf::bendLeaps(rows));
  EXPECT_EQ(pf::defaultQuantity(rows), pf::CalibrationQuantity::kGaugeAtTipAngle);
  for (const pf::Residual& r : pf::residuals(truth, rows, pf::CalibrationQuantity::kGaugeAtTipAngle)) {
    if (r.measured_tip_angle_rad == 0.0) continue;  // before the walls touch: no one pressure holds a straight finger
    EXPECT_NEAR(r.model_gauge_at_tip_angle_pa, r.measured_gauge_pa, 1e-7 * r.measured_gauge_pa) << r.gauge_pa;
  }
  pf::FingerParameters start = truth;
  start.shear_modulus_pa.assign(start.shear_modulus_pa.size(), 5e4);
  start.chamber_gap_m.assign(start.chamber_gap_m.size(), 0.0);
  for (auto objective : {pf::CalibrationObjective::kMinimax, pf::CalibrationObjective::kLeastSquares}) {
    const pf::CalibrationResult fit = pf::calibrate(start, {"shear_modulus_pa", "chamber_gap_m"}, rows, objective,
                                                    pf::CalibrationQuantity::kGaugeAtTipAngle);
    EXPECT_NEAR(fit.values[0], 2e4, 2e4 * 1e-6) << pf::objectiveName(objective);
    EXPECT_NEAR(fit.values[1], 1e-3, 1e-3 * 1e-6) << pf::objectiveName(objective);
  }
  // Table 1's four pressures do not leap: the bend is compared as it is.
  EXPECT_FALSE(pf::bendLeaps(pf::readMeasurementsCsv(kTable1, 4)));
}

// Huber's robust loss: one row off by a blunder (0.2 rad) pulls a least-squares fit away from the truth; Huber's, whose
// scale comes from the least-squares fit's median error, leaves it nearly where the other rows put it.
TEST(Calibration, HubersLossKeepsAnOutlierFromPullingTheFit) {
  const pf::FingerParameters truth = pf_test::membraneFinger(20.0, "chamber_gap_m: 1e-3\n");
  pf::FingerModel model(truth);
  pf::FingerWorkspace ws(model);
  std::vector<pf::Measurement> rows;
  for (int k = 1; k <= 10; ++k) {
    pf::Measurement m;
    m.line = k;
    m.gauge_pa = model.limitGaugePa() * (0.5 + 0.045 * k);  // below the limit point
    m.tip_angle_rad = model.evaluate(m.gauge_pa, ws).tip_angle_rad + 1e-3 * ((k % 3) - 1);  // 1 mrad of noise
    rows.push_back(m);
  }
  rows[6].tip_angle_rad += 0.2;
  pf::FingerParameters start = truth;
  start.shear_modulus_pa.assign(start.shear_modulus_pa.size(), 5e4);
  const std::vector<std::string> keys = {"shear_modulus_pa", "chamber_gap_m"};
  const auto squares = pf::calibrate(start, keys, rows, pf::CalibrationObjective::kLeastSquares,
                                     pf::CalibrationQuantity::kTipAngle);
  const auto huber = pf::calibrate(start, keys, rows, pf::CalibrationObjective::kHuber,
                                   pf::CalibrationQuantity::kTipAngle);
  const double squares_off = std::fabs(squares.values[0] / 2e4 - 1), huber_off = std::fabs(huber.values[0] / 2e4 - 1);
  EXPECT_GT(squares_off, 5 * huber_off) << squares.values[0] << " " << huber.values[0];
  EXPECT_LT(huber_off, 0.01) << huber.values[0];
  EXPECT_EQ(pf::parseObjective("huber"), pf::CalibrationObjective::kHuber);
  EXPECT_STREQ(pf::objectiveName(pf::CalibrationObjective::kHuber), "huber");
}

// A law fitted and predicted row by row (calibrateWallLaws) hands the fit's scan to leave-one-out instead of scanning
// again: each fold must start from the same points as a leave-one-out that scans for itself, and end where it does,
// to the bit.
TEST(Calibration, LeaveOneOutFromTheFitsScanIsTheSameAsFromItsOwn) {
  const std::vector<pf::Measurement> data = pf::readMeasurementsCsv(kTable1, 1);
  pf::FingerParameters base = pf::FingerParameters::defaults();
  const std::vector<std::string> keys = {"shear_modulus_pa", "chamber_gap_m"};
  const auto fits = pf::calibrateWallLaws(base, {pf::WallLaw::kPaper}, keys, data, pf::CalibrationObjective::kMinimax,
                                          pf::CalibrationQuantity::kOuterAverage, {});
  base.wall_law = pf::WallLaw::kPaper;
  const std::vector<pf::Residual> own = pf::leaveOneOut(base, keys, data, pf::CalibrationObjective::kMinimax,
                                                        pf::CalibrationQuantity::kOuterAverage);
  ASSERT_EQ(fits.size(), 1u);
  ASSERT_EQ(fits[0].leave_one_out.size(), data.size());
  std::size_t moved = 0;  // folds whose fit is not the whole fit (a minimax fold without an active row is the same)
  for (std::size_t i = 0; i < data.size(); ++i) {
    EXPECT_EQ(fits[0].leave_one_out[i].model_joint_rad, own[i].model_joint_rad) << "row " << i;
    moved += fits[0].leave_one_out[i].model_joint_rad != fits[0].fit.residuals[i].model_joint_rad;
  }
  EXPECT_GE(moved, 1u);
}

// --wall-law auto on the ribbed segment: the thick wall's keys grow from mu and c to its lock, which predicts the
// bends clearly better held out; its leave-one-out is ACCURACY.md's (5.19 deg). With keys named, each law once.
TEST(Calibration, AutoGrowsTheThickWallsKeysWhereTheyPredictBetter) {
  const std::string root = PACKAGE_SOURCE_DIR;
  pf::RawParameterMap raw;
  pf::loadRawParametersFromYamlFile(root + "/config/marchese2015_ribbed.yaml", raw);
  const pf::FingerParameters base = pf::calibrationBase(raw, "auto");
  const pf::MeasurementSet data = pf::readMeasurementSet(root + "/data/marchese2015_ribbed_bending.csv", 4);
  pf::CalibrationRequest request;
  request.wall_law = "auto";
  request.compare = "tip_angle";
  const pf::CalibrationRun run = pf::runCalibration(base, data, request);
  const std::vector<std::string> two = {"shear_modulus_pa", "chamber_gap_m"};
  std::vector<std::string> three = two;
  three.push_back("wall_locking_jm");
  const auto tried = [&run](pf::WallLaw law, const std::vector<std::string>& keys) {
    return std::any_of(run.candidates.begin(), run.candidates.end(),
                       [&](const pf::CandidateFit& c) { return c.law == law && c.keys == keys; });
  };
  EXPECT_TRUE(tried(pf::WallLaw::kThick, two) && tried(pf::WallLaw::kThick, three));
  EXPECT_EQ(run.best().law, pf::WallLaw::kThick);
  EXPECT_EQ(run.best().fit.keys, three);
  EXPECT_EQ(run.candidates[run.chosen_candidate].keys, three);
  EXPECT_NEAR(run.best().leave_one_out_objective * kDeg, 5.19, 0.005);
  EXPECT_EQ(run.fits.size(), 1u);
  const auto minimax = pf::CalibrationObjective::kMinimax;
  const auto tip = pf::CalibrationQuantity::kTipAngle;
  EXPECT_EQ(pf::calibrateWallLaws(base, pf::parseWallLawChoice("auto"), two, data.rows, minimax, tip, {}).size(), 3u);
}
