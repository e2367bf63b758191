// The chambers' volume, the supplied volume and volume as the input (docs/MODEL.md, "Volume"), against a reference
// that writes the volumes literally in __float128 ((1 + delta)^3 - 1 times L d e; half an ellipse's area, (pi/2) a b,
// before and after; V_g P/(P_o + P)) on the quad-precision reference's stretch, pressure, bulge and half angle.
#include <gtest/gtest.h>

#include <quadmath.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "pneumatic_finger/core/chamber_volume.hpp"
#include "pneumatic_finger/core/finger_model.hpp"
#include "pneumatic_finger/core/pressure_range.hpp"
#include "pneumatic_finger/core/yaml_parameters.hpp"
#include "reference_quad.hpp"
#include "test_support.hpp"

namespace pf = pneumatic_finger;

namespace {

using quad = __float128;

// The membrane finger of test_membrane_wall.cpp (mu = 20 kPa, t = 2 mm, L = 11.5 mm, d = 5 mm, e = 7 mm, N = 7).
constexpr double kMu = 2e4, kThickness = 0.002, kHeight = 0.0115, kDepth = 0.005, kWidth = 0.007;
constexpr int kChambers = 7;
constexpr double kAtmosphere = 101325.0;

pf::FingerParameters finger(const std::string& yaml) { return pf_test::fingerFromYaml(yaml); }

pf::FingerParameters membraneFinger(double jm, double dead_volume_m3, double growth_ratio = 1.0) {
  return pf_test::membraneFinger(jm, "dead_volume_m3: " + pf::formatExact(dead_volume_m3) +
                                         "\nchamber_growth_ratio: " + pf::formatExact(growth_ratio) + "\n");
}

// The supplied volume of the membrane finger at stretch excess delta, literally: r_V N L d e ((1 + delta)^3 - 1) plus
// V_g P/(P_o + P), P the quad reference's law at delta.
double referenceMembraneVolume(double delta, double jm, double dead_volume_m3, double growth_ratio = 1.0) {
  const quad lam = 1 + quad(delta);
  const quad growth =
      quad(growth_ratio) * quad(kChambers) * quad(kHeight) * quad(kDepth) * quad(kWidth) * (lam * lam * lam - 1);
  const quad p = reference::membraneGaugePa({kMu, kThickness, kHeight, jm}, delta);
  return static_cast<double>(growth + quad(dead_volume_m3) * p / (quad(kAtmosphere) + p));
}

// The paper finger's supplied volume at gauge_pa: each chamber's two walls, half ellipses of semi-axes L/2 and
// L/2 + h across e, minus their rest half circles, from the reference chain's bulge, times r_V; plus the dead gas.
double referencePaperVolume(const pf::FingerParameters& p, double gauge_pa) {
  quad total = 0;
  for (int i = 0; i < p.chamber_count; ++i) {
    const auto k = static_cast<std::size_t>(i);
    const reference::ChamberChain c = reference::chamberChain(
        gauge_pa, p.atmospheric_pressure_pa,
        {p.chamber_height_m[k], p.wall_critical_height_m[k], p.chamber_gap_m[k], p.shear_modulus_pa[k]});
    const quad a = quad(p.chamber_height_m[k]) / 2, half_pi = acosq(quad(0));
    total += 2 * quad(p.chamber_width_m[k]) * (half_pi * a * (a + quad(c.bulge_m)) - half_pi * a * a);
  }
  const quad gp = quad(gauge_pa);
  return static_cast<double>(quad(p.chamber_growth_ratio) * total +
                             quad(p.dead_volume_m3) * gp / (quad(p.atmospheric_pressure_pa) + gp));
}

double relativeError(double x, double reference) { return std::fabs(x - reference) / std::fabs(reference); }

}  // namespace

TEST(FingerVolume, TheDeadVolumeIsAKeyInCubicMetresAndZeroByDefault) {
  EXPECT_EQ(pf::FingerParameters::defaults().dead_volume_m3, 0.0);
  EXPECT_EQ(finger("dead_volume_m3: 8.1e-5\n").dead_volume_m3, 8.1e-5);
  try {
    finger("dead_volume_m3: -1e-6\n");
    FAIL() << "a negative dead volume was accepted";
  } catch (const pf::ParameterError& e) {
    EXPECT_NE(std::string(e.what()).find("'dead_volume_m3' = -1e-06 is outside its allowed range [0, 1] m^3"),
              std::string::npos)
        << e.what();
  }
  // 80 mL written in mL by mistake: refused, not a 80 m^3 reservoir.
  EXPECT_THROW(finger("dead_volume_m3: 80\n"), pf::ParameterError);
}

// Under pressure control, below the limit point: the supplied volume at a pressure is the reference's at the
// reference's stretch for that pressure, for the paper law's ellipse and the membrane's sphere, with and without gas.
TEST(FingerVolume, SuppliedVolumeAtAPressureMatchesTheReference) {
  for (double r_v : {1.0, 8.0}) {
    for (double v_g : {0.0, 8e-5}) {
      SCOPED_TRACE("dead volume " + std::to_string(v_g) + ", growth ratio " + std::to_string(r_v));
      const pf::FingerModel paper(finger("dead_volume_m3: " + pf::formatExact(v_g) +
                                         "\nchamber_growth_ratio: " + pf::formatExact(r_v) + "\n"));
      for (double p = 1e-3; p <= 3e5; p *= 1.7) {
        EXPECT_LT(relativeError(paper.suppliedVolumeAt(p), referencePaperVolume(paper.parameters(), p)), 1e-12) << p;
      }
      for (double jm : {0.0, 50.0}) {
        const pf::FingerModel membrane(membraneFinger(jm, v_g, r_v));
        const reference::Membrane wall{kMu, kThickness, kHeight, jm};
        for (double p = 1e-3; p < membrane.limitGaugePa(); p *= 1.3) {
          const double delta = reference::membraneStretchExcess(wall, p);
          // The reference's delta is rounded once; the volume's relative sensitivity to it is below 3.
          EXPECT_LT(relativeError(membrane.suppliedVolumeAt(p), referenceMembraneVolume(delta, jm, v_g, r_v)), 1e-12)
              << p;
        }
      }
    }
  }
}

// The skin's share (chamber_growth_ratio): driven by the reference's volume of a finger whose chambers grow eight
// times what their walls give, the model answers the reference's pressure, bulge and half angle at the walls'
// stretch, past the limit point too; the same volume without the skin stretches the walls further.
TEST(FingerVolume, AChamberWhoseSkinBalloonsTakesItsVolumeWithoutBendingMore) {
  const double r_v = 8.0, v_g = 1e-4;
  const pf::FingerModel skin(membraneFinger(0.0, v_g, r_v)), walls_only(membraneFinger(0.0, v_g));
  pf::FingerWorkspace ws(skin), ws_walls(walls_only);
  const reference::Membrane wall{kMu, kThickness, kHeight, 0.0};
  const double limit_delta = reference::membraneLimitStretchExcess(wall);
  int past_limit = 0;
  for (double delta = 1e-6; delta < 3.0 * limit_delta; delta *= 1.3) {
    const double v = referenceMembraneVolume(delta, 0.0, v_g, r_v);
    if (!(v < skin.volumeLimitM3())) break;  // the gas snaps the finger there
    const pf::FingerState& s = skin.evaluateVolume(v, ws);
    ASSERT_EQ(s.status, pf::EvaluationStatus::kOk) << delta;
    EXPECT_LT(relativeError(s.gauge_pa, reference::membraneGaugePa(wall, delta)), 1e-12) << delta;
    EXPECT_LT(relativeError(s.bulge_m[0], 0.5 * kHeight * delta), 1e-12) << delta;
    // The wall's own stretch at that pressure: the shape the pressure gives, whatever the skin takes.
    const double theta = reference::halfAngleForBulge(0.5 * kHeight * delta, skin.parameters().chamber_gap_m[0],
                                                      skin.parameters().wall_critical_height_m[0]);
    EXPECT_NEAR(s.half_angle_rad[3], theta, 1e-12 * std::max(1.0, theta)) << delta;
    EXPECT_GT(walls_only.evaluateVolume(v, ws_walls).bulge_m[0], s.bulge_m[0]) << "without the skin, more stretch";
    past_limit += delta > limit_delta;
  }
  EXPECT_GT(past_limit, 2);
}

TEST(FingerVolume, SuppliedVolumeHasNoPressureBeyondTheLimitAndAVacuumOnlyForAGas) {
  const pf::FingerModel membrane(membraneFinger(0.0, 8e-5));
  EXPECT_TRUE(std::isnan(membrane.suppliedVolumeAt(membrane.limitGaugePa())));
  EXPECT_TRUE(std::isnan(membrane.suppliedVolumeAt(std::numeric_limits<double>::quiet_NaN())));
  EXPECT_EQ(membrane.suppliedVolumeAt(0.0), 0.0);
  // -10 kPa: the chambers stay at rest, the gas expands by V_g P/(P_o + P).
  EXPECT_DOUBLE_EQ(membrane.suppliedVolumeAt(-1e4), 8e-5 * -1e4 / (kAtmosphere - 1e4));
  const pf::FingerModel water(pf::FingerParameters::defaults());
  EXPECT_EQ(water.suppliedVolumeAt(-1e4), 0.0);
  // The volume at the limit point, which tells a volume past it (the node's diagnostics): the reference's volume at
  // the reference's limit stretch.
  const reference::Membrane wall{kMu, kThickness, kHeight, 0.0};
  EXPECT_LT(relativeError(membrane.limitPointVolumeM3(),
                          referenceMembraneVolume(reference::membraneLimitStretchExcess(wall), 0.0, 8e-5)),
            1e-12);
  EXPECT_TRUE(std::isinf(water.limitPointVolumeM3()));
}

// Volume control of identical membrane chambers: the volume sets the stretch before, at and past the limit point,
// where the pressure falls while the finger keeps bending. The state matches the reference's at the stretch whose
// reference volume was asked for.
TEST(FingerVolume, VolumeInputFollowsTheFingerPastTheLimitPoint) {
  for (double jm : {0.0, 50.0}) {
    SCOPED_TRACE("J_m " + std::to_string(jm));
    const pf::FingerModel model(membraneFinger(jm, 0.0));
    pf::FingerWorkspace ws(model);
    const reference::Membrane wall{kMu, kThickness, kHeight, jm};
    const double limit_delta = reference::membraneLimitStretchExcess(wall);
    const double top = jm > 0 ? 0.99 * pf::membraneWall(kMu, kThickness, kHeight, jm).locking_stretch_excess : 4.0 * limit_delta;
    double previous_tip = -1.0;
    int past_limit = 0;
    for (double delta = 1e-9; delta < top; delta *= 1.25) {
      const double v = referenceMembraneVolume(delta, jm, 0.0);
      const pf::FingerState& s = model.evaluateVolume(v, ws);
      ASSERT_EQ(s.status, pf::EvaluationStatus::kOk) << delta;
      // The bulge, (L/2) delta, keeps delta's digits (the stretch 1 + delta rounds them away near rest).
      EXPECT_LT(relativeError(s.bulge_m[0], 0.5 * kHeight * delta), 1e-12) << delta;
      EXPECT_LT(relativeError(s.gauge_pa, reference::membraneGaugePa(wall, delta)), 1e-12) << delta;
      const double theta = reference::halfAngleForBulge(0.5 * kHeight * delta, model.parameters().chamber_gap_m[0],
                                                        model.parameters().wall_critical_height_m[0]);
      EXPECT_NEAR(s.half_angle_rad[3], theta, 1e-12 * std::max(1.0, theta)) << delta;
      if (previous_tip > 0.0) {
        EXPECT_GT(s.tip_angle_rad, previous_tip) << "once bending, the finger bends more with every step";
      }
      EXPECT_GE(s.tip_angle_rad, previous_tip);
      previous_tip = s.tip_angle_rad;
      past_limit += delta > limit_delta && s.gauge_pa < model.limitGaugePa();
    }
    EXPECT_GT(past_limit, 3) << "the sweep passes the limit point, where the pressure falls";
  }
}

// The paper law: the volume is the pressure's, monotone; the volume input returns that pressure and its shape.
TEST(FingerVolume, VolumeInputOfThePaperLawReturnsThePressure) {
  for (double v_g : {0.0, 8e-5}) {
    const pf::FingerModel model(finger("dead_volume_m3: " + pf::formatExact(v_g) + "\n"));
    pf::FingerWorkspace ws(model), by_pressure(model);
    EXPECT_EQ(model.volumeLimitM3(), std::numeric_limits<double>::infinity());
    for (double p = 1e-3; p <= 3e5; p *= 1.9) {
      const pf::FingerState& s = model.evaluateVolume(referencePaperVolume(model.parameters(), p), ws);
      ASSERT_EQ(s.status, pf::EvaluationStatus::kOk) << p;
      EXPECT_LT(relativeError(s.gauge_pa, p), 1e-12) << p;
      const pf::FingerState& r = model.evaluate(s.gauge_pa, by_pressure);
      EXPECT_EQ(s.tip_angle_rad, r.tip_angle_rad) << "the volume's state is its pressure's, bit for bit";
    }
  }
}

// With a compressible drive the supply's gas re-expands as the pressure falls past the limit point: where it outpaces
// the chambers' growth, the supplied volume has a maximum, and even volume control snaps there.
TEST(FingerVolume, ALargeDeadGasVolumeSnapsEvenUnderVolumeControl) {
  const double v_g = 2e-3;  // 2 L of air behind a 7-chamber finger of 2.8 mL
  const pf::FingerModel model(membraneFinger(0.0, v_g));
  ASSERT_TRUE(std::isfinite(model.volumeLimitM3()));
  // The reference volume's maximum, by golden-section search on its stretch (a maximum is flat: its value is
  // well conditioned even where its place is not).
  const double pressure_limit = reference::membraneLimitStretchExcess({kMu, kThickness, kHeight, 0.0});
  double a = pressure_limit, b = 4.0 * pressure_limit;
  for (int i = 0; i < 200; ++i) {
    const double x1 = b - 0.618 * (b - a), x2 = a + 0.618 * (b - a);
    (referenceMembraneVolume(x1, 0.0, v_g) > referenceMembraneVolume(x2, 0.0, v_g) ? b : a) = (x1 + x2) / 2;
  }
  const double peak_delta = 0.5 * (a + b), peak = referenceMembraneVolume(peak_delta, 0.0, v_g);
  EXPECT_LT(relativeError(model.volumeLimitM3(), peak), 1e-12);
  EXPECT_LT(referenceMembraneVolume(peak_delta * 1.01, 0.0, v_g), peak) << "a maximum, not a plateau";
  pf::FingerWorkspace ws(model);
  const pf::FingerState& at = model.evaluateVolume(model.volumeLimitM3() * (1 - 1e-9), ws);
  ASSERT_EQ(at.status, pf::EvaluationStatus::kOk);
  EXPECT_GT(at.stretch[0] - 1.0, pressure_limit) << "the volume's maximum comes after the pressure's";
  const double tip = at.tip_angle_rad;
  EXPECT_EQ(model.evaluateVolume(model.volumeLimitM3() * (1 + 1e-9), ws).status,
            pf::EvaluationStatus::kBeyondLimitPoint);
  EXPECT_EQ(ws.state().tip_angle_rad, tip) << "beyond it, the last shape stays";
  // Without the gas the same finger follows its volume without end.
  EXPECT_EQ(pf::FingerModel(membraneFinger(0.0, 0.0)).volumeLimitM3(), std::numeric_limits<double>::infinity());
}

TEST(FingerVolume, AGentWallLocksAtItsVolume) {
  const double jm = 6.0;  // no limit point: the pressure rises to the lock
  const pf::FingerModel model(membraneFinger(jm, 1e-4));
  const pf::MembraneWall w = pf::membraneWall(kMu, kThickness, kHeight, jm);
  const quad lam = 1 + quad(w.locking_stretch_excess);
  const double locked = static_cast<double>(quad(kChambers * kHeight * kDepth * kWidth) * (lam * lam * lam - 1) +
                                            quad(1e-4));
  EXPECT_LT(relativeError(model.volumeLimitM3(), locked), 1e-12);
  pf::FingerWorkspace ws(model);
  EXPECT_EQ(model.evaluateVolume(locked * (1 + 1e-9), ws).status, pf::EvaluationStatus::kBeyondLimitPoint);
  EXPECT_EQ(model.evaluateVolume(locked * (1 - 1e-6), ws).status, pf::EvaluationStatus::kOk);
}

// A thick Gent wall rises to its lock only logarithmically, so the gas's last share needs pressures that no double of
// delta below the lock reaches: the stretch found there holds another volume (or its pressure overflows). The volume
// input says so (solver failure, the previous state kept) rather than publish it, and every row it answers holds its
// volume within 1e-9 with a finite pressure.
TEST(FingerVolume, AVolumeThatNoStretchHoldsIsNoAnswer) {
  pf::FingerParameters params = membraneFinger(6.0, 8e-5);
  params.wall_law = pf::WallLaw::kThick;
  const pf::FingerModel model(params);
  ASSERT_FALSE(std::isfinite(model.limitGaugePa()));
  pf::FingerWorkspace ws(model);
  int answered = 0, refused = 0;
  for (int i = 1; i < 100; ++i) {
    const double v = model.volumeLimitM3() * i / 100;
    const pf::FingerState& s = model.evaluateVolume(v, ws);
    if (s.status == pf::EvaluationStatus::kSolverFailure) {
      ++refused;
      continue;
    }
    ASSERT_EQ(s.status, pf::EvaluationStatus::kOk) << i;
    ++answered;
    EXPECT_TRUE(std::isfinite(s.gauge_pa)) << i;
    EXPECT_LT(relativeError(model.suppliedVolumeOf(s), v), 1e-9) << i;
  }
  EXPECT_GT(answered, 50);
  EXPECT_GT(refused, 0);
}

TEST(FingerVolume, UnequalMembraneChambersAreFollowedUpToThePressuresLimit) {
  const pf::FingerModel model(finger("wall_law: membrane\nshear_modulus_pa: [2e4, 2e4, 2e4, 2e4, 2e4, 2e4, 3e4]\n"
                                     "wall_thickness_m: 0.002\n"));
  ASSERT_GT(model.distinctChamberCount(), 1);
  EXPECT_EQ(model.volumeLimitM3(), model.suppliedVolumeAt(model.belowLimitGaugePa()));
  pf::FingerWorkspace ws(model);
  const double p = 0.5 * model.limitGaugePa();
  const pf::FingerState& s = model.evaluateVolume(model.suppliedVolumeAt(p), ws);
  ASSERT_EQ(s.status, pf::EvaluationStatus::kOk);
  EXPECT_LT(relativeError(s.gauge_pa, p), 1e-12);
  EXPECT_EQ(model.evaluateVolume(model.volumeLimitM3() * 1.001, ws).status, pf::EvaluationStatus::kBeyondLimitPoint);
}

TEST(FingerVolume, BadVolumesAreRefusedOrGiveTheRestShape) {
  const pf::FingerModel model(membraneFinger(0.0, 8e-5));
  pf::FingerWorkspace ws(model);
  const double v = 1e-5;
  const double tip = model.evaluateVolume(v, ws).tip_angle_rad;
  for (double bad : {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity()}) {
    const pf::FingerState& s = model.evaluateVolume(bad, ws);
    EXPECT_EQ(s.status, pf::EvaluationStatus::kNotFinite);
    EXPECT_EQ(s.tip_angle_rad, tip) << "the previous numbers stay";
  }
  // Drawn out by 1 mL: the chambers at rest; the gas's pressure P_o v/(V_g - v).
  const pf::FingerState& drawn = model.evaluateVolume(-1e-6, ws);
  EXPECT_EQ(drawn.status, pf::EvaluationStatus::kVacuum);
  EXPECT_EQ(drawn.tip_angle_rad, 0.0);
  EXPECT_DOUBLE_EQ(drawn.gauge_pa, kAtmosphere * -1e-6 / (8e-5 + 1e-6));
  const pf::FingerModel water(membraneFinger(0.0, 0.0));
  pf::FingerWorkspace ws_water(water);
  // An incompressible fluid is the gas's limit V_g -> 0 of P_o v/(V_g - v): absolute zero, where the liquid
  // cavitates (NaN here once, and the node kept the last shape instead).
  const pf::FingerState& drawn_water = water.evaluateVolume(-1e-6, ws_water);
  EXPECT_EQ(drawn_water.status, pf::EvaluationStatus::kVacuum);
  EXPECT_EQ(drawn_water.gauge_pa, -kAtmosphere);
  EXPECT_EQ(drawn_water.tip_angle_rad, 0.0);
  EXPECT_EQ(water.evaluateVolume(0.0, ws_water).gauge_pa, 0.0);
}

// The inverse for a finger filled by volume: the volume at which the tip reaches an angle, on both sides of the
// pressure's limit point, against the reference's volume at the stretch whose tip angle was asked for (the reference's
// bulge through Wang's relation, in quad precision).
TEST(FingerVolume, TheVolumeForATipAngleIsTheReferencesOnBothSidesOfTheLimitPoint) {
  for (const auto& [jm, v_g] : {std::pair{0.0, 0.0}, std::pair{50.0, 8e-5}}) {
    SCOPED_TRACE("J_m " + std::to_string(jm) + ", V_g " + std::to_string(v_g));
    const pf::FingerModel model(membraneFinger(jm, v_g));
    const pf::FingerParameters& p = model.parameters();
    const double turns = 2 * p.chamber_count - 1 + p.base_wall_share;
    const double limit_delta = reference::membraneLimitStretchExcess({kMu, kThickness, kHeight, jm});
    int past_limit = 0;
    // From walls well past their gap (where the half angle is well conditioned in the bulge) to twice the limit.
    for (double delta = 0.05; delta < 2.0 * limit_delta; delta *= 1.1) {
      const double tip = turns * reference::halfAngleForBulge(0.5 * kHeight * delta, p.chamber_gap_m[0],
                                                              p.wall_critical_height_m[0]);
      double v = 0.0;
      std::string why;
      ASSERT_TRUE(model.volumeForTipAngle(tip, 1.0, v, why)) << delta << ": " << why;
      EXPECT_LT(relativeError(v, referenceMembraneVolume(delta, jm, v_g)), 1e-12) << delta;
      past_limit += delta > limit_delta;
    }
    EXPECT_GT(past_limit, 3) << "angles no pressure holds";
  }
  // Below the limit point, and for the paper law, the volume at the pressure's inverse.
  for (const pf::FingerModel& model : {pf::FingerModel(membraneFinger(50.0, 8e-5)),
                                       pf::FingerModel(pf::FingerParameters::defaults())}) {
    double gauge = 0.0, v = 0.0;
    std::string why;
    ASSERT_TRUE(model.gaugeForTipAngle(0.5, 1e9, gauge, why)) << why;
    ASSERT_TRUE(model.volumeForTipAngle(0.5, 1.0, v, why)) << why;
    EXPECT_LT(relativeError(v, model.suppliedVolumeAt(gauge)), 1e-12);
  }
}

TEST(FingerVolume, AVolumeForATipAngleIsRefusedWithItsReason) {
  const pf::FingerModel snaps(membraneFinger(0.0, 2e-3));  // its volume has a maximum: volume control snaps there
  double v = 0.0;
  std::string why;
  EXPECT_FALSE(snaps.volumeForTipAngle(10.0, 1.0, v, why));
  EXPECT_NE(why.find("beyond what volume control follows: the most is"), std::string::npos) << why;
  EXPECT_FALSE(snaps.volumeForTipAngle(-0.1, 1.0, v, why));
  EXPECT_NE(why.find("is not a finite angle >= 0"), std::string::npos) << why;
  const pf::FingerModel water(membraneFinger(0.0, 0.0));
  EXPECT_FALSE(water.volumeForTipAngle(1.0, 1e-9, v, why));
  EXPECT_NE(why.find("m^3, more than the allowed 1e-09 m^3"), std::string::npos) << why;
  EXPECT_FALSE(water.volumeForTipAngle(100.0, 1.0, v, why));
  EXPECT_NE(why.find("beyond the model's limit"), std::string::npos) << why;
}

// The batch by volume: each row the bits of evaluateVolume() along the same sequence (one workspace each), NaN in
// every output where evaluateVolume() keeps a previous state, and every status: a sweep from drawn out to past the
// volume's limit, with NaN and inf among it, for a gas that snaps the finger, a Gent wall, unequal chambers and the
// paper law.
TEST(FingerVolume, TheBatchByVolumeWritesEachRowAsEvaluateVolumeDoesAndNaNWhereItKeepsAPreviousState) {
  const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
  const std::vector<pf::FingerParameters> fingers = {
      membraneFinger(0.0, 2e-3), membraneFinger(50.0, 1e-5),
      finger("wall_law: membrane\nshear_modulus_pa: [2e4, 2e4, 2e4, 2e4, 2e4, 2e4, 3e4]\nwall_thickness_m: 0.002\n"),
      finger("dead_volume_m3: 1e-5\n")};
  for (const pf::FingerParameters& params : fingers) {
    const pf::FingerModel model(params);
    const double top = std::isfinite(model.volumeLimitM3()) ? model.volumeLimitM3() : model.suppliedVolumeAt(3e5);
    std::vector<double> volumes = {-1e-6, 0.0, nan};
    for (int i = 1; i <= 60; ++i) volumes.push_back(top * 1.2 * i / 60.0);
    volumes.insert(volumes.begin() + 30, {inf, -inf, top * 0.5});
    const std::size_t n = static_cast<std::size_t>(model.chamberCount()), count = volumes.size();
    pf::BatchBuffers rows(count, model.chamberCount());
    std::vector<double> gauge(count);
    pf::FingerWorkspace batch_ws(model), single_ws(model);
    model.evaluateVolumeMany(volumes.data(), count, rows.outputs(), gauge.data(), batch_ws);
    int beyond = 0, answered_rows = 0;
    for (std::size_t i = 0; i < count; ++i) {
      SCOPED_TRACE("row " + std::to_string(i) + ", volume " + pf::formatExact(volumes[i]));
      const pf::FingerState& s = model.evaluateVolume(volumes[i], single_ws);
      ASSERT_EQ(rows.status[i], static_cast<std::uint8_t>(s.status));
      const bool answered = s.status == pf::EvaluationStatus::kOk || s.status == pf::EvaluationStatus::kVacuum;
      beyond += s.status == pf::EvaluationStatus::kBeyondLimitPoint;
      answered_rows += answered;
      auto same = [answered](double batch, double single) {
        return answered ? (batch == single || (std::isnan(batch) && std::isnan(single))) : std::isnan(batch);
      };
      EXPECT_TRUE(same(gauge[i], s.gauge_pa)) << gauge[i] << " against " << s.gauge_pa;
      EXPECT_TRUE(same(rows.tip_angle_rad[i], s.tip_angle_rad));
      for (std::size_t k = 0; k < n; ++k) {
        const auto e = static_cast<Eigen::Index>(k);
        EXPECT_TRUE(same(rows.stretch[i * n + k], s.stretch[e]) && same(rows.bulge_m[i * n + k], s.bulge_m[e]) &&
                    same(rows.half_angle_rad[i * n + k], s.half_angle_rad[e]) &&
                    same(rows.joint_angle_rad[i * n + k], s.joint_angle_rad[e]))
            << "chamber " << k;
      }
      for (std::size_t k = 0; k < 2 * (n + 2); ++k) {
        EXPECT_TRUE(same(rows.backbone_m[i * 2 * (n + 2) + k], s.backbone_m.data()[k])) << "backbone " << k;
      }
    }
    EXPECT_GT(answered_rows, 40);
    if (std::isfinite(model.volumeLimitM3())) {
      EXPECT_GT(beyond, 3) << "the sweep passes the volume's limit";
    }
    EXPECT_EQ(batch_ws.state().tip_angle_rad, single_ws.state().tip_angle_rad) << "the workspace holds the last state";
  }
}

// The volume input has the pressure's range. The top is the volume whose pressure is max_gauge_pa;
// the reference is the model's own pressure at that volume (evaluateVolume's output), and on the paper law its forward
// volume at max_gauge_pa. Before, 1 m^3 gave the paper finger an absurd pressure with status ok.
TEST(FingerVolume, AVolumeAboveTheOneThatMakesMaxGaugePaIsClampedToIt) {
  const pf::FingerModel paper(pf::FingerParameters::defaults());
  pf::FingerWorkspace ws(paper);
  const pf::PressureRange range;
  const double top = pf::maxSuppliedVolumeM3(paper, range);
  EXPECT_EQ(top, paper.suppliedVolumeAt(range.max_gauge_pa));
  EXPECT_NEAR(paper.evaluateVolume(top, ws).gauge_pa, range.max_gauge_pa, 1e-9 * range.max_gauge_pa);
  const pf::VolumeCheck big = pf::checkVolumeRange(1.0, top);
  EXPECT_TRUE(big.clamped);
  EXPECT_EQ(big.volume_m3, top);
  EXPECT_FALSE(pf::checkVolumeRange(0.5 * top, top).clamped);
  EXPECT_FALSE(pf::checkVolumeRange(-1e-6, top).clamped) << "a negative volume is the model's vacuum, not a clamp";
  EXPECT_TRUE(std::isnan(pf::checkVolumeRange(NAN, top).volume_m3));
  EXPECT_EQ(pf::volumeClampedMessage(1.0, 2e-6, range),
            "supplied volume 1 m^3 is above 2e-06 m^3, the volume that makes max_gauge_pa 294199.5 Pa (the top of "
            "the model's range): clamped to it");
  // A Gent membrane whose limit point lies inside the range: past it the pressure falls, then climbs on the far
  // branch; the top is where it passes max_gauge_pa there, and just below it the pressure is within the range.
  const pf::FingerModel gent(membraneFinger(19.0, 0.0));
  pf::FingerWorkspace wg(gent);
  const pf::PressureRange low = pf::PressureRange::upTo(1.5 * gent.limitGaugePa());
  const double gent_top = pf::maxSuppliedVolumeM3(gent, low);
  ASSERT_TRUE(std::isfinite(gent_top));
  EXPECT_GT(gent_top, gent.limitPointVolumeM3());
  EXPECT_NEAR(gent.evaluateVolume(gent_top, wg).gauge_pa, low.max_gauge_pa, 1e-9 * low.max_gauge_pa);
  for (double f = 0.0; f < 1.0; f += 0.01) {
    EXPECT_LE(gent.evaluateVolume(f * gent_top, wg).gauge_pa, low.max_gauge_pa * (1 + 1e-12)) << f;
  }
  // A Neo-Hookean balloon never gets back to its limit pressure: no top (its limit point's rule applies).
  const pf::FingerModel balloon(membraneFinger(0.0, 0.0));
  EXPECT_TRUE(std::isinf(pf::maxSuppliedVolumeM3(balloon, pf::PressureRange::upTo(1.5 * balloon.limitGaugePa()))));
}

// The EPFL actuator as drawn with its coupon's elastomer: a Gent wall whose far branch climbs back to the top of its
// range (50 kPa) only just before it locks, within the growth step of the search. Before, the search stepped past
// the crossing into the lock, where the model follows no volume, and gave no top: 1 m^3 was 'beyond limit point'
// (no shape) where 1e7 Pa is clamped. Now the crossing is found between the last followed volume and the lock.
TEST(FingerVolume, AVolumeAboveTheTopIsClampedWhereTheWallLocksJustPastIt) {
  pf::RawParameterMap raw;
  pf::PressureRange range;
  pf::loadRawParametersFromYamlFile(std::string(PACKAGE_SOURCE_DIR) + "/config/epfl_ecoflex30_c7_coupon.yaml", raw,
                                    nullptr, &range);
  const pf::FingerModel model(pf::FingerParameters::fromRaw(raw));
  pf::FingerWorkspace ws(model);
  ASSERT_LT(model.limitGaugePa(), range.max_gauge_pa) << "the limit point lies within the range";
  const double top = pf::maxSuppliedVolumeM3(model, range);
  ASSERT_TRUE(std::isfinite(top));
  EXPECT_GT(top, model.limitPointVolumeM3());
  EXPECT_LT(top, model.volumeLimitM3());
  EXPECT_NEAR(model.evaluateVolume(top, ws).gauge_pa, range.max_gauge_pa, 1e-9 * range.max_gauge_pa);
  for (double f = 0.0; f < 1.0; f += 0.01) {  // below the top, no volume makes more than the top's pressure
    EXPECT_LE(model.evaluateVolume(f * top, ws).gauge_pa, range.max_gauge_pa * (1 + 1e-12)) << f;
  }
  const pf::VolumeCheck big = pf::checkVolumeRange(1.0, top);
  EXPECT_TRUE(big.clamped);
  EXPECT_NE(model.evaluateVolume(big.volume_m3, ws).status, pf::EvaluationStatus::kBeyondLimitPoint);
}
