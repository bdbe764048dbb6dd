// Element blocks: the family's reference data, the threaded gather -> kernel ->
// scatter loop over coloured chunks, lumped mass, the stable time step and the
// inversion guard (docs/theory.md, "Element library").
#include "element/element_block.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "common/errors.hpp"
#include "common/parallel.hpp"
#include "common/simd_pack.hpp"
#include "element/corner_checks.hpp"
#include "element/element_family.hpp"
#include "element/element_isa.hpp"
#include "element/element_loop.hpp"
#include "element/hex8.hpp"
#include "element/hex8_constitutive.hpp"
#include "element/hex8_parallelepiped.hpp"

namespace exdyn::element {

void throw_inverted(std::uint32_t global_element, double det_jacobian) {
  throw InputError("element " + std::to_string(global_element) +
                   ": the reference hexahedron is inverted or degenerate (smallest det J = " +
                   std::to_string(det_jacobian) + "); check the node order (VTK hexahedron)");
}

namespace {

// Chunks of consecutive elements, coloured greedily in chunk order: a chunk takes
// the lowest colour that no earlier chunk sharing one of its nodes has (a bit mask
// of colours per node; structured blocks and meshes in Hilbert order need a few).
// The masks cover 64 colours from `base`; a chunk that finds them all taken (a mesh in
// a scattered order, every chunk touching every other) moves the window past them,
// with the masks cleared: an earlier chunk's colour is below the new base, so it
// cannot clash with a colour chosen from there on.
void build_schedule(ElementBlock& block, std::size_t node_count) {
  const std::uint32_t chunks = (block.count + element_chunk - 1) / element_chunk;
  block.chunk_begin.resize(chunks + 1);
  for (std::uint32_t c = 0; c <= chunks; ++c) block.chunk_begin[c] = std::min(c * element_chunk, block.count);
  std::vector<std::uint64_t> colours_at_node(node_count, 0);
  std::size_t base = 0;
  for (std::uint32_t c = 0; c < chunks; ++c) {
    const std::size_t nodes = static_cast<std::size_t>(block.nodes_per_element);
    const std::uint32_t* begin = block.connectivity + nodes * std::size_t(block.chunk_begin[c]);
    const std::uint32_t* end = block.connectivity + nodes * std::size_t(block.chunk_begin[c + 1]);
    std::uint64_t taken = 0;
    for (const std::uint32_t* node = begin; node != end; ++node) taken |= colours_at_node[*node];
    if (taken == ~std::uint64_t{0}) {
      base += 64;
      std::fill(colours_at_node.begin(), colours_at_node.end(), std::uint64_t{0});
      taken = 0;
    }
    int colour = 0;
    while (taken & (std::uint64_t{1} << colour)) ++colour;
    for (const std::uint32_t* node = begin; node != end; ++node)
      colours_at_node[*node] |= std::uint64_t{1} << colour;
    const std::size_t index = base + std::size_t(colour);
    if (block.colours.size() <= index) block.colours.resize(index + 1);
    block.colours[index].push_back(c);
  }
  block.chunk_energies.assign(chunks, ElementEnergies{});
  block.chunk_checks.assign(chunks, CornerChecks{});
}

// The initial states of every point (material/j2.hpp, initial_state), interleaved by
// packs of the ISA's lanes as the law loops read them: value k of point g of element
// e (pack p, lane l) at ((p G + g) S + k) L + l.
void allocate_material_state(ElementBlock& block) {
  MaterialState& state = block.material_state;
  state.plastic_strain.assign(block.count, 0.0);
  const std::size_t lanes = std::size_t(lanes_for(selected_isa()));
  const std::size_t packs = (block.count + lanes - 1) / lanes;
  if (block.formulation == input::Formulation::hex8r && !block.law.linear_small() &&
      block.hourglass.model == input::HourglassModel::assumed_strain) {
    const std::vector<double> zero(packs * lanes * std::size_t(hex8r::hourglass_state_size), 0.0);
    state.hourglass = {zero, zero};
  }
  if (block.law.failure.active()) {
    block.failure.status.assign(block.count, ElementStatus::alive);
    block.failure.damage.assign(block.count, 0.0);
    block.failure.plastic_strain.assign(block.count, 0.0);
  }
  const int size = block.law.state_size();
  if (size == 0) return;
  state.points_per_element = block.formulation == input::Formulation::hex8r   ? 1
                             : block.formulation == input::Formulation::hex20 ? 27
                                                                              : 8;
  const std::size_t per_pack = lanes * std::size_t(state.points_per_element) * std::size_t(size);
  double initial[material::j2_state_size];
  material::initial_state(block.law.finite, initial);
  std::vector<double> values(packs * per_pack);
  for (std::size_t k = 0; k < values.size(); ++k) values[k] = initial[(k / lanes) % std::size_t(size)];
  state.points = {values, values};
  state.committed = 0;
}

}  // namespace

ElementBlock make_element_block(input::Formulation formulation, const material::ElasticConstants& material,
                                input::HourglassControl hourglass, std::uint32_t first_element,
                                std::uint32_t count, const std::uint32_t* connectivity,
                                const NodalVectors& x_ref, const material::MaterialLaw& law,
                                WholeBlock whole) {
  ElementBlock block;
  block.formulation = formulation;
  block.family = &element_family(formulation);
  block.nodes_per_element = block.family->nodes_per_element;
  block.material = material;
  block.law = law;
  block.hourglass = hourglass;
  block.first_element = first_element;
  block.count = count;
  block.connectivity = connectivity;
  block.whole = std::move(whole);
  block.family->prepare(block, x_ref);
  block.whole = {};
  EXDYN_ASSERT(block.loop != nullptr);
  build_schedule(block, x_ref.size());
  allocate_material_state(block);
  if (block.nodes_per_element != 8 && count > 0) {
    NodalVectors zero(x_ref.size());
    const double corner_step = current_time_step(block, x_ref, zero).dt;
    block.step_scale = block.family->critical_time_step(block, x_ref) / corner_step;
  }
  return block;
}

WholeBlock element_layout(input::Formulation formulation, std::uint32_t count,
                          const std::uint32_t* connectivity, const NodalVectors& x_ref) {
  return element_family(formulation).layout(count, connectivity, x_ref);
}

void commit_material_state(const ElementBlock& block) {
  const MaterialState& s = block.material_state;
  if (!s.points[0].empty() || !s.hourglass[0].empty()) block.material_state.committed ^= 1;
}

void set_material_time_step(const ElementBlock& block, double dt) { block.material_state.dt = dt; }

ElementEnergies add_internal_forces(const ElementBlock& block, std::uint32_t element_begin,
                                    std::uint32_t element_end, const NodalVectors& u, NodalVectors& f_int,
                                    double* stress) {
  EXDYN_ASSERT(element_begin <= element_end && element_end <= block.count);
  // A failing block writes its stresses every step: the damage pass reads them.
  return block.loop(block, element_begin, element_end, u, f_int,
                    stress != nullptr ? stress : block.failure.stress);
}

// Each element on its own: on the threads in the block's chunks, each chunk's counts
// kept apart and added in chunk order.
std::uint32_t update_damage(const ElementBlock& block, double dt) {
  ElementFailure& f = block.failure;
  if (f.status.empty()) return 0;
  EXDYN_ASSERT(f.stress != nullptr);
  const material::Failure& law = block.law.failure;
  const std::vector<double>& eps_p = block.material_state.plastic_strain;
  const std::size_t chunks = block.chunk_begin.size() - 1;
  f.chunk_counts.assign(2 * chunks, 0);  // per chunk: failed now, not alive
  parallel_for_static(std::ptrdiff_t(chunks), [&](std::ptrdiff_t k) {
    std::uint32_t failed = 0, not_alive = 0;
    for (std::uint32_t e = block.chunk_begin[std::size_t(k)]; e < block.chunk_begin[std::size_t(k) + 1];
         ++e) {
      if (f.status[e] != ElementStatus::alive) {
        f.status[e] = ElementStatus::eroded;  // a failed element's energy is booked
        ++not_alive;
        continue;
      }
      const double increment = std::max(eps_p[e] - f.plastic_strain[e], 0.0);
      f.plastic_strain[e] = eps_p[e];
      const double* stress = f.stress + 6 * (std::size_t(block.first_element) + e);
      f.damage[e] = std::min(
          law.damage_after(f.damage[e], eps_p[e], increment, dt, material::Failure::triaxiality(stress)),
          1.0);
      const bool distorted = !f.distorted.empty() && f.distorted[e] != 0;
      if (f.damage[e] >= 1.0 || distorted) f.status[e] = ElementStatus::failed, ++failed, ++not_alive;
    }
    f.chunk_counts[2 * std::size_t(k)] = failed;
    f.chunk_counts[2 * std::size_t(k) + 1] = not_alive;
  });
  std::uint32_t failed = 0, not_alive = 0;
  for (std::size_t k = 0; k < chunks; ++k)
    failed += f.chunk_counts[2 * k], not_alive += f.chunk_counts[2 * k + 1];
  f.any_not_alive = not_alive > 0;
  return failed;
}

ElementEnergies add_internal_forces(const ElementBlock& block, const NodalVectors& u, NodalVectors& f_int,
                                    double* stress) {
  EXDYN_ASSERT(block.chunk_energies.size() + 1 == block.chunk_begin.size());
  for (const std::vector<std::uint32_t>& colour : block.colours)
    add_chunk_forces(block, colour, u, f_int, stress);
  return chunk_energy_total(block);  // in chunk order, whatever the threads
}

ElementEnergies add_internal_forces_as_tasks(const ElementBlock& block, const NodalVectors& u,
                                             NodalVectors& f_int, double* stress) {
  EXDYN_ASSERT(block.chunk_energies.size() + 1 == block.chunk_begin.size());
  for (const std::vector<std::uint32_t>& colour : block.colours) {
    // A task per chunk (512 elements, tens of microseconds): two or three chunks a
    // task balanced the plate impact's two threads worse.
#pragma omp taskgroup
    {
      for (const std::uint32_t c : colour) {
#pragma omp task firstprivate(c) shared(block, u, f_int)
        block.chunk_energies[c] =
            add_internal_forces(block, block.chunk_begin[c], block.chunk_begin[c + 1], u, f_int, stress);
      }
    }
  }
  return chunk_energy_total(block);  // in chunk order, whatever the threads
}

ElementBlock slice_block(const ElementBlock& block, const std::vector<std::uint32_t>& chunks,
                         const std::uint32_t* connectivity, std::uint32_t first_element) {
  ElementBlock slice;
  slice.formulation = block.formulation;
  slice.family = block.family;
  slice.nodes_per_element = block.nodes_per_element;
  slice.material = block.material;
  slice.law = block.law;
  slice.failure.stress = block.failure.stress;
  slice.step_scale = block.step_scale;
  slice.hourglass = block.hourglass;
  slice.first_element = first_element;
  slice.connectivity = connectivity;
  slice.shared = block.shared;
  slice.group_points = block.group_points;
  slice.loop = block.loop;
  slice.corners_in_pass = block.corners_in_pass;
  slice.constant_jacobian = block.constant_jacobian;
  slice.axis_aligned = block.axis_aligned;
  slice.reference_per_element = block.reference_per_element;
  // Packs never straddle chunks (element_chunk is a multiple of every pack width).
  const auto lanes = static_cast<std::uint32_t>(lanes_for(selected_isa()));  // as mark_row_packs
  std::vector<std::uint32_t> local_chunk(block.chunk_begin.size(), ~0u);
  slice.chunk_begin.push_back(0);
  for (const std::uint32_t c : chunks) {
    const std::uint32_t begin = block.chunk_begin[c], end = block.chunk_begin[c + 1];
    const bool last = c + 2 == block.chunk_begin.size();
    local_chunk[c] = std::uint32_t(slice.chunk_begin.size() - 1);
    slice.count += end - begin;
    slice.chunk_begin.push_back(slice.count);
    const std::size_t stride = block.reference_per_element;
    if (stride > 0)
      slice.reference.insert(
          slice.reference.end(), block.reference.begin() + std::ptrdiff_t(stride * begin),
          last ? block.reference.end() : block.reference.begin() + std::ptrdiff_t(stride * end));
    if (!block.reference_index.empty())
      slice.reference_index.insert(slice.reference_index.end(), block.reference_index.begin() + begin,
                                   block.reference_index.begin() + end);
    if (!block.row_pack.empty())
      slice.row_pack.insert(slice.row_pack.end(), block.row_pack.begin() + begin / lanes,
                            last ? block.row_pack.end() : block.row_pack.begin() + end / lanes);
  }
  slice.colours.resize(block.colours.size());
  for (std::size_t k = 0; k < block.colours.size(); ++k)
    for (const std::uint32_t c : block.colours[k])
      if (local_chunk[c] != ~0u) slice.colours[k].push_back(local_chunk[c]);
  slice.chunk_energies.assign(chunks.size(), ElementEnergies{});
  slice.chunk_checks.assign(chunks.size(), CornerChecks{});
  allocate_material_state(slice);  // every point in its initial state, as the whole block's
  return slice;
}

void add_chunk_forces(const ElementBlock& block, const std::vector<std::uint32_t>& chunks,
                      const NodalVectors& u, NodalVectors& f_int, double* stress) {
  const auto count = static_cast<std::ptrdiff_t>(chunks.size());
  // One chunk is serial work: no parallel region (whose barrier costs milliseconds
  // when another process holds the other core). Static: thread t takes the t-th run
  // of the chunks every step, so the nodes it adds forces to are the ones its nodal
  // passes (for_each_chunk, static too) update, and stay in its core's cache; with
  // dynamic chunks half of them came from the other core's. Static ran the one-plate
  // reference 13-18 % faster on two threads (docs/performance.md, "Two threads on the
  // plate impact: the ceiling").
  parallel_for_static(count, [&](std::ptrdiff_t k) {
    const std::uint32_t c = chunks[static_cast<std::size_t>(k)];
    block.chunk_energies[c] =
        add_internal_forces(block, block.chunk_begin[c], block.chunk_begin[c + 1], u, f_int, stress);
  });
}

ElementEnergies chunk_energy_total(const ElementBlock& block) {
  ElementEnergies total;
  for (const ElementEnergies& e : block.chunk_energies) {
    total += e;
  }
  return total;
}

bool uses_parallelepiped_kernel(const ElementBlock& block) { return block.constant_jacobian; }

double critical_time_step(const ElementBlock& block, const NodalVectors& x_ref) {
  return block.family->critical_time_step(block, x_ref);
}

void add_lumped_mass(const ElementBlock& block, const NodalVectors& x_ref, std::vector<double>& mass) {
  EXDYN_ASSERT(mass.size() == x_ref.size());
  block.family->add_lumped_mass(block, x_ref, mass);
}

}  // namespace exdyn::element
