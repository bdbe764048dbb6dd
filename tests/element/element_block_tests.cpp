// Element blocks: gather/scatter, lumped mass, stable step, and the plate-impact
// chain (../shared/reference/plate-impact.md) through the element loop.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <utility>
#include <vector>

#include "box_mesh.hpp"
#include "common/errors.hpp"
#include "element/corner_checks.hpp"
#include "element/element_block.hpp"
#include "element/hex8.hpp"
#include "element/hex8_parallelepiped.hpp"
#include "reference_elements.hpp"

namespace exdyn::element {
namespace {

const material::ElasticConstants steel = material::elastic_constants(2.1e11, 0.3, 7800.0);

// n nodal vectors, each component uniform in [-scale, scale], drawn x, y, z node by node.
NodalVectors random_vectors(std::size_t n, double scale, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  NodalVectors v(n);
  for (std::size_t i = 0; i < n; ++i) {
    v.x[i] = scale * unit(rng);
    v.y[i] = scale * unit(rng);
    v.z[i] = scale * unit(rng);
  }
  return v;
}

ElementVectors gather(const NodalVectors& v, const std::uint32_t* nodes) {
  ElementVectors local;
  for (int I = 0; I < 8; ++I) {
    local.x[I] = v.x[nodes[I]];
    local.y[I] = v.y[nodes[I]];
    local.z[I] = v.z[nodes[I]];
  }
  return local;
}

// A 2x2x2 box of side 1 with every node moved randomly by up to 0.15.
Box distorted_patch(std::mt19937_64& rng) {
  Box box = make_box(2, 2, 2, 0.5);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  for (std::size_t n = 0; n < box.x_ref.size(); ++n) {
    box.x_ref.x[n] += 0.075 * unit(rng);
    box.x_ref.y[n] += 0.075 * unit(rng);
    box.x_ref.z[n] += 0.075 * unit(rng);
  }
  return box;
}

void check_block_against_hand_summed_elements(input::Formulation formulation) {
  std::mt19937_64 rng(41);
  const Box box = distorted_patch(rng);
  const std::uint32_t first_element = 5;
  const double coefficient = 0.05;
  const ElementBlock block = make_element_block(formulation, steel, coefficient, first_element, box.count,
                                                box.connectivity.data(), box.x_ref);
  EXPECT_FALSE(uses_parallelepiped_kernel(block));
  const NodalVectors u = random_vectors(box.x_ref.size(), 1e-4, rng);
  NodalVectors f_int(box.x_ref.size());
  const double sentinel = -12345.0;
  std::vector<double> stress(6 * (first_element + box.count + 2), sentinel);
  const ElementEnergies energies = add_internal_forces(block, u, f_int, stress.data());

  // By hand: each element through the plain reference implementation, assembled.
  Eigen::VectorXd f_expected = Eigen::VectorXd::Zero(3 * static_cast<Eigen::Index>(u.size()));
  double strain = 0.0, hourglass = 0.0;
  for (std::uint32_t e = 0; e < box.count; ++e) {
    const std::uint32_t* nodes = box.connectivity.data() + 8 * e;
    const ElementVectors x = gather(box.x_ref, nodes), u_local = gather(u, nodes);
    const testing::ReferenceResult ref =
        formulation == input::Formulation::hex8
            ? testing::reference_hex8(x, steel.lambda, steel.mu, u_local)
            : testing::reference_hex8r(x, steel.lambda, steel.mu, coefficient, u_local);
    for (int I = 0; I < 8; ++I)
      for (int i = 0; i < 3; ++i) f_expected(3 * nodes[I] + i) += ref.force(3 * I + i);
    strain += ref.strain_energy;
    hourglass += ref.hourglass_energy;
    const double scale = ref.mean_stress.cwiseAbs().maxCoeff();
    for (int k = 0; k < 6; ++k)
      EXPECT_NEAR(stress[6 * (first_element + e) + k], ref.mean_stress(k), 1e-12 * scale);
  }
  for (std::size_t n = 0; n < u.size(); ++n) {
    const Eigen::Index i = static_cast<Eigen::Index>(n);
    EXPECT_NEAR(f_int.x[n], f_expected(3 * i), 1e-12 * f_expected.norm());
    EXPECT_NEAR(f_int.y[n], f_expected(3 * i + 1), 1e-12 * f_expected.norm());
    EXPECT_NEAR(f_int.z[n], f_expected(3 * i + 2), 1e-12 * f_expected.norm());
  }
  EXPECT_NEAR(energies.strain, strain, 1e-12 * strain);
  EXPECT_NEAR(energies.hourglass, hourglass, 1e-12 * (strain + hourglass));
  // Entries of other blocks' elements are untouched.
  for (std::uint32_t k = 0; k < 6 * first_element; ++k) EXPECT_EQ(stress[k], sentinel);
  for (std::size_t k = 6 * (first_element + box.count); k < stress.size(); ++k)
    EXPECT_EQ(stress[k], sentinel);

  // Adding again, in two ranges, doubles the forces (f_int +=).
  const ElementEnergies first = add_internal_forces(block, 0, 3, u, f_int, stress.data());
  const ElementEnergies second = add_internal_forces(block, 3, block.count, u, f_int, stress.data());
  EXPECT_NEAR(first.strain + second.strain, strain, 1e-12 * strain);
  for (std::size_t n = 0; n < u.size(); ++n)
    EXPECT_NEAR(f_int.x[n], 2 * f_expected(3 * static_cast<Eigen::Index>(n)), 1e-12 * f_expected.norm());
}

TEST(ElementBlock, Hex8InternalForcesEqualHandSummedElementKernels) {
  check_block_against_hand_summed_elements(input::Formulation::hex8);
}

TEST(ElementBlock, Hex8rInternalForcesEqualHandSummedElementKernels) {
  check_block_against_hand_summed_elements(input::Formulation::hex8r);
}

TEST(ElementBlock, PatchTestInteriorNodeOfDistortedPatchFeelsNoForce) {
  // A linear field on a patch of distorted elements: the interior node (1,1,1)
  // is in equilibrium, for both formulations.
  std::mt19937_64 rng(42);
  const Box box = distorted_patch(rng);
  const std::size_t interior = 1 + 3 * (1 + 3 * 1);
  NodalVectors u(box.x_ref.size());
  for (std::size_t n = 0; n < u.size(); ++n) {
    const double x = box.x_ref.x[n], y = box.x_ref.y[n], z = box.x_ref.z[n];
    u.x[n] = 1e-3 * x + 2e-4 * y - 3e-4 * z;
    u.y[n] = 5e-4 * x - 7e-4 * y + 1e-4 * z;
    u.z[n] = -2e-4 * x + 3e-4 * y + 4e-4 * z;
  }
  for (input::Formulation formulation : {input::Formulation::hex8, input::Formulation::hex8r}) {
    const ElementBlock block =
        make_element_block(formulation, steel, 0.05, 0, box.count, box.connectivity.data(), box.x_ref);
    NodalVectors f_int(box.x_ref.size());
    std::vector<double> stress(6 * box.count);
    add_internal_forces(block, u, f_int, stress.data());
    double largest = 0.0;
    for (std::size_t n = 0; n < u.size(); ++n) largest = std::max(largest, std::abs(f_int.x[n]));
    EXPECT_LT(std::abs(f_int.x[interior]), 1e-12 * largest);
    EXPECT_LT(std::abs(f_int.y[interior]), 1e-12 * largest);
    EXPECT_LT(std::abs(f_int.z[interior]), 1e-12 * largest);
    const double sigma_xx = steel.lambda * (1e-3 - 7e-4 + 4e-4) + 2 * steel.mu * 1e-3;
    for (std::uint32_t e = 0; e < box.count; ++e) EXPECT_NEAR(stress[6 * e], sigma_xx, 1e-12 * sigma_xx);
  }
}

TEST(ElementBlock, StructuredBoxUsesTheParallelepipedKernelsAndMatchesTheReference) {
  std::mt19937_64 rng(44);
  const Box box = make_box(3, 2, 2, 2.5e-5);
  const NodalVectors u = random_vectors(box.x_ref.size(), 1e-8, rng);
  for (input::Formulation formulation : {input::Formulation::hex8, input::Formulation::hex8r}) {
    const ElementBlock block =
        make_element_block(formulation, steel, 0.05, 0, box.count, box.connectivity.data(), box.x_ref);
    EXPECT_TRUE(uses_parallelepiped_kernel(block));
    NodalVectors f_int(box.x_ref.size());
    std::vector<double> stress(6 * box.count);
    const ElementEnergies energies = add_internal_forces(block, u, f_int, stress.data());
    Eigen::VectorXd f_expected = Eigen::VectorXd::Zero(3 * static_cast<Eigen::Index>(u.size()));
    double energy = 0.0;
    for (std::uint32_t e = 0; e < box.count; ++e) {
      const std::uint32_t* nodes = box.connectivity.data() + 8 * e;
      const ElementVectors x = gather(box.x_ref, nodes), u_local = gather(u, nodes);
      const testing::ReferenceResult ref =
          formulation == input::Formulation::hex8
              ? testing::reference_hex8(x, steel.lambda, steel.mu, u_local)
              : testing::reference_hex8r(x, steel.lambda, steel.mu, 0.05, u_local);
      for (int I = 0; I < 8; ++I)
        for (int i = 0; i < 3; ++i) f_expected(3 * nodes[I] + i) += ref.force(3 * I + i);
      energy += ref.strain_energy + ref.hourglass_energy;
    }
    for (std::size_t n = 0; n < u.size(); ++n) {
      const Eigen::Index i = static_cast<Eigen::Index>(n);
      EXPECT_NEAR(f_int.x[n], f_expected(3 * i), 1e-12 * f_expected.norm());
      EXPECT_NEAR(f_int.y[n], f_expected(3 * i + 1), 1e-12 * f_expected.norm());
      EXPECT_NEAR(f_int.z[n], f_expected(3 * i + 2), 1e-12 * f_expected.norm());
    }
    EXPECT_NEAR(energies.strain + energies.hourglass, energy, 1e-12 * energy);
  }
}

void check_odd_counts_and_ranges(bool distorted) {
  // Blocks run two elements at a time (all but general hex8); an odd count and
  // ranges that split a pair must give exactly the element-by-element result.
  std::mt19937_64 rng(45);
  Box box = make_box(5, 1, 1, 1e-3);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  if (distorted)
    for (std::size_t n = 0; n < box.x_ref.size(); ++n) {
      box.x_ref.x[n] += 1e-4 * unit(rng);
      box.x_ref.y[n] += 1e-4 * unit(rng);
      box.x_ref.z[n] += 1e-4 * unit(rng);
    }
  const NodalVectors u = random_vectors(box.x_ref.size(), 1e-6, rng);
  for (input::Formulation formulation : {input::Formulation::hex8, input::Formulation::hex8r}) {
    const std::uint32_t first_element = 3;
    const ElementBlock block = make_element_block(formulation, steel, 0.05, first_element, box.count,
                                                  box.connectivity.data(), box.x_ref);
    ASSERT_EQ(uses_parallelepiped_kernel(block), !distorted);
    for (std::uint32_t begin = 0; begin <= box.count; ++begin) {
      for (std::uint32_t end = begin; end <= box.count; ++end) {
        NodalVectors f_int(box.x_ref.size());
        std::vector<double> stress(6 * (first_element + box.count), 0.0);
        const ElementEnergies energies = add_internal_forces(block, begin, end, u, f_int, stress.data());
        Eigen::VectorXd f_expected = Eigen::VectorXd::Zero(3 * static_cast<Eigen::Index>(u.size()));
        double energy = 0.0, scale = 0.0;
        for (std::uint32_t e = 0; e < box.count; ++e) {
          const std::uint32_t* nodes = box.connectivity.data() + 8 * e;
          const ElementVectors x = gather(box.x_ref, nodes), u_local = gather(u, nodes);
          const testing::ReferenceResult ref =
              formulation == input::Formulation::hex8
                  ? testing::reference_hex8(x, steel.lambda, steel.mu, u_local)
                  : testing::reference_hex8r(x, steel.lambda, steel.mu, 0.05, u_local);
          scale = std::max(scale, ref.force.norm());
          const bool inside = e >= begin && e < end;
          for (int k = 0; k < 6; ++k)
            EXPECT_NEAR(stress[6 * (first_element + e) + k], inside ? ref.mean_stress(k) : 0.0,
                        1e-12 * ref.mean_stress.cwiseAbs().maxCoeff());
          if (!inside) continue;
          for (int I = 0; I < 8; ++I)
            for (int i = 0; i < 3; ++i) f_expected(3 * nodes[I] + i) += ref.force(3 * I + i);
          energy += ref.strain_energy + ref.hourglass_energy;
        }
        for (std::size_t n = 0; n < u.size(); ++n) {
          const Eigen::Index i = static_cast<Eigen::Index>(n);
          EXPECT_NEAR(f_int.x[n], f_expected(3 * i), 1e-12 * scale);
          EXPECT_NEAR(f_int.y[n], f_expected(3 * i + 1), 1e-12 * scale);
          EXPECT_NEAR(f_int.z[n], f_expected(3 * i + 2), 1e-12 * scale);
        }
        EXPECT_NEAR(energies.strain + energies.hourglass, energy, 1e-12 * (energy + 1e-300));
      }
    }
  }
}

TEST(ElementBlock, RowPacksOfABoxAddTheForcesOfTheElementKernels) {
  // Rows of 8 elements along x: whole packs of 2, 4 or 8 elements lie on one row, so
  // the packed loops take their vector gather and scatter (ElementBlock::row_pack);
  // ranges that cut a pack take the lane-by-lane path for it.
  std::mt19937_64 rng(46);
  const Box box = make_box(8, 2, 2, 2.5e-5);
  const NodalVectors u = random_vectors(box.x_ref.size(), 1e-8, rng);
  for (input::Formulation formulation : {input::Formulation::hex8, input::Formulation::hex8r}) {
    const ElementBlock block =
        make_element_block(formulation, steel, 0.05, 0, box.count, box.connectivity.data(), box.x_ref);
    EXPECT_EQ(block.axis_aligned, formulation == input::Formulation::hex8);
    ASSERT_FALSE(block.row_pack.empty());
    EXPECT_TRUE(
        std::all_of(block.row_pack.begin(), block.row_pack.end(), [](std::uint8_t r) { return r == 1; }));
    for (const auto& [begin, end] :
         {std::pair<std::uint32_t, std::uint32_t>{0, box.count}, {1, 9}, {4, 31}, {8, 24}}) {
      NodalVectors f_int(box.x_ref.size());
      std::vector<double> stress(6 * box.count, 0.0);
      const ElementEnergies energies = add_internal_forces(block, begin, end, u, f_int, stress.data());
      Eigen::VectorXd f_expected = Eigen::VectorXd::Zero(3 * static_cast<Eigen::Index>(u.size()));
      double energy = 0.0;
      for (std::uint32_t e = begin; e < end; ++e) {
        const std::uint32_t* nodes = box.connectivity.data() + 8 * e;
        const ElementVectors x = gather(box.x_ref, nodes), u_local = gather(u, nodes);
        const testing::ReferenceResult ref =
            formulation == input::Formulation::hex8
                ? testing::reference_hex8(x, steel.lambda, steel.mu, u_local)
                : testing::reference_hex8r(x, steel.lambda, steel.mu, 0.05, u_local);
        for (int I = 0; I < 8; ++I)
          for (int i = 0; i < 3; ++i) f_expected(3 * nodes[I] + i) += ref.force(3 * I + i);
        energy += ref.strain_energy + ref.hourglass_energy;
        for (int k = 0; k < 6; ++k)
          EXPECT_NEAR(stress[6 * e + k], ref.mean_stress(k), 1e-12 * ref.mean_stress.cwiseAbs().maxCoeff());
      }
      const double scale = f_expected.cwiseAbs().maxCoeff();
      for (std::size_t n = 0; n < u.size(); ++n) {
        const Eigen::Index i = static_cast<Eigen::Index>(n);
        EXPECT_NEAR(f_int.x[n], f_expected(3 * i), 1e-12 * scale) << begin << ".." << end;
        EXPECT_NEAR(f_int.y[n], f_expected(3 * i + 1), 1e-12 * scale) << begin << ".." << end;
        EXPECT_NEAR(f_int.z[n], f_expected(3 * i + 2), 1e-12 * scale) << begin << ".." << end;
      }
      EXPECT_NEAR(energies.strain + energies.hourglass, energy, 1e-12 * energy);
    }
  }
}

// The element pass as tasks (add_internal_forces_as_tasks, which the solver runs beside
// the contact pass) adds the same forces in the same order as the coloured loop: the
// same bits, on 1, 2 and 3 threads, with a task of other work in the team.
TEST(ElementBlock, TasksAddTheSameBitsAsTheColouredLoop) {
  std::mt19937_64 rng(47);
  const Box box = make_box(40, 3, 20, 2.5e-5);  // 2400 elements: 5 chunks of 512, 2 colours
  const NodalVectors u = random_vectors(box.x_ref.size(), 1e-8, rng);
  for (input::Formulation formulation : {input::Formulation::hex8, input::Formulation::hex8r}) {
    const ElementBlock block =
        make_element_block(formulation, steel, 0.05, 0, box.count, box.connectivity.data(), box.x_ref);
    ASSERT_GE(block.colours.size(), 2u);
    NodalVectors f_loop(box.x_ref.size());
    std::vector<double> stress_loop(6 * box.count, 0.0);
    const ElementEnergies loop = add_internal_forces(block, u, f_loop, stress_loop.data());
    for (const int threads : {1, 2, 3}) {
      NodalVectors f_tasks(box.x_ref.size());
      std::vector<double> stress_tasks(6 * box.count, 0.0);
      ElementEnergies tasks;
      double other_work = 0.0;
#pragma omp parallel num_threads(threads)
#pragma omp single
      {
#pragma omp task shared(other_work)
        for (int k = 0; k < 100000; ++k) other_work += 1e-6 * k;
        tasks = add_internal_forces_as_tasks(block, u, f_tasks, stress_tasks.data());
      }
      EXPECT_GT(other_work, 0.0);
      EXPECT_EQ(f_tasks.x, f_loop.x) << threads;
      EXPECT_EQ(f_tasks.y, f_loop.y) << threads;
      EXPECT_EQ(f_tasks.z, f_loop.z) << threads;
      EXPECT_EQ(stress_tasks, stress_loop) << threads;
      EXPECT_EQ(tasks.strain, loop.strain) << threads;
      EXPECT_EQ(tasks.hourglass, loop.hourglass) << threads;
    }
  }
}

TEST(ElementBlock, BoxBlocksHandleOddCountsAndRangesStartingAnywhere) { check_odd_counts_and_ranges(false); }

TEST(ElementBlock, DistortedBlocksHandleOddCountsAndRangesStartingAnywhere) {
  check_odd_counts_and_ranges(true);
}

TEST(ElementBlock, LumpedMassOfCubeIsRhoHCubedOverEightPerNode) {
  const double h = 2.5e-5;
  const Box box = make_box(1, 1, 1, h);
  const ElementBlock block = make_element_block(input::Formulation::hex8, steel, 0.0, 0, box.count,
                                                box.connectivity.data(), box.x_ref);
  std::vector<double> mass(box.x_ref.size(), 0.0);
  add_lumped_mass(block, box.x_ref, mass);
  for (double m : mass) EXPECT_NEAR(m, steel.density * h * h * h / 8, 1e-12 * m);
}

TEST(ElementBlock, LumpedMassOfDistortedPatchSumsToRhoV) {
  std::mt19937_64 rng(43);
  const Box box = distorted_patch(rng);
  const ElementBlock block = make_element_block(input::Formulation::hex8r, steel, 0.05, 0, box.count,
                                                box.connectivity.data(), box.x_ref);
  std::vector<double> mass(box.x_ref.size(), 0.0);
  add_lumped_mass(block, box.x_ref, mass);
  double total = 0.0, volume = 0.0;
  for (double m : mass) {
    EXPECT_GT(m, 0.0);
    total += m;
  }
  for (std::uint32_t e = 0; e < box.count; ++e)
    volume += hex8::volume(gather(box.x_ref, box.connectivity.data() + 8 * e));
  EXPECT_NEAR(total, steel.density * volume, 1e-12 * total);
}

TEST(ElementBlock, CriticalTimeStepOfCubeIsSideOverDilatationalWaveSpeed) {
  const double h = 2.5e-5;
  const Box box = make_box(2, 1, 1, h);
  const ElementBlock block = make_element_block(input::Formulation::hex8, steel, 0.0, 0, box.count,
                                                box.connectivity.data(), box.x_ref);
  const double c1 = std::sqrt((steel.lambda + 2 * steel.mu) / steel.density);
  EXPECT_NEAR(critical_time_step(block, box.x_ref), h / c1, 1e-12 * h / c1);
  // The plate-impact step: Courant 0.125 gives 5.1909e-10 s.
  EXPECT_NEAR(0.125 * critical_time_step(block, box.x_ref), 5.1909e-10, 1e-14);
}

TEST(ElementBlock, CriticalTimeStepUsesTheSmallestElement) {
  Box box = make_box(2, 1, 1, 1.0);
  // Squash the second element to half its length along x.
  for (std::size_t n = 0; n < box.x_ref.size(); ++n)
    if (box.x_ref.x[n] > 1.5) box.x_ref.x[n] = 1.5;
  const ElementBlock block = make_element_block(input::Formulation::hex8, steel, 0.0, 0, box.count,
                                                box.connectivity.data(), box.x_ref);
  EXPECT_NEAR(critical_time_step(block, box.x_ref) * steel.dilatational_wave_speed(), 0.5, 1e-14);
}

TEST(ElementBlock, NoElementIsInvertedUnderRigidMotionAndModerateStrain) {
  const Box box = make_box(3, 2, 2, 1.0);
  for (const auto formulation : {input::Formulation::hex8, input::Formulation::hex8r}) {
    const ElementBlock block =
        make_element_block(formulation, steel, 0.05, 0, box.count, box.connectivity.data(), box.x_ref);
    NodalVectors u(box.x_ref.size());
    EXPECT_FALSE(find_inverted_element(block, box.x_ref, u).found);
    // A rotation by 170 degrees about z and a 40 % compression along x: all corners stay positive.
    const double c = std::cos(170.0 * M_PI / 180.0), s = std::sin(170.0 * M_PI / 180.0);
    for (std::size_t n = 0; n < u.size(); ++n) {
      const double x = 0.6 * box.x_ref.x[n], y = box.x_ref.y[n];
      u.x[n] = c * x - s * y - box.x_ref.x[n];
      u.y[n] = s * x + c * y - box.x_ref.y[n];
    }
    EXPECT_FALSE(find_inverted_element(block, box.x_ref, u).found);
  }
}

TEST(ElementBlock, InvertedElementIsFoundAndNamedWithItsCorner) {
  const Box box = make_box(3, 1, 1, 1.0);  // elements 0, 1, 2 along x; nodes i + 4 (j + 2 k)
  const ElementBlock block = make_element_block(input::Formulation::hex8r, steel, 0.05, 7, box.count,
                                                box.connectivity.data(), box.x_ref);
  NodalVectors u(box.x_ref.size());
  // Node (2, 0, 0), shared by elements 1 and 2, moves 1.5 h in -x: past its neighbour at x = 1.
  u.x[2] = -1.5;
  const InvertedElement inverted = find_inverted_element(block, box.x_ref, u);
  ASSERT_TRUE(inverted.found);
  EXPECT_EQ(inverted.element, 7u + 1u);  // the lowest global index: first_element 7 + local 1
  // Corner 0 of element 1, node (1,0,0), is checked first and already sees its +xi edge reversed.
  EXPECT_EQ(inverted.corner, 0);
  EXPECT_LT(inverted.det_jacobian, 0.0);
  // Only half way (0.5 h): element 1 is squashed to half its length, not inverted.
  u.x[2] = -0.5;
  EXPECT_FALSE(find_inverted_element(block, box.x_ref, u).found);
  // Element 2 (local), on the other side of the node, is stretched, not inverted.
  u.x[2] = -1.5;
  EXPECT_FALSE(find_inverted_element(block, 2, 3, box.x_ref, u).found);
  EXPECT_TRUE(find_inverted_element(block, 1, 2, box.x_ref, u).found);
}

TEST(ElementBlock, SafetyRadiusOfTheUnitCubeIsOneOverSixRootThree) {
  const Box box = make_box(1, 1, 1, 2.0);  // det J = 8, ||J||_F^2 = 12 at every corner
  const ElementBlock block = make_element_block(input::Formulation::hex8, steel, 0.0, 0, box.count,
                                                box.connectivity.data(), box.x_ref);
  const InvertedElement none = find_inverted_element(block, box.x_ref, NodalVectors(box.x_ref.size()));
  ASSERT_FALSE(none.found);
  EXPECT_NEAR(none.safety_radius, (8.0 / 12.0) / (2.0 * std::sqrt(3.0)), 1e-15);
}

TEST(ElementBlock, NoMotionWithinTheSafetyRadiusInvertsAnElement) {
  // The bound the solver relies on to skip the inversion check: random motions of
  // every node by less than the safety radius (from random distorted states) never
  // invert an element, and motions some 6 times larger do.
  const Box box = make_box(2, 2, 2, 1.0);
  const ElementBlock block = make_element_block(input::Formulation::hex8, steel, 0.0, 0, box.count,
                                                box.connectivity.data(), box.x_ref);
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  int inverted_beyond = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    NodalVectors u(box.x_ref.size());
    for (std::size_t n = 0; n < u.size(); ++n)
      u.x[n] = 0.3 * unit(rng), u.y[n] = 0.3 * unit(rng), u.z[n] = 0.3 * unit(rng);
    const InvertedElement start = find_inverted_element(block, box.x_ref, u);
    if (start.found) continue;
    ASSERT_GT(start.safety_radius, 0.0);
    for (const double factor : {0.999, 6.0}) {
      NodalVectors moved = u;
      for (std::size_t n = 0; n < u.size(); ++n) {  // a random direction, length factor x radius
        double d[3] = {unit(rng), unit(rng), unit(rng)};
        const double length = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
        const double step = factor * start.safety_radius / length;
        moved.x[n] += step * d[0], moved.y[n] += step * d[1], moved.z[n] += step * d[2];
      }
      const bool inverted = find_inverted_element(block, box.x_ref, moved).found;
      if (factor < 1.0) {
        ASSERT_FALSE(inverted) << "trial " << trial;
      } else {
        inverted_beyond += inverted;
      }
    }
  }
  EXPECT_GT(inverted_beyond, 0);  // the bound is not vacuous
}

TEST(ElementBlock, InvertedElementIsAnErrorNamingTheElement) {
  Box box = make_box(1, 1, 1, 1.0);
  std::swap(box.connectivity[0], box.connectivity[4]);  // node order turned upside down at one corner pair
  std::swap(box.connectivity[1], box.connectivity[5]);
  std::swap(box.connectivity[2], box.connectivity[6]);
  std::swap(box.connectivity[3], box.connectivity[7]);
  try {
    make_element_block(input::Formulation::hex8, steel, 0.0, 17, box.count, box.connectivity.data(),
                       box.x_ref);
    FAIL() << "expected an InputError";
  } catch (const InputError& error) {
    EXPECT_NE(std::string(error.what()).find("element 17"), std::string::npos) << error.what();
  }
}

// The plate-impact reference calculation along z = 0: a row of hex8 elements
// whose nodes move only in x, lumped mass, central differences, the contact face
// held. It must equal the 1D chain (masses rho h, rho h / 2 at the ends; springs
// M / h) element by element to round-off.
TEST(ElementBlock, RowOfHex8EqualsTheOneDimensionalChainOfThePlateImpact) {
  const int n = 100;
  const double h = 2.5e-5, v0 = 1.0;
  const Box box = make_box(n, 1, 1, h);
  const ElementBlock block = make_element_block(input::Formulation::hex8, steel, 0.0, 0, box.count,
                                                box.connectivity.data(), box.x_ref);
  std::vector<double> mass(box.x_ref.size(), 0.0);
  add_lumped_mass(block, box.x_ref, mass);
  const double dt = 0.125 * critical_time_step(block, box.x_ref);
  const int steps = 448;
  const double m_modulus = steel.dilatational_modulus();

  // Finite elements: the plate moves toward the wall x = 0 at v0.
  NodalVectors u(box.x_ref.size()), v(box.x_ref.size()), f_int(box.x_ref.size());
  for (std::size_t k = 0; k < u.size(); ++k) v.x[k] = box.x_ref.x[k] > 0.0 ? -v0 : 0.0;
  std::vector<double> stress(6 * box.count);
  // Chain, per unit area.
  std::vector<double> cu(n + 1, 0.0), cv(n + 1, -v0), cf(n + 1), cm(n + 1, steel.density * h), cs(n);
  cv[0] = 0.0;
  cm[0] = cm[n] = 0.5 * steel.density * h;

  for (int step = 0; step < steps; ++step) {
    // u^{n+1} = u^n + dt v^{n+1/2}, then a^{n+1} = -f_int(u^{n+1}) / m, v^{n+3/2} = v^{n+1/2} + dt a^{n+1}.
    for (std::size_t k = 0; k < u.size(); ++k) u.x[k] += dt * v.x[k];
    f_int.fill(0.0);
    add_internal_forces(block, u, f_int, stress.data());
    for (std::size_t k = 0; k < u.size(); ++k)
      if (box.x_ref.x[k] > 0.0) v.x[k] -= dt * f_int.x[k] / mass[k];

    for (int i = 0; i <= n; ++i) cu[i] += dt * cv[i];
    std::fill(cf.begin(), cf.end(), 0.0);
    for (int e = 0; e < n; ++e) {
      cs[e] = m_modulus * (cu[e + 1] - cu[e]) / h;
      cf[e] -= cs[e];
      cf[e + 1] += cs[e];
    }
    for (int i = 1; i <= n; ++i) cv[i] -= dt * cf[i] / cm[i];
  }
  const double plateau = steel.density * steel.dilatational_wave_speed() * v0;  // rho c1 v0
  for (int e = 0; e < n; ++e) EXPECT_NEAR(stress[6 * e], cs[e], 1e-9 * plateau) << "element " << e;

  // Normalised as in the reference: sigma* = sigma c1 / (lambda v0).
  const double to_normalised = steel.dilatational_wave_speed() / (steel.lambda * v0);
  double mean = 0.0;
  for (int e = 5; e <= 44; ++e) mean += stress[6 * e] * to_normalised / 40.0;
  EXPECT_NEAR(mean, -2.3301, 5e-4);
  EXPECT_NEAR(stress[0] * to_normalised, -2.3334, 5e-4);
  // Uniaxial strain in every element: sigma_y = sigma_z = lambda / M sigma_x, so
  // sigma_z* = -1 on the plateau.
  double mean_lateral = 0.0;
  for (int e = 0; e < n; ++e) {
    EXPECT_NEAR(stress[6 * e + 1], steel.lambda / m_modulus * stress[6 * e], 1e-9 * plateau);
    EXPECT_NEAR(stress[6 * e + 2], steel.lambda / m_modulus * stress[6 * e], 1e-9 * plateau);
    if (e >= 5 && e <= 44) mean_lateral += stress[6 * e + 2] * to_normalised / 40.0;
  }
  EXPECT_NEAR(mean_lateral, -1.0, 2e-3);
}

}  // namespace
}  // namespace exdyn::element
