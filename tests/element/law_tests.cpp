// The element loops of a material law (element/constitutive.hpp, hex8_constitutive.hpp,
// hex20_constitutive.hpp): objectivity, forces that are the derivative of the
// energy (so the explicit scheme conserves it), the small-strain limit, the linear
// kernels where the law stays elastic, and every instruction set against the baseline.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "common/isa.hpp"
#include "element/element_block.hpp"
#include "mesh/mesh.hpp"

namespace exdyn::element {
namespace {

using input::Formulation;
const material::ElasticConstants copper = material::elastic_constants(117e9, 0.35, 8930.0);
// Each formulation, hex8r with both hourglass controls.
struct Variant {
  Formulation formulation;
  input::HourglassControl hourglass;
  const char* name;
};
const Variant all_variants[] = {
    {Formulation::hex8, 0.05, "hex8"},
    {Formulation::hex8r, 0.05, "hex8r flanagan_belytschko"},
    {Formulation::hex8r, {input::HourglassModel::assumed_strain, 1.0}, "hex8r assumed_strain"},
    {Formulation::hex20, 0.05, "hex20"},
    {Formulation::hex20r, 0.05, "hex20r"}};

// A distorted 3 x 2 x 2 box of 1 mm elements.
mesh::Mesh distorted_box(Formulation formulation) {
  input::Deck deck;
  input::PartOptions part;
  part.name = "box";
  part.box_min = {0, 0, 0};
  part.box_max = {3e-3, 2e-3, 2e-3};
  part.elements = {3, 2, 2};
  part.formulation = formulation;
  part.material_index = 0;
  part.perturbation_fraction = 0.2;
  part.perturbation_seed = 3;
  deck.parts = {part};
  return mesh::build_mesh(deck);
}

material::MaterialLaw law(bool finite, bool plastic, bool f_bar = true) {
  material::MaterialLaw l;
  l.finite = finite;
  l.f_bar = f_bar;
  if (plastic)
    l.flow = material::FlowRule::hardening, l.hardening = material::Hardening::linear(400e6, 100e6);
  return l;
}

ElementBlock block_of(const mesh::Mesh& mesh, const Variant& v, const material::MaterialLaw& l) {
  ElementBlock block =
      make_element_block(v.formulation, copper, v.hourglass, 0, std::uint32_t(mesh.element_count()),
                         mesh.connectivity.data(), mesh.x_ref, l);
  set_material_time_step(block, 1e-8);
  return block;
}

struct Result {
  NodalVectors f;
  ElementEnergies energies;
  std::vector<double> stress;
};

Result forces(const ElementBlock& block, const mesh::Mesh& mesh, const NodalVectors& u) {
  Result r{NodalVectors(mesh.node_count()), {}, std::vector<double>(6 * mesh.element_count())};
  r.energies = add_internal_forces(block, u, r.f, r.stress.data());
  return r;
}

double largest(const NodalVectors& v) {
  double m = 0.0;
  for (int c = 0; c < 3; ++c)
    for (const double x : v.component(c)) m = std::max(m, std::abs(x));
  return m;
}

NodalVectors smooth_field(const mesh::Mesh& mesh, double scale) {
  NodalVectors u(mesh.node_count());
  for (std::size_t i = 0; i < mesh.node_count(); ++i) {
    const double x = mesh.x_ref.x[i] * 1e3, y = mesh.x_ref.y[i] * 1e3, z = mesh.x_ref.z[i] * 1e3;
    u.x[i] = scale * (0.3 * x - 0.1 * y * y + 0.05 * x * z);
    u.y[i] = scale * (0.2 * std::sin(x) + 0.15 * z);
    u.z[i] = scale * (-0.25 * z + 0.1 * x * y);
  }
  return u;
}

// u = (R - I) X for a rotation of 70 degrees about an oblique axis: no strain, no
// force, no stress, for every formulation, elastic or plastic.
TEST(LawKernels, RigidRotationMakesNoForceAndNoStress) {
  const double c = std::cos(1.2), s = std::sin(1.2);
  const double axis[3] = {0.48, 0.6, 0.64};
  double r[9];
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) r[3 * i + j] = (i == j ? c : 0.0) + (1 - c) * axis[i] * axis[j];
  r[1] -= s * axis[2], r[2] += s * axis[1], r[3] += s * axis[2], r[5] -= s * axis[0], r[6] -= s * axis[1],
      r[7] += s * axis[0];
  for (const Variant& v : all_variants) {
    const mesh::Mesh mesh = distorted_box(v.formulation);
    NodalVectors u(mesh.node_count());
    for (std::size_t i = 0; i < mesh.node_count(); ++i) {
      const double x[3] = {mesh.x_ref.x[i], mesh.x_ref.y[i], mesh.x_ref.z[i]};
      u.x[i] = r[0] * x[0] + r[1] * x[1] + r[2] * x[2] - x[0];
      u.y[i] = r[3] * x[0] + r[4] * x[1] + r[5] * x[2] - x[1];
      u.z[i] = r[6] * x[0] + r[7] * x[1] + r[8] * x[2] - x[2];
    }
    for (const bool plastic : {false, true}) {
      const ElementBlock block = block_of(mesh, v, law(true, plastic));
      const Result result = forces(block, mesh, u);
      const double scale = copper.mu * 1e-6;  // G h^2: the force of a unit strain, N
      EXPECT_LT(largest(result.f), 1e-9 * scale) << v.name << plastic;
      for (const double sigma : result.stress) EXPECT_LT(std::abs(sigma), 1e-9 * copper.mu);
      EXPECT_LT(std::abs(result.energies.strain + result.energies.hourglass), 1e-12 * copper.mu * 1.2e-8);
    }
  }
}

// Hyperelastic: f_i = dW/du_i, checked by central differences of the block's energy
// (strain plus hourglass) at 5 % strain, F-bar and hourglass included. Not the
// assumed-strain control: its rate form on the turning element axes has no potential.
TEST(LawKernels, ForcesAreTheDerivativeOfTheEnergy) {
  for (const Variant& v : all_variants) {
    if (v.hourglass.model == input::HourglassModel::assumed_strain && v.formulation == Formulation::hex8r)
      continue;
    for (const bool f_bar : {true, false}) {
      if (!f_bar && v.formulation != Formulation::hex8) continue;
      const mesh::Mesh mesh = distorted_box(v.formulation);
      const ElementBlock block = block_of(mesh, v, law(true, false, f_bar));
      NodalVectors u = smooth_field(mesh, 5e-5);
      std::mt19937_64 rng(7);
      std::uniform_real_distribution<double> unit(-1.0, 1.0);
      for (int c = 0; c < 3; ++c)
        for (double& x : u.component(c)) x += 2e-5 * unit(rng);  // hourglass modes too
      const Result at = forces(block, mesh, u);
      const double delta = 1e-10;
      for (const std::size_t node : {std::size_t(0), mesh.node_count() / 2, mesh.node_count() - 1})
        for (int c = 0; c < 3; ++c) {
          NodalVectors plus = u, minus = u;
          plus.component(c)[node] += delta;
          minus.component(c)[node] -= delta;
          const ElementEnergies ep = forces(block, mesh, plus).energies,
                                em = forces(block, mesh, minus).energies;
          const double derivative = ((ep.strain + ep.hourglass) - (em.strain + em.hourglass)) / (2.0 * delta);
          EXPECT_NEAR(derivative, at.f.component(c)[node], 1e-5 * largest(at.f))
              << v.name << " f_bar " << f_bar << " node " << node << " component " << c;
        }
    }
  }
}

// At a strain of 1e-7 the finite kernels give the linear ones' forces (hex8: the
// plain 2 x 2 x 2 rule; F-bar changes the volumetric response).
TEST(LawKernels, TinyStrainsGiveTheLinearKernelsForces) {
  for (const Variant& v : all_variants) {
    const mesh::Mesh mesh = distorted_box(v.formulation);
    const NodalVectors u = smooth_field(mesh, 1e-10);
    const Result linear = forces(block_of(mesh, v, material::MaterialLaw{}), mesh, u);
    const Result finite = forces(block_of(mesh, v, law(true, false, false)), mesh, u);
    const double scale = largest(linear.f);
    for (int c = 0; c < 3; ++c)
      for (std::size_t i = 0; i < mesh.node_count(); ++i)
        EXPECT_NEAR(finite.f.component(c)[i], linear.f.component(c)[i], 1e-5 * scale) << v.name;
  }
}

// Small strain below yield: the plastic law's loop gives the linear kernels' forces
// and stresses to round-off.
TEST(LawKernels, ElasticStatesOfThePlasticLawEqualTheLinearKernels) {
  for (const Variant& v : all_variants) {
    const mesh::Mesh mesh = distorted_box(v.formulation);
    const NodalVectors u = smooth_field(mesh, 1e-7);  // strains about 3e-4: below yield (1.2e-3 here)
    const Result linear = forces(block_of(mesh, v, material::MaterialLaw{}), mesh, u);
    const ElementBlock plastic_block = block_of(mesh, v, law(false, true));
    const Result plastic = forces(plastic_block, mesh, u);
    const double scale = largest(linear.f);
    for (int c = 0; c < 3; ++c)
      for (std::size_t i = 0; i < mesh.node_count(); ++i)
        EXPECT_NEAR(plastic.f.component(c)[i], linear.f.component(c)[i], 1e-12 * scale);
    for (std::size_t k = 0; k < linear.stress.size(); ++k)
      EXPECT_NEAR(plastic.stress[k], linear.stress[k], 1e-12 * copper.mu);
    for (const double eps : plastic_block.material_state.plastic_strain) EXPECT_EQ(eps, 0.0);
    EXPECT_NEAR(plastic.energies.strain, linear.energies.strain, 1e-10 * linear.energies.strain);
  }
}

// A pass reads the committed states and writes the others: the same step computed
// twice gives the same bits; after a commit the next pass starts from the new states.
TEST(LawKernels, APassCanBeRepeatedAndCommitMovesOn) {
  for (const Variant& v : all_variants) {
    if (v.formulation != Formulation::hex8r) continue;
    const mesh::Mesh mesh = distorted_box(Formulation::hex8r);
    const ElementBlock block = block_of(mesh, v, law(true, true));
    const NodalVectors u = smooth_field(mesh, 2e-4);  // about 6 % strain: plastic
    const Result first = forces(block, mesh, u), again = forces(block, mesh, u);
    for (int c = 0; c < 3; ++c) EXPECT_EQ(first.f.component(c), again.f.component(c));
    const double eps = *std::max_element(block.material_state.plastic_strain.begin(),
                                         block.material_state.plastic_strain.end());
    EXPECT_GT(eps, 0.01);
    EXPECT_GT(first.energies.plastic, 0.0);
    commit_material_state(block);
    const Result after = forces(block, mesh, u);  // the same u from the committed plastic state: no new flow
    EXPECT_NEAR(after.energies.plastic, first.energies.plastic, 1e-9 * first.energies.plastic);
    EXPECT_NEAR(after.energies.hourglass, first.energies.hourglass,
                1e-9 * std::abs(first.energies.hourglass));
  }
}

// Every instruction set this CPU runs against x86-64-v2, plastic and finite.
TEST(LawKernels, EveryInstructionSetAgreesWithTheBaseline) {
  const Isa saved = selected_isa();
  for (const Variant& v : all_variants) {
    const mesh::Mesh mesh = distorted_box(v.formulation);
    const NodalVectors u = smooth_field(mesh, 2e-4);
    select_isa(Isa::x86_64_v2);
    const Result base = forces(block_of(mesh, v, law(true, true)), mesh, u);
    for (const Isa isa : {Isa::x86_64_v3, Isa::x86_64_v4}) {
      if (!isa_available(isa)) continue;
      select_isa(isa);
      const Result other = forces(block_of(mesh, v, law(true, true)), mesh, u);
      const double scale = largest(base.f);
      for (int c = 0; c < 3; ++c)
        for (std::size_t i = 0; i < mesh.node_count(); ++i)
          EXPECT_NEAR(other.f.component(c)[i], base.f.component(c)[i], 1e-12 * scale);
    }
  }
  select_isa(saved);
}

}  // namespace
}  // namespace exdyn::element
