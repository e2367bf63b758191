// The supplied volume of a finger closing on an object, and the volume as the input there (docs/MODEL.md, "Volume":
// "With an object").
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "pneumatic_finger/core/chamber_volume.hpp"
#include "pneumatic_finger/core/contact.hpp"
#include "pneumatic_finger/core/parameters.hpp"
#include "first_zero.hpp"

namespace pneumatic_finger {

namespace {

// Chamber @p k's walls are at joints k + 1 (its base side) and k + 2 (its tip side; the last chamber's tip wall has
// no neighbour and is never held). A wall at a held joint keeps its chamber's bulge at the pressure that joint was
// held: the contact rule froze that joint's angle there, and the angle is the walls' bulge (Wang's relation).
bool wallHeld(const ContactState& contact, std::size_t joint, double& since_gauge_pa) {
  if (joint >= contact.held.size() || !contact.held[joint]) return false;
  since_gauge_pa = contact.held_since_gauge_pa[static_cast<Eigen::Index>(joint)];
  return true;
}

}  // namespace

double suppliedVolumeInContact(const FingerModel& model, const ContactState& contact, double gauge_pa,
                               const double* free_bulge_given_m) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  std::array<double, kMaxChamberCount> free_bulge_m{}, held_bulge_m{};
  const auto n = static_cast<std::size_t>(model.chamberCount());
  if (free_bulge_given_m) {
    std::copy(free_bulge_given_m, free_bulge_given_m + n, free_bulge_m.begin());
  } else if (!model.chamberBulgesAt(gauge_pa, free_bulge_m.data())) {
    return nan;
  }
  double held_at_pa = nan, growth_m3 = 0.0;
  for (std::size_t k = 0; k < n; ++k) {
    for (std::size_t joint : {k, k + 1}) {  // 0-based: the wall at joint k + 1, then at joint k + 2
      double since_pa = 0.0;
      double wall_bulge_m = free_bulge_m[k];
      if (wallHeld(contact, joint, since_pa)) {
        // The touches are few (one per event): the bulges of the last touch pressure are kept.
        if (!(since_pa == held_at_pa)) {
          if (!model.chamberBulgesAt(since_pa, held_bulge_m.data())) return nan;
          held_at_pa = since_pa;
        }
        wall_bulge_m = held_bulge_m[k];
      }
      growth_m3 += 0.5 * model.chamberGrowthM3(static_cast<int>(k), wall_bulge_m);
    }
  }
  const FingerParameters& p = model.parameters();
  return growth_m3 + deadGasUptakeM3(p.dead_volume_m3, gauge_pa, p.atmospheric_pressure_pa);
}

// V_s(P) rises with P in contact too: free walls grow, held ones keep their growth, and a wall is held at the
// bulge it had, so a touch does not jump the volume. Regula falsi to neighbouring doubles (increasingRoot).
bool gaugeForVolumeInContact(const FingerModel& model, const std::function<ContactState(double)>& contact_at,
                             double supplied_volume_m3, double max_gauge_pa, double& gauge_pa, std::string& why) {
  const double v = supplied_volume_m3;
  if (!(v >= 0.0) || !std::isfinite(v)) {
    why = "supplied volume " + formatMessage(v) + " m^3 is not a finite volume >= 0 (the contact rule has no vacuum)";
    return false;
  }
  const double top = std::fmin(max_gauge_pa, model.belowLimitGaugePa());
  const auto volume_at = [&](double p) { return suppliedVolumeInContact(model, contact_at(p), p); };
  const double most = volume_at(top);
  if (!(most >= v)) {
    why = "supplied volume " + formatMessage(v) + " m^3 is more than the finger takes on the object up to " +
          formatMessage(top) + " Pa gauge (" + (top < max_gauge_pa ? "the limit point" : "the top of its range") +
          "): " + formatMessage(most) + " m^3";
    return false;
  }
  gauge_pa = increasingRoot(volume_at, v, 0.0, top);
  return true;
}

}  // namespace pneumatic_finger
