// A part held by its side (core/side_grip.hpp): the pressure it returns is the lowest at which the cell's grasp rule
// holds, checked on a strip built here and on the cell's own geometry (config/gripper.yaml's fingers closing on a
// finite cylinder, src/cell/side_grasp.cpp); its defaults are the shipped gripper's; bad parts are refused by name.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "pneumatic_finger/cell/side_grasp.hpp"
#include "pneumatic_finger/core/contact.hpp"
#include "pneumatic_finger/core/side_grip.hpp"
#include "pneumatic_finger/core/yaml_parameters.hpp"

namespace pf = pneumatic_finger;

namespace {

const std::string kSource = PACKAGE_SOURCE_DIR;

pf::FingerParameters fromFile(const std::string& name, const pf::RawParameterMap& extra = {}) {
  pf::RawParameterMap raw;
  pf::loadRawParametersFromYamlFile(kSource + "/config/" + name, raw);
  for (const auto& [key, value] : extra) raw[key] = value;
  return pf::FingerParameters::fromRaw(raw);
}

// A 20 g part of 30 mm lifted at 2 m/s^2 by the shipped gripper, up to the shipped finger's range.
pf::SideGripTask part() {
  pf::SideGripTask t = pf::parseSideGripTask("mass_kg=0.02,diameter_m=0.03,lift_mps2=2");
  t.max_gauge_pa = 294199.5;
  return t;
}

// The finger's total normal force on the side, built here from the numbers: the strip 20 mm to 50 mm off the
// finger's axis on its bending side, 1 m long each way.
double forceOnStrip(const pf::FingerModel& model, double gauge_pa) {
  const pf::Obstacle strip = pf::Obstacle::polygon({{-1.0, 0.020}, {1.0, 0.020}, {1.0, 0.050}, {-1.0, 0.050}});
  return pf::totalContactForceN(model, gauge_pa, pf::ContactSolver(model).solve(gauge_pa, strip));
}

}  // namespace

TEST(SideGrip, HoldsAtItsPressureAndNotJustBelow) {
  const pf::FingerModel model(fromFile("finger.yaml"));
  const pf::SideGripTask t = part();
  std::string why;
  const double p = pf::holdingGaugePa(model, t, &why);
  ASSERT_TRUE(std::isfinite(p)) << why;
  const auto at = [&](double gauge) {
    return pf::judgeHold(3, forceOnStrip(model, gauge), 0.02, 1.0, 1.5, 2.0).holds;
  };
  EXPECT_TRUE(at(p));
  EXPECT_FALSE(at(p * (1.0 - 1e-7)));
}

// The shipped gripper's fingers (config/gripper.yaml), their mounts exact: the file writes them to 8 decimals (pi as
// 3.14159265). Each sits at its angle on the ring, pitched -pi/2 along the axis and rolled by its angle + pi/2 so
// that its bending side faces the axis.
std::vector<pf::GripperFinger> exactRing() {
  auto fingers = pf::loadGripperFile(kSource + "/config/gripper.yaml");
  for (auto& f : fingers) {
    const double angle = std::atan2(f.mount.mount_xyz_m[1], f.mount.mount_xyz_m[0]);
    f.mount.mount_xyz_m[0] = 0.035 * std::cos(angle);
    f.mount.mount_xyz_m[1] = 0.035 * std::sin(angle);
    f.mount.mount_rpy_rad = {angle + M_PI / 2, -M_PI / 2, 0.0};
  }
  return fingers;
}

TEST(SideGrip, TheStripIsTheCellsCylinderSide) {
  const auto fingers = exactRing();
  constexpr double kRadius = 0.016, kHeight = 0.035;  // config/cell.yaml's cylinder
  const double depth = pf::sideGraspDepth(fingers, kRadius, kHeight).centre_depth_m;
  pf::SideGripTask t = part();
  t.diameter_m = 2.0 * kRadius;
  for (const double gauge : {100e3, 200e3, 290e3}) {
    const pf::SideGraspForces cell = pf::sideGraspForces(fingers, kRadius, kHeight, depth, gauge);
    for (std::size_t i = 0; i < fingers.size(); ++i) {
      const pf::FingerModel model(fingers[i].parameters);
      const pf::Obstacle side = pf::partSideInFingerPlane(model, t);
      const double strip_n = pf::totalContactForceN(model, gauge, pf::ContactSolver(model).solve(gauge, side));
      ASSERT_GT(cell.normal_force_n[i], 0.0) << gauge;
      EXPECT_NEAR(strip_n, cell.normal_force_n[i], 1e-9 * cell.normal_force_n[i]) << fingers[i].mount.prefix << gauge;
    }
  }
}

TEST(SideGrip, TheDefaultsAreTheShippedGrippers) {
  const auto fingers = pf::loadGripperFile(kSource + "/config/gripper.yaml");
  const pf::SideGripTask defaults;
  ASSERT_EQ(static_cast<int>(fingers.size()), defaults.finger_count);
  for (const auto& f : fingers) {
    EXPECT_NEAR(std::hypot(f.mount.mount_xyz_m[0], f.mount.mount_xyz_m[1]), defaults.mount_radius_m, 1e-7);
    EXPECT_NEAR(f.mount.mount_rpy_rad[1], -M_PI / 2, 1e-7) << "pointing along the gripper's axis";
  }
  EXPECT_EQ(defaults.friction_coefficient, 1.0);  // cell_sequencer's friction_coefficient and hold_margin
  EXPECT_EQ(defaults.hold_margin, 1.5);
}

// A wall of 4 mm balloons at its limit point (about 24 kPa): the grip is sought below limit_share of it.
TEST(SideGrip, StopsShortOfTheLimitPoint) {
  const pf::FingerModel model(fromFile("epfl_ecoflex30_c7.yaml", {{"drawing/wall_thickness_m", {{0.004}, false}}}));
  ASSERT_TRUE(std::isfinite(model.limitGaugePa()));
  pf::SideGripTask t = pf::parseSideGripTask("mass_kg=0.002,diameter_m=0.03");
  t.max_gauge_pa = 5e4;
  for (const double share : {0.5, 0.9, 1.0}) {
    t.limit_share = share;
    std::string why;
    const double p = pf::holdingGaugePa(model, t, &why);
    if (std::isnan(p)) {
      EXPECT_NE(why.find("limit point"), std::string::npos) << why;
    } else {
      EXPECT_LE(p, share * model.limitGaugePa());
    }
  }
  t.limit_share = 1.0;
  EXPECT_TRUE(std::isfinite(pf::holdingGaugePa(model, t))) << "a 2 g part is held before the walls balloon";
  t.limit_share = 0.5;
  EXPECT_TRUE(std::isnan(pf::holdingGaugePa(model, t))) << "but not by half the limit point";
}

TEST(SideGrip, RefusesWhatIsNotAPart) {
  const auto message = [](const std::string& text) {
    try {
      pf::parseSideGripTask(text);
    } catch (const pf::ParameterError& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  EXPECT_NE(message("mass_kg=0.02").find("mass_kg and diameter_m are needed"), std::string::npos);
  EXPECT_NE(message("mass_kg=0.02,diameter_m=0.08").find("does not fit between the fingers' bases"),
            std::string::npos);
  EXPECT_NE(message("mass_kg=-1,diameter_m=0.03").find("mass_kg -1 is not a mass > 0"), std::string::npos);
  EXPECT_NE(message("mass_kg=0.1,diameter_m=0.03,fingers=2.5").find("fingers is a whole number"), std::string::npos);
  EXPECT_NE(message("mass_kg=0.1,diameter_m=0.03,colour=3").find("'colour=3' is not a part's"), std::string::npos);
  EXPECT_NE(message("mass_kg=0.1,diameter_m=x").find("diameter_m 'x' is not a finite number"), std::string::npos);
  EXPECT_NE(message("mass_kg=0.1,diameter_m=0.03,limit_share=1.5").find("limit_share must be in (0, 1]"),
            std::string::npos);
  const pf::FingerModel model(fromFile("finger.yaml"));
  pf::SideGripTask no_top = pf::parseSideGripTask("mass_kg=0.1,diameter_m=0.03");
  EXPECT_THROW(pf::holdingGaugePa(model, no_top), pf::ParameterError);  // no highest pressure given
}
