// The tip's error bar (core/tip_uncertainty.hpp): its interpolation, its refusals, the parameter file round trip, and
// the calibration that makes it.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "pneumatic_finger/calibration/calibration.hpp"
#include "pneumatic_finger/core/parameters.hpp"
#include "pneumatic_finger/calibration/calibration_run.hpp"
#include "pneumatic_finger/core/finger_model.hpp"
#include "pneumatic_finger/core/tip_uncertainty.hpp"
#include "pneumatic_finger/core/units.hpp"
#include "pneumatic_finger/core/yaml_parameters.hpp"

namespace pf = pneumatic_finger;

namespace {

const pf::TipUncertainty kBar = pf::TipUncertainty::fromLists({1e5, 2e5}, {0.02, 0.06}, {0.001, 0.003}, "test");

std::string refusal(const std::vector<double>& p, const std::vector<double>& a, const std::vector<double>& x) {
  try {
    pf::TipUncertainty::fromLists(p, a, x, "f.yaml");
  } catch (const pf::ParameterError& e) {
    return e.what();
  }
  return "(accepted)";
}

// A calibration's residual at @p p: the tip angle, model and measured, and no tip position.
pf::Residual row(double p, double model_angle, double measured_angle) {
  pf::Residual r{};
  r.gauge_pa = p;
  r.model_tip_angle_rad = model_angle;
  r.measured_tip_angle_rad = measured_angle;
  r.model_tip_x_m = r.model_tip_y_m = std::nan("");
  r.measured_tip_x_m = r.measured_tip_y_m = std::nan("");
  return r;
}

}  // namespace

TEST(TipUncertainty, LinearFromRestThroughTheCalibratedPressuresThenFlaggedAbove) {
  // Rest: exact (the straight finger needs no calibration); from 0 to the first pressure and between them: linear.
  EXPECT_EQ(kBar.at(0.0).tip_angle_rad, 0.0);
  EXPECT_EQ(kBar.at(-5.0).tip_position_m, 0.0);
  EXPECT_FALSE(kBar.at(0.0).extrapolated);
  // Below the first calibrated pressure (1e5 Pa): its bar, flagged (it once shrank to 0, unflagged).
  EXPECT_EQ(kBar.at(5e4).tip_angle_rad, kBar.tip_angle_rad[0]);
  EXPECT_EQ(kBar.at(1.0).tip_position_m, kBar.tip_position_m[0]);
  EXPECT_TRUE(kBar.at(5e4).extrapolated);
  EXPECT_FALSE(kBar.at(1e5).extrapolated);
  EXPECT_DOUBLE_EQ(kBar.at(1.5e5).tip_angle_rad, 0.04);
  EXPECT_DOUBLE_EQ(kBar.at(1.5e5).tip_position_m, 0.002);
  EXPECT_EQ(kBar.at(2e5).tip_angle_rad, 0.06);
  EXPECT_FALSE(kBar.at(2e5).extrapolated);
  // Above the last calibrated pressure: said to be a guess, and growing with the pressure.
  const pf::TipUncertainty::At above = kBar.at(3e5);
  EXPECT_TRUE(above.extrapolated);
  EXPECT_DOUBLE_EQ(above.tip_angle_rad, 0.09);
  EXPECT_DOUBLE_EQ(above.tip_position_m, 0.0045);
  // None at all: NaN, not zero.
  EXPECT_TRUE(std::isnan(pf::TipUncertainty{}.at(1e5).tip_angle_rad));
  EXPECT_TRUE(std::isnan(kBar.at(NAN).tip_position_m));
}

TEST(TipUncertainty, MalformedListsAreRefusedNamingTheEntry) {
  EXPECT_NE(refusal({1e5, 2e5}, {0.1}, {0.1, 0.1}).find("f.yaml: tip_uncertainty: gauge_pa, tip_angle_rad and "
                                                         "tip_position_m must have the same length (2, 1, 2)"),
            std::string::npos);
  EXPECT_NE(refusal({2e5, 1e5}, {0.1, 0.1}, {0.1, 0.1}).find("gauge_pa = 100000 (entry 2) must be finite, > 0 and "
                                                            "ascending"),
            std::string::npos);
  EXPECT_NE(refusal({0.0}, {0.1}, {0.1}).find("(entry 1)"), std::string::npos);
  // Numbers in messages as a person wrote them (formatMessage), not the double's 17 digits.
  EXPECT_NE(refusal({1e5}, {-0.1}, {0.1}).find("tip_angle_rad = -0.1 (entry 1)"), std::string::npos);
  EXPECT_NE(refusal({1e5}, {NAN}, {NAN}).find("entry 1 has neither tip_angle_rad nor tip_position_m"),
            std::string::npos);
  EXPECT_EQ(refusal({1e5}, {NAN}, {0.1}), "(accepted)");  // tip positions from a camera: no angle was measured
  EXPECT_NE(refusal({1e5}, {0.1}, {INFINITY}).find("tip_position_m = inf"), std::string::npos);
  EXPECT_EQ(refusal({1e5}, {0.1}, {NAN}), "(accepted)");  // tip-angle data: the position was not measured
}

TEST(TipUncertainty, TheParameterFileCarriesItAndEveryReaderChecksIt) {
  const std::string text = pf::parametersToYaml(pf::FingerParameters::defaults()) + pf::tipUncertaintyToYaml(kBar);
  auto read = [](const std::string& yaml) {
    pf::RawParameterMap raw;
    pf::TipUncertainty bar;
    pf::loadRawParametersFromYamlText(yaml, "f.yaml", raw, &bar);
    return bar;
  };
  const pf::TipUncertainty back = read(text);
  EXPECT_EQ(back.gauge_pa, kBar.gauge_pa);
  EXPECT_EQ(back.tip_angle_rad, kBar.tip_angle_rad);
  EXPECT_EQ(back.tip_position_m, kBar.tip_position_m);
  // The actuator loader skips it (it is not an actuator key) but refuses it malformed, as every reader does.
  pf::RawParameterMap raw;
  EXPECT_NO_THROW(pf::loadRawParametersFromYamlText(text, "f.yaml", raw));
  EXPECT_THROW(pf::loadRawParametersFromYamlText("tip_uncertainty: {gauge_pa: [1e5], tip_angle_rad: [0.1]}", "f.yaml",
                                                 raw),
               pf::ParameterError);
  EXPECT_THROW(read("tip_uncertainty: {gauges: [1]}"), pf::ParameterError);
  EXPECT_TRUE(read("chamber_count: 7\n").empty());
  // The shipped file has one: the calibration's, at the four pressures of Table 1.
  pf::TipUncertainty shipped;
  pf::loadRawParametersFromYamlFile(std::string(PACKAGE_SOURCE_DIR) + "/config/finger.yaml", raw, &shipped);
  EXPECT_EQ(shipped.gauge_pa, (std::vector<double>{49033.25, 98066.5, 147099.75, 196133.0}));
}

TEST(TipUncertainty, TheCalibrationsBarIsTheLargestOfFitLeaveOneOutAndTheFitsScatter) {
  // Two rows, made up: the bar at each is the largest of the two |errors| and the fit's scatter, sqrt(sum e^2 /
  // (n - k)), here with n - k = 1: angles sqrt(0.1^2 + 0.05^2), positions sqrt(0.002^2 + 0.001^2).
  auto row = [](double p, double model_angle, double measured_angle, double dx) {
    pf::Residual r{};
    r.gauge_pa = p;
    r.model_tip_angle_rad = model_angle;
    r.measured_tip_angle_rad = measured_angle;
    r.model_tip_x_m = dx;
    r.model_tip_y_m = 0.0;
    r.measured_tip_x_m = 0.0;
    r.measured_tip_y_m = 0.0;
    return r;
  };
  const std::vector<pf::Residual> fits = {row(2e5, 1.0, 1.1, 0.002), row(1e5, 0.5, 0.45, 0.001)};
  const std::vector<pf::Residual> loos = {row(2e5, 1.0, 1.05, 0.004), row(1e5, 0.5, 0.6, 0.0005)};
  const pf::TipUncertainty bar = pf::tipUncertainty(fits, loos, 1);
  ASSERT_EQ(bar.gauge_pa, (std::vector<double>{1e5, 2e5}));  // sorted by pressure
  EXPECT_NEAR(bar.tip_angle_rad[0], std::sqrt(0.0125), 1e-15);  // the scatter, above both rows' 0.05 and 0.1
  EXPECT_NEAR(bar.tip_angle_rad[1], std::sqrt(0.0125), 1e-15);
  EXPECT_NEAR(bar.tip_position_m[0], std::sqrt(5e-6), 1e-15);    // the scatter, above the fit's 0.001
  EXPECT_EQ(bar.tip_position_m[1], 0.004);                       // leave-one-out's, above the scatter
  // With no keys fitted and many rows the floor is the rows' RMS; with rows the fit hits exactly, none is below it.
  const std::vector<pf::Residual> exact = {row(1e5, 0.5, 0.5, 0.0), row(2e5, 1.0, 1.02, 0.0), row(3e5, 1.5, 1.48, 0.0)};
  const pf::TipUncertainty hit = pf::tipUncertainty(exact, exact, 0);
  EXPECT_NEAR(hit.tip_angle_rad[0], std::sqrt(0.0008 / 3), 1e-15) << "the row the fit hits gets the scatter";
}

// A row whose pressure is beyond the fitted model's limit point has a measured bend and no model shape. It once made
// the calibration throw ("entry 16 has neither tip_angle_rad nor tip_position_m") on a segment whose plateau passes
// the limit (the cylindrical drawing with --wall-law auto). The model publishes no shape there, so no bar is written
// at that pressure; the other rows keep theirs.
TEST(TipUncertainty, ARowWhereTheModelHasNoShapeGetsNoBar) {
  const std::vector<pf::Residual> fits = {row(1e5, 0.5, 0.6), row(2e5, std::nan(""), 1.4), row(3e5, 1.5, 1.45)};
  const pf::TipUncertainty bar = pf::tipUncertainty(fits, fits, 0);
  ASSERT_EQ(bar.gauge_pa, (std::vector<double>{1e5, 3e5}));
  EXPECT_NEAR(bar.tip_angle_rad[0], 0.1, 1e-15);  // its own error, above the scatter sqrt((0.01 + 0.0025) / 2)
  EXPECT_NEAR(bar.tip_angle_rad[1], std::sqrt(0.0125 / 2), 1e-15);
}

// A row the leave-one-out cannot predict (the model fitted without it has no shape at its pressure) has only the fit's
// error in its bar, which may be too small: the calibration says so, naming the rows, and says nothing otherwise.
TEST(TipUncertainty, ARowTheLeaveOneOutCannotPredictIsNamed) {
  const std::vector<pf::Residual> fit = {row(1e5, 0.5, 0.6), row(2e5, 1.0, 1.4), row(3e5, 1.5, 1.45)};
  std::vector<pf::Residual> held_out = {row(1e5, 0.7, 0.6), row(2e5, std::nan(""), 1.4), row(3e5, 1.5, 1.45)};
  // The bar at 2e5 Pa is the fit's error alone (0.4), the held-out NaN not counted.
  EXPECT_NEAR(pf::tipUncertainty(fit, held_out, 0).tip_angle_rad[1], 0.4, 1e-15);
  const std::string warning = pf::unpredictedRowsWarning(fit, held_out);
  EXPECT_NE(warning.find("1 row(s) (gauge_pa 200000) have no prediction"), std::string::npos) << warning;
  held_out[1].model_tip_angle_rad = 1.2;
  EXPECT_EQ(pf::unpredictedRowsWarning(fit, held_out), "");
  // A row the fit itself has no shape at gets no bar (above), and no warning: nothing was predicted by the fit either.
  std::vector<pf::Residual> no_shape = fit;
  no_shape[1].model_tip_angle_rad = std::nan("");
  held_out[1].model_tip_angle_rad = std::nan("");
  EXPECT_EQ(pf::unpredictedRowsWarning(no_shape, held_out), "");
}

// With noise on the measured tip angles, the bar was once near 0 at a row the fit
// happened to hit. The reference is the noise put in: tip angles of the package's finger with +1, -1 and 0 degrees
// added in turn (RMS 0.82 degrees), which one fitted key cannot follow; the rows with none are hit, and their bar was
// near 0. Every bar is now at least the noise's size, and the bar says where it is extrapolated.
TEST(TipUncertainty, NoBarIsBelowTheNoiseOfTheMeasurements) {
  const pf::FingerParameters truth = pf::FingerParameters::defaults();
  const pf::FingerModel model(truth);
  pf::FingerWorkspace ws(model);
  const double noise_rad = pf::kPi / 180.0;
  std::vector<double> gauge, angle;
  for (int i = 1; i <= 8; ++i) {
    gauge.push_back(25000.0 * i);
    angle.push_back(model.evaluate(gauge.back(), ws).tip_angle_rad + ((i % 3) - 1) * noise_rad);
  }
  const pf::MeasurementSet data =
      pf::measurementSetFromColumns({"gauge_pa", "tip_angle_rad"}, {gauge, angle}, "noisy", 1);
  pf::CalibrationRequest request;
  request.keys = {"shear_modulus_pa"};
  request.compare = "tip_angle";
  const pf::CalibrationRun run = pf::runCalibration(truth, data, request);
  ASSERT_EQ(run.tip_uncertainty.gauge_pa.size(), 8u);
  for (double bar : run.tip_uncertainty.tip_angle_rad) EXPECT_GE(bar, 0.8 * noise_rad);
  EXPECT_TRUE(run.tip_uncertainty.at(1000.0).extrapolated);
  EXPECT_FALSE(run.tip_uncertainty.at(1e5).extrapolated);
}
