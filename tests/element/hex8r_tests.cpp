// The one-point hexahedron with Flanagan-Belytschko hourglass stiffness (these tests)
// and the assumed-strain control (hourglass_tests.cpp).
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <random>

#include "element/hex8.hpp"
#include "element/hex8_parallelepiped.hpp"
#include "element/hex8r.hpp"
#include "material/elastic.hpp"
#include "reference_elements.hpp"

namespace exdyn::element {
namespace {

using testing::cube;
using testing::linear_field;
using testing::random_distorted_hex;
using testing::random_parallelepiped;
using testing::random_vectors;
using testing::to_vector;

const material::ElasticConstants steel = material::elastic_constants(2.1e11, 0.3, 7800.0);
constexpr double coefficient = 0.05;

hex8r::Stabilization flanagan_belytschko(double c) {
  return {input::HourglassModel::flanagan_belytschko, c, 2.1e11, steel.mu};
}

struct KernelOutput {
  ElementVectors force;
  material::SymTensor stress{};
  hex8r::Energies energies;
  double k = 0.0;  // hourglass stiffness used
};

KernelOutput run(const ElementVectors& x, const ElementVectors& u,
                 double hourglass_coefficient = coefficient) {
  std::array<double, hex8r::reference_size> reference{};
  EXPECT_GT(hex8r::make_reference(x, flanagan_belytschko(hourglass_coefficient), reference.data()), 0.0);
  KernelOutput out;
  out.energies = hex8r::internal_forces(reference.data(), steel.lambda, steel.mu, u, out.force, out.stress);
  out.k = reference[35];
  return out;
}

KernelOutput run_parallelepiped(const ElementVectors& x, const ElementVectors& u) {
  std::array<double, hex8r::parallelepiped_reference_size> reference{};
  EXPECT_GT(hex8r::make_parallelepiped_reference(x, flanagan_belytschko(coefficient), reference.data()), 0.0);
  KernelOutput out;
  out.energies = hex8r::parallelepiped_internal_forces(reference.data(), steel.lambda, steel.mu, u, out.force,
                                                       out.stress);
  out.k = reference[10];  // K_0,xx = k
  return out;
}

double max_abs(const Eigen::VectorXd& v) { return v.cwiseAbs().maxCoeff(); }

double force_scale(const ElementVectors& u, double size = 1.0) {
  return steel.dilatational_modulus() * size * max_abs(to_vector(u));
}

TEST(Hex8r, BVectorsReproduceTheVolume) {
  // sum_I x_jI b_jI = integral of div-free identity = V for each direction j.
  std::mt19937_64 rng(21);
  const ElementVectors x = random_distorted_hex(rng);
  const auto b = hex8r::b_vectors(x);
  const double volume = hex8::volume(x);
  const std::array<const std::array<double, 8>*, 3> coordinate{&x.x, &x.y, &x.z};
  for (int j = 0; j < 3; ++j) {
    double sum = 0.0, b_sum = 0.0;
    for (int I = 0; I < 8; ++I) {
      sum += (*coordinate[j])[I] * b[j][I];
      b_sum += b[j][I];
    }
    EXPECT_NEAR(sum, volume, 1e-14 * volume);
    EXPECT_NEAR(b_sum, 0.0, 1e-14);
  }
}

TEST(Hex8r, BVectorsMatchVolumeDerivativeByCentralDifferences) {
  // Flanagan-Belytschko: b_jI = dV/dx_jI.
  std::mt19937_64 rng(22);
  const ElementVectors x = random_distorted_hex(rng);
  const auto b = hex8r::b_vectors(x);
  const double step = 1e-6;
  for (int I = 0; I < 8; ++I) {
    for (int j = 0; j < 3; ++j) {
      ElementVectors plus = x, minus = x;
      std::array<double, 8>& p = j == 0 ? plus.x : (j == 1 ? plus.y : plus.z);
      std::array<double, 8>& m = j == 0 ? minus.x : (j == 1 ? minus.y : minus.z);
      p[I] += step;
      m[I] -= step;
      EXPECT_NEAR(b[j][I], (hex8::volume(plus) - hex8::volume(minus)) / (2 * step), 1e-8);
    }
  }
}

TEST(Hex8r, HourglassStiffnessOfCubeIsThreeEighthsCoefficientMuH) {
  const double h = 0.01;
  std::array<double, hex8r::reference_size> reference{};
  hex8r::make_reference(cube(h), flanagan_belytschko(coefficient), reference.data());
  EXPECT_NEAR(reference[35], 0.375 * coefficient * steel.mu * h, 1e-12 * reference[35]);
}

TEST(Hex8r, RigidTranslationGivesZeroForce) {
  std::mt19937_64 rng(23);
  const ElementVectors x = random_distorted_hex(rng);
  ElementVectors u;
  u.x.fill(1e-3);
  u.y.fill(-2e-3);
  u.z.fill(5e-4);
  const KernelOutput out = run(x, u);
  EXPECT_LT(max_abs(to_vector(out.force)), 1e-15 * force_scale(u));
  EXPECT_LT(out.energies.strain + out.energies.hourglass, 1e-20);
}

TEST(Hex8r, InfinitesimalRotationGivesZeroForce) {
  std::mt19937_64 rng(24);
  const ElementVectors x = random_distorted_hex(rng);
  const Eigen::Vector3d omega(1e-3, -2e-3, 1.5e-3);
  Eigen::Matrix3d skew;
  skew << 0, -omega(2), omega(1), omega(2), 0, -omega(0), -omega(1), omega(0), 0;
  const ElementVectors u = linear_field(x, skew, Eigen::Vector3d(1e-4, 0, 0));
  const KernelOutput out = run(x, u);
  EXPECT_LT(max_abs(to_vector(out.force)), 1e-14 * force_scale(u));
}

TEST(Hex8r, PatchTestLinearFieldGivesExactStress) {
  std::mt19937_64 rng(25);
  Eigen::Matrix3d a;
  a << 1e-3, 2e-4, -3e-4, 5e-4, -7e-4, 1e-4, -2e-4, 3e-4, 4e-4;
  const material::SymTensor strain{a(0, 0),
                                   a(1, 1),
                                   a(2, 2),
                                   0.5 * (a(0, 1) + a(1, 0)),
                                   0.5 * (a(1, 2) + a(2, 1)),
                                   0.5 * (a(0, 2) + a(2, 0))};
  const material::SymTensor expected = material::stress_from_strain(steel, strain);
  double scale = 0.0;
  for (double value : expected) scale = std::max(scale, std::abs(value));
  for (const ElementVectors& x :
       {cube(1.0), random_distorted_hex(rng), random_distorted_hex(rng, 1e-3, 0.25)}) {
    const KernelOutput out = run(x, linear_field(x, a, Eigen::Vector3d(1e-4, 2e-4, -1e-4)));
    for (int k = 0; k < 6; ++k) EXPECT_NEAR(out.stress[k], expected[k], 1e-12 * scale);
  }
}

TEST(Hex8r, HourglassForcesAndEnergyVanishForLinearFields) {
  std::mt19937_64 rng(26);
  Eigen::Matrix3d a;
  a << 1e-3, 2e-4, -3e-4, 5e-4, -7e-4, 1e-4, -2e-4, 3e-4, 4e-4;
  for (int trial = 0; trial < 20; ++trial) {
    const ElementVectors x = random_distorted_hex(rng);
    const ElementVectors u = linear_field(x, a, Eigen::Vector3d(1e-4, 2e-4, -1e-4));
    const KernelOutput with = run(x, u, coefficient);
    const KernelOutput without = run(x, u, 0.0);
    // The hourglass part of the force is the difference with and without it.
    const double difference = (to_vector(with.force) - to_vector(without.force)).cwiseAbs().maxCoeff();
    EXPECT_LT(difference, 1e-12 * max_abs(to_vector(without.force)));
    EXPECT_LT(with.energies.hourglass, 1e-12 * with.energies.strain);
  }
}

TEST(Hex8r, HourglassModeGivesForceExactlyScaledByK) {
  // u_x = a h_alpha on a cube: zero mean strain, q_x,alpha = 8 a, so
  // f_x,I = k 8 a h_alpha,I and the hourglass energy is k/2 (8 a)^2.
  const double h = 0.02, amplitude = 1e-6;
  const ElementVectors x = cube(h);
  for (int alpha = 0; alpha < 4; ++alpha) {
    for (int component = 0; component < 3; ++component) {
      ElementVectors u;
      std::array<double, 8>& ui = component == 0 ? u.x : (component == 1 ? u.y : u.z);
      for (int I = 0; I < 8; ++I) ui[I] = amplitude * hex8::mode_value(4 + alpha, I);
      const KernelOutput out = run(x, u);
      EXPECT_GT(out.energies.hourglass, 0.0);
      EXPECT_NEAR(out.energies.hourglass, 0.5 * out.k * 64 * amplitude * amplitude,
                  1e-12 * out.energies.hourglass);
      EXPECT_LT(std::abs(out.energies.strain), 1e-12 * out.energies.hourglass);
      const std::array<double, 8>& fi =
          component == 0 ? out.force.x : (component == 1 ? out.force.y : out.force.z);
      for (int I = 0; I < 8; ++I)
        EXPECT_NEAR(fi[I], out.k * 8 * amplitude * hex8::mode_value(4 + alpha, I), 1e-12 * out.k * amplitude);
    }
  }
}

TEST(Hex8r, HourglassModeHasNoStiffnessWithoutHourglassControl) {
  const ElementVectors x = cube(1.0);
  ElementVectors u;
  for (int I = 0; I < 8; ++I) u.z[I] = 1e-3 * hex8::mode_value(6, I);  // xi eta: a twisting hourglass
  const KernelOutput out = run(x, u, 0.0);
  EXPECT_LT(max_abs(to_vector(out.force)), 1e-15 * force_scale(u));
}

TEST(Hex8r, EnergyIsHalfUDotF) {
  std::mt19937_64 rng(27);
  const ElementVectors x = random_distorted_hex(rng);
  const ElementVectors u = random_vectors(rng);
  const KernelOutput out = run(x, u);
  const double energy = out.energies.strain + out.energies.hourglass;
  EXPECT_NEAR(energy, 0.5 * to_vector(u).dot(to_vector(out.force)), 1e-13 * energy);
  EXPECT_GT(out.energies.hourglass, 0.0);
}

TEST(Hex8r, SumOfNodalForcesIsZero) {
  std::mt19937_64 rng(28);
  const ElementVectors u = random_vectors(rng);
  const KernelOutput out = run(random_distorted_hex(rng), u);
  double sx = 0, sy = 0, sz = 0;
  for (int I = 0; I < 8; ++I) {
    sx += out.force.x[I];
    sy += out.force.y[I];
    sz += out.force.z[I];
  }
  EXPECT_LT(std::abs(sx) + std::abs(sy) + std::abs(sz), 1e-14 * force_scale(u));
}

TEST(Hex8r, StiffnessIsSymmetric) {
  std::mt19937_64 rng(29);
  const ElementVectors x = random_distorted_hex(rng);
  const ElementVectors u1 = random_vectors(rng), u2 = random_vectors(rng);
  const double w12 = to_vector(run(x, u1).force).dot(to_vector(u2));
  const double w21 = to_vector(run(x, u2).force).dot(to_vector(u1));
  EXPECT_NEAR(w12, w21, 1e-13 * std::abs(w12));
}

TEST(Hex8r, FastKernelMatchesReferenceImplementationOnRandomDistortedElements) {
  std::mt19937_64 rng(30);
  for (int trial = 0; trial < 200; ++trial) {
    const double size = trial % 2 == 0 ? 1.0 : 2.5e-5;
    const ElementVectors x =
        trial % 3 == 0 ? random_parallelepiped(rng, size) : random_distorted_hex(rng, size, 0.2);
    const ElementVectors u = random_vectors(rng, 1e-3 * size);
    const KernelOutput out = run(x, u);
    const testing::ReferenceResult ref = testing::reference_hex8r(x, steel.lambda, steel.mu, coefficient, u);
    EXPECT_LT((to_vector(out.force) - ref.force).norm(), 1e-12 * ref.force.norm());
    EXPECT_NEAR(out.energies.strain, ref.strain_energy, 1e-12 * ref.strain_energy);
    EXPECT_NEAR(out.energies.hourglass, ref.hourglass_energy, 1e-12 * ref.hourglass_energy);
    const double stress_scale = ref.mean_stress.cwiseAbs().maxCoeff();
    for (int k = 0; k < 6; ++k) EXPECT_NEAR(out.stress[k], ref.mean_stress(k), 1e-12 * stress_scale);
  }
}

TEST(Hex8r, ParallelepipedKernelMatchesReferenceImplementation) {
  std::mt19937_64 rng(31);
  for (int trial = 0; trial < 200; ++trial) {
    const double size = trial % 2 == 0 ? 1.0 : 2.5e-5;
    const ElementVectors x = random_parallelepiped(rng, size);
    const ElementVectors u = random_vectors(rng, 1e-3 * size);
    const KernelOutput out = run_parallelepiped(x, u);
    const testing::ReferenceResult ref = testing::reference_hex8r(x, steel.lambda, steel.mu, coefficient, u);
    EXPECT_LT((to_vector(out.force) - ref.force).norm(), 1e-12 * ref.force.norm());
    EXPECT_NEAR(out.energies.strain, ref.strain_energy, 1e-12 * ref.strain_energy);
    EXPECT_NEAR(out.energies.hourglass, ref.hourglass_energy, 1e-12 * ref.hourglass_energy);
    const double stress_scale = ref.mean_stress.cwiseAbs().maxCoeff();
    for (int k = 0; k < 6; ++k) EXPECT_NEAR(out.stress[k], ref.mean_stress(k), 1e-12 * stress_scale);
    // And the general kernel on the same element.
    const KernelOutput general = run(x, u);
    EXPECT_LT((to_vector(general.force) - to_vector(out.force)).norm(), 1e-12 * ref.force.norm());
  }
}

TEST(Hex8r, ParallelepipedKernelHasZeroForceForRigidMotionAndExactHourglassForce) {
  std::mt19937_64 rng(32);
  const ElementVectors x = random_parallelepiped(rng);
  const Eigen::Vector3d omega(1e-3, -2e-3, 1.5e-3);
  Eigen::Matrix3d skew;
  skew << 0, -omega(2), omega(1), omega(2), 0, -omega(0), -omega(1), omega(0), 0;
  const ElementVectors u = linear_field(x, skew, Eigen::Vector3d(1e-4, -3e-4, 2e-4));
  EXPECT_LT(max_abs(to_vector(run_parallelepiped(x, u).force)), 1e-14 * force_scale(u));
  // For a parallelepiped gamma = h exactly: u_y = a h_alpha gives f_y = 8 k a h_alpha.
  ElementVectors hourglass;
  for (int I = 0; I < 8; ++I) hourglass.y[I] = 1e-6 * hex8::mode_value(7, I);
  const KernelOutput out = run_parallelepiped(x, hourglass);
  for (int I = 0; I < 8; ++I)
    EXPECT_NEAR(out.force.y[I], 8 * out.k * 1e-6 * hex8::mode_value(7, I), 1e-12 * out.k * 1e-6);
  EXPECT_NEAR(out.energies.hourglass, 0.5 * out.k * 64e-12, 1e-12 * out.energies.hourglass);
}

}  // namespace
}  // namespace exdyn::element
