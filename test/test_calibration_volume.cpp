// Calibration of a finger set by its supplied volume (calibration.hpp: Measurement::supplied_volume_m3,
// driveByVolume, the gauge_pa quantity and the dead_volume_m3 key). The data are made by the model at known keys,
// through evaluateVolume or suppliedVolumeAt, and the fit must find those keys again.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include "pneumatic_finger/calibration/calibration.hpp"
#include "pneumatic_finger/calibration/calibration_run.hpp"
#include "test_support.hpp"

namespace pf = pneumatic_finger;

namespace {

// Rows measured on @p truth filled by volume: each volume's tip angle and pressure (gauge_pa NaN unless
// @p with_gauge), on a volume ramp from a quarter of the volume at the limit point to @p past times it.
std::vector<pf::Measurement> filledByVolume(const pf::FingerParameters& truth, double past, bool with_gauge) {
  pf::FingerModel model(truth);
  pf::FingerWorkspace ws(model);
  const double at_limit = model.suppliedVolumeAt(0.999 * model.limitGaugePa());
  std::vector<pf::Measurement> rows;
  for (int k = 1; k <= 8; ++k) {
    pf::Measurement m;
    m.line = k;
    m.supplied_volume_m3 = at_limit * (0.25 + (past - 0.25) * (k - 1) / 7.0);
    const pf::FingerState& s = model.evaluateVolume(m.supplied_volume_m3, ws);
    EXPECT_TRUE(s.status == pf::EvaluationStatus::kOk || s.status == pf::EvaluationStatus::kSnappedThrough)
        << "row " << k << ": the truth has no shape at " << m.supplied_volume_m3 << " m^3";
    m.tip_angle_rad = s.tip_angle_rad;
    m.gauge_pa = with_gauge ? s.gauge_pa : NAN;
    rows.push_back(m);
  }
  return rows;
}

// Rows measured on @p truth below its limit point, where the pressure sets the volume: six pressures and the volume
// each takes, driven by volume.
std::vector<pf::Measurement> pressuresAgainstVolume(const pf::FingerParameters& truth) {
  const pf::FingerModel model(truth);
  std::vector<pf::Measurement> rows;
  for (int k = 1; k <= 6; ++k) {
    pf::Measurement m;
    m.line = k;
    m.gauge_pa = model.limitGaugePa() * 0.15 * k;
    m.supplied_volume_m3 = model.suppliedVolumeAt(m.gauge_pa);
    rows.push_back(m);
  }
  pf::driveByVolume(rows);
  return rows;
}

std::string refusal(const std::function<void()>& f) {
  try {
    f();
  } catch (const pf::ParameterError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

// Bends against volume, past the limit point: the pressure there falls while the volume and the bend rise, so a
// pressure-driven fit could not use those rows; driven by volume they are data, and the gap comes back. (The
// modulus cannot: with an incompressible fluid the volume alone sets the shape, RefusesWhatTheDriveCannotGive.)
TEST(CalibrationByVolume, RecoversTheGapFromBendsFilledPastTheLimitPoint) {
  const pf::FingerParameters truth = pf_test::membraneFinger(0.0, "chamber_gap_m: 1e-3\n");
  std::vector<pf::Measurement> rows = filledByVolume(truth, 2.0, false);
  pf::driveByVolume(rows);
  pf::FingerParameters start = truth;
  start.chamber_gap_m.assign(start.chamber_gap_m.size(), 0.0);
  const pf::CalibrationResult fit = pf::calibrate(start, {"chamber_gap_m"}, rows, pf::CalibrationObjective::kMinimax,
                                                  pf::CalibrationQuantity::kTipAngle);
  EXPECT_NEAR(fit.values[0], 1e-3, 1e-3 * 1e-6);
  for (const pf::Residual& r : fit.residuals) {
    EXPECT_NEAR(r.tip_angle_error_rad(), 0.0, 1e-9);
    EXPECT_FALSE(std::isnan(r.model_gauge_pa)) << "the model's pressure at " << r.supplied_volume_m3 << " m^3";
  }
  // The ramp went past the limit point: the model's pressure rose, then fell.
  double highest = 0.0;
  for (const pf::Residual& r : fit.residuals) highest = std::max(highest, r.model_gauge_pa);
  EXPECT_LT(fit.residuals.back().model_gauge_pa, highest);
}

// Pressure against volume: the gas of the drive (dead_volume_m3) is what turns the chambers' growth into the volume
// supplied; fitted to the measured pressures at each supplied volume, it comes back.
TEST(CalibrationByVolume, RecoversTheDeadGasFromThePressureAgainstTheVolume) {
  const pf::FingerParameters truth = pf_test::membraneFinger(20.0, "dead_volume_m3: 3e-5\n");
  std::vector<pf::Measurement> rows = pressuresAgainstVolume(truth);
  pf::FingerParameters start = truth;
  start.dead_volume_m3 = 0.0;
  for (auto objective : {pf::CalibrationObjective::kMinimax, pf::CalibrationObjective::kLeastSquares}) {
    const pf::CalibrationResult fit =
        pf::calibrate(start, {"dead_volume_m3"}, rows, objective, pf::CalibrationQuantity::kGauge);
    EXPECT_NEAR(fit.values[0], 3e-5, 3e-5 * 1e-6) << pf::objectiveName(objective);
    for (const pf::Residual& r : fit.residuals) EXPECT_NEAR(r.gauge_error_pa(), 0.0, 1e-3) << r.measured_gauge_pa;
  }
}

// The skin's share of the growth (chamber_growth_ratio) beside the gas: both turn the chambers' growth into more
// volume, the skin in proportion to the growth and the gas to P/(P_o + P), so the pressures against the volume
// tell them apart, and both come back.
TEST(CalibrationByVolume, RecoversTheSkinsShareAndTheGasFromThePressureAgainstTheVolume) {
  const pf::FingerParameters truth =
      pf_test::membraneFinger(20.0, "dead_volume_m3: 3e-5\nchamber_growth_ratio: 6\n");
  std::vector<pf::Measurement> rows = pressuresAgainstVolume(truth);
  pf::FingerParameters start = truth;
  start.dead_volume_m3 = 0.0;
  start.chamber_growth_ratio = 1.0;
  const pf::CalibrationResult fit = pf::calibrate(start, {"chamber_growth_ratio", "dead_volume_m3"}, rows,
                                                  pf::CalibrationObjective::kLeastSquares, pf::CalibrationQuantity::kGauge);
  EXPECT_NEAR(fit.values[0], 6.0, 6.0 * 1e-6);
  EXPECT_NEAR(fit.values[1], 3e-5, 3e-5 * 1e-6);
}

// Bends and pressures against volume together (tip_angle+gauge_pa): with an incompressible fill the bends alone say
// nothing of the modulus (refused below), the pressures alone little of the gap; the two together give both back.
TEST(CalibrationByVolume, FitsTheBendsAndThePressureTogether) {
  const pf::FingerParameters truth = pf_test::membraneFinger(20.0, "chamber_gap_m: 1e-3\n");
  std::vector<pf::Measurement> rows = filledByVolume(truth, 1.5, true);
  pf::Measurement rest;  // a row at rest: measured at zero pressure, it has no relative error and gives its bend
  rest.line = 9;
  rest.supplied_volume_m3 = 0.0;
  rest.gauge_pa = 0.0;
  rest.tip_angle_rad = 0.0;
  rows.push_back(rest);
  pf::driveByVolume(rows);
  pf::FingerParameters start = truth;
  start.shear_modulus_pa.assign(start.shear_modulus_pa.size(), 4e4);
  start.chamber_gap_m.assign(start.chamber_gap_m.size(), 0.0);
  const pf::CalibrationResult fit =
      pf::calibrate(start, {"shear_modulus_pa", "chamber_gap_m"}, rows, pf::CalibrationObjective::kLeastSquares,
                    pf::CalibrationQuantity::kTipAngleAndGauge);
  EXPECT_NEAR(fit.values[0], 2e4, 2e4 * 1e-6);
  EXPECT_NEAR(fit.values[1], 1e-3, 1e-3 * 1e-6);
  for (const pf::Residual& r : fit.residuals) {
    const std::vector<double> terms = r.terms(pf::CalibrationQuantity::kTipAngleAndGauge);
    ASSERT_EQ(terms.size(), r.measured_gauge_pa == 0.0 ? 1U : 2U) << r.supplied_volume_m3;
    EXPECT_EQ(terms[0], r.tip_angle_error_rad());
    if (terms.size() == 2) {
      EXPECT_EQ(terms[1], (r.model_gauge_pa - r.measured_gauge_pa) / r.measured_gauge_pa);
    }
    EXPECT_NEAR(r.tip_angle_error_rad(), 0.0, 1e-9);
    EXPECT_NEAR(r.gauge_error_pa(), 0.0, 1e-6 * truth.shear_modulus_pa[0]);
  }
  std::vector<pf::Measurement> by_pressure = rows;
  pf::driveByVolume(by_pressure, false);  // every row but the rest has its pressure
  EXPECT_EQ(refusal([&] {
              pf::calibrate(start, {"chamber_gap_m"}, by_pressure, pf::CalibrationObjective::kMinimax,
                            pf::CalibrationQuantity::kTipAngleAndGauge);
            }),
            "'tip_angle+gauge_pa' compares the model's pressure at each row's supplied volume with the measured one: "
            "drive the rows by volume (--drive volume, drive=\"volume\")");
  EXPECT_EQ(pf::parseQuantity("tip_angle+gauge_pa"), pf::CalibrationQuantity::kTipAngleAndGauge);
}

// Four keys at once (the nested searches fitted at most three): the modulus, the gap, the gas and the skin's share,
// from bends and pressures against volume, each from a start off the truth, all four back.
TEST(CalibrationByVolume, FitsFourKeysAtOnce) {
  const pf::FingerParameters truth =
      pf_test::membraneFinger(20.0, "chamber_gap_m: 1e-3\ndead_volume_m3: 3e-5\nchamber_growth_ratio: 6\n");
  std::vector<pf::Measurement> rows = filledByVolume(truth, 1.5, true);
  pf::driveByVolume(rows);
  pf::FingerParameters start = truth;
  start.shear_modulus_pa.assign(start.shear_modulus_pa.size(), 4e4);
  start.chamber_gap_m.assign(start.chamber_gap_m.size(), 0.0);
  start.dead_volume_m3 = 1e-4;
  start.chamber_growth_ratio = 1.0;
  const std::vector<std::string> keys = {"shear_modulus_pa", "chamber_gap_m", "dead_volume_m3", "chamber_growth_ratio"};
  const pf::CalibrationResult fit = pf::calibrate(start, keys, rows, pf::CalibrationObjective::kLeastSquares,
                                                  pf::CalibrationQuantity::kTipAngleAndGauge);
  ASSERT_EQ(fit.values.size(), 4U);
  EXPECT_NEAR(fit.values[0], 2e4, 2e4 * 1e-6);
  EXPECT_NEAR(fit.values[1], 1e-3, 1e-3 * 1e-6);
  EXPECT_NEAR(fit.values[2], 3e-5, 3e-5 * 1e-6);
  EXPECT_NEAR(fit.values[3], 6.0, 6.0 * 1e-6);
  EXPECT_EQ(fit.uncertainty.size(), 4U);
  for (double sd : fit.uncertainty) EXPECT_TRUE(std::isfinite(sd));  // exact data: every key determined
}

TEST(CalibrationByVolume, ReadsTheVolumeColumnWithOrWithoutThePressure) {
  const pf::MeasurementSet both =
      pf::parseMeasurementSet("gauge_pa,supplied_volume_m3,tip_angle_rad\n1000,1e-6,0.1\n2000,2e-6,0.2\n", "m.csv", 2);
  EXPECT_DOUBLE_EQ(both.rows[1].gauge_pa, 2000.0);
  EXPECT_DOUBLE_EQ(both.rows[1].supplied_volume_m3, 2e-6);
  EXPECT_TRUE(both.notes.empty()) << both.notes.front();
  const pf::MeasurementSet volume =
      pf::parseMeasurementSet("supplied_volume_m3,tip_angle_rad\n1e-6,0.1\n2e-6,0.2\n", "m.csv", 2);
  EXPECT_TRUE(std::isnan(volume.rows[0].gauge_pa));
  EXPECT_EQ(refusal([] { pf::parseMeasurementSet("tip_angle_rad\n0.1\n", "m.csv", 1); }),
            "m.csv:1: header has no 'gauge_pa' column (nor 'supplied_volume_m3', for a finger set by volume)");
}

TEST(CalibrationByVolume, RefusesWhatTheDriveCannotGive) {
  const pf::FingerParameters base = pf_test::membraneFinger(20.0);
  std::vector<pf::Measurement> volume_only =
      pf::parseMeasurementSet("supplied_volume_m3,tip_angle_rad\n1e-6,0.1\n2e-6,0.2\n3e-6,0.3\n", "m.csv", 2).rows;
  EXPECT_EQ(refusal([&] { pf::driveByVolume(volume_only, false); }),
            "line 2: no gauge_pa to drive the finger by pressure (drive it by volume, or give the column)");
  std::vector<pf::Measurement> pressure_only =
      pf::parseMeasurementSet("gauge_pa,tip_angle_rad\n1000,0.1\n2000,0.2\n3000,0.3\n", "m.csv", 2).rows;
  EXPECT_EQ(refusal([&] { pf::driveByVolume(pressure_only); }),
            "line 2: no supplied_volume_m3 to drive the finger by volume");
  EXPECT_NE(refusal([&] {
              pf::calibrate(base, {"dead_volume_m3"}, pressure_only, pf::CalibrationObjective::kMinimax,
                            pf::CalibrationQuantity::kTipAngle);
            }).find("dead_volume_m3 takes no part in a finger set by its pressure"),
            std::string::npos);
  EXPECT_NE(refusal([&] {
              pf::calibrate(base, {"chamber_growth_ratio"}, pressure_only, pf::CalibrationObjective::kMinimax,
                            pf::CalibrationQuantity::kTipAngle);
            }).find("chamber_growth_ratio takes no part in a finger set by its pressure"),
            std::string::npos);
  EXPECT_NE(refusal([&] {
              pf::calibrate(base, {"shear_modulus_pa"}, pressure_only, pf::CalibrationObjective::kMinimax,
                            pf::CalibrationQuantity::kGauge);
            }).find("drive the rows by volume"),
            std::string::npos);
  pf::driveByVolume(volume_only);
  EXPECT_EQ(refusal([&] {
              pf::calibrate(base, {"shear_modulus_pa", "chamber_gap_m"}, volume_only,
                            pf::CalibrationObjective::kMinimax, pf::CalibrationQuantity::kTipAngle);
            }),
            "shear_modulus_pa cannot be fitted to shapes set by the volume of an incompressible fluid "
            "(dead_volume_m3 = 0): the volume alone sets the shape, the modulus only the pressure (compare gauge_pa, "
            "or fit or give dead_volume_m3)");
  EXPECT_EQ(refusal([&] {
              pf::calibrate(base, {"dead_volume_m3"}, volume_only, pf::CalibrationObjective::kMinimax,
                            pf::CalibrationQuantity::kGauge);
            }),
            "line 2: no gauge_pa to compare the model's pressure with");
  EXPECT_EQ(refusal([] { pf::parseDrive("syringe"); }),
            "unknown drive 'syringe'; known: pressure (rows set by gauge_pa), volume (rows set by supplied_volume_m3)");
}

namespace {

// A quick run (no leave-one-out) on a membrane finger with a 1 mm gap, the truth, filled by volume up to @p past
// times its limit point's volume, with the rows' pressures or without; the start has no gap.
struct VolumeRunCase {
  pf::FingerParameters truth, start;
  pf::MeasurementSet set;
  pf::CalibrationRequest request;
};
VolumeRunCase volumeRunCase(double past, bool with_gauge) {
  VolumeRunCase c;
  c.truth = pf_test::membraneFinger(0.0, "chamber_gap_m: 1e-3\n");
  c.set.rows = filledByVolume(c.truth, past, with_gauge);
  c.request.leave_one_out = false;
  c.start = c.truth;
  c.start.chamber_gap_m.assign(c.start.chamber_gap_m.size(), 0.0);
  return c;
}

}  // namespace

// runCalibration (finger_calibrate, pf.calibrate): with no drive named, a file without gauge_pa is driven by volume.
TEST(CalibrationByVolume, ARunWithoutPressuresIsDrivenByVolume) {
  VolumeRunCase c = volumeRunCase(2.0, false);
  c.request.keys = {"chamber_gap_m"};
  c.request.compare = "tip_angle";
  const pf::CalibrationRun run = pf::runCalibration(c.start, c.set, c.request);
  EXPECT_TRUE(run.by_volume);
  EXPECT_NEAR(run.best().fit.values[0], 1e-3, 1e-3 * 1e-6);
  c.request.drive = "pressure";
  EXPECT_EQ(refusal([&] { pf::runCalibration(c.start, c.set, c.request); }),
            "line 1: no gauge_pa to drive the finger by pressure (drive it by volume, or give the column)");
}

// Filled by volume with the pressure measured, and nothing named to compare: the run compares the bend and the
// pressure together, so that mu, which the bend alone cannot fix under an incompressible fill, is fitted (before, the
// default compared the bend alone and refused mu: a segment filled by volume could not be calibrated with --drive
// volume and the default keys, nor with --wall-law auto). The truth's mu and c come back.
TEST(CalibrationByVolume, ByVolumeWithPressuresTheDefaultComparesBendAndPressure) {
  VolumeRunCase c = volumeRunCase(0.9, true);
  c.request.drive = "volume";
  c.request.keys = {"shear_modulus_pa", "chamber_gap_m"};
  const double mu = c.truth.shear_modulus_pa[0];
  c.start.shear_modulus_pa.assign(c.start.shear_modulus_pa.size(), 3.0 * mu);
  const pf::CalibrationRun run = pf::runCalibration(c.start, c.set, c.request);
  EXPECT_EQ(run.quantity, pf::CalibrationQuantity::kTipAngleAndGauge);
  EXPECT_NEAR(run.best().fit.values[0], mu, 1e-6 * mu);
  EXPECT_NEAR(run.best().fit.values[1], 1e-3, 1e-3 * 1e-6);
  for (pf::Measurement& m : c.set.rows) m.gauge_pa = NAN;  // without pressures: the bend alone, as before
  c.request.keys = {"chamber_gap_m"};
  EXPECT_EQ(pf::runCalibration(c.start, c.set, c.request).quantity, pf::CalibrationQuantity::kTipAngle);
}

// Driven by volume with no gas given or fitted, the run says that the volume is read as an incompressible fill's, and
// how to fit the gas (with pressures) or give it (without); a gas given, or a run by pressure, gets no such warning.
TEST(CalibrationByVolume, ByVolumeWithoutGasTheRunSaysHowToFitIt) {
  VolumeRunCase c = volumeRunCase(0.9, true);
  c.request.keys = {"chamber_gap_m"};
  c.request.compare = "tip_angle";
  const auto gasWarnings = [&c] {
    std::vector<std::string> found;
    for (const std::string& w : pf::runCalibration(c.start, c.set, c.request).warnings) {
      if (w.rfind("driven by volume with dead_volume_m3 = 0", 0) == 0) found.push_back(w);
    }
    return found;
  };
  c.request.drive = "volume";
  std::vector<std::string> found = gasWarnings();
  ASSERT_EQ(found.size(), 1u);
  EXPECT_NE(found[0].find("fit it first (--drive volume --compare gauge_pa --fit dead_volume_m3) or give it "
                          "(--set dead_volume_m3=V;"),
            std::string::npos)
      << found[0];
  c.request.drive = "pressure";
  EXPECT_TRUE(gasWarnings().empty());
  c.request.drive = "volume";
  c.start.dead_volume_m3 = 1e-6;
  EXPECT_TRUE(gasWarnings().empty());
  c.start.dead_volume_m3 = 0.0;
  for (pf::Measurement& m : c.set.rows) m.gauge_pa = NAN;  // nothing to fit the gas to: give it
  found = gasWarnings();
  ASSERT_EQ(found.size(), 1u);
  EXPECT_NE(found[0].find("share: give it (--set dead_volume_m3=V;"), std::string::npos) << found[0];
}

// A header that cannot be read says what it probably meant, and data given as columns name their
// rows as rows everywhere (before: "row 6" in one message, "line 1" in another).
TEST(CalibrationData, RefusalsGiveTheLikelyCauseAndNameRowsOneWay) {
  EXPECT_EQ(refusal([] { pf::parseMeasurementSet("gauge_pa;tip_angle_rad\n1000;0.1\n", "m.csv", 1); }),
            "m.csv:1: the header 'gauge_pa;tip_angle_rad' is separated by ';': the package reads comma-separated values "
            "with a decimal point (export the sheet as CSV with ',' between fields and '.' in numbers)");
  EXPECT_EQ(refusal([] { pf::parseMeasurementSet("pressure_kpa,tip_angle_rad\n10,0.1\n", "m.csv", 1); }),
            "m.csv:1: header has no 'gauge_pa' column (nor 'supplied_volume_m3', for a finger set by volume); column "
            "'pressure_kpa' looks like a pressure: give it as gauge_pa, gauge pressure in Pa (1 kPa = 1000 Pa, 1 bar = "
            "100000 Pa, 1 psi = 6894.76 Pa)");
  const pf::MeasurementSet table =
      pf::measurementSetFromColumns({"gauge_pa", "tip_angle_rad"}, {{1000, 2000}, {0.1, 40.0}}, "data", 1, "");
  EXPECT_EQ(table.rows[1].where(), "row 2");
  EXPECT_EQ(refusal([&] { pf::checkMeasurementsPlausible(pf::FingerParameters::defaults(), table.rows); }).rfind(
                "row 2: tip_angle_rad = 40 rad is beyond 2 pi", 0),
            0u);
  const pf::MeasurementSet file = pf::parseMeasurementSet("gauge_pa,tip_angle_rad\n1000,0.1\n", "m.csv", 1);
  EXPECT_EQ(file.rows[0].where(), "line 2");
}
