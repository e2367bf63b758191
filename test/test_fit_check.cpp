// Whether a calibration follows its data (fit_check.hpp) and the record it leaves in the file
// (calibration_error.hpp): the data's scatter against a known noise, the missed rows named worst first, the record
// read back as written, a malformed one refused.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "pneumatic_finger/calibration/calibration_run.hpp"
#include "pneumatic_finger/calibration/fit_check.hpp"
#include <yaml-cpp/yaml.h>

#include "pneumatic_finger/core/yaml_parameters.hpp"

namespace pf = pneumatic_finger;

// Bends on a curve with Gaussian noise of a known standard deviation: the data's scatter finds it (2000 rows: its
// sampling error is a few percent), and a snap's few rows do not move it.
TEST(FitCheck, TheDatasScatterIsTheNoiseOfTheBends) {
  std::mt19937 random(7);
  std::normal_distribution<double> noise(0.0, 0.01);
  std::vector<pf::Measurement> rows;
  for (int k = 0; k < 2000; ++k) {
    pf::Measurement m;
    m.gauge_pa = 1000.0 + 20.0 * k;
    m.tip_angle_rad = 0.3 * std::sqrt(m.gauge_pa / 1000.0) + (k > 1000 && k < 1010 ? 0.5 : 0.0) + noise(random);
    rows.push_back(m);
  }
  EXPECT_NEAR(pf::bendScatterRad(rows), 0.01, 0.0006);
  rows.resize(pf::kScatterRows - 1);  // a few rows far apart: the curve's own bend would pass for noise
  EXPECT_EQ(pf::bendScatterRad(rows), 0.0);
}

// The EPFL ramp of chords under the paper law: it misses the snap's rows by tens of degrees held out. The warning
// names them worst first with what to try, and the record says so; auto's fit of the same data follows it.
// The bar's reason, as the report and the warning print it: the scatter where it is measured, else why it is not.
TEST(FitCheck, TheFollowBarSaysWhereItComesFrom) {
  EXPECT_EQ(pf::followBarReason(0.02), "the larger of 5 deg and 3 times the data's own scatter, 1.15 deg");
  EXPECT_EQ(pf::followBarReason(0.0), "5 deg: the data's own scatter is measured on 8 rows or more set by their "
                                      "pressure, each with a bend, and these have fewer");
}

TEST(FitCheck, AFitThatMissesItsDataSaysWhichRowsAndWhatToTry) {
  const std::string root = PACKAGE_SOURCE_DIR;
  pf::RawParameterMap raw;
  pf::loadRawParametersFromYamlFile(root + "/config/epfl_ecoflex30_c7_coupon.yaml", raw);
  const pf::MeasurementSet data = pf::readMeasurementSet(root + "/data/epfl_ecoflex30_c7_bending.csv", 4);
  pf::CalibrationRequest request;
  request.wall_law = "paper";
  const pf::CalibrationRun run = pf::runCalibration(pf::calibrationBase(raw, "paper"), data, request);
  const pf::CalibrationError& e = run.calibration_error;
  ASSERT_FALSE(e.empty());
  EXPECT_FALSE(e.follows_data);
  EXPECT_EQ(e.compared, "chord_angle");
  EXPECT_GT(e.missed_rows, 10);
  double largest = 0.0, at = 0.0;
  for (const pf::Residual& r : run.best().leave_one_out) {
    if (std::fabs(r.chord_angle_error_rad()) > largest) largest = std::fabs(r.chord_angle_error_rad()), at = r.gauge_pa;
  }
  EXPECT_EQ(e.held_out_largest_rad, largest);
  EXPECT_EQ(e.largest_at_gauge_pa, at);
  const std::string& w = run.warnings.back();
  EXPECT_NE(w.find("the fit does not follow its data: " + std::to_string(e.missed_rows) + " of 71 rows"),
            std::string::npos) << w;
  EXPECT_NE(w.find("the worst at " + pf::formatMessage(at) + " Pa ("), std::string::npos) << w;
  EXPECT_NE(w.find("try: let --wall-law auto choose the law and the keys"), std::string::npos) << w;
  // Written and read back: the same record, and the words a person reads.
  const std::string text = pf::calibratedParameterYaml(run, pf::PressureRange());
  const pf::ParameterTree tree = pf::readParameterTree(YAML::Load(text), "written");
  EXPECT_EQ(tree.calibration_error.held_out_largest_rad, e.held_out_largest_rad);
  EXPECT_EQ(tree.calibration_error.missed_rows, e.missed_rows);
  EXPECT_FALSE(tree.calibration_error.follows_data);
  EXPECT_NE(tree.calibration_error.describe().find("does NOT follow its data: " + std::to_string(e.missed_rows)),
            std::string::npos);
}

TEST(FitCheck, AMalformedRecordIsRefusedNamingItsKey) {
  const auto refusal = [](const std::string& text) {
    try {
      pf::readParameterTree(YAML::Load(text), "f.yaml");
    } catch (const pf::ParameterError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  const std::string good = "calibration_error: {compared: tip_angle, held_out_rms_rad: 0.01, held_out_largest_rad: "
                           "0.02, largest_at_gauge_pa: 30000, missed_rows: 0, follows_data: true}\n";
  EXPECT_EQ(refusal(good), "");
  EXPECT_NE(refusal("calibration_error: {compared: tip_angle}\n").find("'held_out_rms_rad' is missing"),
            std::string::npos);
  EXPECT_NE(refusal("calibration_error: {compared: tip_angle, held_out_rms_rad: -1, held_out_largest_rad: 0, "
                    "largest_at_gauge_pa: 0, missed_rows: 0, follows_data: true}\n")
                .find("'held_out_rms_rad' = -1 must be finite and >= 0"),
            std::string::npos);
  EXPECT_NE(refusal("calibration_error: {compared: tip_angle, held_out_rms_rad: 0, held_out_largest_rad: 0, "
                    "largest_at_gauge_pa: 0, missed_rows: 0, follows_data: maybe}\n")
                .find("'follows_data' must be true or false"),
            std::string::npos);
  EXPECT_NE(refusal("calibration_error: {compared: tip_angle, rms: 0}\n").find("unknown key 'rms'"),
            std::string::npos);
}
