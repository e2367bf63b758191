// The inverse model (finger_inverse.cpp): the pressure for a tip angle, in closed form for identical chambers and by
// bisection otherwise, round-trips through the forward model.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "pneumatic_finger/core/finger_model.hpp"

namespace pf = pneumatic_finger;

TEST(FingerInverse, InverseModelRoundTrips) {
  pf::FingerModel model(pf::FingerParameters::defaults());
  pf::FingerWorkspace ws(model);
  for (double p : {1e4, 5e4, 1e5, 1.5e5, 2e5}) {
    const double tip = model.evaluate(p, ws).tip_angle_rad;
    double back = 0;
    std::string why;
    ASSERT_TRUE(model.gaugeForTipAngle(tip, 1e6, back, why)) << why;
    EXPECT_NEAR(back, p, 1e-9 * p);
  }
  double out = 0;
  std::string why;
  EXPECT_FALSE(model.gaugeForTipAngle(-0.1, 1e6, out, why));
  EXPECT_NE(why.find("-0.1"), std::string::npos) << why;
  EXPECT_FALSE(model.gaugeForTipAngle(3.0, 2e5, out, why));  // needs more than 2e5 Pa
  EXPECT_NE(why.find("needs more than"), std::string::npos) << why;
  EXPECT_FALSE(model.gaugeForTipAngle(100.0, 1e300, out, why));  // beyond (2N-1) pi/2
}

TEST(FingerInverse, InverseModelBisectsForUnequalChambers) {
  pf::RawParameterMap raw;
  raw["chamber_gap_m"] = {{3e-5, 4e-5, 5e-5, 6e-5, 7e-5, 8e-5, 9e-5}, true};
  pf::FingerModel model(pf::FingerParameters::fromRaw(raw));
  pf::FingerWorkspace ws(model);
  const double tip = model.evaluate(1.2e5, ws).tip_angle_rad;
  double back = 0;
  std::string why;
  ASSERT_TRUE(model.gaugeForTipAngle(tip, 1e6, back, why)) << why;
  EXPECT_NEAR(back, 1.2e5, 1e-6);
}
