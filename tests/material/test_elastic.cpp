#include <gtest/gtest.h>

#include <cmath>

#include "material/elastic.hpp"

namespace {

using exdyn::material::elastic_constants;

TEST(Elastic, LameConstantsOfSteelMatchTheReferencePage) {
  // ../shared/reference/plate-impact.md: lambda = 1.211538e11, mu = 8.076923e10,
  // M = 2.826923e11 Pa, c1 = 6020.18 m/s.
  const auto steel = elastic_constants(2.1e11, 0.3, 7800);
  EXPECT_NEAR(steel.lambda, 1.211538e11, 1e5);
  EXPECT_NEAR(steel.mu, 8.076923e10, 1e5);
  EXPECT_NEAR(steel.dilatational_modulus(), 2.826923e11, 1e5);
  EXPECT_NEAR(steel.dilatational_wave_speed(), 6020.18, 0.01);
  EXPECT_NEAR(steel.bulk_modulus(), 2.1e11 / (3 * (1 - 2 * 0.3)), 1e-3 * 2.1e11 * 1e-9);
}

TEST(Elastic, UniaxialStrainGivesTheLateralStressRatioLambdaOverM) {
  const auto c = elastic_constants(2.1e11, 0.3, 7800);
  const auto s = exdyn::material::stress_from_strain(c, {1e-4, 0, 0, 0, 0, 0});
  EXPECT_DOUBLE_EQ(s[0], c.dilatational_modulus() * 1e-4);
  EXPECT_DOUBLE_EQ(s[1], c.lambda * 1e-4);
  EXPECT_DOUBLE_EQ(s[2], c.lambda * 1e-4);
  EXPECT_EQ(s[3], 0.0);
}

TEST(Elastic, ShearStrainGivesTwoMuTimesTensorStrainInItsOwnComponent) {
  const auto c = elastic_constants(2.1e11, 0.3, 7800);
  for (int k = 3; k < 6; ++k) {
    exdyn::material::SymTensor eps{};
    eps[k] = 1e-4;  // tensor (not engineering) shear strain
    const auto s = exdyn::material::stress_from_strain(c, eps);
    for (int j = 0; j < 6; ++j) EXPECT_DOUBLE_EQ(s[j], j == k ? 2 * c.mu * 1e-4 : 0.0) << k << " " << j;
  }
}

TEST(Elastic, StrainEnergyDensityCountsShearTwice) {
  // W = sigma_ij eps_ij / 2 sums both off-diagonal entries: pure shear with
  // eps_xy = eps_yx = g has sigma_xy = 2 mu g and W = 2 mu g^2.
  const auto c = elastic_constants(2.1e11, 0.3, 7800);
  const exdyn::material::SymTensor eps{0, 0, 0, 1e-4, 0, 0};
  const auto s = exdyn::material::stress_from_strain(c, eps);
  EXPECT_DOUBLE_EQ(exdyn::material::strain_energy_density(s, eps), 2 * c.mu * 1e-8);
}

TEST(Elastic, VonMisesOfUniaxialStressAndPureShear) {
  EXPECT_DOUBLE_EQ(exdyn::material::von_mises({100, 0, 0, 0, 0, 0}), 100.0);
  EXPECT_NEAR(exdyn::material::von_mises({0, 0, 0, 0, 0, 100}), std::sqrt(3.0) * 100.0, 1e-12);
  EXPECT_NEAR(exdyn::material::von_mises({-7, -7, -7, 0, 0, 0}), 0.0, 1e-12);  // hydrostatic
}

}  // namespace
