// Where a wall snaps under a rising pressure (docs/MODEL.md, "The snap-through": "Where it snaps"): its limit point
// where it folds; else, for a Gent wall whose lock comes before any fold, where it is softest, the least pressure per
// bulge of the face that bends the finger.
#include <cmath>
#include <limits>

#include "pneumatic_finger/core/golden_section.hpp"
#include "pneumatic_finger/core/membrane_wall.hpp"
#include "thick_wall.hpp"

namespace pneumatic_finger {

namespace {

// dP/dh (Pa/m) at stretch excess @p delta: the law's slope over the bending face's dh/ddelta. The inner face's h is
// linear in delta; the outer face's grows by (A/B)^3 (lambda_a/lambda_b)^2 per unit of delta (incompressibility:
// lambda_b^2 dlambda_b = (A/B)^3 lambda_a^2 dlambda_a).
double gaugePerBulge(const MembraneWall& w, double delta) {
  double gauge_pa = 0.0, slope_pa = 0.0;  // a thick wall's slope alone, without its pressure's integral
  if (w.thick) slope_pa = thickGaugeSlope(w, delta); else membraneGaugeAndSlope(w, delta, gauge_pa, slope_pa);
  if (!w.outer_face_bends) return slope_pa / w.bulge_per_stretch_m;
  const double ratio = (1.0 + delta) / (1.0 + thickOuterStretchExcess(w, delta));
  return slope_pa / (w.bulge_per_stretch_m * w.inner_outer_volume_ratio * ratio * ratio);
}

}  // namespace

void setSnapPoint(MembraneWall& w) {
  w.snap_stretch_excess = w.limit_stretch_excess;
  w.snap_gauge_pa = w.limit_gauge_pa;
  if (std::isfinite(w.limit_stretch_excess) || !std::isfinite(w.locking_stretch_excess)) return;
  // dP/dh falls from rest while the elastomer softens and rises without bound towards the lock: a scan of the branch
  // finds its least value's neighbourhood, a golden section the point. Least at rest: the wall only stiffens.
  constexpr int kScan = 128;
  const double end = w.locking_stretch_excess;
  int best = 0;
  double best_value = gaugePerBulge(w, 0.0);
  for (int i = 1; i < kScan; ++i) {
    const double value = gaugePerBulge(w, end * i / kScan);
    if (value < best_value) best = i, best_value = value;
  }
  if (best == 0) return;
  const GoldenMinimum m = goldenSection([&w](double x) { return gaugePerBulge(w, x); }, end * (best - 1) / kScan,
                                        end * (best + 1) / kScan, 200,
                                        [](double a, double b, double, double) { return b - a > 1e-13 * b; });
  w.snap_stretch_excess = m.x;
  w.snap_gauge_pa = membraneGaugeForStretchExcess(w, m.x);
}

}  // namespace pneumatic_finger
