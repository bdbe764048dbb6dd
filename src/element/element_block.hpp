// A block of hexahedra of one formulation and one material (one part), and the
// threaded loop that adds their internal forces: gather -> kernel -> scatter.
// What depends on the formulation (reference data, kernel, lumped mass, stable
// step) comes from its element family (element_family.hpp), chosen once per block;
// the kernels (hex8.hpp, hex8r.hpp, hex20.hpp) are free functions on fixed-size data.
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <vector>

#include "common/nodal_vectors.hpp"
#include "input/options.hpp"
#include "material/elastic.hpp"
#include "material/material_law.hpp"

namespace exdyn::element {

struct ElementEnergies {
  double strain = 0.0;     // internal energy: stored elastic energy plus plastic work, J
  double hourglass = 0.0;  // sum of hourglass spring energies (hex8r), J
  double plastic = 0.0;    // plastic work so far (a part of `strain`), J
  // The energy of the elements that left the model in this pass (ElementStatus::failed),
  // J: see ElementFailure.
  double eroded = 0.0;
  ElementEnergies& operator+=(const ElementEnergies& other) {
    strain += other.strain;
    hourglass += other.hourglass;
    plastic += other.plastic;
    eroded += other.eroded;
    return *this;
  }
};

// An element of a block whose material fails (material/failure.hpp).
enum ElementStatus : std::uint8_t {
  eroded = 0,  // gone: no force, no energy, no stable step or inversion check of its own
  alive = 1,
  failed = 2,  // its damage reached 1 at the last step: this pass books its energy, then eroded
};

// Damage and erosion of a block (docs/theory.md, "Damage and erosion"), per element;
// empty vectors where the material does not fail. The solver's damage pass
// (update_damage) sets them after each step's element pass from the elements' mean
// plastic strain and stress. An element that fails at step n carried its force at n;
// the pass of step n+1 does not scatter it and books the energy that leaves with it,
// E = U^{n+1} + H^{n+1} - dt/2 f^{n+1}.v^{n+1/2} (= U^n + H^n + dt/2 f^n.v^{n+1/2} to the
// order of the step: the energy at the half step, with which the balance closes to
// round-off for a linear element). Its mass stays on its nodes: a node with no element
// left flies on with it, in contact as before.
struct ElementFailure {
  std::vector<std::uint8_t> status;    // ElementStatus
  std::vector<double> damage;          // D, 0 .. 1
  std::vector<double> plastic_strain;  // the mean eps_p at the last damage update
  // What the element pass reads for the failing elements: v^{n+1/2} (set by the solver
  // before the pass), and where a failing block writes its element stresses every step
  // (the damage pass reads them).
  const NodalVectors* velocity = nullptr;
  double* stress = nullptr;
  bool any_not_alive = false;  // some element is failed or eroded (the loops check then)
  // time.erode: the stable step (without the Courant factor, s) below which a live
  // element is too distorted to go on, 0 when the rule is off; the corner passes mark
  // such elements, and inverted ones, here (corner_pack.hpp) and the damage pass fails them.
  double erode_step = 0.0;
  std::vector<std::uint8_t> distorted;
  // What an element marked distorted carried at its last step n, held for the pass of
  // n+1 to book E = U^n + H^n + dt/2 f^n.v^{n+1/2} exactly (held_size values per
  // element: U^n + H^n, NaN while none is held, then f^n node by node): evaluated at
  // u^{n+1}, a crushed element's energy and forces are no measure of what it carried.
  std::vector<double> held;
  static constexpr std::size_t held_size(int nodes) { return 1 + 3 * std::size_t(nodes); }
  std::vector<std::uint32_t> chunk_counts;  // scratch of update_damage
};

// The integration-point states of a block whose law has them (material/j2.hpp), and
// what its element pass leaves beside the forces. A pass reads the committed states
// and writes the other array, so that a step's forces can be computed again with the
// same result; commit_material_state makes the written states the committed ones
// when the solver moves to the next step.
struct MaterialState {
  std::array<std::vector<double>, 2> points;  // per element pack and point, interleaved by lane
  int committed = 0;                          // index of the committed array
  int points_per_element = 0;
  // hex8r with assumed-strain hourglass control under a law: per element pack, the
  // hourglass forces, amplitudes and work (hex8r::hourglass_state_size values,
  // interleaved by lane), committed and written as the points.
  std::array<std::vector<double>, 2> hourglass;
  std::vector<double> plastic_strain;  // per element: the last pass's mean equivalent plastic strain
  double dt = 0.0;                     // the step of the pass's strain increment, s (rate laws)
};

// Elements per chunk of the parallel element loop (even: an element pair is never split).
inline constexpr std::uint32_t element_chunk = 512;

struct ElementBlock;
struct ElementFamily;

// The stable step of a block's elements (current_time_step) and the element (global
// index) that sets it.
struct CurrentStep {
  double dt = 0.0;
  std::uint32_t element = 0;
};

// An element whose current configuration x = x_ref + u is inverted.
struct InvertedElement {
  bool found = false;
  std::uint32_t element = 0;  // global element index
  int corner = 0;             // local node (VTK order) where det J <= 0
  double det_jacobian = 0.0;  // det of the corner's edge vectors there, m^3
  // When none is inverted: no element can invert before some node has moved by this
  // much from the configuration checked, m (a lower bound, see below).
  double safety_radius = 0.0;
};

// A pass over the corners of a block's elements: its stable step and inversion check.
struct CornerChecks {
  CurrentStep step;
  InvertedElement inverted;
};

// What the next element pass of a block checks at its corners as well
// (ElementBlock::corners_in_pass), on x = x_ref + u: its stable step, its inversion
// check, or both (corner_checks.hpp). Each chunk's result goes to
// ElementBlock::chunk_checks.
struct CornerRequest {
  const NodalVectors* x_ref = nullptr;  // null: no checks
  bool step = false;
  bool inversion = false;
};

// What a rank's part of a block, built alone (ranks/rank_setup.cpp), takes from the
// whole block, so that its elements run the kernels and share the data they do there:
// whether every element of the whole block is a parallelepiped (and, hex8, has its
// edges along x, y, z), and a 20-node block's groups (ElementBlock::group_points).
// The defaults leave a block to its own elements.
struct WholeBlock {
  bool parallelepipeds = true, axis_aligned = true;
  std::vector<std::array<double, 60>> group_points;
};

// Adds the internal forces of the block's elements [begin, end) (local indices):
// the family's loop for the block's reference layout, chosen once when the block is built.
using ElementLoopFn = ElementEnergies (*)(const ElementBlock& block, std::uint32_t begin, std::uint32_t end,
                                          const NodalVectors& u, NodalVectors& f_int, double* stress);

struct ElementBlock {
  input::Formulation formulation = input::Formulation::hex8;
  const ElementFamily* family = nullptr;  // what the formulation's elements are and do
  int nodes_per_element = 8;              // 8 or 20
  material::ElasticConstants material;
  // The law beyond small-strain linear elasticity (plasticity, finite strain); the
  // linear small-strain kernels run where law.linear_small().
  material::MaterialLaw law;
  mutable MaterialState material_state;
  // The family's stable step over the corner-based one, L_e / c1 with L_e from the 8
  // corners, on the reference mesh (1 for 8-node elements): current_time_step scales by it.
  double step_scale = 1.0;
  input::HourglassControl hourglass;            // hex8r only
  mutable ElementFailure failure;               // law.failure.active() only
  std::uint32_t first_element = 0;              // global index of the block's first element
  std::uint32_t count = 0;                      // number of elements
  const std::uint32_t* connectivity = nullptr;  // nodes_per_element ids per element (VTK order)
  // Reference-configuration data precomputed once per element, and data shared by
  // the block's elements (layouts private to the family: e.g. inverse Jacobians and
  // weights at the Gauss points; shape function tables; element matrices).
  std::vector<double> reference;
  std::vector<double> shared;
  std::vector<std::uint32_t> reference_index;  // per element, where the family keeps its data there
  // 20-node blocks of parallelepipeds (hex20_family.cpp): the first element of each
  // group of equal Jacobians, whose reference data and stable step the group shares:
  // its 20 nodes' x, then y, then z, m. A rank's part of a block built alone has the
  // whole block's (WholeBlock), so it shares its matrices and steps.
  std::vector<std::array<double, 60>> group_points;
  WholeBlock whole;  // what make_element_block was given; prepare reads it
  // Doubles of `reference` per element (its layout interleaves packs of elements,
  // element_loop.hpp, but element e's data starts at e * this for e a multiple of the
  // pack width; slice_block relies on it).
  std::size_t reference_per_element = 0;
  ElementLoopFn loop = nullptr;  // the kernel loop of the layout in use
  // The loop runs the corner checks on the corners it gathers when asked
  // (corner_request): the 8-node loops of a material law, whose finite-strain parts
  // need the step of the current configuration every step.
  bool corners_in_pass = false;
  mutable CornerRequest corner_request;
  bool constant_jacobian = false;  // every element is a parallelepiped (a faster kernel)
  bool axis_aligned = false;       // hex8: and has its edges along x, y, z (diagonal dxi/dx: faster still)
  // Per pack of the packed loops (hex8_family.cpp, packs of 2, 4 or 8 elements): 1 when
  // the pack is a run along a node row, whose node k of lane l is node k of lane 0 plus
  // l and whose edges 0-1, 3-2, 4-5, 7-6 join consecutive nodes (the x-rows of a
  // structured box), so that its gather and scatter are whole-vector loads and stores.
  std::vector<std::uint8_t> row_pack;
  // The parallel schedule (docs/performance.md): the elements in chunks of
  // element_chunk consecutive ones, grouped in colours whose chunks share no node,
  // so that the chunks of a colour scatter their forces at once without a race and
  // every node adds its elements' forces in the same order on any number of threads.
  std::vector<std::uint32_t> chunk_begin;               // chunk c is [chunk_begin[c], chunk_begin[c + 1])
  std::vector<std::vector<std::uint32_t>> colours;      // the chunks of each colour, ascending
  mutable std::vector<ElementEnergies> chunk_energies;  // scratch: the energies of each chunk
  // Scratch of the threaded passes over the corners (corner_checks.hpp): each chunk's
  // result, reduced in chunk order.
  mutable std::vector<CornerChecks> chunk_checks;
};

// Builds a block and precomputes its reference data from the reference
// coordinates. `connectivity` must outlive the block. `whole`: the whole block's layout
// and groups where this block is a rank's part of it.
ElementBlock make_element_block(input::Formulation formulation, const material::ElasticConstants& material,
                                input::HourglassControl hourglass, std::uint32_t first_element,
                                std::uint32_t count, const std::uint32_t* connectivity,
                                const NodalVectors& x_ref, const material::MaterialLaw& law = {},
                                WholeBlock whole = {});

// The layout elements [0, count) of a formulation allow alone (WholeBlock's flags): a
// rank's part of a block takes the flags of all parts together.
WholeBlock element_layout(input::Formulation formulation, std::uint32_t count,
                          const std::uint32_t* connectivity, const NodalVectors& x_ref);

// The elements [0, count) of a 20-node block that start its groups of equal Jacobians
// (ElementBlock::group_points), ascending: none for 8-node formulations or elements
// that are not all parallelepipeds, and 65 when there are more than 64 (too many for
// the shared-matrix layout). A rank's part of a block gives the candidates: the whole
// block's groups start at those of the ranks' starts that start one among them all.
std::vector<std::uint32_t> jacobian_group_starts(input::Formulation formulation, std::uint32_t count,
                                                 const std::uint32_t* connectivity,
                                                 const NodalVectors& x_ref);

// After the element pass of a step (stresses written to block.failure.stress): each
// live element's damage from the increment of its mean plastic strain over dt (s) and
// its mean stress; one that reaches 1 fails (ElementStatus::failed), and those that
// failed at the step before become eroded. Returns how many failed at this step.
std::uint32_t update_damage(const ElementBlock& block, double dt);

// Makes the states the last element pass wrote the committed ones (the solver, once
// per step before its element pass; nothing for a block without states), and undoes
// that (going back one step).
void commit_material_state(const ElementBlock& block);
// The step over which the next element pass's strain increment happens, s.
void set_material_time_step(const ElementBlock& block, double dt);

// f_int += internal forces (N) of the block's elements for the displacement u
// (small strain, reference configuration). Writes each element's volume-averaged
// Cauchy stress (xx yy zz xy yz xz, Pa) to stress[6 * global_element ...] and
// returns the block's energies. Runs the colours one after the other and the chunks
// of a colour on the threads; the result does not depend on the number of threads.
ElementEnergies add_internal_forces(const ElementBlock& block, const NodalVectors& u, NodalVectors& f_int,
                                    double* stress);

// The same as OpenMP tasks of the team that meets it: a task per chunk, a colour's
// tasks in a taskgroup, the colours one after the other. Call from one thread of a
// parallel region (a `single`): the team takes the chunks, and can run other tasks
// beside them (the solver's contact pass). Each node gets the same additions in the
// same order, and the energies are added in chunk order: the same bits as above.
ElementEnergies add_internal_forces_as_tasks(const ElementBlock& block, const NodalVectors& u,
                                             NodalVectors& f_int, double* stress);

// The chunks `chunks` (ascending) of a prepared block, as a block of their own for
// one MPI rank (docs/parallel.md): the same reference data, kernels, packs and
// colours, so each of its elements adds the same forces in the same order as in the
// whole block. `connectivity` holds the chunks' elements' nodes (the rank's node
// numbers, which must keep the global order, so that row packs stay rows) and must
// outlive the block; `first_element` is the block's first element in the rank's
// numbering. Each colour keeps its index (possibly with no chunk).
ElementBlock slice_block(const ElementBlock& block, const std::vector<std::uint32_t>& chunks,
                         const std::uint32_t* connectivity, std::uint32_t first_element);

// f_int += the forces of the block's chunks `chunks` (local indices, all of one
// colour: they share no node), on the threads; each chunk's energies go to
// block.chunk_energies. The pieces of add_internal_forces, for a caller that
// interleaves the colours with other work (solver/simulation.cpp on many ranks).
void add_chunk_forces(const ElementBlock& block, const std::vector<std::uint32_t>& chunks,
                      const NodalVectors& u, NodalVectors& f_int, double* stress);

// The index of the chunk that starts at element `begin` (local).
inline std::size_t chunk_index(const ElementBlock& block, std::uint32_t begin) {
  const auto after = std::upper_bound(block.chunk_begin.begin(), block.chunk_begin.end(), begin);
  return std::size_t(after - block.chunk_begin.begin()) - 1;
}

// The sum of block.chunk_energies in chunk order.
ElementEnergies chunk_energy_total(const ElementBlock& block);

// Smallest stable time step of the block, s, by the family's rule (docs/theory.md):
// 8-node elements min over elements of L_e / c1, with L_e the characteristic length
// (element volume / largest face area) and c1 = sqrt((lambda + 2 mu) / rho); 20-node
// elements 2 / omega_max of each element's own M^-1 K. The caller multiplies by the
// Courant number.
double critical_time_step(const ElementBlock& block, const NodalVectors& x_ref);

// Lumped mass, kg, added to m (one entry per node): 8-node elements the row sums
// rho integral of N_I dV; 20-node elements HRZ (docs/theory.md).
void add_lumped_mass(const ElementBlock& block, const NodalVectors& x_ref, std::vector<double>& mass);

// add_internal_forces for the block's elements [element_begin, element_end)
// (local indices), e.g. one thread's share of a coloured block.
ElementEnergies add_internal_forces(const ElementBlock& block, std::uint32_t element_begin,
                                    std::uint32_t element_end, const NodalVectors& u, NodalVectors& f_int,
                                    double* stress);

// True when every element of the block is a parallelepiped, so that the block
// runs the constant-Jacobian kernels (hex8::parallelepiped_internal_forces,
// hex8r::parallelepiped_internal_forces, the element matrices of hex20_family.cpp).
bool uses_parallelepiped_kernel(const ElementBlock& block);

}  // namespace exdyn::element
