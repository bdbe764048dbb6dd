// Ductile damage (material/failure.hpp): the stress triaxiality of known states, the
// Johnson-Cook failure strain at a point against a hand value, and the range where it
// is used (no damage below sigma* = -1/3, eps_f held above 1.5, the rate ratio held at
// 1e12).
#include <gtest/gtest.h>

#include <array>
#include <cmath>

#include "material/failure.hpp"

namespace {

using exdyn::material::Failure;

// A set of the usual form for a structural steel (D3 < 0: ductility falls with
// triaxiality; D4 < 0: and with rate), eps_dot_0 = 5e-4 /s.
Failure steel() {
  Failure f;
  f.model = exdyn::input::FailureModel::johnson_cook;
  f.d = {0.0705, 1.732, -0.54, -0.0123, 0.0};
  f.reference_rate = 5.0e-4;
  return f;
}

TEST(Failure, TriaxialityOfKnownStates) {
  const std::array<double, 6> uniaxial{300e6, 0, 0, 0, 0, 0};
  EXPECT_NEAR(Failure::triaxiality(uniaxial.data()), 1.0 / 3.0, 1e-15);
  const std::array<double, 6> compression{0, 0, -300e6, 0, 0, 0};
  EXPECT_NEAR(Failure::triaxiality(compression.data()), -1.0 / 3.0, 1e-15);
  const std::array<double, 6> shear{0, 0, 0, 100e6, 0, 0};
  EXPECT_EQ(Failure::triaxiality(shear.data()), 0.0);
  const std::array<double, 6> equibiaxial{200e6, 200e6, 0, 0, 0, 0};
  EXPECT_NEAR(Failure::triaxiality(equibiaxial.data()), 2.0 / 3.0, 1e-15);
  const std::array<double, 6> hydrostatic{1e8, 1e8, 1e8, 0, 0, 0};
  EXPECT_EQ(Failure::triaxiality(hydrostatic.data()), 0.0);  // no deviator: no flow either
  // Uniaxial strain at eps = 1e-3 in the elastic range, nu = 0.3: sigma = (lambda + 2 mu, lambda,
  // lambda) eps; sigma_m / sigma_vm = (lambda + 2 mu / 3) / (2 mu) = (1 + nu) / (3 (1 - 2 nu)).
  const double e = 200e9, nu = 0.3, lambda = e * nu / ((1 + nu) * (1 - 2 * nu)), mu = e / (2 * (1 + nu));
  const std::array<double, 6> strain{lambda * 1e-3, lambda * 1e-3, (lambda + 2 * mu) * 1e-3, 0, 0, 0};
  EXPECT_NEAR(Failure::triaxiality(strain.data()), (1 + nu) / (3 * (1 - 2 * nu)), 1e-14);
}

TEST(Failure, JohnsonCookFailureStrainAgainstAHandValue) {
  const Failure f = steel();
  // Uniaxial tension (sigma* = 1/3) at eps_dot_p = 1000 /s: the rate ratio 2e6,
  // eps_f = (0.0705 + 1.732 exp(-0.18)) (1 - 0.0123 ln 2e6)
  //       = (0.0705 + 1.4466978...) (1 - 0.0123 x 14.508658) = 1.5171978 x 0.8215435 = 1.2464...
  const double by_hand = (0.0705 + 1.732 * std::exp(-0.54 / 3.0)) * (1.0 - 0.0123 * std::log(2.0e6));
  EXPECT_NEAR(by_hand, 1.24644, 1e-5);
  EXPECT_DOUBLE_EQ(f.failure_strain(1.0 / 3.0, 2.0e6), by_hand);
  // One step of 1e-3 plastic strain over 1e-6 s in uniaxial tension: D grows by 1e-3 / eps_f.
  EXPECT_DOUBLE_EQ(f.damage_after(0.25, 0.5, 1.0e-3, 1.0e-6, 1.0 / 3.0), 0.25 + 1.0e-3 / by_hand);
  // Slower than eps_dot_0: the rate term is 1.
  EXPECT_DOUBLE_EQ(f.damage_after(0.0, 0.5, 1.0e-3, 1.0e3, 0.0), 1.0e-3 / (0.0705 + 1.732));
}

TEST(Failure, RangeWhereTheJohnsonCookStrainIsUsed) {
  const Failure f = steel();
  // Below sigma* = -1/3 no damage; above 1.5 the value at 1.5; rate ratios above 1e12 the
  // value at 1e12.
  EXPECT_EQ(f.damage_after(0.1, 0.5, 1.0e-3, 1.0e-6, -0.34), 0.1);
  EXPECT_GT(f.damage_after(0.1, 0.5, 1.0e-3, 1.0e-6, -0.33), 0.1);
  EXPECT_EQ(f.damage_after(0.0, 0.5, 1.0e-3, 1.0e-6, 3.0), f.damage_after(0.0, 0.5, 1.0e-3, 1.0e-6, 1.5));
  EXPECT_EQ(f.damage_after(0.0, 0.5, 1.0e-3, 1.0e-18, 1.0), 1.0e-3 / f.failure_strain(1.0, 1.0e12));
  // No plastic increment: no damage.
  EXPECT_EQ(f.damage_after(0.3, 0.5, 0.0, 1.0e-6, 1.0), 0.3);
}

TEST(Failure, PlasticStrainFailureIsTheStrainOverEpsF) {
  Failure f;
  f.model = exdyn::input::FailureModel::plastic_strain;
  f.strain = 0.4;
  EXPECT_EQ(f.damage_after(0.0, 0.1, 0.1, 1e-6, -5.0), 0.25);  // whatever the triaxiality
  EXPECT_EQ(f.damage_after(0.25, 0.4, 0.3, 1e-6, 1.0), 1.0);
  EXPECT_FALSE(Failure{}.active());
  EXPECT_TRUE(f.active());
}

}  // namespace
