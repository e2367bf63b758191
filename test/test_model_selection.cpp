// --wall-law auto's choice (model_selection.hpp): the yardstick against hand-computed values, the paired rule, and
// the selection recovering the keys a known actuator was made with.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "pneumatic_finger/calibration/model_selection.hpp"
#include "pneumatic_finger/core/yaml_parameters.hpp"

namespace pf = pneumatic_finger;

namespace {

pf::Residual residual(double measured_tip, double model_tip, double measured_chord, double model_chord) {
  const double nan = std::nan("");
  pf::Residual r{};
  r.gauge_pa = r.measured_gauge_pa = r.model_gauge_pa = 1e4;
  r.supplied_volume_m3 = nan;
  r.measured_avg_rad = r.model_avg_rad = r.measured_joint1_rad = r.model_joint1_rad = nan;
  r.measured_tip_x_m = r.measured_tip_y_m = r.model_tip_x_m = r.model_tip_y_m = nan;
  r.model_gauge_at_tip_angle_pa = nan;
  r.measured_blocked_force_n = r.model_blocked_force_n = nan;  // no force measured
  r.force_scale_n = 1.0;
  r.measured_tip_angle_rad = measured_tip;
  r.model_tip_angle_rad = model_tip;
  r.measured_chord_angle_rad = measured_chord;
  r.model_chord_angle_rad = model_chord;
  return r;
}

pf::FingerParameters load(const std::string& file) {
  pf::RawParameterMap raw;
  pf::loadRawParametersFromYamlFile(std::string(PACKAGE_SOURCE_DIR) + "/config/" + file, raw);
  return pf::FingerParameters::fromRaw(raw);
}

}  // namespace

// Each row's squared bend error: the tip angle where measured, else the chord; a row without a shape a quarter turn.
TEST(ModelSelection, TheYardstickIsTheRowsBendsHeldOut) {
  const double nan = std::nan("");
  const std::vector<pf::Residual> rows = {residual(0.5, 0.6, nan, nan), residual(0.5, 0.3, 0.2, 0.9),
                                          residual(nan, nan, 0.2, 0.5), residual(0.4, nan, nan, nan)};
  const pf::HeldOutError e = pf::heldOutError(rows, false);
  const double q = M_PI / 2;
  const std::vector<double> expected = {0.01, 0.04, 0.09, q * q};
  ASSERT_EQ(e.row_squared.size(), 4u);
  for (std::size_t i = 0; i < 4; ++i) EXPECT_NEAR(e.row_squared[i], expected[i], 1e-15);
  const double mean = (0.01 + 0.04 + 0.09 + q * q) / 4;
  EXPECT_NEAR(e.score, std::sqrt(mean), 1e-15);
  EXPECT_NEAR(e.bend_rad, std::sqrt(mean), 1e-15);
  EXPECT_EQ(e.pressure, 0.0);
  EXPECT_EQ(e.unshaped, 1);
  double var = 0.0;
  for (double x : expected) var += (x - mean) * (x - mean) / 3.0;
  EXPECT_NEAR(e.standard_error, std::sqrt(var / 4.0) / (2.0 * std::sqrt(mean)), 1e-15);
  // By volume, a row's pressure joins its bend: 1 rad of bend weighs as the whole pressure.
  std::vector<pf::Residual> by_volume = {residual(0.5, 0.6, nan, nan)};
  by_volume[0].model_gauge_pa = 1.2e4;  // 20 % high
  const pf::HeldOutError v = pf::heldOutError(by_volume, true);
  EXPECT_NEAR(v.row_squared[0], 0.01 + 0.04, 1e-15);
  EXPECT_NEAR(v.pressure, 0.2, 1e-15);
  EXPECT_NEAR(v.bend_rad, 0.1, 1e-15);
}

// Paired: a gain on every row clears the bar; one row's large gain against the others' losses does not.
TEST(ModelSelection, ClearlyBetterIsAPairedOneStandardErrorTest) {
  pf::HeldOutError a, b;
  a.row_squared = {1.0, 1.0, 1.0, 1.0, 1.0};
  b.row_squared = {0.9, 0.88, 0.91, 0.89, 0.9};
  a.score = 1.0, b.score = std::sqrt(0.896);
  EXPECT_TRUE(pf::clearlyBetter(b, a));
  EXPECT_FALSE(pf::clearlyBetter(a, b));
  pf::HeldOutError c = b;
  c.row_squared = {0.0, 1.05, 1.05, 1.05, 1.05};  // mean gain 0.16, its standard error 0.21
  EXPECT_FALSE(pf::clearlyBetter(c, a));
  // A gain on every row, tiny and all alike (its standard error near 0), under 1 % of the score: none a user sees.
  pf::HeldOutError d;
  d.row_squared = {0.99, 0.9901, 0.99, 0.9899, 0.99};
  d.score = std::sqrt(0.99);  // 0.5 % below a's
  EXPECT_FALSE(pf::clearlyBetter(d, a));
  d.row_squared = {0.97, 0.9701, 0.97, 0.9699, 0.97};
  d.score = std::sqrt(0.97);  // 1.5 % below
  EXPECT_TRUE(pf::clearlyBetter(d, a));
}

// Chords made by a known thick wall (the shipped EPFL fit: its lock and its tilt), fitted from the coupon's file:
// the selection must grow the keys to both, and its chosen fit must then follow the chords.
TEST(ModelSelection, ForwardSelectionFindsTheKeysTheDataWereMadeWith) {
  const pf::FingerParameters truth = load("epfl_ecoflex30_c7.yaml");
  const pf::FingerModel model(truth);
  pf::FingerWorkspace ws(model);
  std::vector<pf::Measurement> data;
  for (int k = 0; k < 16; ++k) {
    pf::Measurement m;
    m.line = k + 1;
    m.gauge_pa = 12e3 + 2e3 * k;  // 12 to 42 kPa, through the steep rise
    m.chord_angle_rad = model.evaluate(m.gauge_pa, ws).chordAngle();
    data.push_back(m);
  }
  const pf::ModelSelection s = pf::selectModel(load("epfl_ecoflex30_c7_coupon.yaml"), {pf::WallLaw::kThick},
                                               {pf::CalibrationQuantity::kChordAngle}, data,
                                               pf::CalibrationObjective::kMinimax, false);
  const std::vector<std::string>& keys = s.chosen.fit.keys;
  EXPECT_EQ(s.chosen.law, pf::WallLaw::kThick);
  EXPECT_EQ(std::count(keys.begin(), keys.end(), "wall_bulge_share"), 1) << s.tried.size();
  EXPECT_EQ(std::count(keys.begin(), keys.end(), "wall_locking_jm"), 1);
  EXPECT_LT(s.tried[s.chosen_index].held_out.bend_rad, 1e-3);
  EXPECT_GT(s.tried.front().held_out.bend_rad, 0.02);  // mu and c alone cannot follow them
  EXPECT_EQ(s.chosen.leave_one_out.size(), data.size());
}

// Chords and blocked forces made by the shipped EPFL fit with a 10 mm roof, where its drawing leaves the roof to its
// default (7 mm, as thick as the walls). The bend alone cannot tell the roof from kappa and the gap: auto lists the
// roof as skipped, with why. The forces can (their lever is the roof's b): auto fits the roof, and finds the 10 mm.
TEST(ModelSelection, AutoFitsARoofTheDrawingLeavesToItsDefaultWhereTheDataCanTellIt) {
  const pf::FingerParameters base = load("epfl_ecoflex30_c7.yaml");
  ASSERT_EQ(base.drawing.count("drawing/roof_thickness_m"), 0u);
  pf::RawParameterMap raw = base.toRaw();
  raw["drawing/roof_thickness_m"] = pf::RawParameterValue{{0.010}, false};
  const pf::FingerModel model(pf::FingerParameters::fromRaw(raw));
  pf::FingerWorkspace ws(model);
  std::vector<pf::Measurement> data;
  for (int k = 0; k < 16; ++k) {
    pf::Measurement m;
    m.line = k + 1;
    m.gauge_pa = 12e3 + 2e3 * k;
    m.chord_angle_rad = model.evaluate(m.gauge_pa, ws).chordAngle();
    data.push_back(m);
  }
  const auto select = [&base](const std::vector<pf::Measurement>& rows) {
    return pf::selectModel(base, {pf::WallLaw::kThick}, {pf::CalibrationQuantity::kChordAngle}, rows,
                           pf::CalibrationObjective::kMinimax, false);
  };
  const pf::ModelSelection bends = select(data);
  const std::string roof = "drawing/roof_thickness_m";
  const pf::CandidateFit& last = bends.tried.back();
  ASSERT_EQ(last.keys.back(), roof) << pf::candidatesTable(bends.tried, bends.chosen_index);
  EXPECT_NE(last.skipped.find("cannot tell the roof (it sets the walls' lever b"), std::string::npos) << last.skipped;
  EXPECT_EQ(std::count(bends.chosen.fit.keys.begin(), bends.chosen.fit.keys.end(), roof), 0);
  for (int k = 0; k < 8; ++k) {
    pf::Measurement m;
    m.line = 100 + k;
    m.gauge_pa = 5e3 + 5e3 * k;  // through the free finger's limit point: the force is defined past it
    m.blocked_tip_force_n = model.blockedTipForceN(m.gauge_pa);
    data.push_back(m);
  }
  const pf::ModelSelection both = select(data);
  const std::vector<std::string>& keys = both.chosen.fit.keys;
  const auto at = std::find(keys.begin(), keys.end(), roof);
  ASSERT_NE(at, keys.end()) << pf::candidatesTable(both.tried, both.chosen_index);
  EXPECT_NEAR(both.chosen.fit.values[static_cast<std::size_t>(at - keys.begin())], 0.010, 1e-5);
  EXPECT_LT(both.tried[both.chosen_index].held_out.score, 1e-3);
  // Forces made by a 1 mm roof, below a quarter of the drawn 7 mm: the roof runs to its search range's end, and auto
  // skips it (a drawn size the data push out of the drawing's reach stands for what the model lacks).
  raw["drawing/roof_thickness_m"] = pf::RawParameterValue{{0.001}, false};
  const pf::FingerModel thin(pf::FingerParameters::fromRaw(raw));
  std::vector<pf::Measurement> thin_data = data;
  for (pf::Measurement& m : thin_data) {
    if (m.hasBlockedForce()) m.blocked_tip_force_n = thin.blockedTipForceN(m.gauge_pa);
    if (m.hasChordAngle()) m.chord_angle_rad = thin.evaluate(m.gauge_pa, ws).chordAngle();
  }
  const pf::ModelSelection out_of_reach = select(thin_data);
  const pf::CandidateFit& roofed = out_of_reach.tried.back();
  ASSERT_EQ(roofed.keys.back(), roof) << pf::candidatesTable(out_of_reach.tried, out_of_reach.chosen_index);
  EXPECT_NE(roofed.skipped.find("sits on the lower end of its search range"), std::string::npos) << roofed.skipped;
  EXPECT_NE(roofed.skipped.find("the data want a body the drawing is not"), std::string::npos) << roofed.skipped;
  raw["drawing/roof_thickness_m"] = pf::RawParameterValue{{0.010}, false};
  // A drawing that states its roof was measured: auto keeps it.
  const pf::ModelSelection stated = pf::selectModel(pf::FingerParameters::fromRaw(raw), {pf::WallLaw::kThick},
                                                    {pf::CalibrationQuantity::kChordAngle}, data,
                                                    pf::CalibrationObjective::kMinimax, false);
  for (const pf::CandidateFit& c : stated.tried) EXPECT_EQ(std::count(c.keys.begin(), c.keys.end(), roof), 0);
}

// A candidate the data cannot identify is skipped with its reason, and the run goes on (Table 1: four rows).
TEST(ModelSelection, ACandidateTheDataCannotIdentifyIsSkippedNotFatal) {
  pf::FingerParameters base = pf::FingerParameters::defaults();
  const std::vector<pf::Measurement> data =
      pf::readMeasurementsCsv(std::string(PACKAGE_SOURCE_DIR) + "/data/sierra2022_table1.csv", 1);
  const pf::ModelSelection s = pf::selectModel(base, {pf::WallLaw::kPaper, pf::WallLaw::kMembrane},
                                               {pf::CalibrationQuantity::kEveryJoint}, data,
                                               pf::CalibrationObjective::kMinimax, false);
  int skipped = 0;
  for (const pf::CandidateFit& c : s.tried) {
    if (c.skipped.empty()) continue;
    ++skipped;
    EXPECT_NE(c.skipped.find("4 rows; fitting 3 chamber keys with leave-one-out needs at least 5"), std::string::npos)
        << c.skipped;
  }
  EXPECT_EQ(skipped, 2);
  EXPECT_EQ(s.chosen.law, pf::WallLaw::kPaper);  // the membrane does not predict Table 1 clearly better
  const std::string table = pf::candidatesTable(s.tried, s.chosen_index);
  EXPECT_NE(table.find("#   paper; joints; shear_modulus_pa,chamber_gap_m,base_wall_share: held out"), std::string::npos)
      << table;
  EXPECT_NE(table.find("<- chosen"), std::string::npos);
}

// The blocked force as data: a file of forces alone is read (a finger held straight has no shape to measure), and a
// fit to forces made by a known actuator, its pressures past the free finger's limit point included, recovers its
// modulus; each row's model force is the model's own blocked force at the row's pressure.
TEST(ModelSelection, TheBlockedForceIsDataEvenPastTheLimitPoint) {
  const pf::FingerParameters truth = load("epfl_ecoflex30_c7_coupon.yaml");
  const pf::FingerModel model(truth);
  std::string csv = "gauge_pa,blocked_tip_force_n\n";
  for (double p = 5000.0; p <= 40000.0; p += 5000.0) {  // the free finger's limit point: 24.2 kPa
    csv += pf::formatExact(p) + "," + pf::formatExact(model.blockedTipForceN(p)) + "\n";
  }
  std::vector<pf::Measurement> data = pf::parseMeasurementsCsv(csv, "force.csv", 4);
  ASSERT_TRUE(data.front().forceOnly());
  pf::setForceScale(data);
  pf::FingerParameters start = truth;
  start.shear_modulus_pa.assign(start.shear_modulus_pa.size(), 2e4 * 1.5);
  const pf::CalibrationResult fit = pf::calibrate(start, {"shear_modulus_pa"}, data, pf::CalibrationObjective::kMinimax,
                                                  pf::CalibrationQuantity::kTipAngle);
  EXPECT_NEAR(fit.values[0], truth.shear_modulus_pa[0], truth.shear_modulus_pa[0] * 1e-6);
  for (std::size_t i = 0; i < data.size(); ++i) {
    const pf::Residual& r = fit.residuals[i];
    EXPECT_EQ(r.measured_blocked_force_n, data[i].blocked_tip_force_n);
    EXPECT_TRUE(r.force_only);
    EXPECT_EQ(r.terms(pf::CalibrationQuantity::kTipAngle).size(), 1u);  // the force's term alone
    EXPECT_NEAR(r.blocked_force_error_n(), 0.0, 1e-9);
  }
}

// Bends and forces of one actuator in two files are one data set: each file's rows, its notes named by file.
TEST(ModelSelection, TwoFilesOfOneActuatorAreOneDataSet) {
  const std::string root = std::string(PACKAGE_SOURCE_DIR) + "/data/";
  const pf::MeasurementSet set = pf::readMeasurementSets(
      {root + "epfl_ecoflex30_c7_bending.csv", root + "epfl_ecoflex30_c7_blocked_force.csv"}, 4);
  const pf::MeasurementSet bends = pf::readMeasurementSet(root + "epfl_ecoflex30_c7_bending.csv", 4);
  const pf::MeasurementSet forces = pf::readMeasurementSet(root + "epfl_ecoflex30_c7_blocked_force.csv", 4);
  ASSERT_EQ(set.rows.size(), bends.rows.size() + forces.rows.size());
  EXPECT_TRUE(set.rows[bends.rows.size()].forceOnly());
  EXPECT_EQ(set.rows[bends.rows.size()].blocked_tip_force_n, forces.rows[0].blocked_tip_force_n);
  EXPECT_EQ(pf::defaultQuantity(set.rows), pf::CalibrationQuantity::kChordAngle);
  ASSERT_EQ(set.notes.size(), 2u);
  EXPECT_EQ(set.notes[1].rfind(root + "epfl_ecoflex30_c7_blocked_force.csv: columns not read: n", 0), 0u)
      << set.notes[1];
}

// The choice's optimism by Tibshirani & Tibshirani's rule, by hand: 16 rows in 8 interleaved folds (rows i and i + 8).
// The chosen misses every row by 1 (squared); another candidate misses fold 0's two rows by 0.5 and the rest by 2.
// Fold 0: the chosen misses 0.5 more than the best there; every other fold: the chosen is the best. The mean over
// the 8 folds: 0.5 / 8. A skipped candidate takes no part, and a chosen one that is best everywhere has none.
TEST(ModelSelection, TheChoicesOptimismIsTibshiranisRule) {
  pf::CandidateFit chosen, other, skipped;
  chosen.held_out.row_squared.assign(16, 1.0);
  other.held_out.row_squared.assign(16, 2.0);
  other.held_out.row_squared[0] = other.held_out.row_squared[8] = 0.5;
  skipped.held_out.row_squared.assign(16, 0.0);
  skipped.skipped = "the data cannot identify its keys";
  EXPECT_DOUBLE_EQ(pf::selectionOptimism({chosen, other, skipped}, 0), 0.5 / 8.0);
  other.held_out.row_squared[0] = other.held_out.row_squared[8] = 1.5;
  EXPECT_EQ(pf::selectionOptimism({chosen, other, skipped}, 0), 0.0);
  EXPECT_EQ(pf::selectionOptimism({chosen}, 0), 0.0);
  // A row the chosen could not be scored on (NaN) is left out of its fold's mean: fold 0 is row 8 alone.
  chosen.held_out.row_squared[0] = std::nan("");
  other.held_out.row_squared[8] = 0.25;
  EXPECT_DOUBLE_EQ(pf::selectionOptimism({chosen, other}, 0), (1.0 - 0.25) / 8.0);
}
