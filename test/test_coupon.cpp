// The elastomer from a coupon test (src/calibration): the uniaxial stress against the strain energy it comes from,
// a fit that gives back the material a synthetic coupon was made with, and bad coupons refused with the reason.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <string>
#include <vector>

#include "pneumatic_finger/calibration/coupon.hpp"
#include "pneumatic_finger/core/parameters.hpp"

namespace pf = pneumatic_finger;

namespace {

// Gent's strain energy per unit volume, W = -(mu J_m / 2) ln(1 - (I1 - 3) / J_m), for uniaxial stretch l of an
// incompressible solid (I1 = l^2 + 2 / l); J_m = 0: Neo-Hookean, W = mu (I1 - 3) / 2.
long double energy(long double l, long double mu, long double jm) {
  const long double i = l * l + 2.0L / l - 3.0L;
  return jm > 0 ? -0.5L * mu * jm * std::log(1.0L - i / jm) : 0.5L * mu * i;
}

// A coupon made with mu, J_m and a preload, at strains 0 .. @p last in @p rows steps, each stress times (1 + noise).
pf::CouponTest synthetic(double mu, double jm, double preload, double last, int rows,
                         const std::vector<double>& noise = {}) {
  std::vector<double> strain, stress;
  for (int k = 0; k < rows; ++k) {
    strain.push_back(last * k / (rows - 1));
    const double l = (1.0 + strain.back()) * (1.0 + preload);
    stress.push_back(pf::uniaxialNominalStressPa(l, mu, jm) * (1.0 + (noise.empty() ? 0.0 : noise[k % noise.size()])));
  }
  return pf::couponFromColumns(strain, stress, "synthetic");
}

std::string refusal(const std::vector<double>& strain, const std::vector<double>& stress) {
  try {
    pf::couponFromColumns(strain, stress, "coupon");
  } catch (const pf::ParameterError& e) {
    return e.what();
  }
  return "(accepted)";
}

}  // namespace

// The nominal stress is dW/dl: checked by a central difference of the energy in long double, for both laws, up to
// near the lock.
TEST(Coupon, TheUniaxialStressIsTheStrainEnergysDerivative) {
  for (double jm : {0.0, 5.0, 70.0}) {
    for (double l : {1.01, 1.5, 2.0, 2.6}) {
      if (jm > 0 && l * l + 2 / l - 3 >= 0.98 * jm) continue;
      const long double h = 1e-6L;
      const double numeric = static_cast<double>((energy(l + h, 2e4, jm) - energy(l - h, 2e4, jm)) / (2 * h));
      EXPECT_NEAR(pf::uniaxialNominalStressPa(l, 2e4, jm), numeric, 1e-6 * numeric) << "J_m " << jm << ", l " << l;
    }
  }
  EXPECT_TRUE(std::isnan(pf::uniaxialNominalStressPa(3.0, 2e4, 5.0))) << "past the lock: I1 - 3 = 6.67 > J_m";
}

// A coupon made with known material is given back: Gent with a preload, and a Neo-Hookean one.
TEST(Coupon, TheFitGivesBackTheMaterialACouponWasMadeWith) {
  const pf::CouponFit gent = pf::fitCoupon(synthetic(25e3, 40.0, 0.05, 4.0, 60));
  EXPECT_NEAR(gent.shear_modulus_pa, 25e3, 1e-6 * 25e3);
  EXPECT_NEAR(gent.wall_locking_jm, 40.0, 1e-6 * 40.0);
  EXPECT_NEAR(gent.preload_strain, 0.05, 1e-7);
  EXPECT_LT(gent.max_relative_error, 1e-8);
  const pf::CouponFit neo = pf::fitCoupon(synthetic(60e3, 0.0, 0.0, 2.0, 30), false);
  EXPECT_NEAR(neo.shear_modulus_pa, 60e3, 1e-6 * 60e3);
  EXPECT_EQ(neo.wall_locking_jm, 0.0);
  EXPECT_NEAR(neo.preload_strain, 0.0, 1e-8);
}

// With 1 % noise on the stress the material comes back within its reported uncertainty (three standard deviations),
// and the uncertainty is not zero.
TEST(Coupon, TheUncertaintyCoversTheTruthUnderNoise) {
  const std::vector<double> noise = {0.01, -0.008, 0.004, -0.012, 0.007, -0.003, 0.011, -0.009};
  const pf::CouponFit fit = pf::fitCoupon(synthetic(25e3, 40.0, 0.05, 4.0, 60, noise));
  EXPECT_GT(fit.shear_modulus_sd_pa, 0.0);
  EXPECT_GT(fit.wall_locking_jm_sd, 0.0);
  EXPECT_GT(fit.preload_strain_sd, 0.0);
  EXPECT_LT(std::fabs(fit.shear_modulus_pa - 25e3), 3 * fit.shear_modulus_sd_pa);
  EXPECT_LT(std::fabs(fit.wall_locking_jm - 40.0), 3 * fit.wall_locking_jm_sd);
  EXPECT_LT(std::fabs(fit.preload_strain - 0.05), 3 * fit.preload_strain_sd);
  EXPECT_NEAR(fit.max_relative_error, 0.012, 0.004) << "the noise's own size";
}

// Bad coupons get the reason: percent strain, a stress in MPa or kPa, a stress that falls, a strain that does not rise,
// too few rows.
TEST(Coupon, BadCouponsAreRefusedWithTheReason) {
  const std::vector<double> strain = {0.0, 0.5, 1.0, 1.5, 2.0}, stress = {0.0, 2e4, 3.5e4, 5e4, 6.5e4};
  std::vector<double> percent = strain;
  for (double& e : percent) e *= 100;
  EXPECT_NE(refusal(percent, stress).find("is it in percent? Give a ratio"), std::string::npos) << refusal(percent, stress);
  std::vector<double> mpa = stress;
  for (double& s : mpa) s *= 1e-6;
  EXPECT_NE(refusal(strain, mpa).find("is the stress in kPa or MPa (N/mm^2), or the strain in percent? Give the stress "
                                      "in Pa"),
            std::string::npos)
      << refusal(strain, mpa);
  std::vector<double> kpa = stress;
  for (double& s : kpa) s *= 1e-3;
  EXPECT_NE(refusal(strain, kpa).find("softer than any elastomer"), std::string::npos) << refusal(strain, kpa);
  const std::vector<double> falls = {0.0, 2e4, 3.5e4, 2.5e4, 6.5e4};
  EXPECT_NE(refusal(strain, falls).find("coupon: row 4: the stress falls to 25000 Pa from 35000 Pa"), std::string::npos)
      << refusal(strain, falls);
  const std::vector<double> back = {0.0, 0.5, 0.4, 1.5, 2.0};
  EXPECT_NE(refusal(back, stress).find("row 3: engineering strain 0.4 must be >= 0 and rise row by row"),
            std::string::npos) << refusal(back, stress);
  EXPECT_NE(refusal({0, 1, 2}, {0, 1e4, 2e4}).find("3 rows; a coupon fit needs at least 4"), std::string::npos);
  EXPECT_EQ(refusal(strain, stress), "(accepted)");
}

// The package's coupon file reads (its header, its comments, its 311 rows) and a missing column is named.
TEST(Coupon, TheCsvReaderTakesThePackagesCouponAndNamesAMissingColumn) {
  const pf::CouponTest test = pf::loadCouponCsv(std::string(PACKAGE_SOURCE_DIR) + "/data/epfl_ecoflex30_uniaxial.csv");
  ASSERT_EQ(test.rows.size(), 311u);
  EXPECT_EQ(test.rows.front().nominal_stress_pa, 6933.3);
  EXPECT_EQ(test.rows.back().engineering_strain, 6.2);
  const std::string path = testing::TempDir() + "/coupon_mpa.csv";
  std::ofstream(path) << "engineering_strain,nominal_stress_mpa\n0,0\n1,0.05\n";
  try {
    pf::loadCouponCsv(path);
    ADD_FAILURE() << "a stress column in MPa was read";
  } catch (const pf::ParameterError& e) {
    EXPECT_NE(std::string(e.what()).find("header needs the columns engineering_strain and nominal_stress_pa; give the "
                                         "stress in Pa"), std::string::npos) << e.what();
  }
}

// A stiffer elastomer's first rows, to 20 % strain, written in percent (0..20), pass every row's check: their secant is
// an elastomer's and no strain is past 2000 %. Before, they were fitted (mu 1.5e4 +- 1.3e5 Pa, the preload on its
// bound); the fit now refuses a modulus its data do not fix, and asks about percent. The same rows as ratios fit.
TEST(Coupon, PercentStrainOfSmallStretchesIsRefusedByTheFitItself) {
  const pf::CouponTest file = pf::loadCouponCsv(std::string(PACKAGE_SOURCE_DIR) + "/data/epfl_ecoflex30_uniaxial.csv");
  std::vector<double> ratio, percent, stiff;
  for (const pf::CouponRow& r : file.rows) {
    if (r.engineering_strain > 0.2) break;
    ratio.push_back(r.engineering_strain);
    percent.push_back(100.0 * r.engineering_strain);
    stiff.push_back(28.0 * r.nominal_stress_pa);  // about 0.6 MPa: a stiffer silicone than Ecoflex 00-30
  }
  // As ratios, 20 % of strain fixes the modulus (Neo-Hookean: it does not reach the lock, which Gent refuses below).
  const pf::CouponFit as_ratio = pf::fitCoupon(pf::couponFromColumns(ratio, stiff, "coupon"), false);
  EXPECT_LT(as_ratio.shear_modulus_sd_pa, 0.2 * as_ratio.shear_modulus_pa);
  try {
    pf::fitCoupon(pf::couponFromColumns(ratio, stiff, "coupon"), true);
    ADD_FAILURE() << "a lock 20 % of strain cannot reach was fitted";
  } catch (const pf::ParameterError& e) {
    EXPECT_NE(std::string(e.what()).find("coupon: the coupon does not fix where the elastomer locks"),
              std::string::npos) << e.what();
  }
  try {
    pf::fitCoupon(pf::couponFromColumns(percent, stiff, "coupon"), true);
    ADD_FAILURE() << "a coupon in percent was fitted";
  } catch (const pf::ParameterError& e) {
    EXPECT_NE(std::string(e.what()).find("coupon: the coupon does not fix the shear modulus"), std::string::npos)
        << e.what();
    EXPECT_NE(std::string(e.what()).find("is the strain in percent? Give it as a ratio (0.2 for 20 %)"),
              std::string::npos) << e.what();
  }
}

// A refused row of a file is named by its line, as an editor counts (comments and the header included).
TEST(Coupon, ARefusedRowOfAFileIsNamedByItsLine) {
  const std::string path = testing::TempDir() + "coupon_lines.csv";
  std::ofstream(path) << "# a comment\nengineering_strain,nominal_stress_pa\n0,0\n0.5,2e4\n# mid\n1.0,1.5e4\n2,3e4\n";
  try {
    pf::loadCouponCsv(path);
    ADD_FAILURE() << "a falling stress was read";
  } catch (const pf::ParameterError& e) {
    EXPECT_NE(std::string(e.what()).find(path + ":6 (data row 3): the stress falls"), std::string::npos) << e.what();
  }
}
