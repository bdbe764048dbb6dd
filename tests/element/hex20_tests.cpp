// The 20-node serendipity brick: shape functions, HRZ lumped mass, the force
// kernel (rigid motions, uniform strain), the affine fast path against the general
// kernel, and the element eigenvalue time step
// (../shared/reference/quadratic-and-hertz.md).
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <random>
#include <utility>
#include <vector>

#include "element/element_block.hpp"
#include "element/hex20.hpp"
#include "mesh/mesh.hpp"

namespace exdyn::element {
namespace {

using hex20::ElementVectors20;

const material::ElasticConstants steel = material::elastic_constants(2.1e11, 0.3, 7800.0);

// The unit cube [0, a]^3 as one hex20 element, nodes at a (1 + xi) / 2.
ElementVectors20 cube(double a) {
  ElementVectors20 x;
  for (int k = 0; k < 20; ++k) {
    const Vector3& s = hex20::node_natural_coordinates[std::size_t(k)];
    x.x[std::size_t(k)] = 0.5 * a * (1 + s[0]);
    x.y[std::size_t(k)] = 0.5 * a * (1 + s[1]);
    x.z[std::size_t(k)] = 0.5 * a * (1 + s[2]);
  }
  return x;
}

// A deck of one box part of 20-node elements.
input::Deck box_deck(input::Formulation formulation, std::array<int, 3> n, input::Vec3 size,
                     double perturbation = 0.0) {
  input::Deck deck;
  input::PartOptions part;
  part.name = "box";
  part.box_min = {0, 0, 0};
  part.box_max = size;
  part.elements = n;
  part.formulation = formulation;
  part.material_index = 0;
  part.perturbation_fraction = perturbation;
  part.perturbation_seed = 3;
  deck.parts = {part};
  return deck;
}

TEST(Hex20, ShapeFunctionsAreKroneckerAndPartitionOfUnity) {
  for (int node = 0; node < 20; ++node) {
    const Vector3& s = hex20::node_natural_coordinates[std::size_t(node)];
    const std::array<double, 20> n = hex20::shape_functions(s[0], s[1], s[2]);
    for (int other = 0; other < 20; ++other)
      EXPECT_NEAR(n[std::size_t(other)], node == other ? 1.0 : 0.0, 1e-15);
  }
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  for (int trial = 0; trial < 20; ++trial) {
    const double xi = unit(rng), eta = unit(rng), zeta = unit(rng);
    const std::array<double, 20> n = hex20::shape_functions(xi, eta, zeta);
    const std::array<Vector3, 20> d = hex20::shape_function_derivatives(xi, eta, zeta);
    double sum = 0.0;
    Vector3 derivative_sum{};
    for (int k = 0; k < 20; ++k) {
      sum += n[std::size_t(k)];
      for (int a = 0; a < 3; ++a) derivative_sum[std::size_t(a)] += d[std::size_t(k)][std::size_t(a)];
    }
    EXPECT_NEAR(sum, 1.0, 1e-14);
    for (int a = 0; a < 3; ++a) EXPECT_NEAR(derivative_sum[std::size_t(a)], 0.0, 1e-14);
    // Derivatives against central differences.
    const double step = 1e-6;
    const std::array<double, 20> xp = hex20::shape_functions(xi + step, eta, zeta);
    const std::array<double, 20> xm = hex20::shape_functions(xi - step, eta, zeta);
    const std::array<double, 20> zp = hex20::shape_functions(xi, eta, zeta + step);
    const std::array<double, 20> zm = hex20::shape_functions(xi, eta, zeta - step);
    for (int k = 0; k < 20; ++k) {
      EXPECT_NEAR(d[std::size_t(k)][0], (xp[std::size_t(k)] - xm[std::size_t(k)]) / (2 * step), 1e-9);
      EXPECT_NEAR(d[std::size_t(k)][2], (zp[std::size_t(k)] - zm[std::size_t(k)]) / (2 * step), 1e-9);
    }
  }
}

// quadratic-and-hertz.md: row sums of the consistent mass -1/8 (corner) and +1/6
// (mid-edge) of rho V; HRZ 7/248 and 16/248.
TEST(Hex20, ConsistentRowSumsAreNegativeAtCornersAndHrzFractionsAre7And16Over248) {
  const hex20::GaussRule rule = hex20::gauss_rule(3);
  std::array<double, 20> row_sum{};
  for (int g = 0; g < rule.count; ++g) {
    const Vector3& p = rule.point[std::size_t(g)];
    const std::array<double, 20> n = hex20::shape_functions(p[0], p[1], p[2]);
    double total = 0.0;
    for (double value : n) total += value;
    // The cube [-1, 1]^3: V = 8, so the fraction of rho V is the sum / 8.
    for (int k = 0; k < 20; ++k)
      row_sum[std::size_t(k)] += rule.weight[std::size_t(g)] * n[std::size_t(k)] * total / 8.0;
  }
  for (int k = 0; k < 20; ++k) EXPECT_NEAR(row_sum[std::size_t(k)], k < 8 ? -1.0 / 8.0 : 1.0 / 6.0, 1e-15);

  const double a = 0.3, rho = 7800.0;
  const std::array<double, 20> m = hex20::hrz_masses(cube(a), rho);
  double total = 0.0;
  for (int k = 0; k < 20; ++k) {
    EXPECT_NEAR(m[std::size_t(k)] / (rho * a * a * a), k < 8 ? 7.0 / 248.0 : 16.0 / 248.0, 1e-15);
    total += m[std::size_t(k)];
  }
  EXPECT_NEAR(total, rho * a * a * a, 1e-15 * rho * a * a * a);
}

// Every HRZ mass is positive and the element's total is exactly rho V, also on a
// distorted element.
TEST(Hex20, HrzMassOfADistortedBlockIsPositiveAndAddsUpToRhoV) {
  const input::Deck deck = box_deck(input::Formulation::hex20, {3, 2, 2}, {3, 2, 2}, 0.25);
  const mesh::Mesh mesh = mesh::build_mesh(deck);
  const ElementBlock block =
      make_element_block(input::Formulation::hex20, steel, 0.0, 0, 12, mesh.connectivity.data(), mesh.x_ref);
  std::vector<double> mass(mesh.node_count(), 0.0);
  add_lumped_mass(block, mesh.x_ref, mass);
  double total = 0.0;
  for (double m : mass) {
    EXPECT_GT(m, 0.0);
    total += m;
  }
  EXPECT_NEAR(total, steel.density * 12.0, 1e-12 * steel.density * 12.0);
}

// A rigid motion (translation and small rotation) gives no force; a uniform
// strain gives its stress exactly, in every element, on a distorted block.
TEST(Hex20, RigidMotionGivesNoForceAndUniformStrainItsStress) {
  for (const auto formulation : {input::Formulation::hex20, input::Formulation::hex20r}) {
    const input::Deck deck = box_deck(formulation, {2, 2, 2}, {2, 2, 2}, 0.2);
    const mesh::Mesh mesh = mesh::build_mesh(deck);
    const ElementBlock block =
        make_element_block(formulation, steel, 0.0, 0, 8, mesh.connectivity.data(), mesh.x_ref);
    ASSERT_FALSE(uses_parallelepiped_kernel(block));
    NodalVectors u(mesh.node_count()), f(mesh.node_count());
    std::vector<double> stress(6 * 8);
    // Linearised rotation w x x plus a translation.
    const Vector3 w{1e-3, -2e-3, 0.5e-3};
    for (std::size_t n = 0; n < mesh.node_count(); ++n) {
      const Vector3 x = mesh.x_ref.at(n);
      u.x[n] = 1e-3 + w[1] * x[2] - w[2] * x[1];
      u.y[n] = -2e-3 + w[2] * x[0] - w[0] * x[2];
      u.z[n] = 0.5e-3 + w[0] * x[1] - w[1] * x[0];
    }
    const ElementEnergies rigid = add_internal_forces(block, u, f, stress.data());
    double largest = 0.0;
    for (std::size_t n = 0; n < mesh.node_count(); ++n)
      largest = std::max({largest, std::abs(f.x[n]), std::abs(f.y[n]), std::abs(f.z[n])});
    EXPECT_LT(largest, 1e-12 * steel.lambda * 1e-3);
    EXPECT_LT(std::abs(rigid.strain), 1e-12 * steel.lambda * 1e-6);

    // u = H x with a general H: sigma = lambda tr(eps) I + 2 mu eps everywhere.
    const double h[9] = {1e-3, 2e-4, -3e-4, 5e-4, -1e-3, 4e-4, -2e-4, 6e-4, 2e-3};
    for (std::size_t n = 0; n < mesh.node_count(); ++n) {
      const Vector3 x = mesh.x_ref.at(n);
      u.x[n] = h[0] * x[0] + h[1] * x[1] + h[2] * x[2];
      u.y[n] = h[3] * x[0] + h[4] * x[1] + h[5] * x[2];
      u.z[n] = h[6] * x[0] + h[7] * x[1] + h[8] * x[2];
    }
    f.fill(0.0);
    const ElementEnergies uniform = add_internal_forces(block, u, f, stress.data());
    const double trace = h[0] + h[4] + h[8];
    const double expected[6] = {steel.lambda * trace + 2 * steel.mu * h[0],
                                steel.lambda * trace + 2 * steel.mu * h[4],
                                steel.lambda * trace + 2 * steel.mu * h[8],
                                steel.mu * (h[1] + h[3]),
                                steel.mu * (h[5] + h[7]),
                                steel.mu * (h[2] + h[6])};
    for (int e = 0; e < 8; ++e)
      for (int k = 0; k < 6; ++k)
        EXPECT_NEAR(stress[std::size_t(6 * e + k)], expected[k], 1e-9 * std::abs(expected[0]));
    // Energy V sigma:eps / 2 over the volume 8.
    double work = 0.0;
    const double eps[6] = {h[0], h[4], h[8], h[1] + h[3], h[5] + h[7], h[2] + h[6]};
    for (int k = 0; k < 6; ++k) work += expected[k] * eps[k];
    EXPECT_NEAR(uniform.strain, 0.5 * 8.0 * work, 1e-9 * 0.5 * 8.0 * work);
  }
}

// The fast path: a box part shares one element matrix; its forces, stresses and
// energy equal the general kernel's element by element to round-off.
TEST(Hex20, AffineMatrixPathEqualsTheGaussPointKernel) {
  for (const auto formulation : {input::Formulation::hex20, input::Formulation::hex20r}) {
    const input::Deck deck = box_deck(formulation, {5, 3, 2}, {1.0, 0.5, 0.3});
    const mesh::Mesh mesh = mesh::build_mesh(deck);
    const ElementBlock block =
        make_element_block(formulation, steel, 0.0, 7, 30, mesh.connectivity.data(), mesh.x_ref);
    ASSERT_TRUE(uses_parallelepiped_kernel(block));
    std::mt19937_64 rng(11);
    std::uniform_real_distribution<double> unit(-1e-4, 1e-4);
    NodalVectors u(mesh.node_count()), f(mesh.node_count()), f_simple(mesh.node_count());
    for (std::size_t n = 0; n < mesh.node_count(); ++n)
      u.x[n] = unit(rng), u.y[n] = unit(rng), u.z[n] = unit(rng);
    std::vector<double> stress(6 * 37, 0.0);
    const ElementEnergies fast = add_internal_forces(block, u, f, stress.data());

    const int per_direction = formulation == input::Formulation::hex20 ? 3 : 2;
    const hex20::GaussRule rule = hex20::gauss_rule(per_direction);
    std::vector<double> table(std::size_t(hex20::table_stride * rule.count));
    hex20::derivative_table(rule, table.data());
    std::vector<double> reference(std::size_t(hex20::reference_size(rule.count)));
    double energy = 0.0, scale = 0.0;
    for (std::uint32_t e = 0; e < 30; ++e) {
      const std::uint32_t* nodes = mesh.connectivity.data() + 20 * std::size_t(e);
      ElementVectors20 x, ue, fe;
      for (int k = 0; k < 20; ++k) {
        const auto n = nodes[k];
        x.x[std::size_t(k)] = mesh.x_ref.x[n], x.y[std::size_t(k)] = mesh.x_ref.y[n],
        x.z[std::size_t(k)] = mesh.x_ref.z[n];
        ue.x[std::size_t(k)] = u.x[n], ue.y[std::size_t(k)] = u.y[n], ue.z[std::size_t(k)] = u.z[n];
      }
      hex20::make_reference(x, rule, table.data(), reference.data());
      material::SymTensor s;
      energy += hex20::internal_forces(rule.count, table.data(), reference.data(), steel.lambda, steel.mu, ue,
                                       fe, s);
      for (int k = 0; k < 6; ++k) {
        EXPECT_NEAR(stress[std::size_t(6 * (7 + e) + std::size_t(k))], s[std::size_t(k)],
                    1e-11 * std::max(1.0, std::abs(s[0])));
        scale = std::max(scale, std::abs(s[std::size_t(k)]));
      }
      for (int k = 0; k < 20; ++k) {
        const auto n = nodes[k];
        f_simple.x[n] += fe.x[std::size_t(k)], f_simple.y[n] += fe.y[std::size_t(k)],
            f_simple.z[n] += fe.z[std::size_t(k)];
      }
    }
    double largest = 0.0, difference = 0.0;
    for (std::size_t n = 0; n < mesh.node_count(); ++n) {
      largest =
          std::max({largest, std::abs(f_simple.x[n]), std::abs(f_simple.y[n]), std::abs(f_simple.z[n])});
      difference = std::max({difference, std::abs(f.x[n] - f_simple.x[n]), std::abs(f.y[n] - f_simple.y[n]),
                             std::abs(f.z[n] - f_simple.z[n])});
    }
    EXPECT_GT(largest, 0.0);
    EXPECT_LT(difference, 1e-12 * largest);
    EXPECT_NEAR(fast.strain, energy, 1e-12 * energy);
    EXPECT_GT(scale, 0.0);
  }
}

// A rank's part of a block built alone (ranks/rank_setup.cpp) shares the whole
// block's groups of equal Jacobians: the groups start at those of the parts' starts
// that start one among them all, and a part given the whole block's group points has
// its matrices, each element's group and its stable step, bit for bit.
TEST(Hex20, APartGivenTheWholeBlocksGroupsSharesItsMatricesAndStep) {
  for (const auto formulation : {input::Formulation::hex20, input::Formulation::hex20r}) {
    input::Deck deck = box_deck(formulation, {6, 4, 5}, {1.0, 0.5, 0.3});
    deck.parts[0].grading = {2.0, 1.0, 1.5};  // 6 x 5 spacings: 30 groups
    const mesh::Mesh mesh = mesh::build_mesh(deck);
    const std::uint32_t count = 120, split = 77;
    const ElementBlock whole =
        make_element_block(formulation, steel, 0.0, 0, count, mesh.connectivity.data(), mesh.x_ref);
    ASSERT_TRUE(whole.constant_jacobian);
    const std::vector<std::uint32_t> starts =
        jacobian_group_starts(formulation, count, mesh.connectivity.data(), mesh.x_ref);
    ASSERT_EQ(starts.size(), whole.group_points.size());
    ASSERT_EQ(starts.size(), 30u);
    for (std::size_t g = 0; g < starts.size(); ++g) {
      const std::uint32_t* nodes = mesh.connectivity.data() + 20 * std::size_t(starts[g]);
      for (std::size_t k = 0; k < 20; ++k) {
        EXPECT_EQ(whole.group_points[g][k], mesh.x_ref.x[nodes[k]]);
        EXPECT_EQ(whole.group_points[g][40 + k], mesh.x_ref.z[nodes[k]]);
      }
    }
    // The two parts' starts, then the starts among them: the whole block's.
    const std::uint32_t* second = mesh.connectivity.data() + 20 * std::size_t(split);
    std::vector<std::uint32_t> candidates =
        jacobian_group_starts(formulation, split, mesh.connectivity.data(), mesh.x_ref);
    for (const std::uint32_t e : jacobian_group_starts(formulation, count - split, second, mesh.x_ref))
      candidates.push_back(split + e);
    std::vector<std::uint32_t> candidate_nodes;
    for (const std::uint32_t e : candidates)
      candidate_nodes.insert(candidate_nodes.end(), mesh.connectivity.begin() + 20 * std::ptrdiff_t(e),
                             mesh.connectivity.begin() + 20 * std::ptrdiff_t(e + 1));
    std::vector<std::uint32_t> found;
    for (const std::uint32_t c : jacobian_group_starts(formulation, std::uint32_t(candidates.size()),
                                                       candidate_nodes.data(), mesh.x_ref))
      found.push_back(candidates[c]);
    EXPECT_EQ(found, starts);

    const ElementBlock part = make_element_block(formulation, steel, 0.0, split, count - split, second,
                                                 mesh.x_ref, {}, WholeBlock{true, true, whole.group_points});
    ASSERT_TRUE(part.constant_jacobian);
    EXPECT_EQ(part.shared, whole.shared);
    for (std::uint32_t e = 0; e < count - split; ++e)
      ASSERT_EQ(part.reference_index[e], whole.reference_index[split + e]) << e;
    EXPECT_EQ(critical_time_step(part, mesh.x_ref), critical_time_step(whole, mesh.x_ref));
    // Built alone, the part numbers its own groups: other matrices.
    const ElementBlock alone =
        make_element_block(formulation, steel, 0.0, split, count - split, second, mesh.x_ref);
    EXPECT_NE(alone.shared, whole.shared);
  }
}

TEST(Hex20, PackedGeneralLoopEqualsTheElementKernelOnAnyRange) {
  // A distorted box of 15 elements (not a multiple of 2, 4 or 8): the general kernel on
  // packs of elements, for ranges that start and end inside packs, against the
  // single-element kernel summed by hand.
  for (const auto formulation : {input::Formulation::hex20, input::Formulation::hex20r}) {
    const input::Deck deck = box_deck(formulation, {5, 3, 1}, {1.0, 0.6, 0.2}, 0.15);
    const mesh::Mesh mesh = mesh::build_mesh(deck);
    const auto count = static_cast<std::uint32_t>(mesh.element_count());
    const ElementBlock block =
        make_element_block(formulation, steel, 0.0, 2, count, mesh.connectivity.data(), mesh.x_ref);
    ASSERT_FALSE(uses_parallelepiped_kernel(block));
    std::mt19937_64 rng(12);
    std::uniform_real_distribution<double> unit(-1e-4, 1e-4);
    NodalVectors u(mesh.node_count());
    for (std::size_t n = 0; n < mesh.node_count(); ++n)
      u.x[n] = unit(rng), u.y[n] = unit(rng), u.z[n] = unit(rng);
    const int per_direction = formulation == input::Formulation::hex20 ? 3 : 2;
    const hex20::GaussRule rule = hex20::gauss_rule(per_direction);
    std::vector<double> table(std::size_t(hex20::table_stride * rule.count));
    hex20::derivative_table(rule, table.data());
    std::vector<double> reference(std::size_t(hex20::reference_size(rule.count)));
    for (const auto& [begin, end] :
         {std::pair<std::uint32_t, std::uint32_t>{0, count}, {1, 14}, {3, 9}, {5, 6}}) {
      NodalVectors f(mesh.node_count()), f_simple(mesh.node_count());
      std::vector<double> stress(6 * std::size_t(2 + count), 0.0);
      const ElementEnergies packed = add_internal_forces(block, begin, end, u, f, stress.data());
      double energy = 0.0, largest = 0.0;
      for (std::uint32_t e = begin; e < end; ++e) {
        const std::uint32_t* nodes = mesh.connectivity.data() + 20 * std::size_t(e);
        ElementVectors20 x, ue, fe;
        for (std::size_t k = 0; k < 20; ++k) {
          const auto n = nodes[k];
          x.x[k] = mesh.x_ref.x[n], x.y[k] = mesh.x_ref.y[n], x.z[k] = mesh.x_ref.z[n];
          ue.x[k] = u.x[n], ue.y[k] = u.y[n], ue.z[k] = u.z[n];
        }
        ASSERT_GT(hex20::make_reference(x, rule, table.data(), reference.data()), 0.0);
        material::SymTensor s;
        energy += hex20::internal_forces(rule.count, table.data(), reference.data(), steel.lambda, steel.mu,
                                         ue, fe, s);
        for (std::size_t k = 0; k < 6; ++k)
          EXPECT_NEAR(stress[6 * (2 + e) + k], s[k],
                      1e-12 * std::max({std::abs(s[0]), std::abs(s[1]), std::abs(s[2])}));
        for (std::size_t k = 0; k < 20; ++k) {
          const auto n = nodes[k];
          f_simple.x[n] += fe.x[k], f_simple.y[n] += fe.y[k], f_simple.z[n] += fe.z[k];
        }
      }
      double difference = 0.0;
      for (std::size_t n = 0; n < mesh.node_count(); ++n) {
        largest =
            std::max({largest, std::abs(f_simple.x[n]), std::abs(f_simple.y[n]), std::abs(f_simple.z[n])});
        difference = std::max({difference, std::abs(f.x[n] - f_simple.x[n]), std::abs(f.y[n] - f_simple.y[n]),
                               std::abs(f.z[n] - f_simple.z[n])});
      }
      EXPECT_GT(largest, 0.0);
      EXPECT_LE(difference, 1e-12 * largest) << begin << ".." << end;
      EXPECT_NEAR(packed.strain, energy, 1e-12 * energy) << begin << ".." << end;
      // Elements outside the range: no stress written.
      for (std::uint32_t e = 0; e < count; ++e)
        if (e < begin || e >= end) {
          EXPECT_EQ(stress[6 * (2 + e)], 0.0) << e;
        }
    }
  }
}

// quadratic-and-hertz.md: one cube of side a, HRZ mass, 3x3x3 Gauss points:
// dt_crit = 2 / omega_max = 0.268 a / c1. The rule is that element eigenvalue.
TEST(Hex20, CriticalStepOfACubeIs0268ATimesC1) {
  const double a = 2.0;
  const input::Deck deck = box_deck(input::Formulation::hex20, {1, 1, 1}, {a, a, a});
  const mesh::Mesh mesh = mesh::build_mesh(deck);
  const ElementBlock block =
      make_element_block(input::Formulation::hex20, steel, 0.0, 0, 1, mesh.connectivity.data(), mesh.x_ref);
  const double c1 = steel.dilatational_wave_speed();
  EXPECT_NEAR(critical_time_step(block, mesh.x_ref) * c1 / a, 0.268, 0.0005);
  // The reduced-integration brick is softer: a longer step.
  const ElementBlock reduced =
      make_element_block(input::Formulation::hex20r, steel, 0.0, 0, 1, mesh.connectivity.data(), mesh.x_ref);
  EXPECT_GT(critical_time_step(reduced, mesh.x_ref), critical_time_step(block, mesh.x_ref));
}

}  // namespace
}  // namespace exdyn::element
