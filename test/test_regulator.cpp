// The cell's pressure source: constant flow into ideal-spring chambers (the paper's eq 2-4).
#include <gtest/gtest.h>

#include "pneumatic_finger/core/regulator.hpp"
#include "pneumatic_finger/core/stages.hpp"

namespace pf = pneumatic_finger;

TEST(Regulator, RestVolumeIsTheSumOfChamberVolumes) {
  const auto p = pf::FingerParameters::defaults();
  EXPECT_DOUBLE_EQ(pf::restVolumeM3(p, 3), 3 * 7 * 0.0115 * 0.005 * 0.007);
}

TEST(Regulator, ConstantFlowGivesALinearGaugeRampAndEq4sEnergy) {
  const double p_o = 101325, v_o = 8.45e-6, q = 1.6e-5, mu = 2.2e8;
  const double rate = pf::fillRatePaPerS(q, v_o, p_o);
  for (double t : {0.1, 0.5, 1.0}) {
    // Ideal spring: P_abs = P_o V / V_o with V = V_o + Q t.
    const double v = v_o + q * t;
    const double gauge = p_o * v / v_o - p_o;
    EXPECT_NEAR(rate * t, gauge, 1e-9 * gauge);
    // Eq 2 by the trapezoid rule, independent of eq 4's closed form.
    double w = 0;
    const int steps = 100000;
    for (int i = 0; i < steps; ++i) {
      const double a = v_o + (v - v_o) * i / steps, b = v_o + (v - v_o) * (i + 1) / steps;
      w += 0.5 * (p_o * a / v_o + p_o * b / v_o) * (b - a);
    }
    // docs/MODEL.md stage 1: g = 2 (W / V_o) / mu is the energy group of the ramp's gauge pressure.
    EXPECT_NEAR(2 * w / v_o / mu, pf::energyGroup(gauge, p_o, mu), 1e-12);
  }
}

TEST(Regulator, FillsToTheSetpointHoldsItAndVents) {
  double p = 0;
  for (int i = 0; i < 150; ++i) p = pf::regulatorStep(p, 196133, 196133, 0.01);  // 1.5 s at 2 kg/cm^2 per second
  EXPECT_EQ(p, 196133);                                                          // reached after 1 s, then held
  p = pf::regulatorStep(p, 0, 196133, 0.5);
  EXPECT_NEAR(p, 196133 / 2.0, 1e-9);
  p = pf::regulatorStep(p, 0, 196133, 10);
  EXPECT_EQ(p, 0);
}
