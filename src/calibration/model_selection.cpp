// What --wall-law auto chooses (model_selection.hpp): forward selection of the keys for each law and comparison,
// every candidate judged by its bends held out at their measured pressures.
#include "pneumatic_finger/calibration/model_selection.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cmath>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "fit_space.hpp"
#include "pneumatic_finger/core/drawing.hpp"
#include "shared_scan.hpp"

namespace pneumatic_finger {

namespace {

// One held-out row's squared error: the mean of its bends' squared errors (a row without a shape: kUnshapedBendRad
// each) plus, where compared, its pressure's squared relative error (none: the whole pressure). NaN: nothing measured.
double rowSquaredError(const Residual& r, bool by_volume, int& unshaped) {
  const std::vector<double> bends = heldOutBendErrors(r);
  double sum = 0.0;
  bool without_shape = false;
  for (double e : bends) {
    without_shape = without_shape || std::isnan(e);
    sum += std::isnan(e) ? kUnshapedBendRad * kUnshapedBendRad : e * e;
  }
  unshaped += without_shape ? 1 : 0;
  const bool pressure = by_volume && r.measured_gauge_pa > 0.0 && !r.force_only;
  const bool force = !std::isnan(r.measured_blocked_force_n);
  if (bends.empty() && !pressure && !force) return std::numeric_limits<double>::quiet_NaN();
  const double p = pressure ? r.gauge_relative_error() : 0.0;
  // The blocked force as a share of the data's largest: the whole force range weighs as 1 rad of bend.
  const double f = force ? r.blocked_force_error_n() / r.force_scale_n : 0.0;
  return (bends.empty() ? 0.0 : sum / static_cast<double>(bends.size())) + (std::isnan(p) ? 1.0 : p * p) + f * f;
}

}  // namespace

std::vector<double> heldOutBendErrors(const Residual& r) {
  std::vector<double> bends;
  if (!r.measured_joint_rad.empty()) {  // every joint is a bend the row measured
    for (std::size_t k = 0; k < r.measured_joint_rad.size(); ++k) {
      bends.push_back(r.model_joint_rad[k] - r.measured_joint_rad[k]);
    }
  } else if (!std::isnan(r.measured_tip_angle_rad)) {
    bends.push_back(r.tip_angle_error_rad());
  } else if (!std::isnan(r.measured_chord_angle_rad)) {
    bends.push_back(r.chord_angle_error_rad());
  }
  return bends;
}

HeldOutError heldOutError(const std::vector<Residual>& held_out, bool by_volume) {
  HeldOutError out;
  std::vector<double> rows;
  double pressure_sq = 0.0, force_sq = 0.0, sum = 0.0;
  int shaped_rows = 0;
  for (const Residual& r : held_out) {
    const double row = rowSquaredError(r, by_volume, out.unshaped);
    out.row_squared.push_back(row);
    if (std::isnan(row)) continue;
    rows.push_back(row);
    sum += row;
    const double p = by_volume && r.measured_gauge_pa > 0.0 && !r.force_only ? r.gauge_relative_error() : 0.0;
    const double f = std::isnan(r.measured_blocked_force_n) ? 0.0 : r.blocked_force_error_n() / r.force_scale_n;
    pressure_sq += std::isnan(p) ? 1.0 : p * p;
    force_sq += f * f;
    out.force = std::max(out.force, std::fabs(f));
    shaped_rows += r.force_only ? 0 : 1;
  }
  if (rows.empty()) return out;
  const auto n = static_cast<double>(rows.size());
  // The bends' rms over the rows that measured a shape; the score over every row, each its whole squared error.
  out.bend_rad = shaped_rows > 0 ? std::sqrt(std::max(0.0, sum - pressure_sq - force_sq) / shaped_rows) : 0.0;
  out.pressure = std::sqrt(pressure_sq / n);
  const double mean = sum / n;
  out.score = std::sqrt(mean);
  double var = 0.0;
  for (double x : rows) var += (x - mean) * (x - mean);
  // The standard error of the mean square, sd / sqrt(n), carried to its root: d sqrt(m) = dm / (2 sqrt(m)).
  out.standard_error = rows.size() > 1 && mean > 0.0 ? std::sqrt(var / (n - 1.0) / n) / (2.0 * out.score) : 0.0;
  return out;
}

bool clearlyBetter(const HeldOutError& candidate, const HeldOutError& current) {
  std::vector<double> gain;  // per row: how much less the candidate misses it (squared)
  for (std::size_t i = 0; i < candidate.row_squared.size() && i < current.row_squared.size(); ++i) {
    const double d = current.row_squared[i] - candidate.row_squared[i];
    if (!std::isnan(d)) gain.push_back(d);
  }
  // A gain under kNegligibleGain of the error is none a user can see (a key the others already settle scores the same
  // to a few digits, and its rows' gains are all tiny and positive).
  if (candidate.score >= current.score * (1.0 - kNegligibleGain)) return false;
  if (gain.size() < 2) return true;
  const auto n = static_cast<double>(gain.size());
  double mean = 0.0, var = 0.0;
  for (double d : gain) mean += d / n;
  for (double d : gain) var += (d - mean) * (d - mean) / (n - 1.0);
  return mean > std::sqrt(var / n);
}

namespace {

// The keys forward selection may add to @p keys under @p law: the wall's lock and tilt where the law has them, and
// where the rows were set by their volume with their pressure measured, the drive's gas and the skin's share.
std::vector<std::string> furtherKeys(WallLaw law, const std::vector<std::string>& keys, bool by_volume,
                                     bool has_gauge) {
  std::vector<std::string> extra;
  if (law != WallLaw::kPaper) extra = {"wall_locking_jm", "wall_bulge_share"};
  if (by_volume && has_gauge) {
    extra.push_back("dead_volume_m3");
    extra.push_back("chamber_growth_ratio");
  }
  extra.erase(std::remove_if(extra.begin(), extra.end(),
                             [&keys](const std::string& k) { return std::count(keys.begin(), keys.end(), k) > 0; }),
              extra.end());
  return extra;
}

// The drawing's sizes auto may fit under @p law, not yet among @p keys: the roof, where the drawing leaves it to its
// default and the law's lever b is drawn from it (the membrane and thick walls: b is the body's top). It is the size
// a drawing most often leaves out, and it moves the prediction as much as the elastomer does (docs/DRAWING.md). The
// sizes a drawing states were measured on the part, and the body's width moves no model key.
std::vector<std::string> drawingKeys(const FingerParameters& start, WallLaw law, const std::vector<std::string>& keys) {
  const std::string roof = std::string(kDrawingPrefix) + "roof_thickness_m";
  // A roof the drawing states was measured; one it leaves to its default is a guess.
  if (start.drawing.empty() || start.drawing.count(roof) > 0 || law == WallLaw::kPaper ||
      std::count(keys.begin(), keys.end(), roof) > 0) {
    return {};
  }
  return {roof};
}

// Why @p key cannot be told apart from @p keys by @p data, or empty. The bend takes b, c and kappa as (b/kappa,
// c/kappa) (docs/MODEL.md, "How much of that bulge tilts the wall"): with the gap and kappa fitted, a roof (b) moves
// no bend they cannot; only the blocked force, whose lever is b itself, separates them.
std::string unidentifiable(const std::string& key, const std::vector<std::string>& keys,
                           const std::vector<Measurement>& data) {
  const bool forces = std::any_of(data.begin(), data.end(), [](const Measurement& m) { return m.hasBlockedForce(); });
  const auto has = [&keys](const char* k) { return std::count(keys.begin(), keys.end(), k) > 0; };
  if (key.rfind(kDrawingPrefix, 0) != 0 || forces || !has("wall_bulge_share") || !has("chamber_gap_m")) return "";
  return "the bends cannot tell the roof (it sets the walls' lever b, wall_critical_height_m: the body's top above the "
         "bending axis) from wall_bulge_share and chamber_gap_m: the bend takes b, c and kappa only as b/kappa and "
         "c/kappa; a blocked force, whose lever is b itself, can";
}

// Why @p fit's drawn sizes are no sizes, or empty: one sits on an end of its search range (a quarter to four times the
// drawn value), so the data want a body the drawing is not; the fit then stands for what the model lacks, not for the
// actuator. Auto skips it before its folds.
std::string drawnSizeOutOfRange(const FingerParameters& start, const CalibrationResult& fit) {
  for (std::size_t k = 0; k < fit.keys.size(); ++k) {
    if (fit.keys[k].rfind(kDrawingPrefix, 0) != 0) continue;
    const std::string w = boundWarning(axisFor(fit.keys[k], start), fit.values[k]);
    if (w.empty()) continue;
    const std::string name = fit.keys[k].substr(std::string(kDrawingPrefix).size());
    return w.substr(0, w.find(':')) + ", a quarter to four times the drawing's " +
           formatMessage(drawnSize(start, name)) + " m" + (start.drawing.count(fit.keys[k]) > 0 ? "" : " (its default)") +
           ": the data want a body the drawing is not";
  }
  return "";
}

// Row i's fold: i mod kCrossValidationFolds (each row its own where there are no more rows than folds).
std::vector<std::size_t> interleavedFolds(std::size_t rows) {
  std::vector<std::size_t> fold(rows);
  for (std::size_t i = 0; i < rows; ++i) fold[i] = rows <= kCrossValidationFolds ? i : i % kCrossValidationFolds;
  return fold;
}

// A candidate fitted and cross-validated, or skipped with the reason; its fit and scan kept for the one chosen.
struct Tried {
  CandidateFit candidate;
  CalibrationResult fit;
  ScanRecord scan;
  std::vector<Residual> held_out;
};

Tried tryCandidate(const FingerParameters& start, CandidateFit c, const std::vector<Measurement>& data,
                   CalibrationObjective objective, bool by_volume, const CalibrationProgress& progress) {
  const auto began = std::chrono::steady_clock::now();
  Tried t;
  std::string name = std::string(wallLawName(c.law)) + " law, " + quantityName(c.quantity) + ", ";
  for (std::size_t k = 0; k < c.keys.size(); ++k) name += (k ? "+" : "") + c.keys[k];
  try {
    const CalibrationProgress heard =
        progress ? CalibrationProgress([&](const std::string& s) { progress(name + ": the fit: " + s); })
                 : CalibrationProgress();
    t.fit = calibrateKeepingScan(start, c.keys, data, objective, c.quantity, heard, &t.scan, false);
    c.skipped = drawnSizeOutOfRange(start, t.fit);
    if (!c.skipped.empty()) throw ParameterError(c.skipped);
    t.held_out = heldOutFromScan(start, c.keys, data, objective, c.quantity, progress, name + ": cross-validation",
                                 t.scan, interleavedFolds(data.size()));
    c.held_out = heldOutError(t.held_out, by_volume);
  } catch (const ParameterError& e) {
    c.skipped = e.what();
  }
  c.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - began).count();
  t.candidate = std::move(c);
  return t;
}

// Forward selection from @p current: each round tries every key @p further names for the keys so far, one at a time,
// and keeps the one that lowers the yardstick most while it is clearlyBetter. Every candidate goes to @p tried;
// returns the candidate it stopped at.
template <typename FurtherKeys>
Tried growKeys(const FingerParameters& start, Tried current, const FurtherKeys& further,
               const std::vector<Measurement>& data, CalibrationObjective objective, bool by_volume,
               const CalibrationProgress& progress, std::vector<CandidateFit>& tried) {
  while (true) {
    Tried best;
    best.candidate.held_out.score = std::numeric_limits<double>::infinity();
    for (const std::string& key : further(current.candidate.keys)) {
      CandidateFit grown = current.candidate;
      grown.keys.push_back(key);
      grown.selected = false;
      const std::string why = unidentifiable(key, current.candidate.keys, data);
      if (!why.empty()) {  // skipped unfitted: its fit would cost as much as any other, to score the same
        grown.skipped = why;
        tried.push_back(grown);
        continue;
      }
      Tried t = tryCandidate(start, grown, data, objective, by_volume, progress);
      tried.push_back(t.candidate);
      if (t.candidate.skipped.empty() && t.candidate.held_out.score < best.candidate.held_out.score) best = std::move(t);
    }
    if (!std::isfinite(best.candidate.held_out.score) || !clearlyBetter(best.candidate.held_out, current.candidate.held_out)) {
      return current;
    }
    current = std::move(best);
  }
}

// Forward selection for one law and comparison: from its default keys, the law's further keys (furtherKeys).
Tried selectKeys(const FingerParameters& start, WallLaw law, CalibrationQuantity quantity,
                 const std::vector<Measurement>& data, CalibrationObjective objective, bool by_volume,
                 const CalibrationProgress& progress, std::vector<CandidateFit>& tried) {
  CandidateFit first{law, quantity, defaultFitKeys(quantity, law), {}, 0.0, "", false};
  Tried current = tryCandidate(start, first, data, objective, by_volume, progress);
  tried.push_back(current.candidate);
  if (!current.candidate.skipped.empty()) return current;
  const bool has_gauge = !data.empty() && data.front().hasGauge();
  return growKeys(
      start, std::move(current),
      [&](const std::vector<std::string>& keys) { return furtherKeys(law, keys, by_volume, has_gauge); }, data,
      objective, by_volume, progress, tried);
}

// The drawing's stage, for the chosen law and comparison only (a drawing's size costs a fit per law otherwise): its
// first round tries the drawing's sizes (drawingKeys); once one is kept, the law's keys may join it again.
Tried growDrawing(const FingerParameters& start, Tried chosen, const std::vector<Measurement>& data,
                  CalibrationObjective objective, bool by_volume, const CalibrationProgress& progress,
                  std::vector<CandidateFit>& tried) {
  const WallLaw law = chosen.candidate.law;
  const std::vector<std::string> law_keys = chosen.candidate.keys;
  const bool has_gauge = !data.empty() && data.front().hasGauge();
  return growKeys(
      start, std::move(chosen),
      [&](const std::vector<std::string>& keys) {
        std::vector<std::string> extra = drawingKeys(start, law, keys);
        if (keys == law_keys) return extra;  // the law's further keys were tried on these keys already
        for (const std::string& k : furtherKeys(law, keys, by_volume, has_gauge)) extra.push_back(k);
        return extra;
      },
      data, objective, by_volume, progress, tried);
}

// Every candidate's reason, for a run in which none could be fitted.
std::string noCandidateMessage(const std::vector<CandidateFit>& tried) {
  std::string message = "no candidate could be fitted:";
  for (const CandidateFit& c : tried) {
    message += std::string(" ") + wallLawName(c.law) + " law, " + quantityName(c.quantity) + ": " + c.skipped + ";";
  }
  return message;
}

}  // namespace

ModelSelection selectModel(const FingerParameters& base, const std::vector<WallLaw>& laws,
                           const std::vector<CalibrationQuantity>& comparisons, const std::vector<Measurement>& data,
                           CalibrationObjective objective, bool by_volume, const CalibrationProgress& progress) {
  ModelSelection s;
  Tried chosen;
  chosen.candidate.held_out.score = std::numeric_limits<double>::infinity();
  FingerParameters chosen_start = base;
  std::string chosen_note;
  for (WallLaw law : laws) {
    std::string note;
    const FingerParameters start = lawStart(base, law, note);
    for (CalibrationQuantity quantity : comparisons) {
      Tried t = selectKeys(start, law, quantity, data, objective, by_volume, progress, s.tried);
      if (!t.candidate.skipped.empty()) continue;
      const auto it = std::find_if(s.tried.begin(), s.tried.end(), [&t](const CandidateFit& c) {
        return c.law == t.candidate.law && c.quantity == t.candidate.quantity && c.keys == t.candidate.keys;
      });
      it->selected = true;
      // A later law or comparison replaces the chosen one only where it predicts clearly better (the laws in the
      // order paper, membrane, thick): where the data cannot tell them apart, the first stays.
      if (!std::isfinite(chosen.candidate.held_out.score) ||
          clearlyBetter(t.candidate.held_out, chosen.candidate.held_out)) {
        s.chosen_index = static_cast<std::size_t>(it - s.tried.begin());
        chosen = std::move(t);
        chosen_start = start;
        chosen_note = note;
      }
    }
  }
  if (!std::isfinite(chosen.candidate.held_out.score)) throw ParameterError(noCandidateMessage(s.tried));
  const std::size_t before_drawing = s.tried.size();
  chosen = growDrawing(chosen_start, std::move(chosen), data, objective, by_volume, progress, s.tried);
  for (std::size_t i = before_drawing; i < s.tried.size(); ++i) {  // a drawing's size kept: the chosen moves to it
    if (s.tried[i].keys == chosen.candidate.keys && s.tried[i].skipped.empty()) s.chosen_index = i;
  }
  s.tried[s.chosen_index].selected = true;
  const CandidateFit& c = chosen.candidate;
  s.chosen.law = c.law;
  s.chosen.quantity = c.quantity;
  s.chosen.note = chosen_note;
  s.chosen.fit = std::move(chosen.fit);
  calibrationUncertainty(chosen_start, data, c.quantity, objective, s.chosen.fit);  // the candidates' were skipped
  s.chosen.leave_one_out = data.size() <= kCrossValidationFolds
                               ? std::move(chosen.held_out)
                               : leaveOneOutFromScan(chosen_start, c.keys, data, objective, c.quantity, progress,
                                                     std::string(wallLawName(c.law)) + " law: leave-one-out",
                                                     std::move(chosen.scan));
  s.chosen.leave_one_out_objective = leaveOneOutObjective(s.chosen.leave_one_out, c.quantity, objective);
  return s;
}

double selectionOptimism(const std::vector<CandidateFit>& tried, std::size_t chosen) {
  const std::vector<double>& own = tried.at(chosen).held_out.row_squared;
  const std::vector<std::size_t> fold_of = interleavedFolds(own.size());
  const std::size_t folds = own.empty() ? 0 : *std::max_element(fold_of.begin(), fold_of.end()) + 1;
  // A candidate's mean squared error on fold f's rows that the chosen one is scored on (NaN where it has none of
  // them, or was skipped): the candidates compared on the same rows.
  const auto foldError = [&fold_of, &own](const CandidateFit& c, std::size_t f) {
    double sum = 0.0;
    int rows = 0;
    for (std::size_t i = 0; i < c.held_out.row_squared.size() && i < fold_of.size(); ++i) {
      if (fold_of[i] != f || std::isnan(own[i]) || std::isnan(c.held_out.row_squared[i])) continue;
      sum += c.held_out.row_squared[i];
      ++rows;
    }
    return rows > 0 && c.skipped.empty() ? sum / rows : std::numeric_limits<double>::quiet_NaN();
  };
  double total = 0.0;
  int counted = 0;
  for (std::size_t f = 0; f < folds; ++f) {
    const double mine = foldError(tried[chosen], f);
    if (std::isnan(mine)) continue;
    double least = mine;
    for (const CandidateFit& c : tried) {
      const double e = foldError(c, f);
      if (!std::isnan(e)) least = std::min(least, e);
    }
    total += mine - least;
    ++counted;
  }
  return counted > 0 ? total / counted : 0.0;
}

double correctedScore(const std::vector<CandidateFit>& tried, std::size_t chosen) {
  const double score = tried.at(chosen).held_out.score;
  return std::sqrt(score * score + selectionOptimism(tried, chosen));
}

std::string candidatesTable(const std::vector<CandidateFit>& tried, std::size_t chosen) {
  std::string t = "# auto: every candidate tried, judged by its bends held out at their measured pressures (with the "
                  "pressure by volume and the blocked force, where they are data; rms over " +
                  std::to_string(kCrossValidationFolds) + " interleaved folds; each row alone with " +
                  std::to_string(kCrossValidationFolds) + " rows or fewer; score +- one standard error); a further "
                  "key, a later law or comparison, is kept where it lowers the rows' squared errors by more than their standard "
                  "error, row by row\n";
  for (std::size_t i = 0; i < tried.size(); ++i) {
    const CandidateFit& c = tried[i];
    std::string keys;
    for (std::size_t k = 0; k < c.keys.size(); ++k) keys += (k ? "," : "") + c.keys[k];
    t += std::string("#   ") + wallLawName(c.law) + "; " + quantityName(c.quantity) + "; " + keys + ": ";
    if (!c.skipped.empty()) {
      t += "skipped: " + c.skipped + "\n";
      continue;
    }
    t += "held out " + formatNumber("%.2f", c.held_out.bend_rad * 180.0 / M_PI) + " deg" +
         " (score " + formatNumber("%.2f", c.held_out.score * 180.0 / M_PI) + " +- " +
         formatNumber("%.2f", c.held_out.standard_error * 180.0 / M_PI) + ")" +
         (c.held_out.pressure > 0.0 ? ", pressure " + formatNumber("%.1f", 100.0 * c.held_out.pressure) + " %" : "") +
         (c.held_out.force > 0.0 ? ", force largest " + formatNumber("%.0f", 100.0 * c.held_out.force) + " % of the largest" : "") +
         (c.held_out.unshaped > 0 ? ", " + std::to_string(c.held_out.unshaped) + " rows without a shape" : "") + "; " +
         formatNumber("%.2f", c.seconds) + " s" + (i == chosen ? "  <- chosen" : c.selected ? "  (selected)" : "") + "\n";
  }
  const double score = tried.at(chosen).held_out.score, corrected = correctedScore(tried, chosen);
  t += "#   the chosen score, corrected for being the best of those tried (Tibshirani & Tibshirani's rule: per fold, "
       "how much more the chosen misses than that fold's best): " + formatNumber("%.2f", corrected * 180.0 / M_PI) +
       " deg, against its own " + formatNumber("%.2f", score * 180.0 / M_PI) + "\n";
  return t + "#\n";
}

}  // namespace pneumatic_finger
