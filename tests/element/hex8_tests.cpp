// The fully integrated hexahedron: shape functions, geometry, and the kernels
// (general and parallelepiped) against the plain reference implementation.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <random>

#include "element/hex8.hpp"
#include "element/hex8_parallelepiped.hpp"
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

struct KernelOutput {
  ElementVectors force;
  material::SymTensor stress{};
  double energy = 0.0;
};

// The general kernel, through its reference data.
KernelOutput run_general(const ElementVectors& x, const ElementVectors& u,
                         const material::ElasticConstants& m = steel) {
  std::array<double, hex8::reference_size> reference{};
  EXPECT_GT(hex8::make_reference(x, reference.data()), 0.0);
  KernelOutput out;
  out.energy = hex8::internal_forces(reference.data(), m.lambda, m.mu, u, out.force, out.stress);
  return out;
}

KernelOutput run_parallelepiped(const ElementVectors& x, const ElementVectors& u,
                                const material::ElasticConstants& m = steel) {
  std::array<double, hex8::parallelepiped_reference_size> reference{};
  EXPECT_GT(hex8::make_parallelepiped_reference(x, reference.data()), 0.0);
  KernelOutput out;
  out.energy =
      hex8::parallelepiped_internal_forces(reference.data(), m.lambda, m.mu, u, out.force, out.stress);
  return out;
}

double max_abs(const Eigen::VectorXd& v) { return v.cwiseAbs().maxCoeff(); }

// Force scale of an element: |K| |u| ~ (lambda + 2 mu) h |u|.
double force_scale(const ElementVectors& u, double size = 1.0) {
  return steel.dilatational_modulus() * size * max_abs(to_vector(u));
}

TEST(Hex8, ShapeFunctionsArePartitionOfUnity) {
  std::mt19937_64 rng(1);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  for (int trial = 0; trial < 100; ++trial) {
    const std::array<double, 8> n = hex8::shape_functions(unit(rng), unit(rng), unit(rng));
    double sum = 0.0;
    for (double value : n) sum += value;
    EXPECT_NEAR(sum, 1.0, 1e-15);
  }
}

TEST(Hex8, ShapeFunctionsAreOneAtTheirNodeAndZeroAtTheOthers) {
  for (int J = 0; J < 8; ++J) {
    const Vector3& s = hex8::node_natural_coordinates[J];
    const std::array<double, 8> n = hex8::shape_functions(s[0], s[1], s[2]);
    for (int I = 0; I < 8; ++I) EXPECT_EQ(n[I], I == J ? 1.0 : 0.0);
  }
}

TEST(Hex8, NodeOrderIsVtkHexahedron) {
  // 0..3 the face zeta = -1 counter-clockwise seen from +zeta, 4..7 above them.
  const double expected[8][3] = {{-1, -1, -1}, {1, -1, -1}, {1, 1, -1}, {-1, 1, -1},
                                 {-1, -1, 1},  {1, -1, 1},  {1, 1, 1},  {-1, 1, 1}};
  for (int I = 0; I < 8; ++I)
    for (int a = 0; a < 3; ++a) EXPECT_EQ(hex8::node_natural_coordinates[I][a], expected[I][a]);
}

TEST(Hex8, ShapeFunctionDerivativesMatchCentralDifferences) {
  std::mt19937_64 rng(2);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  const double step = 1e-6;
  for (int trial = 0; trial < 20; ++trial) {
    const Vector3 p{unit(rng), unit(rng), unit(rng)};
    const std::array<Vector3, 8> d = hex8::shape_function_derivatives(p[0], p[1], p[2]);
    for (int a = 0; a < 3; ++a) {
      Vector3 plus = p, minus = p;
      plus[a] += step;
      minus[a] -= step;
      const std::array<double, 8> n_plus = hex8::shape_functions(plus[0], plus[1], plus[2]);
      const std::array<double, 8> n_minus = hex8::shape_functions(minus[0], minus[1], minus[2]);
      for (int I = 0; I < 8; ++I) EXPECT_NEAR(d[I][a], (n_plus[I] - n_minus[I]) / (2 * step), 1e-9);
    }
  }
}

TEST(Hex8, ModeTransformsInvertEachOtherAndMatchTheModeVectors) {
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  std::array<double, 8> u{};
  for (double& value : u) value = unit(rng);
  const std::array<double, 8> c = hex8::modes_from_nodal(u);
  for (int m = 0; m < 8; ++m) {
    double expected = 0.0;
    for (int I = 0; I < 8; ++I) expected += hex8::mode_value(m, I) * u[I] / 8.0;
    EXPECT_NEAR(c[m], expected, 1e-15);
  }
  const std::array<double, 8> back = hex8::nodal_from_modes(c);
  for (int I = 0; I < 8; ++I) EXPECT_NEAR(back[I], u[I], 1e-15);
}

TEST(Hex8, UnitCubeVolumeIsOne) { EXPECT_NEAR(hex8::volume(cube(1.0)), 1.0, 1e-15); }

// Volume of a hexahedron as 24 tetrahedra, each with the element centroid, a
// face centroid and one edge of that face. Exact for the trilinear hexahedron
// (whose faces are the bilinear patches through their four nodes).
double tetrahedral_volume(const ElementVectors& x) {
  auto point = [&](int I) { return Eigen::Vector3d(x.x[I], x.y[I], x.z[I]); };
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  for (int I = 0; I < 8; ++I) centre += point(I) / 8.0;
  double volume = 0.0;
  for (const auto& face : hex8::faces) {  // outward by the right-hand rule
    Eigen::Vector3d face_centre = Eigen::Vector3d::Zero();
    for (int k = 0; k < 4; ++k) face_centre += point(face[k]) / 4.0;
    for (int k = 0; k < 4; ++k) {
      const Eigen::Vector3d a = point(face[k]) - centre, b = point(face[(k + 1) % 4]) - centre,
                            c = face_centre - centre;
      volume += a.cross(b).dot(c) / 6.0;
    }
  }
  return volume;
}

TEST(Hex8, DistortedHexVolumeMatchesTetrahedralDecomposition) {
  std::mt19937_64 rng(4);
  for (int trial = 0; trial < 20; ++trial) {
    const ElementVectors x = random_distorted_hex(rng, 2.0, 0.2);
    EXPECT_NEAR(hex8::volume(x), tetrahedral_volume(x), 1e-13 * std::abs(tetrahedral_volume(x)));
  }
}

TEST(Hex8, FrustumVolumeIsTheExactPyramidFrustum) {
  // Square base of side 2 at z = 0, top of side 1 at z = 1: planar faces, not a
  // parallelepiped. V = h (A1 + A2 + sqrt(A1 A2)) / 3 = 7/3.
  ElementVectors x = cube(2.0);
  for (int I = 4; I < 8; ++I) {
    x.x[I] = 0.5 + 0.5 * x.x[I];
    x.y[I] = 0.5 + 0.5 * x.y[I];
    x.z[I] = 1.0;
  }
  EXPECT_NEAR(hex8::volume(x), 7.0 / 3.0, 1e-14);
  EXPECT_FALSE(hex8::is_parallelepiped(x));
}

TEST(Hex8, CubeCharacteristicLengthIsItsSide) {
  EXPECT_NEAR(hex8::characteristic_length(cube(0.25)), 0.25, 1e-15);
  EXPECT_NEAR(hex8::face_area(cube(3.0), hex8::faces[0]), 9.0, 1e-14);
}

TEST(Hex8, ShapeFunctionIntegralsOfCubeAreAnEighthOfItsVolume) {
  const double h = 0.3;
  const std::array<double, 8> integral = hex8::shape_function_integrals(cube(h));
  for (double value : integral) EXPECT_NEAR(value, h * h * h / 8.0, 1e-17);
}

TEST(Hex8, ShapeFunctionIntegralsOfDistortedHexSumToItsVolume) {
  std::mt19937_64 rng(5);
  const ElementVectors x = random_distorted_hex(rng, 1.0, 0.2);
  const std::array<double, 8> integral = hex8::shape_function_integrals(x);
  double sum = 0.0;
  for (double value : integral) sum += value;
  EXPECT_NEAR(sum, hex8::volume(x), 1e-15);
}

TEST(Hex8, CubeAndBoxAreParallelepipedsAndDistortedHexIsNot) {
  std::mt19937_64 rng(6);
  EXPECT_TRUE(hex8::is_parallelepiped(cube(1e-5)));
  EXPECT_TRUE(hex8::is_parallelepiped(random_parallelepiped(rng)));
  EXPECT_FALSE(hex8::is_parallelepiped(random_distorted_hex(rng)));
}

TEST(Hex8, RigidTranslationGivesZeroForce) {
  std::mt19937_64 rng(7);
  const ElementVectors x = random_distorted_hex(rng);
  ElementVectors u;
  u.x.fill(1e-3);
  u.y.fill(-2e-3);
  u.z.fill(5e-4);
  const KernelOutput out = run_general(x, u);
  EXPECT_LT(max_abs(to_vector(out.force)), 1e-15 * force_scale(u));
  EXPECT_LT(std::abs(out.energy), 1e-20);
  const ElementVectors p = random_parallelepiped(rng);
  EXPECT_LT(max_abs(to_vector(run_parallelepiped(p, u).force)), 1e-15 * force_scale(u));
}

TEST(Hex8, InfinitesimalRotationGivesZeroForce) {
  std::mt19937_64 rng(8);
  const ElementVectors x = random_distorted_hex(rng);
  // u = omega x X: a skew-symmetric gradient, zero small strain.
  const Eigen::Vector3d omega(1e-3, -2e-3, 1.5e-3);
  Eigen::Matrix3d skew;
  skew << 0, -omega(2), omega(1), omega(2), 0, -omega(0), -omega(1), omega(0), 0;
  const ElementVectors u = linear_field(x, skew, Eigen::Vector3d::Zero());
  const KernelOutput out = run_general(x, u);
  EXPECT_LT(max_abs(to_vector(out.force)), 1e-14 * force_scale(u));
  const ElementVectors p = random_parallelepiped(rng);
  const ElementVectors u_p = linear_field(p, skew, Eigen::Vector3d::Zero());
  EXPECT_LT(max_abs(to_vector(run_parallelepiped(p, u_p).force)), 1e-14 * force_scale(u_p));
}

// The exact stress of the linear field u = A x + d.
material::SymTensor exact_stress(const Eigen::Matrix3d& a) {
  const material::SymTensor strain{a(0, 0),
                                   a(1, 1),
                                   a(2, 2),
                                   0.5 * (a(0, 1) + a(1, 0)),
                                   0.5 * (a(1, 2) + a(2, 1)),
                                   0.5 * (a(0, 2) + a(2, 0))};
  return material::stress_from_strain(steel, strain);
}

void expect_stress_near(const material::SymTensor& actual, const material::SymTensor& expected) {
  double scale = 0.0;
  for (double value : expected) scale = std::max(scale, std::abs(value));
  for (int k = 0; k < 6; ++k) EXPECT_NEAR(actual[k], expected[k], 1e-12 * scale) << "component " << k;
}

Eigen::Matrix3d some_gradient() {
  Eigen::Matrix3d a;
  a << 1e-3, 2e-4, -3e-4, 5e-4, -7e-4, 1e-4, -2e-4, 3e-4, 4e-4;
  return a;
}

TEST(Hex8, PatchTestLinearFieldGivesExactStressAtEveryGaussPointAndAsMean) {
  std::mt19937_64 rng(9);
  const Eigen::Matrix3d a = some_gradient();
  const material::SymTensor expected = exact_stress(a);
  for (const ElementVectors& x :
       {cube(1.0), random_distorted_hex(rng), random_distorted_hex(rng, 1e-3, 0.25)}) {
    const ElementVectors u = linear_field(x, a, Eigen::Vector3d(1e-4, 2e-4, -1e-4));
    for (const material::SymTensor& s : hex8::gauss_point_stresses(x, steel.lambda, steel.mu, u))
      expect_stress_near(s, expected);
    expect_stress_near(run_general(x, u).stress, expected);
  }
  const ElementVectors p = random_parallelepiped(rng);
  expect_stress_near(run_parallelepiped(p, linear_field(p, a, Eigen::Vector3d::Zero())).stress, expected);
}

TEST(Hex8, StrainEnergyIsHalfUDotF) {
  std::mt19937_64 rng(10);
  const ElementVectors x = random_distorted_hex(rng);
  const ElementVectors u = random_vectors(rng);
  const KernelOutput out = run_general(x, u);
  EXPECT_NEAR(out.energy, 0.5 * to_vector(u).dot(to_vector(out.force)), 1e-13 * std::abs(out.energy));
  EXPECT_GT(out.energy, 0.0);
}

TEST(Hex8, SumOfNodalForcesIsZero) {
  std::mt19937_64 rng(11);
  const ElementVectors x = random_distorted_hex(rng);
  const ElementVectors u = random_vectors(rng);
  const KernelOutput out = run_general(x, u);
  double sx = 0, sy = 0, sz = 0;
  for (int I = 0; I < 8; ++I) {
    sx += out.force.x[I];
    sy += out.force.y[I];
    sz += out.force.z[I];
  }
  const double scale = force_scale(u);
  EXPECT_LT(std::abs(sx) + std::abs(sy) + std::abs(sz), 1e-14 * scale);
}

TEST(Hex8, StiffnessIsSymmetric) {
  std::mt19937_64 rng(12);
  const ElementVectors x = random_distorted_hex(rng);
  const ElementVectors u1 = random_vectors(rng), u2 = random_vectors(rng);
  const double w12 = to_vector(run_general(x, u1).force).dot(to_vector(u2));
  const double w21 = to_vector(run_general(x, u2).force).dot(to_vector(u1));
  EXPECT_NEAR(w12, w21, 1e-13 * std::abs(w12));
}

TEST(Hex8, FastKernelMatchesReferenceImplementationOnRandomDistortedElements) {
  std::mt19937_64 rng(13);
  for (int trial = 0; trial < 200; ++trial) {
    const double size = trial % 2 == 0 ? 1.0 : 2.5e-5;
    const ElementVectors x = random_distorted_hex(rng, size, 0.2);
    const ElementVectors u = random_vectors(rng, 1e-3 * size);
    const KernelOutput out = run_general(x, u);
    const testing::ReferenceResult ref = testing::reference_hex8(x, steel.lambda, steel.mu, u);
    EXPECT_LT((to_vector(out.force) - ref.force).norm(), 1e-12 * ref.force.norm());
    EXPECT_NEAR(out.energy, ref.strain_energy, 1e-12 * ref.strain_energy);
    const double stress_scale = ref.mean_stress.cwiseAbs().maxCoeff();
    for (int k = 0; k < 6; ++k) EXPECT_NEAR(out.stress[k], ref.mean_stress(k), 1e-12 * stress_scale);
  }
}

TEST(Hex8, ParallelepipedKernelMatchesReferenceImplementation) {
  std::mt19937_64 rng(14);
  for (int trial = 0; trial < 200; ++trial) {
    const double size = trial % 2 == 0 ? 1.0 : 2.5e-5;
    const ElementVectors x = random_parallelepiped(rng, size);
    const ElementVectors u = random_vectors(rng, 1e-3 * size);
    const KernelOutput out = run_parallelepiped(x, u);
    const testing::ReferenceResult ref = testing::reference_hex8(x, steel.lambda, steel.mu, u);
    EXPECT_LT((to_vector(out.force) - ref.force).norm(), 1e-12 * ref.force.norm());
    EXPECT_NEAR(out.energy, ref.strain_energy, 1e-12 * ref.strain_energy);
    const double stress_scale = ref.mean_stress.cwiseAbs().maxCoeff();
    for (int k = 0; k < 6; ++k) EXPECT_NEAR(out.stress[k], ref.mean_stress(k), 1e-12 * stress_scale);
    // And the general kernel on the same element.
    const KernelOutput general = run_general(x, u);
    EXPECT_LT((to_vector(general.force) - to_vector(out.force)).norm(), 1e-12 * ref.force.norm());
  }
}

TEST(Hex8, AxisAlignedKernelEqualsTheParallelepipedKernelOnBricks) {
  // Bricks of random sides and place: the axis-aligned kernel reads only the diagonal
  // of dxi/dx and skips the products with its zeros, so the forces, stress and energy
  // agree with the parallelepiped kernel's to round-off.
  std::mt19937_64 rng(15);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  for (int trial = 0; trial < 200; ++trial) {
    const double size = trial % 2 == 0 ? 1.0 : 2.5e-5;
    const std::array<double, 3> side{size * (1.0 + 0.5 * unit(rng)), size * (1.0 + 0.5 * unit(rng)),
                                     size * (1.0 + 0.5 * unit(rng))};
    const std::array<double, 3> corner{size * unit(rng), size * unit(rng), size * unit(rng)};
    ElementVectors x;
    for (int I = 0; I < 8; ++I) {
      const Vector3& s = hex8::node_natural_coordinates[std::size_t(I)];
      x.x[std::size_t(I)] = corner[0] + 0.5 * (1.0 + s[0]) * side[0];
      x.y[std::size_t(I)] = corner[1] + 0.5 * (1.0 + s[1]) * side[1];
      x.z[std::size_t(I)] = corner[2] + 0.5 * (1.0 + s[2]) * side[2];
    }
    std::array<double, hex8::parallelepiped_reference_size> reference{};
    ASSERT_GT(hex8::make_parallelepiped_reference(x, reference.data()), 0.0);
    ASSERT_TRUE(hex8::is_axis_aligned(reference.data()));
    const ElementVectors u = random_vectors(rng, 1e-3 * size);
    const KernelOutput full = run_parallelepiped(x, u);
    KernelOutput aligned;
    aligned.energy = hex8::axis_aligned_internal_forces(reference.data(), steel.lambda, steel.mu, u,
                                                        aligned.force, aligned.stress);
    const double scale = to_vector(full.force).cwiseAbs().maxCoeff();
    EXPECT_LT((to_vector(aligned.force) - to_vector(full.force)).cwiseAbs().maxCoeff(), 1e-14 * scale);
    EXPECT_NEAR(aligned.energy, full.energy, 1e-14 * full.energy);
    double stress_scale = 0.0;
    for (double value : full.stress) stress_scale = std::max(stress_scale, std::abs(value));
    for (int k = 0; k < 6; ++k)
      EXPECT_NEAR(aligned.stress[std::size_t(k)], full.stress[std::size_t(k)], 1e-14 * stress_scale);
    // And against the plain reference implementation.
    const testing::ReferenceResult ref = testing::reference_hex8(x, steel.lambda, steel.mu, u);
    EXPECT_LT((to_vector(aligned.force) - ref.force).norm(), 1e-12 * ref.force.norm());
  }
  // A sheared parallelepiped is not axis-aligned.
  std::mt19937_64 shear_rng(16);
  std::array<double, hex8::parallelepiped_reference_size> reference{};
  ASSERT_GT(hex8::make_parallelepiped_reference(testing::random_parallelepiped(shear_rng), reference.data()),
            0.0);
  EXPECT_FALSE(hex8::is_axis_aligned(reference.data()));
}

TEST(Hex8, UniaxialStrainOfCubeGivesDilatationalModulusTimesStrain) {
  // The plate-impact state: u_x = eps x only. sigma_x = (lambda + 2 mu) eps,
  // sigma_y = sigma_z = lambda eps; each node of the face x = h carries
  // sigma_x h^2 / 4.
  const double h = 2.5e-5, strain = -1e-4;
  const ElementVectors x = cube(h);
  ElementVectors u;
  for (int I = 0; I < 8; ++I) u.x[I] = strain * x.x[I];
  const KernelOutput out = run_parallelepiped(x, u);
  EXPECT_NEAR(out.stress[0], steel.dilatational_modulus() * strain, 1e-9 * std::abs(out.stress[0]));
  EXPECT_NEAR(out.stress[1], steel.lambda * strain, 1e-9 * std::abs(out.stress[0]));
  EXPECT_NEAR(out.stress[2], steel.lambda * strain, 1e-9 * std::abs(out.stress[0]));
  for (int I = 0; I < 8; ++I)
    EXPECT_NEAR(out.force.x[I], (x.x[I] > 0 ? 1 : -1) * out.stress[0] * h * h / 4,
                1e-9 * std::abs(out.stress[0]) * h * h);
}

}  // namespace
}  // namespace exdyn::element
