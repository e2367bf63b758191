// The tip's error bar (core/tip_uncertainty.hpp): its interpolation, its refusals, the parameter file round trip, and
// the calibration that makes it.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "pneumatic_finger/core/calibration.hpp"
#include "pneumatic_finger/core/parameters.hpp"
#include "pneumatic_finger/core/tip_uncertainty.hpp"
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

}  // namespace

TEST(TipUncertainty, LinearFromRestThroughTheCalibratedPressuresThenFlaggedAbove) {
  // Rest: exact (the straight finger needs no calibration); from 0 to the first pressure and between them: linear.
  EXPECT_EQ(kBar.at(0.0).tip_angle_rad, 0.0);
  EXPECT_EQ(kBar.at(-5.0).tip_position_m, 0.0);
  EXPECT_DOUBLE_EQ(kBar.at(5e4).tip_angle_rad, 0.01);
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

TEST(TipUncertainty, TheCalibrationsBarIsTheLargerOfFitAndLeaveOneOut) {
  // Two rows, made up: the bar at each is the larger |error| of the two, for the angle and the position.
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
  const pf::TipUncertainty bar = pf::tipUncertainty(fits, loos);
  ASSERT_EQ(bar.gauge_pa, (std::vector<double>{1e5, 2e5}));  // sorted by pressure
  EXPECT_NEAR(bar.tip_angle_rad[0], 0.1, 1e-15);   // leave-one-out's
  EXPECT_NEAR(bar.tip_angle_rad[1], 0.1, 1e-15);   // the fit's
  EXPECT_EQ(bar.tip_position_m[0], 0.001);         // the fit's
  EXPECT_EQ(bar.tip_position_m[1], 0.004);         // leave-one-out's
}
