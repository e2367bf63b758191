// A newcomer's first calibration (docs/CALIBRATE.md): tip positions alone give an error bar; data a finger cannot
// have made (degrees in a radian column, millimetres in a metre column) is refused with the likely unit named;
// columns calibration does not read are named; the membrane law's wall is not refused before the law is chosen.
// Each of these failed before the shared calibration run (calibration_run.hpp) existed.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "pneumatic_finger/calibration/calibration.hpp"
#include "pneumatic_finger/calibration/calibration_run.hpp"
#include "pneumatic_finger/core/finger_model.hpp"
#include "pneumatic_finger/core/yaml_parameters.hpp"

namespace pf = pneumatic_finger;

namespace {

const std::vector<double> kPressures = {50000, 100000, 150000, 200000};

pf::FingerParameters truth() {
  pf::RawParameterMap raw;
  raw["shear_modulus_pa"] = {{3.7e8}, false};
  raw["chamber_gap_m"] = {{8.5e-5}, false};
  return pf::FingerParameters::fromRaw(raw);
}

// The CSV a camera gives: gauge_pa,tip_x_m,tip_y_m from the model at truth(), each length times @p scale (1000: mm).
std::string tipCsv(const std::string& header, double scale) {
  const pf::FingerModel model(truth());
  pf::FingerWorkspace ws(model);
  std::string csv = header + "\n";
  for (double p : kPressures) {
    const pf::FingerState& s = model.evaluate(p, ws);
    csv += pf::formatExact(p) + "," + pf::formatExact(s.tip().x() * scale) + "," +
           pf::formatExact(s.tip().y() * scale) + "\n";
  }
  return csv;
}

std::string refusal(const std::string& csv) {
  try {
    const pf::MeasurementSet data = pf::parseMeasurementSet(csv, "tips.csv", 1);
    pf::runCalibration(pf::FingerParameters::defaults(), data, pf::CalibrationRequest());
  } catch (const pf::ParameterError& e) {
    return e.what();
  }
  return "(accepted)";
}

}  // namespace

TEST(FirstCalibration, TipPositionsAloneRecoverTheFingerAndGiveAPositionBar) {
  const pf::MeasurementSet data = pf::parseMeasurementSet(tipCsv("gauge_pa,tip_x_m,tip_y_m", 1.0), "tips.csv", 1);
  const pf::CalibrationRun run = pf::runCalibration(pf::FingerParameters::defaults(), data, pf::CalibrationRequest());
  ASSERT_EQ(run.quantity, pf::CalibrationQuantity::kTipPosition);
  EXPECT_NEAR(run.best().fit.values[0], 3.7e8, 3.7e8 * 1e-6);
  EXPECT_NEAR(run.best().fit.values[1], 8.5e-5, 8.5e-5 * 1e-6);
  // The bar: no angle was measured (NaN), the position's is the leave-one-out error (tiny for exact data).
  ASSERT_EQ(run.tip_uncertainty.gauge_pa, kPressures);
  for (std::size_t i = 0; i < kPressures.size(); ++i) {
    EXPECT_TRUE(std::isnan(run.tip_uncertainty.tip_angle_rad[i]));
    EXPECT_LT(run.tip_uncertainty.tip_position_m[i], 1e-9);
  }
  // And it reads back, as finger_node reads the calibrated file.
  const pf::TipUncertainty& bar = run.tip_uncertainty;
  EXPECT_NO_THROW(pf::TipUncertainty::fromLists(bar.gauge_pa, bar.tip_angle_rad, bar.tip_position_m, "f.yaml"));
  EXPECT_TRUE(run.warnings.size() <= 1) << "only the keys' trade-off, no data warning";
}

TEST(FirstCalibration, DegreesInARadianColumnAreRefusedNamingTheUnit) {
  const std::string why = refusal("gauge_pa,tip_angle_rad\n50000,16\n100000,33\n150000,51\n200000,69\n");
  EXPECT_NE(why.find("line 2: tip_angle_rad = 16 rad is beyond 2 pi"), std::string::npos) << why;
  EXPECT_NE(why.find("were the angles in degrees?"), std::string::npos) << why;
  // A joint turns at most pi (two walls of pi/2 each).
  const std::string joint = refusal("gauge_pa,joint_1_rad,joint_2_rad\n1e5,0.1,3.5\n2e5,0.2,0.3\n");
  EXPECT_NE(joint.find("line 2: joint_2_rad = 3.5 rad is beyond pi"), std::string::npos) << joint;
  // The same numbers in radians pass the check (a real bend of 16..69 degrees).
  EXPECT_EQ(refusal("gauge_pa,tip_angle_rad\n50000,0.28\n100000,0.58\n150000,0.89\n200000,1.2\n")
                .find("beyond"),
            std::string::npos);
}

TEST(FirstCalibration, MillimetresInAMetreColumnAreRefusedNamingTheUnit) {
  const std::string why = refusal(tipCsv("gauge_pa,tip_x_m,tip_y_m", 1000.0));
  EXPECT_NE(why.find("farther than the finger is long (0.085 m) by more than a camera's 5 %; were the positions in "
                     "mm?"),
            std::string::npos)
      << why;
}

// A camera's tip lies a little past the straight finger's end: 0.01 mm and 0.5 mm past it are measurements (the first
// was refused at its first row before); 10 % past is a wrong origin or scale, and says so.
TEST(FirstCalibration, ATipACameraReadsJustPastTheFingersEndIsAMeasurement) {
  const double length_m = pf::restState(pf::FingerParameters::defaults()).tip().norm();
  auto csv = [length_m](double past_m) {
    const std::string x = pf::formatExact(length_m + past_m);
    return "gauge_pa,tip_x_m,tip_y_m\n0," + x + ",0\n50000,0.08,0.012\n100000,0.075,0.025\n150000,0.068,0.035\n" +
           "200000,0.06,0.043\n";
  };
  const pf::FingerParameters finger = pf::FingerParameters::defaults();
  for (double past_m : {1e-5, 5e-4}) {
    const pf::MeasurementSet data = pf::parseMeasurementSet(csv(past_m), "tips.csv", 1);
    EXPECT_NO_THROW(pf::checkMeasurementsPlausible(finger, data.rows)) << past_m;
  }
  const std::string why = refusal(csv(0.1 * length_m));
  EXPECT_NE(why.find("by more than a camera's 5 %; is the origin at the mount"), std::string::npos) << why;
}

TEST(FirstCalibration, ColumnsNotReadAreNamedWithWhatTheyMayMean) {
  // Alone, a column in mm is not data: refused, with the column it may have meant.
  const std::string why = refusal(tipCsv("gauge_pa,tip_x_mm,tip_y_mm", 1000.0));
  EXPECT_NE(why.find("header has nothing measured"), std::string::npos) << why;
  EXPECT_NE(why.find("column 'tip_x_mm' is not read: did you mean 'tip_x_m'?"), std::string::npos) << why;
  // Beside data: named in the report's warnings, the fit goes on.
  const pf::MeasurementSet data =
      pf::parseMeasurementSet("gauge_pa,tip_angle_rad,tip_angle_deg,operator\n5e4,0.1,5.7,A\n1e5,0.2,11.5,A\n"
                              "1.5e5,0.3,17.2,A\n2e5,0.4,22.9,A\n", "tips.csv", 1);
  ASSERT_EQ(data.notes.size(), 2u);
  EXPECT_EQ(data.notes[0], "column 'tip_angle_deg' is not read: did you mean 'tip_angle_rad'? (SI units: Pa, rad, m)");
  EXPECT_EQ(data.notes[1].rfind("columns not read: operator (calibration reads gauge_pa", 0), 0u) << data.notes[1];
  const pf::CalibrationRun run = pf::runCalibration(pf::FingerParameters::defaults(), data, pf::CalibrationRequest());
  EXPECT_EQ(run.warnings[0], data.notes[0]);
}

TEST(FirstCalibration, ColumnsFromPythonAreCheckedAsAFileIs) {
  const pf::MeasurementSet set =
      pf::measurementSetFromColumns({"gauge_pa", "tip_angle_rad"}, {{5e4, 1e5}, {0.1, 0.2}}, "data", 1);
  ASSERT_EQ(set.rows.size(), 2u);
  EXPECT_EQ(set.rows[1].tip_angle_rad, 0.2);
  try {
    pf::measurementSetFromColumns({"gauge_pa", "tip_angle_rad"}, {{5e4, 1e5}, {0.1}}, "data", 1);
    ADD_FAILURE() << "columns of unequal length accepted";
  } catch (const pf::ParameterError& e) {
    EXPECT_NE(std::string(e.what()).find("column tip_angle_rad has 1 values, column gauge_pa 2"), std::string::npos);
  }
  try {
    pf::measurementSetFromColumns({"gauge_pa", "tip_angle_rad"}, {{5e4, 1e5}, {0.1, NAN}}, "data", 1);
    ADD_FAILURE() << "NaN accepted";
  } catch (const pf::ParameterError& e) {
    EXPECT_NE(std::string(e.what()).find("data: row 2: nan in column tip_angle_rad is not a finite number"),
              std::string::npos) << e.what();
  }
}

TEST(FirstCalibration, TheMembraneWallIsNotRefusedBeforeTheLawIsChosen) {
  // A wall taller than its chamber: the membrane law allows it, the paper law does not.
  pf::RawParameterMap raw = pf::FingerParameters::defaults().toRaw();
  raw["wall_critical_height_m"] = {{0.02}, false};
  EXPECT_THROW(pf::calibrationBase(raw, ""), pf::ParameterError);  // the file's law is the paper's
  EXPECT_THROW(pf::calibrationBase(raw, "paper"), pf::ParameterError);
  EXPECT_EQ(pf::calibrationBase(raw, "auto").wall_critical_height_m[0], 0.02);
  EXPECT_EQ(pf::calibrationBase(raw, "membrane").wall_law, pf::WallLaw::kMembrane);
}

// A drawn actuator calibrated in its drawing's keys: the roof (which the drawing guesses) fitted as
// drawing/roof_thickness_m is written back into the drawing, and the written file, loaded by the loader every
// interface calls, gives the report's model bends to 1e-12. A key the drawing makes is refused, naming the drawing's
// key (before: --fit chamber_height_m reported 0.0079 m and wrote the drawing's 0.010 m, and the file missed by 685 deg).
TEST(FirstCalibration, ADrawnActuatorIsFittedInItsDrawingAndTheWrittenFileReproducesTheReport) {
  pf::RawParameterMap raw;
  pf::PressureRange range;
  pf::loadRawParametersFromYamlFile(std::string(PACKAGE_SOURCE_DIR) + "/config/epfl_ecoflex30_c7_coupon.yaml", raw,
                                    nullptr, &range);
  const pf::FingerParameters base = pf::FingerParameters::fromRaw(raw);
  raw["drawing/roof_thickness_m"] = {{0.009}, false};
  const pf::FingerModel truth_model(pf::FingerParameters::fromRaw(raw));
  pf::FingerWorkspace ws(truth_model);
  std::string csv = "gauge_pa,tip_angle_rad\n";
  for (double p = 2000.0; p <= 20000.0; p += 2000.0) {
    csv += pf::formatExact(p) + "," + pf::formatExact(truth_model.evaluate(p, ws).tip_angle_rad) + "\n";
  }
  const pf::MeasurementSet data = pf::parseMeasurementSet(csv, "roof.csv", 1);
  pf::CalibrationRequest request;
  request.keys = {"drawing/roof_thickness_m"};
  const pf::CalibrationRun run = pf::runCalibration(base, data, request);
  EXPECT_NEAR(run.best().fit.values[0], 0.009, 1e-9);
  pf::RawParameterMap written;
  pf::loadRawParametersFromYamlText(pf::calibratedParameterYaml(run, range), "written.yaml", written);
  EXPECT_EQ(written.at("drawing/roof_thickness_m").values[0], run.best().fit.values[0]);
  const pf::FingerModel loaded(pf::FingerParameters::fromRaw(written));
  pf::FingerWorkspace lw(loaded);
  for (const pf::Residual& r : run.best().fit.residuals) {
    EXPECT_NEAR(loaded.evaluate(r.gauge_pa, lw).tip_angle_rad, r.model_tip_angle_rad, 1e-12) << r.gauge_pa;
  }
  request.keys = {"chamber_height_m"};
  try {
    pf::runCalibration(base, data, request);
    ADD_FAILURE() << "a key the drawing makes was fitted";
  } catch (const pf::ParameterError& e) {
    EXPECT_NE(std::string(e.what()).find("parameter 'chamber_height_m' is made by the drawing (docs/DRAWING.md), "
                                         "which the written file keeps: fit drawing/cavity_height_m instead"),
              std::string::npos) << e.what();
  }
}
