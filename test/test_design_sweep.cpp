// sweepDesigns against one model per design, built and evaluated on its own: the same bits, NaN and the loader's
// message for a refused design, and an unknown key refused before anything runs.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "pneumatic_finger/core/design_sweep.hpp"
#include "pneumatic_finger/core/evaluation_report.hpp"
#include "pneumatic_finger/core/self_contact.hpp"
#include "pneumatic_finger/core/yaml_parameters.hpp"

namespace pf = pneumatic_finger;

namespace {

struct Swept {
  std::vector<double> tip, x, y, contact;
  std::vector<std::uint8_t> status;
  std::vector<pf::DesignRefusal> refused;
};

Swept sweep(const std::vector<std::string>& keys, const std::vector<double>& values, double gauge_pa) {
  const std::size_t designs = values.size() / keys.size();
  Swept s{std::vector<double>(designs), std::vector<double>(designs), std::vector<double>(designs),
          std::vector<double>(designs), std::vector<std::uint8_t>(designs), {}};
  const pf::DesignOutputs out{s.tip.data(), s.x.data(), s.y.data(), s.contact.data(), s.status.data()};
  s.refused = pf::sweepDesigns(pf::FingerParameters::defaults(), pf::ModelOptions(), keys, values.data(), designs,
                               gauge_pa, out);
  return s;
}

}  // namespace

TEST(DesignSweep, EachDesignIsItsOwnModelBitForBit) {
  // Two keys, a chamber count among them: the layout changes within the sweep.
  const std::vector<std::string> keys = {"chamber_gap_m", "chamber_count"};
  const std::vector<double> values = {2e-5, 7, 5e-5, 7, 1e-4, 4, 5e-5, 12, 2e-4, 12};
  const Swept s = sweep(keys, values, 1.5e5);
  ASSERT_TRUE(s.refused.empty());
  for (std::size_t d = 0; d < 5; ++d) {
    pf::RawParameterMap raw = pf::FingerParameters::defaults().toRaw();
    raw["chamber_gap_m"] = {{values[2 * d]}, false};
    raw["chamber_count"] = {{values[2 * d + 1]}, false};
    const pf::FingerModel model(pf::FingerParameters::fromRaw(raw));
    pf::FingerWorkspace ws(model);
    const pf::FingerState& state = model.evaluate(1.5e5, ws);
    EXPECT_EQ(s.tip[d], state.tip_angle_rad) << d;
    EXPECT_EQ(s.x[d], state.tip().x()) << d;
    EXPECT_EQ(s.y[d], state.tip().y()) << d;
    EXPECT_EQ(s.contact[d], model.contactGaugePa()) << d;
    EXPECT_EQ(s.status[d], static_cast<std::uint8_t>(pf::EvaluationStatus::kOk)) << d;
  }
  EXPECT_GT(s.tip[0], s.tip[2]);  // a wider gap bends less at the same pressure
}

TEST(DesignSweep, ARefusedDesignIsNanWithTheLoadersMessage) {
  const Swept s = sweep({"chamber_gap_m"}, {5e-5, -1.0, 5e-5}, 1e5);
  ASSERT_EQ(s.refused.size(), 1u);
  EXPECT_EQ(s.refused[0].design, 1u);
  EXPECT_NE(s.refused[0].message.find("parameter 'chamber_gap_m' = -1 is outside its allowed range"), std::string::npos)
      << s.refused[0].message;
  EXPECT_TRUE(std::isnan(s.tip[1]) && std::isnan(s.x[1]) && std::isnan(s.contact[1]));
  EXPECT_EQ(s.tip[0], s.tip[2]);
  EXPECT_FALSE(std::isnan(s.tip[2]));
}

TEST(DesignSweep, AnUnknownKeyIsRefusedBeforeAnyDesign) {
  std::vector<double> tip(1, -7.0);
  pf::DesignOutputs out;
  out.tip_angle_rad = tip.data();
  const double value = 1.0;
  EXPECT_THROW(pf::sweepDesigns(pf::FingerParameters::defaults(), pf::ModelOptions(), {"chamber_gapp"}, &value, 1, 1e5,
                                out),
               pf::ParameterError);
  EXPECT_EQ(tip[0], -7.0);
}

// A sibling sweep (the drawing's wall thickness) of the fitted EPFL actuator: each design's snap and limit point are
// those of its own model, built with the snap point asked for. Its 3 mm wall folds (a finite limit point, the snap
// there); the thicker ones lock first (no limit point: inf), and their snap rises with the wall.
TEST(DesignSweep, SnapAndLimitPointAreEachDesignsOwn) {
  pf::RawParameterMap raw;
  pf::loadRawParametersFromYamlFile(std::string(PACKAGE_SOURCE_DIR) + "/config/epfl_ecoflex30_c7.yaml", raw);
  const pf::FingerParameters base = pf::FingerParameters::fromRaw(raw);
  const std::vector<double> walls_m = {0.003, 0.005, 0.007, 0.010};
  std::vector<double> snap(walls_m.size()), limit(walls_m.size());
  pf::DesignOutputs out;
  out.snap_gauge_pa = snap.data();
  out.limit_gauge_pa = limit.data();
  ASSERT_TRUE(pf::sweepDesigns(base, pf::ModelOptions(), {"drawing/wall_thickness_m"}, walls_m.data(), walls_m.size(),
                               0.0, out)
                  .empty());
  for (std::size_t d = 0; d < walls_m.size(); ++d) {
    pf::RawParameterMap own = raw;
    own["drawing/wall_thickness_m"] = {{walls_m[d]}, false};
    pf::ModelOptions options;
    options.snap_point = true;
    const pf::FingerModel model(pf::FingerParameters::fromRaw(own), options);
    EXPECT_EQ(snap[d], model.snapGaugePa()) << walls_m[d];
    EXPECT_EQ(limit[d], model.limitGaugePa()) << walls_m[d];
  }
  EXPECT_TRUE(std::isfinite(limit[0]));
  EXPECT_EQ(snap[0], limit[0]);
  for (std::size_t d = 1; d < walls_m.size(); ++d) {
    EXPECT_TRUE(std::isinf(limit[d])) << walls_m[d];
    EXPECT_GT(snap[d], snap[d - 1]) << walls_m[d];
  }
}

// A sweep reuses one workspace per chamber layout; the walls' branch (the snap's memory) must not travel from one
// design to the next. On the ribbed segment with J_m = 40 at 32 kPa, mu = 22 kPa alone is on its near branch
// (ok, about 1 rad); after mu = 20 kPa, whose walls snap there, it came back 'snapped through' at 15 rad. Each design,
// in either order, is its own model evaluated from rest.
TEST(DesignSweep, ADesignsAnswerDoesNotDependOnTheDesignBeforeIt) {
  pf::RawParameterMap raw;
  pf::loadRawParametersFromYamlFile(std::string(PACKAGE_SOURCE_DIR) + "/config/marchese2015_ribbed.yaml", raw);
  raw["wall_locking_jm"] = {{40.0}, false};
  const pf::FingerParameters base = pf::FingerParameters::fromRaw(raw);
  const double gauge_pa = 32000.0;
  for (const std::vector<double>& mu : {std::vector<double>{20e3, 22e3}, std::vector<double>{22e3, 20e3}}) {
    std::vector<double> tip(2);
    std::vector<std::uint8_t> status(2);
    pf::DesignOutputs out;
    out.tip_angle_rad = tip.data();
    out.status = status.data();
    ASSERT_TRUE(pf::sweepDesigns(base, pf::ModelOptions(), {"shear_modulus_pa"}, mu.data(), 2, gauge_pa, out).empty());
    for (std::size_t d = 0; d < 2; ++d) {
      pf::RawParameterMap one = base.toRaw();
      one["shear_modulus_pa"] = {{mu[d]}, false};
      const pf::FingerModel model(pf::FingerParameters::fromRaw(one));
      pf::FingerWorkspace ws(model);
      const pf::FingerState& state = model.evaluate(gauge_pa, ws);
      EXPECT_NEAR(tip[d], state.tip_angle_rad, 1e-12) << "mu " << mu[d] << " after " << mu[1 - d];
      // The status by the one report every interface gives (a far branch whose backbone crosses itself: 7).
      const bool meets = pf::jointsMeetThemselves(model.parameters(), state.joint_angle_rad.data());
      EXPECT_EQ(status[d], static_cast<std::uint8_t>(pf::reportEvaluation(state.status, {}, meets).status))
          << "mu " << mu[d];
    }
  }
}
