// Design to spec (design_target.hpp): the drawing's free sizes searched for the targets, the chamber count enumerated.
#include "pneumatic_finger/calibration/design_target.hpp"

#include <nlopt.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <functional>
#include <limits>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "fit_space.hpp"
#include "pneumatic_finger/core/drawing.hpp"
#include "pneumatic_finger/core/self_contact.hpp"
#include "pneumatic_finger/core/yaml_parameters.hpp"

namespace pneumatic_finger {

namespace {

// The body's outline as drawn (m): along (base, end walls, cavities and the walls between), across, up.
struct BodySize {
  double length_m, width_m, height_m;
};

BodySize bodyOf(const ActuatorDrawing& d) { return {bodyLengthM(d), d.body_width_m, bodyTopM(d)}; }

bool castableKey(const std::string& key) {
  return key == "drawing/wall_thickness_m" || key == "drawing/end_wall_thickness_m" ||
         key == "drawing/roof_thickness_m";
}

// The search over one chamber count: each free key's bracket in log10, the base drawing with that count.
class DesignSpace {
 public:
  DesignSpace(const FingerParameters& base, const DesignRequest& request, int count);
  std::size_t size() const { return keys_.size(); }
  /// The design at @p u in the unit cube; false where the drawing is refused or the body exceeds its limits.
  bool design(const double* u, FingerParameters& p) const;
  /// The targets' relative misses squared and summed; a large number where there is no design or no quantity.
  double objective(const double* u) const;
  /// Each target's weight in objective() (all 1 at first).
  void setWeights(std::vector<double> weights) { weights_ = std::move(weights); }
  /// Where @p values (m, one per free key) sit in the cube.
  std::vector<double> pointOf(const std::vector<double>& values) const;
  std::vector<double> values(const double* u) const;
  const FingerParameters& start() const { return start_; }
  const std::vector<double>& drawn() const { return drawn_; }
  const std::vector<double>& logLo() const { return lo_; }
  const std::vector<double>& logHi() const { return hi_; }

 private:
  FingerParameters start_;
  const DesignRequest* request_;
  std::vector<std::string> keys_;
  std::vector<double> lo_, hi_, drawn_;  // log10 of m; the drawn sizes (m)
  std::vector<double> weights_;
};

DesignSpace::DesignSpace(const FingerParameters& base, const DesignRequest& request, int count)
    : start_(base), request_(&request), weights_(request.targets.size(), 1.0) {
  if (count > 0) setKey(start_, "drawing/chamber_count", count);
  for (const FreeDrawingKey& f : request.free) {
    const double drawn = drawnSize(start_, f.key.substr(std::string(kDrawingPrefix).size()));
    const double floor = castableKey(f.key) ? request.castable_m : 0.0;
    const double lo = std::max(f.lo > 0.0 ? f.lo : drawn / 4.0, floor), hi = f.hi > 0.0 ? f.hi : 4.0 * drawn;
    if (f.lo > 0.0 && f.hi > 0.0 && !(f.hi > f.lo)) {
      throw ParameterError(f.key + "=" + formatMessage(f.lo) + ":" + formatMessage(f.hi) + ": LO must be below HI (m)");
    }
    if (!(hi > lo)) {
      throw ParameterError(f.key + ": its bounds [" + formatMessage(lo) + ", " + formatMessage(hi) +
                           "] m hold no size (the castable thickness is " + formatMessage(request.castable_m) + " m)");
    }
    keys_.push_back(f.key);
    lo_.push_back(std::log10(lo));
    hi_.push_back(std::log10(hi));
    drawn_.push_back(drawn);
  }
}

std::vector<double> DesignSpace::pointOf(const std::vector<double>& values) const {
  std::vector<double> u;
  for (std::size_t k = 0; k < keys_.size(); ++k) {
    u.push_back(std::clamp((std::log10(values[k]) - lo_[k]) / (hi_[k] - lo_[k]), 0.0, 1.0));
  }
  return u;
}

std::vector<double> DesignSpace::values(const double* u) const {
  std::vector<double> v;
  for (std::size_t k = 0; k < keys_.size(); ++k) v.push_back(std::pow(10.0, lo_[k] + u[k] * (hi_[k] - lo_[k])));
  return v;
}

bool DesignSpace::design(const double* u, FingerParameters& p) const {
  p = start_;
  const std::vector<double> v = values(u);
  try {
    for (std::size_t k = 0; k < keys_.size(); ++k) setKey(p, keys_[k], v[k]);
  } catch (const ParameterError&) {
    return false;  // a drawing the rule refuses (a wall the gap leaves no elastomer in, ...)
  }
  const BodySize body = bodyOf(*drawingFromRaw(p.drawing));
  const auto over = [](double size, double most) { return most > 0.0 && size > most; };
  return !over(body.length_m, request_->max_body_length_m) && !over(body.width_m, request_->max_body_width_m) &&
         !over(body.height_m, request_->max_body_height_m);
}

// How far @p achieved misses @p target, as a share of the value (the value itself where it is 0); a target to
// minimise misses nothing.
double relativeMiss(double achieved, const DesignTarget& target) {
  if (target.minimize) return 0.0;
  return target.value != 0.0 ? achieved / target.value - 1.0 : achieved;
}

// The objective where there is no design, or a target has no quantity: beyond every real one, so that the search
// leaves it.
constexpr double kNoDesign = 1e15;
// The targets with a value weigh this much more than the logarithm of a quantity to minimise: a thousandth's miss
// costs as much as the quantity's e-fold, so the search meets them first and lowers the other while they stay met.
constexpr double kMeetFirst = 1e6;

double DesignSpace::objective(const double* u) const {
  FingerParameters p;
  if (!design(u, p)) return kNoDesign;
  double sum = 0.0;
  for (std::size_t i = 0; i < request_->targets.size(); ++i) {
    const DesignTarget& t = request_->targets[i];
    const double q = designQuantity(p, t);
    if (t.minimize) {
      if (!(q > 0.0)) return kNoDesign;
      sum += std::log(q);  // a pressure above 0: the search lowers it by its share
      continue;
    }
    const double e = relativeMiss(q, t);
    if (!std::isfinite(e)) return kNoDesign;
    sum += kMeetFirst * weights_[i] * e * e;
  }
  return sum;
}

// The grid's points of a search over @p k keys, in the unit cube: 17 along one key, 9 by 9 for two, a 3^k lattice
// for more.
std::vector<std::vector<double>> gridPoints(std::size_t k) {
  const int per = k == 1 ? 17 : k == 2 ? 9 : 3;
  std::vector<std::vector<double>> points;
  std::vector<int> index(k, 0);
  while (true) {
    std::vector<double> u(k);
    for (std::size_t j = 0; j < k; ++j) u[j] = static_cast<double>(index[j]) / (per - 1);
    points.push_back(u);
    std::size_t j = 0;
    while (j < k && ++index[j] == per) index[j++] = 0;
    if (j == k) return points;
  }
}

// NLopt's Subplex from @p start, bounded by the cube: it needs no derivative and steps over the region with no
// design (whose objective is a constant).
std::pair<double, std::vector<double>> localSearch(const DesignSpace& space, std::vector<double> u) {
  const auto k = static_cast<unsigned>(u.size());
  nlopt::opt opt(nlopt::LN_SBPLX, k);
  opt.set_lower_bounds(std::vector<double>(k, 0.0));
  opt.set_upper_bounds(std::vector<double>(k, 1.0));
  opt.set_min_objective([](unsigned, const double* x, double*, void* s) {
    return static_cast<const DesignSpace*>(s)->objective(x);
  }, const_cast<DesignSpace*>(&space));
  opt.set_xtol_abs(1e-12);
  opt.set_ftol_abs(1e-24);
  opt.set_maxeval(1000 * static_cast<int>(k));
  opt.set_initial_step(std::vector<double>(k, 0.05));
  double value = HUGE_VAL;
  try {
    opt.optimize(u, value);
  } catch (const std::exception&) {
    value = space.objective(u.data());  // a roundoff limit: the point reached stands
  }
  return {value, u};
}

// The best point over one chamber count: the grid's five best, each searched locally, the best searched again from
// where it ended (Subplex's simplex, restarted, leaves a narrow valley it had stalled in).
std::pair<double, std::vector<double>> searchCount(const DesignSpace& space) {
  std::vector<std::pair<double, std::vector<double>>> scanned;
  for (const auto& u : gridPoints(space.size())) scanned.emplace_back(space.objective(u.data()), u);
  std::stable_sort(scanned.begin(), scanned.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  std::pair<double, std::vector<double>> best{HUGE_VAL, {}};
  for (std::size_t i = 0; i < scanned.size() && i < 5; ++i) {
    auto found = localSearch(space, scanned[i].second);
    if (found.first < best.first) best = std::move(found);
  }
  auto again = localSearch(space, best.second);
  return again.first < best.first ? again : best;
}

// A free key that moves no target (the same quantities at both ends of its bounds, the others at the middle) would
// be set anywhere: refused, naming it. @throws ParameterError
void refuseWhatMovesNoTarget(const DesignSpace& space, const DesignRequest& request) {
  for (std::size_t k = 0; k < space.size(); ++k) {
    std::vector<double> lo(space.size(), 0.5), hi(space.size(), 0.5);
    lo[k] = 0.0, hi[k] = 1.0;
    FingerParameters a, b;
    if (!space.design(lo.data(), a) || !space.design(hi.data(), b)) continue;
    bool moves = false;
    for (const DesignTarget& t : request.targets) moves = moves || designQuantity(a, t) != designQuantity(b, t);
    if (moves) continue;
    throw ParameterError("--free " + request.free[k].key + ": no target moves with it (each is the same at both ends "
                         "of its bounds): free a size that moves it, such as drawing/wall_thickness_m");
  }
}

// A note for each target at a pressure where the designed finger's backbone meets itself.
void noteSelfContact(DesignAnswer& a, const DesignRequest& request) {
  const FingerModel model(a.parameters);
  FingerWorkspace ws(model);
  for (const DesignTarget& t : request.targets) {
    if (t.quantity != "tip_angle_rad" && t.quantity != "chord_angle_rad") continue;
    const FingerState& s = model.evaluate(t.at, ws);
    if (backboneMeetsItself(s.backbone_m, s.joint_angle_rad.data())) {
      a.notes.push_back("at " + formatMessage(t.at) + " Pa the designed finger meets itself (its backbone crosses "
                        "itself, tip angle " + formatMessage(s.tip_angle_rad) + " rad): no finger bends so far");
    }
  }
}

// A note for each target met, or asked at, above the base file's validated range: an extrapolation of its data.
void noteExtrapolation(DesignAnswer& a, const DesignRequest& request) {
  const double top_pa = request.validated_max_gauge_pa;
  for (std::size_t i = 0; top_pa > 0.0 && i < request.targets.size(); ++i) {
    const DesignTarget& t = request.targets[i];
    const bool pressure_at = t.quantity == "tip_angle_rad" || t.quantity == "chord_angle_rad" ||
                             t.quantity == "blocked_tip_force_n";
    const double pressure = pressure_at ? t.at : t.quantity.find("gauge") != std::string::npos ? a.achieved[i] : 0.0;
    if (!(pressure > top_pa)) continue;
    a.notes.push_back(t.text + ": at " + formatMessage(pressure) + " Pa, above the base actuator's validated range (to " +
                      formatMessage(top_pa) + " Pa): its data say nothing there, and the answer extrapolates them");
  }
}

// A minimised quantity often ends where the next design has none (a grip lowered until a thinner wall balloons
// before it holds): a note for each free key, not at a bound, whose 1 % step leaves what the model answers.
void noteEdge(DesignAnswer& a, const DesignSpace& space, const DesignRequest& request, const std::vector<double>& u) {
  const bool minimising = std::any_of(request.targets.begin(), request.targets.end(),
                                      [](const DesignTarget& t) { return t.minimize; });
  for (std::size_t k = 0; minimising && k < u.size(); ++k) {
    const double step = std::log10(1.01) / (space.logHi()[k] - space.logLo()[k]);
    for (const double sign : {-1.0, 1.0}) {
      std::vector<double> next = u;
      next[k] += sign * step;
      if (next[k] < 0.0 || next[k] > 1.0 || space.objective(next.data()) < kNoDesign) continue;
      a.notes.push_back(request.free[k].key + " 1 % " + (sign < 0 ? "smaller" : "larger") + " gives no design: a "
                        "quantity has no value there (for a grip: the walls reach their limit point, where they "
                        "balloon, before limit_share of it holds the part). The answer sits at that edge, whatever "
                        "the part, and a cast part's scatter may cross it");
    }
  }
}

// The answer at @p u: the design, what it achieves, how far it reaches, and the keys at a bound.
DesignAnswer answerAt(const DesignSpace& space, const DesignRequest& request, const std::vector<double>& u) {
  DesignAnswer a;
  if (!space.design(u.data(), a.parameters)) throw ParameterError("no design in the bounds that the model accepts");
  a.chamber_count = a.parameters.chamber_count;
  a.values = space.values(u.data());
  a.drawn = space.drawn();
  for (const DesignTarget& t : request.targets) {
    a.achieved.push_back(designQuantity(a.parameters, t));
    a.misses.push_back(relativeMiss(a.achieved.back(), t));
    a.miss = std::max(a.miss, std::fabs(a.misses.back()));
  }
  a.met = a.miss <= kDesignTolerance &&
          std::all_of(a.achieved.begin(), a.achieved.end(), [](double q) { return std::isfinite(q); });
  for (std::size_t k = 0; k < u.size(); ++k) {
    a.reach = std::max(a.reach, std::fabs(std::log(a.values[k] / space.drawn()[k])));
    if (u[k] > 1e-9 && u[k] < 1.0 - 1e-9) continue;
    a.at_bound.push_back(request.free[k].key + " at its " + (u[k] <= 1e-9 ? "lower" : "upper") + " bound " +
                         formatMessage(a.values[k]) + " m");
  }
  noteSelfContact(a, request);
  noteExtrapolation(a, request);
  noteEdge(a, space, request, u);
  return a;
}

// The sum of the logarithms of the quantities to minimise (0 where there are none): what choosing among chamber
// counts lowers.
double minimised(const DesignAnswer& a, const DesignRequest& request) {
  double sum = 0.0;
  for (std::size_t i = 0; i < request.targets.size(); ++i) {
    if (request.targets[i].minimize) sum += std::log(a.achieved[i]);
  }
  return sum;
}

// A grip target's part, checked before the search (a missing part would otherwise surface as no design).
// @throws ParameterError naming the target
void checkGripTargets(const DesignRequest& request) {
  for (const DesignTarget& t : request.targets) {
    if (t.quantity != "grip_gauge_pa") continue;
    if (!(t.grip.mass_kg > 0.0)) {
      throw ParameterError("--target " + t.text + " needs the part: --part mass_kg=M,diameter_m=D[,lift_mps2=A]");
    }
    checkSideGripTask(t.grip);
    if (!(t.grip.max_gauge_pa > 0.0) || !std::isfinite(t.grip.max_gauge_pa)) {
      throw ParameterError("--target " + t.text + ": the base file's max_gauge_pa (the highest pressure the grip may "
                           "use) is not a finite pressure > 0");
    }
  }
}

// Why the base drawing itself has no quantity for a target, for the message of a search that found no design.
std::string whyNoDesign(const FingerParameters& base, const DesignRequest& request) {
  std::string out;
  for (const DesignTarget& t : request.targets) {
    std::string why;
    if (t.quantity == "grip_gauge_pa") {
      if (std::isnan(holdingGaugePa(FingerModel(base), t.grip, &why))) out += "; the base drawing's grip: " + why;
    } else if (std::isnan(designQuantity(base, t))) {
      out += "; the base drawing has no " + t.quantity + (std::isnan(t.at) ? "" : " at " + formatMessage(t.at));
    }
  }
  return out;
}

}  // namespace

DesignAnswer designToTarget(const FingerParameters& base, const DesignRequest& request) {
  const auto began = std::chrono::steady_clock::now();
  if (!drawingFromRaw(base.drawing)) {
    throw ParameterError("the base parameters have no drawing to design from: give a drawn, calibrated file (the "
                         "package's config/epfl_ecoflex30_c7.yaml is one; docs/DRAWING.md)");
  }
  if (request.targets.empty()) throw ParameterError("a design needs a target (--target QUANTITY=VALUE)");
  if (request.free.empty()) throw ParameterError("a design needs a drawing size to change (--free drawing/KEY)");
  checkGripTargets(request);
  for (const FreeDrawingKey& f : request.free) {
    const std::string name = f.key.substr(std::min(f.key.size(), std::string(kDrawingPrefix).size()));
    const bool known = f.key.rfind(kDrawingPrefix, 0) == 0 && std::count(std::begin(kFittableDrawn),
                                                                          std::end(kFittableDrawn), name) > 0;
    if (!known) {
      std::string sizes;
      for (const char* k : kFittableDrawn) sizes += (sizes.empty() ? "" : ", ") + std::string(kDrawingPrefix) + k;
      throw ParameterError("--free " + f.key + ": not a drawing size the search may change (" + sizes +
                           "; the chamber count: --chamber-count)");
    }
    const auto same = [&f](const FreeDrawingKey& g) { return g.key == f.key; };
    if (std::count_if(request.free.begin(), request.free.end(), same) > 1) {
      throw ParameterError("--free " + f.key + " given twice");
    }
  }
  const std::vector<int> counts =
      request.chamber_counts.empty() ? std::vector<int>{base.chamber_count} : request.chamber_counts;
  DesignAnswer best;
  bool found = false;
  for (int count : counts) {
    const DesignSpace space(base, request, count);
    const auto point = searchCount(space);
    if (!(point.first < kNoDesign)) continue;  // no design of this count in the bounds
    refuseWhatMovesNoTarget(space, request);
    DesignAnswer a = answerAt(space, request, point.second);
    // Of the counts that meet the targets, the one that lowers a quantity to minimise most, else the one nearest the
    // base drawing; of those that do not, the one that misses least.
    const double lower = minimised(a, request), lowest = found ? minimised(best, request) : 0.0;
    const bool nearer = lower < lowest || (lower == lowest && a.reach < best.reach);
    const bool better = !found || (a.met && !best.met) || (a.met == best.met && (a.met ? nearer : a.miss < best.miss));
    if (better) best = std::move(a), found = true;
  }
  if (!found) {
    throw ParameterError("no design in the bounds gives every target a value (the model refuses the drawing, or a "
                         "quantity has none: no snap, no pressure that holds the part)" + whyNoDesign(base, request) +
                         "; widen the bounds, free another size, or ask for less");
  }
  // A quantity lowered by the count as far as the counts tried go: the count is a bound like a size's.
  const auto [fewest, most] = std::minmax_element(counts.begin(), counts.end());
  const bool minimising = std::any_of(request.targets.begin(), request.targets.end(),
                                      [](const DesignTarget& t) { return t.minimize; });
  if (minimising && *fewest != *most &&
      (best.chamber_count == *fewest || best.chamber_count == *most)) {
    best.at_bound.push_back(std::string("drawing/chamber_count at the ") +
                            (best.chamber_count == *most ? "largest" : "smallest") + " tried, " +
                            std::to_string(best.chamber_count) + " (--chamber-count)");
  }
  best.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - began).count();
  return best;
}

namespace {

// Every weight vector of @p targets entries, each a multiple of 1 / @p points, summing to 1.
std::vector<std::vector<double>> simplexWeights(std::size_t targets, int points) {
  std::vector<std::vector<double>> out;
  std::vector<int> steps(targets, 0);
  const std::function<void(std::size_t, int)> fill = [&](std::size_t i, int left) {
    if (i + 1 == targets) {
      steps[i] = left;
      std::vector<double> w;
      for (int s : steps) w.push_back(static_cast<double>(s) / points);
      out.push_back(w);
      return;
    }
    for (int s = 0; s <= left; ++s) steps[i] = s, fill(i + 1, left - s);
  };
  fill(0, points);
  return out;
}

// Misses that differ by less than this are the same: the local searches end within it of each other.
constexpr double kSameMiss = 1e-6;

// Whether @p a misses no target more than @p b, and one clearly less.
bool dominates(const DesignAnswer& a, const DesignAnswer& b) {
  bool less = false;
  for (std::size_t i = 0; i < a.misses.size(); ++i) {
    if (std::fabs(a.misses[i]) > std::fabs(b.misses[i]) + kSameMiss) return false;
    less = less || std::fabs(a.misses[i]) < std::fabs(b.misses[i]) - kSameMiss;
  }
  return less;
}

bool sameMisses(const DesignAnswer& a, const DesignAnswer& b) {
  for (std::size_t i = 0; i < a.misses.size(); ++i) {
    if (std::fabs(a.misses[i] - b.misses[i]) > kSameMiss) return false;
  }
  return true;
}

}  // namespace

std::vector<DesignAnswer> designParetoFront(const FingerParameters& base, const DesignRequest& request, int points) {
  if (request.targets.size() < 2 || points < 1) {
    throw ParameterError("a Pareto front needs two targets or more (--target) and at least one step (--pareto N)");
  }
  for (const DesignTarget& t : request.targets) {
    if (t.minimize) {
      throw ParameterError("--pareto trades targets with values; --target " + t.text + " asks for the lowest: give "
                           "it a value (grip_gauge_pa=PRESSURE) for a front");
    }
  }
  const DesignAnswer first = designToTarget(base, request);
  DesignSpace space(base, request, first.chamber_count);
  const std::vector<double> start = space.pointOf(first.values);
  std::vector<DesignAnswer> found;
  for (const std::vector<double>& w : simplexWeights(request.targets.size(), points)) {
    space.setWeights(w);
    const auto point = localSearch(space, start);
    FingerParameters p;
    if (space.design(point.second.data(), p)) found.push_back(answerAt(space, request, point.second));
  }
  std::vector<DesignAnswer> front;
  for (const DesignAnswer& a : found) {
    const bool beaten = std::any_of(found.begin(), found.end(), [&a](const DesignAnswer& b) { return dominates(b, a); });
    const bool repeated =
        std::any_of(front.begin(), front.end(), [&a](const DesignAnswer& b) { return sameMisses(a, b); });
    if (!beaten && !repeated) front.push_back(a);
  }
  std::sort(front.begin(), front.end(), [](const DesignAnswer& a, const DesignAnswer& b) {
    return std::fabs(a.misses[0]) < std::fabs(b.misses[0]);
  });
  return front;
}

std::string designParameterYaml(const DesignAnswer& answer, const DesignRequest& request, double max_gauge_pa) {
  std::ostringstream head;
  head << "# A designed actuator, written by `finger_design --target` (docs/DESIGN.md): the base file's material and\n"
       << "# effective keys, its drawing with these sizes. No actuator's data validate it: every answer is a zero-shot\n"
       << "# prediction until it is cast and measured.\n# targets:";
  for (std::size_t i = 0; i < request.targets.size(); ++i) {
    head << " " << request.targets[i].text << " (achieved " << formatExact(answer.achieved[i]) << ")";
  }
  head << "\n# chamber_count " << answer.chamber_count << ";";
  for (std::size_t k = 0; k < request.free.size(); ++k) {
    head << " " << request.free[k].key << " = " << formatExact(answer.values[k]);
  }
  head << "\n# " << (answer.met ? "met" : "NOT met: the nearest design the bounds allow") << "; largest miss "
       << formatMessage(100.0 * answer.miss) << " %; reach from the base drawing (largest |ln(size / drawn)|) "
       << formatMessage(answer.reach) << "\n";
  for (const std::string& b : answer.at_bound) head << "# stopped by " << b << "\n";
  for (const std::string& n : answer.notes) head << "# note: " << n << "\n";
  PressureRange range;
  range.max_gauge_pa = max_gauge_pa;
  range.validated_max_gauge_pa = 0.0;
  return head.str() + "\n" + parametersToYaml(answer.parameters) + "\n" + rangeToYaml(range);
}

}  // namespace pneumatic_finger
