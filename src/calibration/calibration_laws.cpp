// Calibration that picks the wall law (calibration.hpp, calibrateWallLaws): each law fitted and predicted row by row,
// the one that predicts better kept.
#include <algorithm>
#include <string>
#include <utility>
#include <vector>

#include "pneumatic_finger/calibration/calibration.hpp"
#include "shared_scan.hpp"

namespace pneumatic_finger {

std::vector<WallLaw> parseWallLawChoice(const std::string& name) {
  if (name == "auto") return {WallLaw::kPaper, WallLaw::kMembrane, WallLaw::kThick};
  for (WallLaw law : {WallLaw::kPaper, WallLaw::kMembrane, WallLaw::kThick}) {
    if (name == wallLawName(law)) return {law};
  }
  throw ParameterError("unknown wall law '" + name + "'; known: auto (choose the law, the keys and the comparison), "
                       "paper, membrane, thick");
}

namespace {

// The keys @p law is fitted with: @p keys where named, else its defaultFitKeys (with no keys and several laws, auto
// chooses the keys too: selectModel, model_selection.hpp).
std::vector<std::string> keysFor(const std::vector<std::string>& keys, CalibrationQuantity quantity, WallLaw law) {
  return keys.empty() ? defaultFitKeys(quantity, law) : keys;
}

// One law with one key set: its fit, and each row predicted by a fit to the others from the fit's own scan.
WallLawFit fitAndPredict(const FingerParameters& start, WallLaw law, const std::vector<std::string>& keys,
                         const std::vector<Measurement>& data, CalibrationObjective objective,
                         CalibrationQuantity quantity, const CalibrationProgress& progress, const std::string& name) {
  WallLawFit f;
  f.law = law;
  try {
    ScanRecord scan;  // the fit's, which leave-one-out's folds start from
    f.fit = calibrateKeepingScan(
        start, keys, data, objective, quantity,
        progress ? CalibrationProgress([&](const std::string& s) { progress(name + ": the fit: " + s); })
                 : CalibrationProgress(),
        &scan);
    f.leave_one_out =
        leaveOneOutFromScan(start, keys, data, objective, quantity, progress, name + ": leave-one-out", std::move(scan));
  } catch (const ParameterError& e) {
    throw ParameterError(std::string("wall law '") + wallLawName(law) + "': " + e.what());
  }
  f.leave_one_out_objective = leaveOneOutObjective(f.leave_one_out, quantity, objective);
  return f;
}

}  // namespace

FingerParameters lawStart(const FingerParameters& base, WallLaw law, std::string& note) {
  FingerParameters start = base;
  start.wall_law = law;
  for (std::size_t k = 0; law == WallLaw::kPaper && k < start.wall_critical_height_m.size(); ++k) {
    if (start.wall_critical_height_m[k] > start.chamber_height_m[k]) {
      note = "wall_critical_height_m exceeds chamber_height_m, which the paper law does not allow: it starts from "
             "its uniform wall, b = L/2";
      start.wall_critical_height_m[k] = 0.5 * start.chamber_height_m[k];
    }
  }
  return start;
}

std::vector<WallLawFit> calibrateWallLaws(const FingerParameters& base, const std::vector<WallLaw>& laws,
                                          const std::vector<std::string>& keys, const std::vector<Measurement>& data,
                                          CalibrationObjective objective, CalibrationQuantity quantity,
                                          const CalibrationProgress& progress) {
  std::vector<WallLawFit> fits;
  for (WallLaw law : laws) {
    std::string note;
    const FingerParameters start = lawStart(base, law, note);
    fits.push_back(fitAndPredict(start, law, keysFor(keys, quantity, law), data, objective, quantity, progress,
                                 std::string(wallLawName(law)) + " law"));
    fits.back().note = note;
    fits.back().quantity = quantity;
  }
  return fits;
}

std::size_t chosenWallLaw(const std::vector<WallLawFit>& fits) {
  const auto best = std::min_element(fits.begin(), fits.end(), [](const WallLawFit& a, const WallLawFit& b) {
    return a.leave_one_out_objective < b.leave_one_out_objective;
  });
  return static_cast<std::size_t>(best - fits.begin());
}

}  // namespace pneumatic_finger
