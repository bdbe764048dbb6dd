// The assumed-strain hourglass control of hex8r (element/hourglass.hpp): the beam's
// bending energy in one element, the linear kernels' symmetry and fast path, the
// law kernel's plastic limit and its rotation with the body.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <random>

#include "element/hex8_constitutive.hpp"
#include "element/hex8r.hpp"
#include "element/hourglass.hpp"
#include "material/elastic.hpp"
#include "reference_elements.hpp"

namespace exdyn::element {
namespace {

using testing::random_distorted_hex;
using testing::random_parallelepiped;
using testing::random_vectors;
using testing::to_vector;

constexpr double youngs = 2.1e11, poisson = 0.3;
const material::ElasticConstants steel = material::elastic_constants(youngs, poisson, 7800.0);
const hex8r::Stabilization physical{input::HourglassModel::assumed_strain, 1.0, youngs, steel.mu};

// A rotation of `angle` about a unit axis.
Eigen::Matrix3d rotation(double angle, Eigen::Vector3d axis) {
  return Eigen::AngleAxisd(angle, axis.normalized()).toRotationMatrix();
}

// The brick [-a0, a0] x [-a1, a1] x [-a2, a2], turned by r and moved by d; with the
// field u = r v(r^T (x - d)) given in its own axes.
template <class Field>
void oriented_brick(const std::array<double, 3>& a, const Eigen::Matrix3d& r, const Eigen::Vector3d& d,
                    Field field, ElementVectors& x, ElementVectors& u) {
  for (int I = 0; I < 8; ++I) {
    const Eigen::Vector3d local(a[0] * testing::node_sign[I][0], a[1] * testing::node_sign[I][1],
                                a[2] * testing::node_sign[I][2]);
    const Eigen::Vector3d p = r * local + d, v = r * field(local);
    x.x[I] = p(0), x.y[I] = p(1), x.z[I] = p(2);
    u.x[I] = v(0), u.y[I] = v(1), u.z[I] = v(2);
  }
}

hex8r::Energies linear(const ElementVectors& x, const ElementVectors& u, ElementVectors& f) {
  std::array<double, hex8r::reference_size> reference{};
  EXPECT_GT(hex8r::make_reference(x, physical, reference.data()), 0.0);
  std::array<double, 6> stress{};
  return hex8r::internal_forces(reference.data(), steel.lambda, steel.mu, u, f, stress);
}

// Pure bending u_x = kappa x y, u_y = -kappa x^2 / 2 of a brick of length L = 2 a0,
// depth 2 a1 and width 2 a2: the element stores beam theory's E I kappa^2 L / 2
// (I = 2 a2 (2 a1)^3 / 12), turned in space or not; the uniform strain is zero.
TEST(AssumedStrainHourglass, PureBendingStoresTheBeamEnergy) {
  const std::array<double, 3> a{2.0e-3, 0.5e-3, 0.75e-3};
  const double kappa = 3.0;  // 1/m
  const double inertia = 2 * a[2] * std::pow(2 * a[1], 3) / 12.0;
  const double beam = 0.5 * youngs * inertia * kappa * kappa * 2 * a[0];
  const auto bending = [kappa](const Eigen::Vector3d& p) {
    return Eigen::Vector3d(kappa * p(0) * p(1), -0.5 * kappa * p(0) * p(0), 0.0);
  };
  for (const Eigen::Matrix3d& r :
       {Eigen::Matrix3d(Eigen::Matrix3d::Identity()), rotation(0.7, Eigen::Vector3d(1, -2, 0.5))}) {
    ElementVectors x, u, f;
    oriented_brick(a, r, Eigen::Vector3d(1e-3, 2e-3, -1e-3), bending, x, u);
    const hex8r::Energies e = linear(x, u, f);
    EXPECT_NEAR(e.hourglass, beam, 1e-12 * beam);
    EXPECT_NEAR(e.strain, 0.0, 1e-12 * beam);
  }
}

// The twisting field u_z = kappa x y is one the trilinear brick holds: the control
// stores its exact energy, integral of 2 mu (eps_xz^2 + eps_yz^2) dV.
TEST(AssumedStrainHourglass, WarpingStoresTheExactShearEnergy) {
  const std::array<double, 3> a{1.0e-3, 0.6e-3, 0.4e-3};
  const double kappa = 2.0;
  // eps_xz = kappa y / 2, eps_yz = kappa x / 2: 2 mu (kappa^2 / 4)(a1^2 + a0^2) / 3 times V.
  const double volume = 8 * a[0] * a[1] * a[2];
  const double exact = 2 * steel.mu * kappa * kappa / 4 * (a[0] * a[0] + a[1] * a[1]) / 3 * volume;
  ElementVectors x, u, f;
  oriented_brick(
      a, Eigen::Matrix3d::Identity(), Eigen::Vector3d::Zero(),
      [kappa](const Eigen::Vector3d& p) { return Eigen::Vector3d(0, 0, kappa * p(0) * p(1)); }, x, u);
  const hex8r::Energies e = linear(x, u, f);
  EXPECT_NEAR(e.hourglass + e.strain, exact, 1e-12 * exact);
}

// On distorted bricks: f . v = u . K v = v . f(u) (symmetric), E = u . f / 2, and
// the parallelepiped kernel equals the general one where both apply.
TEST(AssumedStrainHourglass, LinearKernelsAreSymmetricAndAgree) {
  std::mt19937_64 rng(41);
  for (int trial = 0; trial < 20; ++trial) {
    const ElementVectors x = random_distorted_hex(rng, 1e-3);
    const ElementVectors u = random_vectors(rng, 1e-6), v = random_vectors(rng, 1e-6);
    ElementVectors fu, fv;
    const hex8r::Energies e = linear(x, u, fu);
    linear(x, v, fv);
    const double a = to_vector(fu).dot(to_vector(v)), b = to_vector(fv).dot(to_vector(u));
    EXPECT_NEAR(a, b, 1e-12 * std::abs(a) + 1e-12 * to_vector(fu).norm() * 1e-6);
    EXPECT_NEAR(e.strain + e.hourglass, 0.5 * to_vector(fu).dot(to_vector(u)),
                1e-12 * (e.strain + e.hourglass));

    const ElementVectors p = random_parallelepiped(rng, 1e-3);
    ElementVectors general, fast;
    const hex8r::Energies eg = linear(p, u, general);
    std::array<double, hex8r::parallelepiped_reference_size> reference{};
    hex8r::make_parallelepiped_reference(p, physical, reference.data());
    std::array<double, 6> stress{};
    const hex8r::Energies ef =
        hex8r::parallelepiped_internal_forces(reference.data(), steel.lambda, steel.mu, u, fast, stress);
    EXPECT_LT((to_vector(fast) - to_vector(general)).cwiseAbs().maxCoeff(),
              1e-12 * to_vector(general).cwiseAbs().maxCoeff());
    EXPECT_NEAR(ef.hourglass, eg.hourglass, 1e-12 * eg.hourglass);
  }
}

// The law kernel, one element (Real = double) from its initial states.
struct LawPass {
  ElementVectors f;
  std::array<double, hex8r::hourglass_state_size> hourglass{};
  double hourglass_work = 0.0;
  ConstitutiveResult<double> result;
};

template <class Flow, bool Finite>
LawPass law_pass(const ElementVectors& x, const ElementVectors& u, const Flow& flow) {
  std::array<double, hex8r::law_reference_size> reference{};
  EXPECT_GT(hex8r::make_reference(x, physical, reference.data(), true), 0.0);
  std::array<double, material::j2_state_size> old_state{}, new_state{};
  material::initial_state(Finite, old_state.data());
  const std::array<double, hex8r::hourglass_state_size> old_hourglass{};
  LawPass pass;
  pass.result = hex8r::assumed_strain_forces<Flow, Finite>(
      reference.data(), steel, flow, u, pass.f, old_state.data(), new_state.data(), old_hourglass.data(),
      pass.hourglass.data(), 1e-8, pass.hourglass_work);
  return pass;
}

// Bending far past yield with no mean strain: the bending mode's plastic part is at the
// limit sigma_y V / (8 sqrt(3) a0); with the mean stress at yield besides, nothing is
// left for the modes and their plastic parts are zero (the elastic share remains).
TEST(AssumedStrainHourglass, ModesFlowAtThePlasticLimit) {
  const std::array<double, 3> a{1.0e-3, 1.0e-3, 1.0e-3};
  const double sigma_y = 300e6;
  const material::Hardening flow = material::Hardening::linear(sigma_y, 0.0);
  const double kappa = 20.0;  // bending strain kappa a1 = 2 %, ten times the yield strain
  ElementVectors x, u;
  oriented_brick(
      a, Eigen::Matrix3d::Identity(), Eigen::Vector3d::Zero(),
      [kappa](const Eigen::Vector3d& p) {
        return Eigen::Vector3d(kappa * p(0) * p(1), -0.5 * kappa * p(0) * p(0), 0.0);
      },
      x, u);
  const LawPass bent = law_pass<material::Hardening, false>(x, u, flow);
  const double limit = sigma_y * 8 * a[0] * a[1] * a[2] / (8 * std::sqrt(3.0) * a[0]);
  // u_x in the xi eta mode (alpha 2), direction x (j 0): index 6.
  EXPECT_NEAR(std::abs(bent.hourglass[6]), limit, 1e-12 * limit);
  for (int index = 0; index < 12; ++index) {
    if (index == 6) continue;
    EXPECT_LT(std::abs(bent.hourglass[index]), 1e-9 * limit) << index;
  }

  // Plus a uniaxial stretch of 1 %: the mean point flows, the modes' plastic parts carry nothing.
  ElementVectors stretched = u;
  for (int I = 0; I < 8; ++I) stretched.x[I] += 0.01 * x.x[I];
  const LawPass both = law_pass<material::Hardening, false>(x, stretched, flow);
  EXPECT_GT(both.result.eps_p, 0.0);
  for (int index = 0; index < 12; ++index) EXPECT_EQ(both.hourglass[index], 0.0) << index;
}

// Finite strain, elastic: a deformed brick and the same brick turned by R give forces
// turned by R, and the same hourglass forces and amplitudes on the element's axes.
TEST(AssumedStrainHourglass, ForcesTurnWithTheBody) {
  std::mt19937_64 rng(42);
  const ElementVectors x = random_distorted_hex(rng, 1e-3);
  const ElementVectors u = random_vectors(rng, 5e-5);
  const Eigen::Matrix3d r = rotation(1.1, Eigen::Vector3d(0.3, 1.0, -0.4));
  ElementVectors turned;  // u' = R (x + u) - x
  for (int I = 0; I < 8; ++I) {
    const Eigen::Vector3d p = r * Eigen::Vector3d(x.x[I] + u.x[I], x.y[I] + u.y[I], x.z[I] + u.z[I]);
    turned.x[I] = p(0) - x.x[I], turned.y[I] = p(1) - x.y[I], turned.z[I] = p(2) - x.z[I];
  }
  const material::NoYield elastic;
  const LawPass a = law_pass<material::NoYield, true>(x, u, elastic);
  const LawPass b = law_pass<material::NoYield, true>(x, turned, elastic);
  double largest = 0.0;
  for (int I = 0; I < 8; ++I)
    largest = std::max(largest, Eigen::Vector3d(a.f.x[I], a.f.y[I], a.f.z[I]).norm());
  for (int I = 0; I < 8; ++I) {
    const Eigen::Vector3d expected = r * Eigen::Vector3d(a.f.x[I], a.f.y[I], a.f.z[I]);
    EXPECT_LT((expected - Eigen::Vector3d(b.f.x[I], b.f.y[I], b.f.z[I])).norm(), 1e-9 * largest);
  }
  for (int index = 0; index < 24; ++index)
    EXPECT_NEAR(b.hourglass[index], a.hourglass[index], 1e-9 * std::abs(a.hourglass[index]) + 1e-20);
  EXPECT_NEAR(b.hourglass_work, a.hourglass_work, 1e-9 * a.hourglass_work);
}

}  // namespace
}  // namespace exdyn::element
