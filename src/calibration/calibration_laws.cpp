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
  throw ParameterError("unknown wall law '" + name + "'; known: auto (fit each, keep the best prediction), paper, "
                       "membrane, thick");
}

namespace {

// The key sets @p law is fitted with: @p keys where named; else its defaultFitKeys and, where auto compares the laws
// (@p comparing), the thick wall's with its lock as well: J_m fitted always lowers the fit's error but, on some
// segments, raises the prediction's (the cylindrical segment's), so leave-one-out chooses, as it chooses the law.
std::vector<std::vector<std::string>> keySets(const std::vector<std::string>& keys, CalibrationQuantity quantity,
                                              WallLaw law, bool comparing) {
  if (!keys.empty()) return {keys};
  std::vector<std::vector<std::string>> sets = {defaultFitKeys(quantity, law)};
  const auto& own = sets.front();
  const auto has = [&own](const char* k) { return std::find(own.begin(), own.end(), k) != own.end(); };
  if (comparing && law == WallLaw::kThick && !has("wall_locking_jm") && !has("base_wall_share")) {
    sets.push_back(own);
    sets.back().push_back("wall_locking_jm");
  }
  return sets;
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

std::vector<WallLawFit> calibrateWallLaws(const FingerParameters& base, const std::vector<WallLaw>& laws,
                                          const std::vector<std::string>& keys, const std::vector<Measurement>& data,
                                          CalibrationObjective objective, CalibrationQuantity quantity,
                                          const CalibrationProgress& progress) {
  std::vector<WallLawFit> fits;
  for (WallLaw law : laws) {
    FingerParameters start = base;
    start.wall_law = law;
    std::string note;
    for (std::size_t k = 0; law == WallLaw::kPaper && k < start.wall_critical_height_m.size(); ++k) {
      if (start.wall_critical_height_m[k] > start.chamber_height_m[k]) {
        note = "wall_critical_height_m exceeds chamber_height_m, which the paper law does not allow: it starts from "
               "its uniform wall, b = L/2";
        start.wall_critical_height_m[k] = 0.5 * start.chamber_height_m[k];
      }
    }
    const auto sets = keySets(keys, quantity, law, laws.size() > 1);
    for (std::size_t i = 0; i < sets.size(); ++i) {
      const std::string name = std::string(wallLawName(law)) + " law" + (i > 0 ? " with its lock fitted" : "");
      fits.push_back(fitAndPredict(start, law, sets[i], data, objective, quantity, progress, name));
      fits.back().note = note;
    }
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
