// The force model (docs/MODEL.md, "Force"): the moment the walls exert about each joint of the straight finger, and
// the tip force of a finger held straight by a plate at its tip, from the fitted bending parameters alone. A held
// wall cannot bulge past its neighbour's: the part of its free bulge beyond the contact plane is flattened against the
// neighbour, and a flattened membrane carries no pressure difference, so that strip presses with the chamber's
// pressure. The strip grows as the free wall would balloon: the force rises faster than the pressure.
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <vector>

#include "pneumatic_finger/core/finger_model.hpp"

namespace pneumatic_finger {

// The free wall's bulge at @p gauge_pa (m): stages 1-3 of its law, on a rising pressure. At or beyond a membrane or
// thick wall's limit point the free wall has snapped: to its far branch where it has one (a Gent wall), else it
// balloons without bound (+inf). Either way a held wall's strip is then the whole wall (stripHeightM caps it at R), so
// the held finger's force jumps where the free finger's bend does (docs/MODEL.md, "Force").
double FingerModel::freeBulgeM(const ChamberGroup& g, double gauge_pa) const {
  if (!(gauge_pa > 0)) return 0.0;
  if (membrane_ && gauge_pa >= g.membrane.limit_gauge_pa) {
    const double far = membraneFarStretchExcess(g.membrane, gauge_pa);
    return std::isnan(far) ? std::numeric_limits<double>::infinity() : membraneBulgeM(g.membrane, far);
  }
  if (membrane_) return membraneBulgeM(g.membrane, membraneStretchExcess(g.membrane, gauge_pa));
  return bulge(stretchExcess(energyGroup(gauge_pa, parameters_.atmospheric_pressure_pa, g.shear_modulus_pa)),
               g.chamber_height_m);
}

// The strip's height 2a (m). The free wall at this pressure is the law's own shape, grown by h from the rest circle of
// radius R = L/2: a sphere of radius R + h (membrane law), or half an ellipse of semi-axes R and R + h (paper law,
// stage 3). The contact plane lies R + h_plane from its centre: h_plane = c for the straight finger, where the walls
// first touch, and the bulge at its touch for a joint held since (docs/MODEL.md). a is the shape's half-chord there,
// at most R (the wall is L tall). 0 up to the contact pressure and for a vacuum; 2R beyond the limit point.
double FingerModel::contactStripHeightM(const ChamberGroup& g, double gauge_pa, double plane_bulge_m) const {
  if (!(gauge_pa > g.contact_gauge_pa)) return 0.0;
  return stripHeightM(g, freeBulgeM(g, gauge_pa), plane_bulge_m);
}

// The strip for a free bulge @p h already known (NaN stays NaN).
double FingerModel::stripHeightM(const ChamberGroup& g, double h, double plane_bulge_m) const {
  if (std::isnan(h)) return h;
  if (!(h > plane_bulge_m)) return 0.0;
  const double r = 0.5 * g.chamber_height_m, p = plane_bulge_m;
  const double chord = std::sqrt((h - p) * (2.0 * r + h + p));  // sqrt((R + h)^2 - (R + p)^2), no cancellation
  return 2.0 * (membrane_ ? std::min(chord, r) : r / (r + h) * chord);
}

// The joints' distances to the tip and their compliance weights. Joint n >= 2 turns by the half angles of both facing
// walls, joint 1 by chamber 1's wall and the base face's share s0 of it (stage 5): with every wall equally compliant,
// the weights are 2 and 1 + s0.
void FingerModel::buildForceModel() {
  const int n = parameters_.chamber_count;
  const auto un = static_cast<std::size_t>(n);
  push_lever_m2_.resize(un);
  for (std::size_t k = 0; k < un; ++k) {
    push_lever_m2_[k] = parameters_.chamber_width_m[k] * parameters_.wall_critical_height_m[k];
  }
  force_joints_.assign(un, ForceJoint{});
  double tip_distance_m = 0.0, l_w = 0.0;
  force_l2w_ = 0.0;
  for (int j = n - 1; j >= 0; --j) {
    tip_distance_m += parameters_.segment_length_m[static_cast<std::size_t>(j)];
    const double weight = j == 0 ? 1.0 + parameters_.base_wall_share : 2.0;
    force_joints_[static_cast<std::size_t>(j)] = {std::max(j - 1, 0), j, tip_distance_m, weight};
    l_w += tip_distance_m * weight;
    force_l2w_ += tip_distance_m * tip_distance_m * weight;
  }
  const bool uniform = std::all_of(push_lever_m2_.begin(), push_lever_m2_.end(),
                                   [&](double v) { return v == push_lever_m2_[0]; });
  uniform_force_lever_ = groups_.size() == 1 && uniform ? l_w / force_l2w_ : 0.0;
}

// The weaker of a joint's two facing walls bounds what passes between them: min_k P (2a)_k e_k b_k, from each group's
// strip 2a (@p strip_m, indexed by group; NaN stays NaN).
double FingerModel::jointMomentNm(std::size_t joint, double gauge_pa, const double* strip_m) const {
  double m = std::numeric_limits<double>::infinity();
  for (const int k : {force_joints_[joint].chamber_a, force_joints_[joint].chamber_b}) {
    const auto uk = static_cast<std::size_t>(k);
    const double strip = strip_m[static_cast<std::size_t>(group_of_chamber_[uk])];
    if (std::isnan(strip)) return strip;
    m = std::min(m, strip > 0 ? gauge_pa * strip * push_lever_m2_[uk] : 0.0);
  }
  return m;
}

void FingerModel::straightJointMomentsNm(double gauge_pa, double* moment_nm) const {
  const std::array<double, kMaxChamberCount> none{};  // held since rest: every plane at c (no allocation per step)
  heldJointMomentsNm(gauge_pa, none.data(), moment_nm);
}

// Each group's free bulge at P is solved once, and its contact plane and strip once per distinct touch pressure (a
// grasp has a touch or two): a wall solve per group and per touch, not per joint.
void FingerModel::heldJointMomentsNm(double gauge_pa, const double* held_since_gauge_pa, double* moment_nm) const {
  const std::size_t groups = groups_.size();
  std::array<double, kMaxChamberCount> bulge_m, strip_m;  // the first groups_.size() are used
  for (std::size_t g = 0; g < groups; ++g) {
    bulge_m[g] = gauge_pa > groups_[g].contact_gauge_pa ? freeBulgeM(groups_[g], gauge_pa) : 0.0;
  }
  double strips_since = std::numeric_limits<double>::quiet_NaN();
  for (std::size_t j = 0; j < force_joints_.size(); ++j) {
    const double since = held_since_gauge_pa[j];
    if (std::isnan(gauge_pa) || std::isnan(since)) {
      moment_nm[j] = std::isnan(gauge_pa) ? gauge_pa : 0.0;
      continue;
    }
    if (!(since == strips_since)) {
      for (std::size_t g = 0; g < groups; ++g) {
        const ChamberGroup& group = groups_[g];
        const double plane_m = std::max(group.chamber_gap_m, freeBulgeM(group, since));
        strip_m[g] = std::isnan(plane_m)                     ? plane_m
                     : gauge_pa > group.contact_gauge_pa ? stripHeightM(group, bulge_m[g], plane_m)
                                                         : 0.0;
      }
      strips_since = since;
    }
    moment_nm[j] = jointMomentNm(j, gauge_pa, strip_m.data());
  }
}

double FingerModel::jointComplianceWeight(int joint) const {
  return force_joints_.at(static_cast<std::size_t>(joint)).weight;
}

// The plate holds the tip. Joint j turns by (M_j - F l_j) w_j, its moment less the tip force's times its compliance;
// the tip does not move, sum_j l_j (M_j - F l_j) w_j = 0, which gives F (the planar balance of the chain, linear about
// the straight finger, where the joints are held).
double FingerModel::blockedTipForceN(double gauge_pa) const {
  if (std::isnan(gauge_pa)) return gauge_pa;
  if (uniform_force_lever_ > 0) {
    const double strip_m = contactStripHeightM(groups_[0], gauge_pa, groups_[0].chamber_gap_m);
    return strip_m > 0 || std::isnan(strip_m) ? gauge_pa * strip_m * push_lever_m2_[0] * uniform_force_lever_ : 0.0;
  }
  std::vector<double> moment(force_joints_.size());
  straightJointMomentsNm(gauge_pa, moment.data());
  double moment_lever = 0.0;
  for (std::size_t j = 0; j < force_joints_.size(); ++j) {
    moment_lever += moment[j] * force_joints_[j].tip_distance_m * force_joints_[j].weight;
  }
  return moment_lever / force_l2w_;
}

}  // namespace pneumatic_finger
