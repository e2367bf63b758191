// The chambers' volume, the supplied volume, and volume as the input (docs/MODEL.md, "Volume").
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "pneumatic_finger/core/chamber_volume.hpp"
#include "pneumatic_finger/core/finger_model.hpp"
#include "pneumatic_finger/core/units.hpp"
#include "first_zero.hpp"
#include "uniform_shape.hpp"
#include "wall_chain.hpp"

namespace pneumatic_finger {

namespace {
constexpr double kInf = std::numeric_limits<double>::infinity();
// How closely the stretch found must hold the volume asked for (relative): a root holds it to its last bits; a
// stretch stopped at the last double before a lock is off by far more.
constexpr double kVolumeTolerance = 1e-9;
}  // namespace

double paperVolumePerBulgeM2(double chamber_height_m, double chamber_width_m) {
  return 0.5 * kPi * chamber_height_m * chamber_width_m;
}

namespace {

// The supplied volume V = V_o (lambda^3 - 1) + V_g P/(P_o + P) and dV/ddelta at stretch excess @p d, whose pressure and
// dP/ddelta are @p p and @p dp (the gas's share of a finite P).
void suppliedVolumeAndSlope(double v_o, double v_g, double p_o, double d, double p, double dp, double& volume,
                            double& slope) {
  volume = v_o * membraneVolumeGrowthFactor(d) + v_g * (p / (p_o + p));
  slope = v_o * membraneVolumeGrowthSlope(d) + v_g * p_o * dp / ((p_o + p) * (p_o + p));
}

}  // namespace

double deadGasUptakeM3(double dead_volume_m3, double gauge_pa, double atmospheric_pa) {
  if (dead_volume_m3 == 0.0) return 0.0;  // an incompressible fluid, at any pressure
  return dead_volume_m3 * (gauge_pa / (atmospheric_pa + gauge_pa));
}

void FingerModel::buildVolumeModel() {
  volume_coefficient_.assign(groups_.size(), 0.0);
  chamber_volume_coefficient_.assign(group_of_chamber_.size(), 0.0);
  for (std::size_t k = 0; k < group_of_chamber_.size(); ++k) {
    const double l = parameters_.chamber_height_m[k], e = parameters_.chamber_width_m[k];
    // r_V scales the whole growth: the skin balloons with the walls, by the same stretch (docs/MODEL.md, "Volume").
    chamber_volume_coefficient_[k] = parameters_.chamber_growth_ratio *
                                     (membrane_ ? l * parameters_.chamber_thickness_m[k] * e : paperVolumePerBulgeM2(l, e));
    volume_coefficient_[static_cast<std::size_t>(group_of_chamber_[k])] += chamber_volume_coefficient_[k];
  }
  volume_by_stretch_ = membrane_ && groups_.size() == 1;
  // At the limit point itself where the stretch is known there; else just below it (the pressure's last double).
  const double below_limit_m3 = std::isfinite(limit_gauge_pa_) ? suppliedVolumeAt(belowLimitGaugePa()) : kInf;
  limit_point_volume_m3_ = volume_by_stretch_ && std::isfinite(limit_gauge_pa_)
                               ? suppliedVolumeAtStretch(groups_[0].membrane.limit_stretch_excess)
                               : below_limit_m3;
  volume_limit_stretch_excess_ = kInf;
  if (!volume_by_stretch_) {
    // The pressure sets the volume, increasingly, up to the limit point (if any).
    volume_limit_m3_ = below_limit_m3;
    return;
  }
  const MembraneWall& wall = groups_[0].membrane;
  const double v_g = parameters_.dead_volume_m3, p_o = parameters_.atmospheric_pressure_pa;
  double end = wall.locking_stretch_excess;
  if (v_g > 0.0) {
    // dV/ddelta = 3 V_o lambda^2 + V_g P_o P'/(P_o + P)^2. The second term is negative only past the pressure's
    // limit point. A Neo-Hookean wall has |P'| <= (4 mu t/L)/lambda^2 there, so beyond
    // lambda^4 = V_g (4 mu t/L) / (3 V_o P_o) the chambers' growth wins for good: the scan ends there (or at the lock).
    const double slope_end = std::pow(v_g * wall.decay_scale_pa / (3.0 * volume_coefficient_[0] * p_o), 0.25) - 1.0;
    if (!std::isfinite(end)) end = 1.01 * std::max(slope_end, wall.limit_stretch_excess);
    const auto slope = [this, &wall, v_g, p_o](double d) {
      double p = 0.0, dp = 0.0;
      membraneGaugeAndSlope(wall, d, p, dp);
      return volume_coefficient_[0] * membraneVolumeGrowthSlope(d) + v_g * p_o * dp / ((p_o + p) * (p_o + p));
    };
    if (std::isfinite(wall.limit_stretch_excess)) {
      volume_limit_stretch_excess_ = firstFallBelowZero(slope, wall.limit_stretch_excess, end);
    }
  }
  buildVolumeGuess();
  if (std::isfinite(volume_limit_stretch_excess_)) {
    volume_limit_m3_ = suppliedVolumeAtStretch(volume_limit_stretch_excess_);
  } else if (std::isfinite(wall.locking_stretch_excess)) {
    // At the lock the pressure is unbounded: the chambers' volume there, and all of the dead gas.
    volume_limit_stretch_excess_ = wall.locking_stretch_excess;
    volume_limit_m3_ = volume_coefficient_[0] * membraneVolumeGrowthFactor(wall.locking_stretch_excess) + v_g;
  } else {
    volume_limit_m3_ = kInf;
  }
}

// The volume input's starting table: V and dV/ddelta at the wall's nodes (rest to the limit point, or to the lock,
// where P and dV/ddelta are infinite and the gas is all taken). V rises over them: past the limit point is where
// the gas could give some back.
void FingerModel::buildVolumeGuess() {
  const MembraneWall& wall = groups_[0].membrane;
  const double v_g = parameters_.dead_volume_m3, p_o = parameters_.atmospheric_pressure_pa;
  has_volume_guess_ = v_g > 0.0 && wall.has_guess;
  if (!has_volume_guess_) return;
  for (std::size_t i = 0; i < volume_guess_m3_.size(); ++i) {
    const double d = wall.guess_stretch_excess[i], p = wall.guess_gauge_pa[i];
    if (std::isinf(p)) {
      volume_guess_m3_[i] = volume_coefficient_[0] * membraneVolumeGrowthFactor(d) + v_g;
      volume_guess_slope_m3_[i] = kInf;
      continue;
    }
    suppliedVolumeAndSlope(volume_coefficient_[0], v_g, p_o, d, p, wall.guess_slope_pa[i], volume_guess_m3_[i],
                           volume_guess_slope_m3_[i]);
  }
}

double FingerModel::groupGrowthM3(std::size_t group, double bulge_m) const {
  if (!membrane_) return volume_coefficient_[group] * bulge_m;
  // The membrane's stretch from its bulge (the bulge keeps the digits that 1 + delta rounds away near rest).
  return volume_coefficient_[group] *
         membraneVolumeGrowthFactor(membraneStretchForBulge(groups_[group].membrane, bulge_m));
}

double FingerModel::suppliedVolumeForBulges(const double* bulge_m, double gauge_pa) const {
  if (std::isnan(gauge_pa)) return std::numeric_limits<double>::quiet_NaN();
  std::array<bool, kMaxChamberCount> counted{};
  double growth_m3 = 0.0;
  for (std::size_t k = 0; k < group_of_chamber_.size(); ++k) {
    const auto g = static_cast<std::size_t>(group_of_chamber_[k]);
    if (counted[g]) continue;  // the group's coefficient holds all its chambers
    counted[g] = true;
    growth_m3 += groupGrowthM3(g, bulge_m[k]);
  }
  return growth_m3 + deadGasUptakeM3(parameters_.dead_volume_m3, gauge_pa, parameters_.atmospheric_pressure_pa);
}

double FingerModel::suppliedVolumeOf(const FingerState& state) const {
  return suppliedVolumeForBulges(state.bulge_m.data(), state.gauge_pa);
}

bool FingerModel::chamberBulgesAt(double gauge_pa, double* bulge_m) const {
  if (std::isnan(gauge_pa) || gauge_pa >= limit_gauge_pa_) return false;
  const double p_o = parameters_.atmospheric_pressure_pa;
  std::array<double, kMaxChamberCount> group_bulge_m{};  // one wall solve per group, not per chamber
  for (std::size_t g = 0; g < groups_.size() && gauge_pa > 0.0; ++g) {
    const ChamberGroup& group = groups_[g];
    group_bulge_m[g] = membrane_ ? membraneBulgeM(group.membrane, membraneStretchExcess(group.membrane, gauge_pa))
                                 : bulge(stretchExcess(energyGroup(gauge_pa, p_o, group.shear_modulus_pa)),
                                         group.chamber_height_m);
  }
  for (std::size_t k = 0; k < group_of_chamber_.size(); ++k) {
    bulge_m[k] = group_bulge_m[static_cast<std::size_t>(group_of_chamber_[k])];
  }
  return true;
}

double FingerModel::chamberGrowthM3(int chamber, double bulge_m) const {
  const auto k = static_cast<std::size_t>(chamber);
  const double c = chamber_volume_coefficient_.at(k);
  if (!membrane_) return c * bulge_m;
  const MembraneWall& wall = groups_[static_cast<std::size_t>(group_of_chamber_[k])].membrane;
  return c * membraneVolumeGrowthFactor(membraneStretchForBulge(wall, bulge_m));
}

double FingerModel::suppliedVolumeAt(double gauge_pa) const {
  std::array<double, kMaxChamberCount> bulge_m{};
  if (!chamberBulgesAt(gauge_pa, bulge_m.data())) return std::numeric_limits<double>::quiet_NaN();
  return suppliedVolumeForBulges(bulge_m.data(), gauge_pa);
}

double FingerModel::suppliedVolumeAtStretch(double delta) const {
  const double p = membraneGaugeForStretchExcess(groups_[0].membrane, delta);
  const double gas = std::isinf(p) ? parameters_.dead_volume_m3
                                   : deadGasUptakeM3(parameters_.dead_volume_m3, p, parameters_.atmospheric_pressure_pa);
  return volume_coefficient_[0] * membraneVolumeGrowthFactor(delta) + gas;
}

double FingerModel::stretchForSuppliedVolume(double v) const {
  // The chambers take all of v when the fluid is incompressible, lambda^3 - 1 = v / V_o, and at most v otherwise (the
  // gas takes its share): that stretch bounds the root, below the volume's own limit.
  if (!(v > 0.0)) return 0.0;  // rest (the steps would halve their way to the smallest double)
  const double v_o = volume_coefficient_[0], v_g = parameters_.dead_volume_m3, p_o = parameters_.atmospheric_pressure_pa;
  const double incompressible = std::expm1(std::log1p(v / v_o) / 3.0);
  if (v_g == 0.0) return incompressible;
  const MembraneWall& wall = groups_[0].membrane;
  const auto volume_and_slope = [&wall, v_o, v_g, p_o](double d, double& volume, double& slope) {
    double p = 0.0, dp = 0.0;
    membraneGaugeAndSlope(wall, d, p, dp);
    suppliedVolumeAndSlope(v_o, v_g, p_o, d, p, dp, volume, slope);
  };
  const auto& nodes = volume_guess_m3_;
  if (has_volume_guess_ && v >= 0.0 && v < nodes.back()) {
    // The table's interval brackets the root, and the inverse's Hermite interpolation starts the steps near it.
    const auto i = static_cast<std::size_t>(std::upper_bound(nodes.begin(), nodes.end(), v) - nodes.begin()) - 1;
    const double lo = wall.guess_stretch_excess[i], hi = wall.guess_stretch_excess[i + 1];
    const double s0 = volume_guess_slope_m3_[i];
    const double start = hermiteInverseStart(lo, hi, nodes[i], nodes[i + 1], s0, volume_guess_slope_m3_[i + 1], v);
    return increasingNewtonRoot(volume_and_slope, v, lo, hi, start, lo, s0);
  }
  const double hi = std::min(incompressible, volume_limit_stretch_excess_);
  return increasingNewtonRoot(volume_and_slope, v, 0.0, hi, 0.5 * hi);
}

bool FingerModel::writeStretchState(double delta, double supplied_volume_m3, FingerState& out) const {
  const ChamberGroup& group = groups_[0];
  // Next to a Gent wall's lock the pressure climbs faster than a double's last bits of delta can follow, and a volume
  // that needs more of the gas than they reach has no stretch: the one found holds another volume (or none, where the
  // pressure overflows). That is no answer.
  const double gauge_pa = membraneGaugeForStretchExcess(group.membrane, delta);
  if (!std::isfinite(gauge_pa)) return false;
  const double held_m3 = volume_coefficient_[0] * membraneVolumeGrowthFactor(delta) +
                         deadGasUptakeM3(parameters_.dead_volume_m3, gauge_pa, parameters_.atmospheric_pressure_pa);
  if (!(std::fabs(held_m3 - supplied_volume_m3) <= kVolumeTolerance * supplied_volume_m3)) return false;
  const double bulge_m = membraneBulgeM(group.membrane, delta);
  const HalfAngle half = halfAngle(bulge_m, group.chamber_gap_m, group.wall_critical_height_m);
  if (!std::isfinite(half.rad)) return false;
  uniformWriterFor(parameters_.chamber_count)(parameters_, first_joint_series_, options_.chamber_detail, 1.0 + delta,
                                              bulge_m, half.rad, half.cos, half.sin, half.tan, out);
  out.gauge_pa = gauge_pa;
  return true;
}

const FingerState& FingerModel::evaluateVolume(double supplied_volume_m3, FingerWorkspace& ws) const {
  if (ws.shape_ != shape_) refuseWorkspace(ws);
  FingerState& state = ws.state_;
  ws.has_last_ = false;  // the state is not that of a pressure the cache could answer
  const double v = supplied_volume_m3, v_g = parameters_.dead_volume_m3;
  if (!std::isfinite(v)) {
    state.status = EvaluationStatus::kNotFinite;
    return state;
  }
  if (!(v < volume_limit_m3_)) {
    state.status = EvaluationStatus::kBeyondLimitPoint;
    return state;
  }
  ++ws.computations_;
  bool written = false;
  if (v < 0.0) {
    // Drawn out: the chambers are at rest (the model has no vacuum), and only a gas can give the volume. An
    // incompressible fluid is the gas's limit v_g -> 0: the pressure falls to absolute zero (the liquid cavitates).
    written = writeStateAt(0.0, ws, state);
    state.gauge_pa = v_g > 0.0 ? parameters_.atmospheric_pressure_pa * v / (v_g - v)
                               : -parameters_.atmospheric_pressure_pa;
    state.status = written ? EvaluationStatus::kVacuum : EvaluationStatus::kSolverFailure;
    return state;
  }
  if (volume_by_stretch_) {
    written = writeStretchState(stretchForSuppliedVolume(v), v, state);
  } else if (!membrane_ && groups_.size() == 1 && v_g == 0.0) {
    // The paper law's incompressible fill is closed-form: the chambers' growth is linear in the bulge (half an
    // ellipse), so the bulge is v over the group's coefficient, and the law's inverse gives its pressure.
    const ChamberGroup& g = groups_[0];
    const double p = gaugeForBulge(v / volume_coefficient_[0], g.chamber_height_m, g.shear_modulus_pa,
                                   parameters_.atmospheric_pressure_pa);
    written = std::isfinite(p) && writeStateAt(p, ws, state);
  } else {
    double hi = std::isfinite(limit_gauge_pa_) ? belowLimitGaugePa() : 1e3;
    while (!std::isfinite(limit_gauge_pa_) && suppliedVolumeAt(hi) < v && hi < 1e300) hi *= 2.0;
    const double p = increasingRoot([this](double x) { return suppliedVolumeAt(x); }, v, 0.0, hi);
    written = writeStateAt(p, ws, state);
  }
  state.status = written ? EvaluationStatus::kOk : EvaluationStatus::kSolverFailure;
  return state;
}

}  // namespace pneumatic_finger
