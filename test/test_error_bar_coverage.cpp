// An honest error bar: the one standard deviation a calibration states must be one. A synthetic finger (mu 1.3 times
// the shipped one's) is measured at ten pressures with noise of known size, and fitted again and again over 100 noise
// seeds; the spread of (fitted - truth) / stated sd must lie between 0.8 and 1.25, for every objective (minimax, least
// squares, Huber's) and every input: tip angles, chord angles, tip positions, every joint, and rows set by volume
// (the tip angle and the pressure), one key and two. Least squares and Huber's state s^2 (J^T J)^-1; minimax its own
// spread, by a parametric bootstrap of its linearisation (calibration.hpp, calibrationUncertainty).
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <random>
#include <string>
#include <vector>

#include "pneumatic_finger/calibration/calibration.hpp"

namespace pf = pneumatic_finger;

namespace {

constexpr int kSeeds = 100;
constexpr double kAngleNoiseRad = M_PI / 180.0;  // 1 degree, a protractor or a video
constexpr double kPositionNoiseM = 0.5e-3;       // 0.5 mm, a camera
constexpr double kGaugeNoise = 0.0175;           // 1.75 % of the pressure: weighs as 1 degree (kTipAngleAndGauge)

enum class Input { kTipAngle, kChordAngle, kTipPosition, kEveryJoint, kVolume };

const char* nameOf(Input i) {
  switch (i) {
    case Input::kTipAngle: return "tip angles";
    case Input::kChordAngle: return "chord angles";
    case Input::kTipPosition: return "tip positions";
    case Input::kEveryJoint: return "every joint";
    case Input::kVolume: return "by volume";
  }
  return "";
}

pf::CalibrationQuantity quantityOf(Input i) {
  switch (i) {
    case Input::kTipAngle: return pf::CalibrationQuantity::kTipAngle;
    case Input::kChordAngle: return pf::CalibrationQuantity::kChordAngle;
    case Input::kTipPosition: return pf::CalibrationQuantity::kTipPosition;
    case Input::kEveryJoint: return pf::CalibrationQuantity::kEveryJoint;
    case Input::kVolume: return pf::CalibrationQuantity::kTipAngleAndGauge;
  }
  return pf::CalibrationQuantity::kTipAngle;
}

pf::FingerParameters withMu(double scale) {
  pf::RawParameterMap raw;
  raw["shear_modulus_pa"] = {{scale * pf::FingerParameters::defaults().shear_modulus_pa[0]}, false};
  return pf::FingerParameters::fromRaw(raw);
}

// Ten rows of the truth at pressures up to 2 kg/cm^2, as the input measures them, with noise drawn by @p random.
std::vector<pf::Measurement> measured(const pf::FingerParameters& truth, Input input, std::mt19937_64& random) {
  std::normal_distribution<double> normal(0.0, 1.0);
  const pf::FingerModel model(truth);
  pf::FingerWorkspace ws(model);
  std::vector<pf::Measurement> rows;
  for (int i = 0; i < 10; ++i) {
    const double p = 2e4 + i * (196133.0 - 2e4) / 9.0;
    const pf::FingerState& s = model.evaluate(p, ws);
    pf::Measurement m;
    m.line = i + 1;
    m.gauge_pa = p;
    if (input == Input::kTipAngle) m.tip_angle_rad = s.tip_angle_rad + kAngleNoiseRad * normal(random);
    if (input == Input::kChordAngle) m.chord_angle_rad = s.chordAngle() + kAngleNoiseRad * normal(random);
    if (input == Input::kTipPosition) {
      m.tip_x_m = s.tip().x() + kPositionNoiseM * normal(random);
      m.tip_y_m = s.tip().y() + kPositionNoiseM * normal(random);
    }
    for (int k = 0; input == Input::kEveryJoint && k < truth.chamber_count; ++k) {
      m.joint_rad.push_back(s.joint_angle_rad[k] + kAngleNoiseRad * normal(random));
    }
    if (input == Input::kVolume) {
      m.supplied_volume_m3 = model.suppliedVolumeAt(p);
      m.gauge_pa = p * (1.0 + kGaugeNoise * normal(random));
      m.tip_angle_rad = s.tip_angle_rad + kAngleNoiseRad * normal(random);
    }
    rows.push_back(m);
  }
  if (input == Input::kVolume) pf::driveByVolume(rows);
  return rows;
}

// The spread of (fitted - truth) / sd of each key over kSeeds noise seeds.
std::vector<double> spreadOfZ(Input input, pf::CalibrationObjective objective, const std::vector<std::string>& keys) {
  const pf::FingerParameters truth = withMu(1.3), start = withMu(1.0);
  const std::vector<double> true_values = {truth.shear_modulus_pa[0], truth.chamber_gap_m[0]};
  std::vector<double> sum(keys.size(), 0.0), squares(keys.size(), 0.0);
  std::mt19937_64 random(7);
  for (int seed = 0; seed < kSeeds; ++seed) {
    const pf::CalibrationResult fit = pf::calibrate(start, keys, measured(truth, input, random), objective,
                                                    quantityOf(input));
    for (std::size_t k = 0; k < keys.size(); ++k) {
      const double z = (fit.values[k] - true_values[k]) / fit.uncertainty[k];
      sum[k] += z;
      squares[k] += z * z;
    }
  }
  std::vector<double> spread;
  for (std::size_t k = 0; k < keys.size(); ++k) {
    spread.push_back(std::sqrt((squares[k] - sum[k] * sum[k] / kSeeds) / (kSeeds - 1)));
  }
  return spread;
}

void expectOneSd(Input input, pf::CalibrationObjective objective, const std::vector<std::string>& keys) {
  const std::vector<double> spread = spreadOfZ(input, objective, keys);
  for (std::size_t k = 0; k < keys.size(); ++k) {
    std::cout << nameOf(input) << ", " << pf::objectiveName(objective) << ", " << (keys.size() > 1 ? "two keys" : "one key")
              << ", " << keys[k] << ": spread " << spread[k] << "\n";
    EXPECT_GE(spread[k], 0.8) << nameOf(input) << ", " << pf::objectiveName(objective) << ", " << keys[k];
    EXPECT_LE(spread[k], 1.25) << nameOf(input) << ", " << pf::objectiveName(objective) << ", " << keys[k];
  }
}

const Input kInputs[] = {Input::kTipAngle, Input::kChordAngle, Input::kTipPosition, Input::kEveryJoint,
                         Input::kVolume};

}  // namespace

TEST(ErrorBarCoverage, MinimaxStatesItsOwnSpread) {
  for (Input input : kInputs) expectOneSd(input, pf::CalibrationObjective::kMinimax, {"shear_modulus_pa"});
  expectOneSd(Input::kTipAngle, pf::CalibrationObjective::kMinimax, {"shear_modulus_pa", "chamber_gap_m"});
}

TEST(ErrorBarCoverage, LeastSquaresStatesItsSpread) {
  for (Input input : kInputs) expectOneSd(input, pf::CalibrationObjective::kLeastSquares, {"shear_modulus_pa"});
  expectOneSd(Input::kTipAngle, pf::CalibrationObjective::kLeastSquares, {"shear_modulus_pa", "chamber_gap_m"});
}

TEST(ErrorBarCoverage, HubersLossStatesItsSpread) {
  for (Input input : kInputs) expectOneSd(input, pf::CalibrationObjective::kHuber, {"shear_modulus_pa"});
  expectOneSd(Input::kTipAngle, pf::CalibrationObjective::kHuber, {"shear_modulus_pa", "chamber_gap_m"});
}
