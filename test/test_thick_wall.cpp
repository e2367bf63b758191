// The thick wall (wall_law: thick; docs/MODEL.md "The thick wall") against a reference that writes its pressure
// literally from the elastomer's energy: P = int_{lambda_b}^{lambda_a} W'(lambda)/(lambda^3 - 1) dlambda, W the
// equibiaxial Neo-Hookean or Gent energy differentiated by hand, lambda_b from the wall's volume by a cube root, the
// integral by Simpson's rule with Richardson's correction, all in __float128. None of the library's forms (the closed
// Neo-Hookean antiderivative, Gauss-Legendre panels, the cancellation-free differences) appear in it.
#include <gtest/gtest.h>

#include <quadmath.h>

#include <cmath>
#include <iterator>
#include <limits>
#include <string>
#include <vector>

#include "pneumatic_finger/core/finger_model.hpp"
#include "pneumatic_finger/core/membrane_wall.hpp"
#include "pneumatic_finger/core/yaml_parameters.hpp"
#include "reference_quad.hpp"

namespace pf = pneumatic_finger;

namespace {

using quad = __float128;

constexpr double kMu = 2e4, kHeight = 0.0115;

// dW/dlambda of W(lambda, lambda, lambda^-2): Neo-Hookean (mu/2)(I1 - 3), Gent -(mu J/2) ln(1 - (I1 - 3)/J).
quad energySlope(quad lam, quad jm) {
  const quad i1_m3 = 2 * lam * lam + 1 / (lam * lam * lam * lam) - 3;
  const quad di1 = 4 * lam - 4 / (lam * lam * lam * lam * lam);
  const quad neo = quad(kMu) / 2 * di1;
  return jm == 0 ? neo : neo * jm / (jm - i1_m3);
}

quad simpson(quad a, quad b, quad jm, int panels) {
  const quad h = (b - a) / panels;
  quad sum = 0;
  for (int i = 0; i <= panels; ++i) {
    const quad lam = a + h * i;
    const quad f = energySlope(lam, jm) / (lam * lam * lam - 1);
    sum += f * (i == 0 || i == panels ? 1 : (i % 2 ? 4 : 2));
  }
  return sum * h / 3;
}

double referenceGauge(double delta, double thickness, double jm) {
  const quad a = quad(kHeight) / 2, b = a + quad(thickness);
  const quad la = 1 + quad(delta);
  const quad lb = cbrtq(1 + (a * a * a) / (b * b * b) * (la * la * la - 1));
  const quad coarse = simpson(lb, la, quad(jm), 1024), fine = simpson(lb, la, quad(jm), 2048);
  return static_cast<double>(fine + (fine - coarse) / 15);
}

pf::FingerParameters thickFinger(double thickness, double jm, const std::string& extra = "") {
  pf::RawParameterMap raw;
  pf::loadRawParametersFromYamlText("wall_law: thick\nshear_modulus_pa: 2e4\nwall_thickness_m: " +
                                        pf::formatExact(thickness) + "\nwall_locking_jm: " + std::to_string(jm) + "\n" +
                                        extra,
                                    "test", raw);
  return pf::FingerParameters::fromRaw(raw);
}

struct Case {
  double thickness, jm;
};
// Walls from a fifth of the chamber's radius to three times it (the cylindrical segment's), Neo-Hookean and Gent.
const Case kCases[] = {{0.2 * kHeight / 2, 0.0}, {kHeight / 2, 0.0}, {3 * kHeight / 2, 0.0},
                       {0.2 * kHeight / 2, 50.0}, {kHeight / 2, 50.0}, {3 * kHeight / 2, 50.0}};
// The closed form's hard ends: a lock close to rest (J_m = 1.16, the ribbed segment's, with no limit point before
// it), and a lock so far away that the Gent factor's partial fractions nearly cancel (J_m = 1e4).
const Case kPressureCases[] = {{0.2 * kHeight / 2, 1.16}, {kHeight / 2, 1.16}, {3 * kHeight / 2, 1.16},
                               {0.2 * kHeight / 2, 1e4}, {3 * kHeight / 2, 1e4}};

}  // namespace

TEST(ThickWall, PressureMatchesTheQuadReferenceFromRestToNearTheLock) {
  std::vector<Case> cases(std::begin(kCases), std::end(kCases));
  cases.insert(cases.end(), std::begin(kPressureCases), std::end(kPressureCases));
  for (const Case& c : cases) {
    SCOPED_TRACE("t " + std::to_string(c.thickness) + " J_m " + std::to_string(c.jm));
    const pf::MembraneWall w = pf::membraneWall(kMu, c.thickness, kHeight, c.jm, true);
    const double top = c.jm > 0 ? 0.95 * w.locking_stretch_excess : 5.0;
    for (double d = 1e-6; d < top; d *= 1.4) {
      const double ref = referenceGauge(d, c.thickness, c.jm);
      EXPECT_LT(std::fabs(pf::membraneGaugeForStretchExcess(w, d) - ref) / ref, 1e-12) << d;
    }
  }
}

// The wall's inverse (docs/MODEL.md, "The wall's inverse") for every wall above and the early lock: built, and at
// pressures from 1e-12 of its top to just below it, the stretch it gives solves the reference's law: the reference
// pressure there is the one asked for, within 1e-12 of delta's own worth (|P_ref - P| / (delta dP/ddelta), delta's
// relative error to first order); the outer face's bulge B (lambda_b - 1), which the inverse gives from a polynomial
// of its own, is the reference's from that delta within 1e-12. The far lock (J_m = 1e4) has none: its law's partial fractions round to about
// 1e-13 of P, more than the inverse's check allows its root, so the Newton steps answer there, as they did.
TEST(ThickWall, TheInverseSolvesTheQuadReferencesLaw) {
  std::vector<Case> cases(std::begin(kCases), std::end(kCases));
  cases.insert(cases.end(), std::begin(kPressureCases), std::end(kPressureCases));
  for (const Case& c : cases) {
    SCOPED_TRACE("t " + std::to_string(c.thickness) + " J_m " + std::to_string(c.jm));
    pf::MembraneWall w = pf::membraneWall(kMu, c.thickness, kHeight, c.jm, true);
    pf::buildRisingInverse(w);
    if (c.jm == 1e4) {
      EXPECT_EQ(w.inverse_pieces, 0);
      continue;
    }
    ASSERT_GT(w.inverse_pieces, 0);
    for (int i = 0; i <= 40; ++i) {
      const double p = (1 - 1e-6) * w.inverse_top_gauge_pa * std::pow(10.0, -12.0 * (1.0 - i / 40.0));
      const double d = pf::membraneStretchExcess(w, p);
      double gauge_pa = 0.0, slope_pa = 0.0;
      pf::membraneGaugeAndSlope(w, d, gauge_pa, slope_pa);
      EXPECT_LT(std::fabs(referenceGauge(d, c.thickness, c.jm) - p) / (slope_pa * d), 1e-12) << p;
      const pf::WallSolution s = pf::solveMembraneWall(w, p, 4e-5, 0.00575);
      EXPECT_EQ(s.stretch_excess, d);
      const quad a = quad(kHeight) / 2, b = a + quad(c.thickness), la = 1 + quad(d);
      const quad h_ref = b * (cbrtq(1 + (a * a * a) / (b * b * b) * (la * la * la - 1)) - 1);
      EXPECT_LT(std::fabs(static_cast<double>((quad(s.bulge_m) - h_ref) / h_ref)), 1e-12) << p;
    }
  }
}

TEST(ThickWall, TheTurningPointsMatchTheQuadReference) {
  for (const Case& c : kCases) {
    SCOPED_TRACE("t " + std::to_string(c.thickness) + " J_m " + std::to_string(c.jm));
    const pf::MembraneWall w = pf::membraneWall(kMu, c.thickness, kHeight, c.jm, true);
    ASSERT_TRUE(std::isfinite(w.limit_gauge_pa));
    // The reference's maximum (and, for Gent, its minimum past it) by golden-section search: values, not places,
    // are well conditioned there.
    auto extremum = [&](double a, double b, bool maximum) {
      for (int i = 0; i < 100; ++i) {
        const double x1 = b - 0.618 * (b - a), x2 = a + 0.618 * (b - a);
        const double f1 = referenceGauge(x1, c.thickness, c.jm), f2 = referenceGauge(x2, c.thickness, c.jm);
        ((f1 > f2) == maximum ? b : a) = (x1 + x2) / 2;
      }
      return referenceGauge(0.5 * (a + b), c.thickness, c.jm);
    };
    const double peak = extremum(0.5 * w.limit_stretch_excess, 1.5 * w.limit_stretch_excess, true);
    EXPECT_LT(std::fabs(w.limit_gauge_pa - peak) / peak, 1e-12);
    if (c.jm > 0) {
      ASSERT_TRUE(std::isfinite(w.far_turning_gauge_pa));
      const double low = extremum(w.limit_stretch_excess, 0.95 * w.locking_stretch_excess, false);
      EXPECT_LT(std::fabs(w.far_turning_gauge_pa - low) / low, 1e-12);
    } else {
      EXPECT_EQ(w.far_turning_gauge_pa, std::numeric_limits<double>::infinity());
    }
  }
}

// A thin wall is the membrane: the two laws differ by O(t/R). A thick one's limit pressure grows more slowly than
// the membrane's mu t/L: twice the wall is less than twice the limit.
TEST(ThickWall, ThinItIsTheMembraneAndThickItsLimitGrowsSlowerThanTheWall) {
  for (double jm : {0.0, 50.0}) {
    const double t = 1e-6 * kHeight;
    const pf::MembraneWall thick = pf::membraneWall(kMu, t, kHeight, jm, true);
    const pf::MembraneWall thin = pf::membraneWall(kMu, t, kHeight, jm, false);
    EXPECT_NEAR(thick.limit_gauge_pa / thin.limit_gauge_pa, 1.0, 1e-5);
    EXPECT_NEAR(pf::membraneGaugeForStretchExcess(thick, 0.2) / pf::membraneGaugeForStretchExcess(thin, 0.2), 1.0,
                1e-5);
  }
  double previous = 0.0;
  for (double ratio : {0.25, 0.5, 1.0, 2.0, 4.0}) {
    const pf::MembraneWall w = pf::membraneWall(kMu, ratio * kHeight / 2, kHeight, 0.0, true);
    const pf::MembraneWall m = pf::membraneWall(kMu, ratio * kHeight / 2, kHeight, 0.0, false);
    EXPECT_LT(w.limit_gauge_pa, m.limit_gauge_pa) << ratio;
    if (previous > 0.0) {
      EXPECT_LT(w.limit_gauge_pa, 2.0 * previous) << ratio;
    }
    EXPECT_GT(w.limit_gauge_pa, previous) << ratio;
    previous = w.limit_gauge_pa;
  }
}

// The finger under the thick law: its stretch solves the law, its bulge is the outer face's, the volume input and
// the snap-through work as for the membrane.
TEST(ThickWall, TheFingerSolvesItAndFollowsItsVolumeAndItsSnap) {
  const pf::FingerModel model(thickFinger(kHeight / 2, 50.0));
  pf::FingerWorkspace ws(model);
  const double p = 0.6 * model.limitGaugePa();
  const pf::FingerState& s = model.evaluate(p, ws);
  ASSERT_EQ(s.status, pf::EvaluationStatus::kOk);
  const double delta = s.stretch[0] - 1.0;
  EXPECT_LT(std::fabs(referenceGauge(delta, kHeight / 2, 50.0) - p) / p, 1e-12);
  const quad la = 1 + quad(delta), lb = cbrtq(1 + (la * la * la - 1) / 8);  // B/A = 2
  EXPECT_NEAR(s.bulge_m[0], static_cast<double>(quad(kHeight) * (lb - 1)), 1e-15);
  const double v = model.suppliedVolumeAt(p);
  pf::FingerWorkspace by_volume(model);
  EXPECT_LT(std::fabs(model.evaluateVolume(v, by_volume).gauge_pa - p) / p, 1e-12);
  EXPECT_EQ(model.evaluate(1.01 * model.limitGaugePa(), ws).status, pf::EvaluationStatus::kSnappedThrough);
  EXPECT_EQ(model.evaluate(0.99 * model.farTurningGaugePa(), ws).status, pf::EvaluationStatus::kOk);
  EXPECT_STREQ(pf::wallLawName(pf::WallLaw::kThick), "thick");
}

// wall_flexion_face: inner. The wall's law is the same (the same stretch, to the bit, at every pressure), but the bulge
// that bends the finger is the chamber's own, (L/2) delta, and Wang's half angle follows from it (the quad
// reference's). A wall three times the chamber's radius (B/A = 7): its outer face moves so little that the inner one
// bends the finger far more; the contact pressure is where the inner face crosses the gap; the volume input returns
// its pressure.
TEST(ThickWall, TheInnerFaceBendsTheFingerByTheChambersOwnGrowth) {
  const pf::FingerParameters outer_params = thickFinger(3 * kHeight / 2, 0.0);
  const pf::FingerParameters inner_params = thickFinger(3 * kHeight / 2, 0.0, "wall_flexion_face: inner\n");
  EXPECT_EQ(inner_params.wall_flexion_face, pf::FlexionFace::kInner);
  const pf::FingerModel outer(outer_params), inner(inner_params);
  pf::FingerWorkspace outer_ws(outer), inner_ws(inner);
  EXPECT_EQ(inner.limitGaugePa(), outer.limitGaugePa());
  for (double share : {0.3, 0.6, 0.9}) {
    const double p = share * inner.limitGaugePa();
    const pf::FingerState& s = inner.evaluate(p, inner_ws);
    ASSERT_EQ(s.status, pf::EvaluationStatus::kOk) << share;
    const double delta = s.stretch[0] - 1.0;
    EXPECT_EQ(delta, outer.evaluate(p, outer_ws).stretch[0] - 1.0) << share;
    EXPECT_LT(std::fabs(referenceGauge(delta, 3 * kHeight / 2, 0.0) - p) / p, 1e-12) << share;
    const double h = static_cast<double>(quad(kHeight) / 2 * quad(delta));
    EXPECT_NEAR(s.bulge_m[0], h, 1e-18) << share;
    const double theta =
        reference::halfAngleForBulge(h, inner_params.chamber_gap_m[0], inner_params.wall_critical_height_m[0]);
    EXPECT_NEAR(s.half_angle_rad[0], theta, 1e-12) << share;
    EXPECT_GT(s.half_angle_rad[0], 2.0 * outer.evaluate(p, outer_ws).half_angle_rad[0]) << share;
  }
  // The walls touch where the inner face has crossed the gap: P at delta = 2c/L.
  const double touch_delta = 2.0 * inner_params.chamber_gap_m[0] / kHeight;
  EXPECT_LT(std::fabs(referenceGauge(touch_delta, 3 * kHeight / 2, 0.0) / inner.contactGaugePa() - 1.0), 1e-12);
  const double p = 0.7 * inner.limitGaugePa();
  pf::FingerWorkspace by_volume(inner);
  EXPECT_LT(std::fabs(inner.evaluateVolume(inner.suppliedVolumeAt(p), by_volume).gauge_pa - p) / p, 1e-12);
}

// wall_bulge_share kappa: the wall's law is the same (the same stretch, to the bit), but only kappa times the bending
// face's bulge tilts the wall, and Wang's half angle follows from that (the quad reference's). A thick Gent wall
// (J_m = 26, B/A = 2) bent by its outer face, at pressures below 0.75 mu; the contact pressure is where kappa times that
// face's bulge crosses the gap; the volume input returns its pressure. A share outside (0, 1] is refused by name.
TEST(ThickWall, ABulgeShareTiltsTheWallByThatShareOfItsBulge) {
  const double kappa = 0.2;
  const pf::FingerParameters whole_params = thickFinger(kHeight / 2, 26.0);
  const pf::FingerParameters share_params = thickFinger(kHeight / 2, 26.0, "wall_bulge_share: 0.2\n");
  EXPECT_EQ(share_params.wall_bulge_share, kappa);
  const pf::FingerModel whole(whole_params), share(share_params);
  pf::FingerWorkspace whole_ws(whole), share_ws(share);
  EXPECT_EQ(share.limitGaugePa(), whole.limitGaugePa());
  for (double p : {2e3, 6e3, 10e3, 14e3}) {
    const pf::FingerState& s = share.evaluate(p, share_ws);
    ASSERT_EQ(s.status, pf::EvaluationStatus::kOk) << p;
    const double delta = s.stretch[0] - 1.0;
    EXPECT_EQ(delta, whole.evaluate(p, whole_ws).stretch[0] - 1.0) << p;
    EXPECT_LT(std::fabs(referenceGauge(delta, kHeight / 2, 26.0) - p) / p, 1e-12) << p;
    const quad la = 1 + quad(delta), lb = cbrtq(1 + (la * la * la - 1) / 8);  // B/A = 2
    const double h = static_cast<double>(quad(kappa) * quad(kHeight) * (lb - 1));
    EXPECT_NEAR(s.bulge_m[0], h, 1e-18) << p;
    const double theta =
        reference::halfAngleForBulge(h, share_params.chamber_gap_m[0], share_params.wall_critical_height_m[0]);
    EXPECT_NEAR(s.half_angle_rad[0], theta, 1e-12) << p;
  }
  // The walls touch where kappa B (lambda_b - 1) = c: lambda_b from the gap, lambda_a from the wall's volume.
  const quad lb = 1 + quad(share_params.chamber_gap_m[0]) / (quad(kappa) * quad(kHeight));
  const double touch_delta = static_cast<double>(cbrtq(1 + 8 * (lb * lb * lb - 1)) - 1);
  EXPECT_LT(std::fabs(referenceGauge(touch_delta, kHeight / 2, 26.0) / share.contactGaugePa() - 1.0), 1e-12);
  const double p = 12e3;
  pf::FingerWorkspace by_volume(share);
  EXPECT_LT(std::fabs(share.evaluateVolume(share.suppliedVolumeAt(p), by_volume).gauge_pa - p) / p, 1e-12);
  for (const char* bad : {"wall_bulge_share: 0\n", "wall_bulge_share: 1.5\n"}) {
    try {
      thickFinger(kHeight / 2, 26.0, bad);
      ADD_FAILURE() << bad << " was accepted";
    } catch (const pf::ParameterError& e) {
      EXPECT_NE(std::string(e.what()).find("'wall_bulge_share'"), std::string::npos) << e.what();
    }
  }
}

// The snap point (docs/MODEL.md, "Where it snaps"). A thick Gent wall that locks before it folds (B/A = 2.75,
// J_m = 24.9, bent by a share 0.22 of its outer face's bulge: the EPFL fit's wall) has no limit point, and snaps
// where it is softest: there the quad reference's pressure per bulge, dP/dh by central differences of its pressure
// and of its outer face's bulge, is less than a thousandth of delta to either side, and the pressure is the
// reference's. Along a ramp the tip angle rises fastest there. A wall that folds snaps at its limit point; the paper
// law never snaps.
TEST(ThickWall, AWallThatDoesNotFoldSnapsWhereItIsSoftest) {
  const double thickness = 1.75 * kHeight / 2, kappa = 0.22, jm = 24.9;
  const pf::FingerModel model(thickFinger(thickness, jm, "wall_bulge_share: 0.22\nchamber_gap_m: 0\n"));
  ASSERT_TRUE(std::isinf(model.limitGaugePa()));
  const double p_snap = model.snapGaugePa();
  ASSERT_TRUE(std::isfinite(p_snap));
  const quad ratio = (quad(kHeight) / 2 + quad(thickness)) / (quad(kHeight) / 2);  // B/A
  auto bulge = [&](double delta) {
    const quad la = 1 + quad(delta), lb = cbrtq(1 + (la * la * la - 1) / (ratio * ratio * ratio));
    return quad(kappa) * quad(kHeight) / 2 * ratio * (lb - 1);
  };
  auto per_bulge = [&](double delta) {
    const double step = 1e-5 * delta;
    const quad dp = quad(referenceGauge(delta + step, thickness, jm)) - quad(referenceGauge(delta - step, thickness, jm));
    return static_cast<double>(dp / (bulge(delta + step) - bulge(delta - step)));
  };
  pf::FingerWorkspace ws(model);
  const double delta = model.evaluate(p_snap, ws).stretch[0] - 1.0;
  EXPECT_LT(std::fabs(referenceGauge(delta, thickness, jm) - p_snap) / p_snap, 1e-12);
  EXPECT_LT(per_bulge(delta), per_bulge(0.999 * delta));
  EXPECT_LT(per_bulge(delta), per_bulge(1.001 * delta));
  // The tip angle's steepest rise between neighbouring pressures of a fine ramp brackets the snap.
  double steepest_pa = 0.0, steepest = 0.0, last = model.evaluate(0.5 * p_snap, ws).tip_angle_rad;
  for (double p = 0.5 * p_snap + 10.0; p < 1.5 * p_snap; p += 10.0) {
    const double angle = model.evaluate(p, ws).tip_angle_rad;
    if (angle - last > steepest) steepest = angle - last, steepest_pa = p - 5.0;
    last = angle;
  }
  EXPECT_NEAR(steepest_pa, p_snap, 0.01 * p_snap);
  const pf::FingerModel folds(thickFinger(kHeight / 2, 50.0));
  EXPECT_EQ(folds.snapGaugePa(), folds.limitGaugePa());
  EXPECT_TRUE(std::isinf(pf::FingerModel(pf::FingerParameters::defaults()).snapGaugePa()));  // the paper law
}
