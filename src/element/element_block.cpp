// Element blocks: reference data, the gather -> kernel -> scatter loop, lumped
// mass and the stable time step (docs/theory.md, "Element library").
#include "element/element_block.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "common/errors.hpp"
#include "element/hex8.hpp"
#include "element/hex8r.hpp"

namespace exdyn::element {
namespace {

// block.reference = [layout, 0, element data...]; the two header entries keep
// the element data 16-byte aligned. All layouts but the general hex8 one store
// element pairs (2p, 2p+1) interleaved value by value,
// [.., value k of 2p, value k of 2p+1, ..], for the kernels that run on two
// elements at once (Pack2); an odd last element is paired with zeros. (The
// general hex8 kernel vectorises over its 8 Gauss points instead.)
enum class ReferenceLayout { hex8_general = 1, hex8_parallelepiped = 2, hex8r = 3, hex8r_parallelepiped = 4 };
constexpr std::size_t header_size = 2;

ReferenceLayout layout_of(const ElementBlock& block) {
  EXDYN_ASSERT(block.reference.size() >= header_size);
  return static_cast<ReferenceLayout>(static_cast<int>(block.reference[0]));
}

bool is_paired(ReferenceLayout layout) { return layout != ReferenceLayout::hex8_general; }

// Doubles of reference data per element.
std::size_t stride_of(ReferenceLayout layout) {
  switch (layout) {
    case ReferenceLayout::hex8_general:
      return hex8::reference_size;
    case ReferenceLayout::hex8_parallelepiped:
      return hex8::parallelepiped_reference_size;
    case ReferenceLayout::hex8r:
      return hex8r::reference_size;
    case ReferenceLayout::hex8r_parallelepiped:
      return hex8r::parallelepiped_reference_size;
  }
  return 0;
}

ElementVectors gather(const NodalVectors& v, const std::uint32_t* nodes) {
  ElementVectors local{ElementVectors::Uninitialized{}};  // every entry written below
  const double* x = v.x.data();
  const double* y = v.y.data();
  const double* z = v.z.data();
  for (int k = 0; k < 8; ++k) {
    const std::uint32_t n = nodes[k];
    local.x[k] = x[n];
    local.y[k] = y[n];
    local.z[k] = z[n];
  }
  return local;
}

void scatter_add(const ElementVectors& local, const std::uint32_t* nodes, NodalVectors& v) {
  double* x = v.x.data();
  double* y = v.y.data();
  double* z = v.z.data();
  for (int k = 0; k < 8; ++k) {
    const std::uint32_t n = nodes[k];
    x[n] += local.x[k];
    y[n] += local.y[k];
    z[n] += local.z[k];
  }
}

// The element loop, one instantiation per kernel: kernel(reference, u, f, stress)
// returns the element's energies.
template <class Kernel>
ElementEnergies element_loop(const ElementBlock& block, std::uint32_t begin, std::uint32_t end,
                             std::size_t stride, const NodalVectors& u, NodalVectors& f_int, double* stress,
                             Kernel kernel) {
  ElementEnergies total;
  const double* reference = block.reference.data() + header_size;
  for (std::uint32_t e = begin; e < end; ++e) {
    const std::uint32_t* nodes = block.connectivity + 8 * static_cast<std::size_t>(e);
    const ElementVectors u_local = gather(u, nodes);
    ElementVectors f_local{ElementVectors::Uninitialized{}};  // the kernel writes every entry
    material::SymTensor element_stress;
    const ElementEnergies energies = kernel(reference + stride * e, u_local, f_local, element_stress);
    scatter_add(f_local, nodes, f_int);
    total.strain += energies.strain;
    total.hourglass += energies.hourglass;
    if (stress != nullptr) {
      double* out = stress + 6 * (static_cast<std::size_t>(block.first_element) + e);
      for (int k = 0; k < 6; ++k) out[k] = element_stress[k];
    }
  }
  return total;
}

BasicElementVectors<Pack2> gather_pair(const NodalVectors& v, const std::uint32_t* nodes0,
                                       const std::uint32_t* nodes1) {
  BasicElementVectors<Pack2> local{BasicElementVectors<Pack2>::Uninitialized{}};  // every entry written below
  const double* x = v.x.data();
  const double* y = v.y.data();
  const double* z = v.z.data();
  for (int k = 0; k < 8; ++k) {
    const std::uint32_t n0 = nodes0[k], n1 = nodes1[k];
    local.x[k] = Pack2{x[n0], x[n1]};
    local.y[k] = Pack2{y[n0], y[n1]};
    local.z[k] = Pack2{z[n0], z[n1]};
  }
  return local;
}

void scatter_add_lane(const BasicElementVectors<Pack2>& local, int lane, const std::uint32_t* nodes,
                      NodalVectors& v) {
  double* x = v.x.data();
  double* y = v.y.data();
  double* z = v.z.data();
  for (int k = 0; k < 8; ++k) {
    const std::uint32_t n = nodes[k];
    x[n] += local.x[k][lane];
    y[n] += local.y[k][lane];
    z[n] += local.z[k][lane];
  }
}

// The element loop over pairs: kernel(reference, u, f, stress) on two elements
// at once returns their energies (strain, hourglass) as Pack2. Lanes outside
// [begin, end) are computed but neither scattered nor counted.
template <class Kernel>
ElementEnergies element_pair_loop(const ElementBlock& block, std::uint32_t begin, std::uint32_t end,
                                  std::size_t stride, const NodalVectors& u, NodalVectors& f_int,
                                  double* stress, Kernel kernel) {
  ElementEnergies total;
  if (begin >= end) return total;
  const double* reference = block.reference.data() + header_size;
  for (std::uint32_t pair = begin / 2; pair <= (end - 1) / 2; ++pair) {
    const std::uint32_t element[2] = {2 * pair, 2 * pair + 1};
    const std::uint32_t* nodes[2] = {block.connectivity + 8 * static_cast<std::size_t>(element[0]),
                                     block.connectivity + 8 * static_cast<std::size_t>(element[1])};
    if (element[1] >= block.count) nodes[1] = nodes[0];  // the zero-padded partner of an odd last element
    const BasicElementVectors<Pack2> u_local = gather_pair(u, nodes[0], nodes[1]);
    BasicElementVectors<Pack2> f_local{
        BasicElementVectors<Pack2>::Uninitialized{}};  // the kernel writes every entry
    std::array<Pack2, 6> element_stress;
    const std::array<Pack2, 2> energies =
        kernel(reference + 2 * stride * pair, u_local, f_local, element_stress);
    for (int lane = 0; lane < 2; ++lane) {
      if (element[lane] < begin || element[lane] >= end) continue;
      scatter_add_lane(f_local, lane, nodes[lane], f_int);
      total.strain += energies[0][lane];
      total.hourglass += energies[1][lane];
      if (stress != nullptr) {
        double* out = stress + 6 * (static_cast<std::size_t>(block.first_element) + element[lane]);
        for (int k = 0; k < 6; ++k) out[k] = element_stress[k][lane];
      }
    }
  }
  return total;
}

[[noreturn]] void throw_inverted(std::uint32_t global_element, double det_jacobian) {
  throw InputError("element " + std::to_string(global_element) +
                   ": the reference hexahedron is inverted or degenerate (smallest det J = " +
                   std::to_string(det_jacobian) + "); check the node order (VTK hexahedron)");
}

// Chunks of consecutive elements, coloured greedily in chunk order: a chunk takes
// the lowest colour that no earlier chunk sharing one of its nodes has (a bit mask
// of colours per node; structured blocks need two or three colours).
void build_schedule(ElementBlock& block, std::size_t node_count) {
  const std::uint32_t chunks = (block.count + element_chunk - 1) / element_chunk;
  block.chunk_begin.resize(chunks + 1);
  for (std::uint32_t c = 0; c <= chunks; ++c) block.chunk_begin[c] = std::min(c * element_chunk, block.count);
  std::vector<std::uint64_t> colours_at_node(node_count, 0);
  for (std::uint32_t c = 0; c < chunks; ++c) {
    const std::uint32_t* begin = block.connectivity + 8 * std::size_t(block.chunk_begin[c]);
    const std::uint32_t* end = block.connectivity + 8 * std::size_t(block.chunk_begin[c + 1]);
    std::uint64_t taken = 0;
    for (const std::uint32_t* node = begin; node != end; ++node) taken |= colours_at_node[*node];
    if (taken == ~std::uint64_t{0}) throw std::logic_error("element colouring: more than 64 colours");
    int colour = 0;
    while (taken & (std::uint64_t{1} << colour)) ++colour;
    for (const std::uint32_t* node = begin; node != end; ++node)
      colours_at_node[*node] |= std::uint64_t{1} << colour;
    if (block.colours.size() <= std::size_t(colour)) block.colours.resize(std::size_t(colour) + 1);
    block.colours[std::size_t(colour)].push_back(c);
  }
  block.chunk_energies.assign(chunks, ElementEnergies{});
}

}  // namespace

ElementBlock make_element_block(input::Formulation formulation, const material::ElasticConstants& material,
                                double hourglass_coefficient, std::uint32_t first_element,
                                std::uint32_t count, const std::uint32_t* connectivity,
                                const NodalVectors& x_ref) {
  ElementBlock block;
  block.formulation = formulation;
  block.material = material;
  block.hourglass_coefficient = hourglass_coefficient;
  block.first_element = first_element;
  block.count = count;
  block.connectivity = connectivity;

  // The constant-Jacobian kernels when every element is a parallelepiped (the
  // structured boxes of this program), the general ones otherwise.
  bool all_parallelepipeds = true;
  for (std::uint32_t e = 0; e < count && all_parallelepipeds; ++e)
    all_parallelepipeds =
        hex8::is_parallelepiped(gather(x_ref, connectivity + 8 * static_cast<std::size_t>(e)));
  ReferenceLayout layout = ReferenceLayout::hex8_general;
  if (formulation == input::Formulation::hex8)
    layout = all_parallelepipeds ? ReferenceLayout::hex8_parallelepiped : ReferenceLayout::hex8_general;
  else
    layout = all_parallelepipeds ? ReferenceLayout::hex8r_parallelepiped : ReferenceLayout::hex8r;
  const std::size_t stride = stride_of(layout);
  const bool paired = is_paired(layout);
  const std::size_t stored = paired ? 2 * ((static_cast<std::size_t>(count) + 1) / 2) : count;
  block.reference.assign(header_size + stride * stored, 0.0);
  block.reference[0] = static_cast<double>(static_cast<int>(layout));
  static_assert(hex8::reference_size >= hex8r::reference_size &&
                hex8::reference_size >= hex8r::parallelepiped_reference_size &&
                hex8::reference_size >= hex8::parallelepiped_reference_size);
  std::array<double, hex8::reference_size> scratch{};  // one element's data, the largest layout
  for (std::uint32_t e = 0; e < count; ++e) {
    const ElementVectors x = gather(x_ref, connectivity + 8 * static_cast<std::size_t>(e));
    double* reference = paired ? scratch.data() : block.reference.data() + header_size + stride * e;
    double min_det_jacobian = 0.0;
    switch (layout) {
      case ReferenceLayout::hex8_general:
        min_det_jacobian = hex8::make_reference(x, reference);
        break;
      case ReferenceLayout::hex8_parallelepiped:
        min_det_jacobian = hex8::make_parallelepiped_reference(x, reference);
        break;
      case ReferenceLayout::hex8r:
        min_det_jacobian = hex8r::make_reference(x, material.mu, hourglass_coefficient, reference);
        break;
      case ReferenceLayout::hex8r_parallelepiped:
        min_det_jacobian =
            hex8r::make_parallelepiped_reference(x, material.mu, hourglass_coefficient, reference);
        break;
    }
    if (!(min_det_jacobian > 0.0)) throw_inverted(first_element + e, min_det_jacobian);
    if (paired) {
      double* pair_data = block.reference.data() + header_size + 2 * stride * (e / 2);
      for (std::size_t k = 0; k < stride; ++k) pair_data[2 * k + e % 2] = scratch[k];
    }
  }
  build_schedule(block, x_ref.size());
  return block;
}

ElementEnergies add_internal_forces(const ElementBlock& block, std::uint32_t element_begin,
                                    std::uint32_t element_end, const NodalVectors& u, NodalVectors& f_int,
                                    double* stress) {
  EXDYN_ASSERT(element_begin <= element_end && element_end <= block.count);
  const double lambda = block.material.lambda, mu = block.material.mu;
  const ReferenceLayout layout = layout_of(block);
  const std::size_t stride = stride_of(layout);
  switch (layout) {
    case ReferenceLayout::hex8_general:
      return element_loop(
          block, element_begin, element_end, stride, u, f_int, stress,
          [lambda, mu](const double* reference, const ElementVectors& u_local, ElementVectors& f_local,
                       material::SymTensor& s) {
            return ElementEnergies{hex8::internal_forces(reference, lambda, mu, u_local, f_local, s), 0.0};
          });
    case ReferenceLayout::hex8_parallelepiped:
      return element_pair_loop(
          block, element_begin, element_end, stride, u, f_int, stress,
          [lambda, mu](const double* reference, const BasicElementVectors<Pack2>& u_local,
                       BasicElementVectors<Pack2>& f_local, std::array<Pack2, 6>& s) {
            return std::array<Pack2, 2>{
                hex8::parallelepiped_internal_forces(reference, lambda, mu, u_local, f_local, s),
                Pack2{0.0, 0.0}};
          });
    case ReferenceLayout::hex8r:
      return element_pair_loop(
          block, element_begin, element_end, stride, u, f_int, stress,
          [lambda, mu](const double* reference, const BasicElementVectors<Pack2>& u_local,
                       BasicElementVectors<Pack2>& f_local, std::array<Pack2, 6>& s) {
            const hex8r::BasicEnergies<Pack2> e =
                hex8r::internal_forces(reference, lambda, mu, u_local, f_local, s);
            return std::array<Pack2, 2>{e.strain, e.hourglass};
          });
    case ReferenceLayout::hex8r_parallelepiped:
      return element_pair_loop(
          block, element_begin, element_end, stride, u, f_int, stress,
          [lambda, mu](const double* reference, const BasicElementVectors<Pack2>& u_local,
                       BasicElementVectors<Pack2>& f_local, std::array<Pack2, 6>& s) {
            const hex8r::BasicEnergies<Pack2> e =
                hex8r::parallelepiped_internal_forces(reference, lambda, mu, u_local, f_local, s);
            return std::array<Pack2, 2>{e.strain, e.hourglass};
          });
  }
  return {};
}

ElementEnergies add_internal_forces(const ElementBlock& block, const NodalVectors& u, NodalVectors& f_int,
                                    double* stress) {
  EXDYN_ASSERT(block.chunk_energies.size() + 1 == block.chunk_begin.size());
  for (const std::vector<std::uint32_t>& colour : block.colours) {
    const auto chunks = static_cast<std::ptrdiff_t>(colour.size());
#pragma omp parallel for schedule(dynamic, 1)
    for (std::ptrdiff_t k = 0; k < chunks; ++k) {
      const std::uint32_t c = colour[static_cast<std::size_t>(k)];
      block.chunk_energies[c] =
          add_internal_forces(block, block.chunk_begin[c], block.chunk_begin[c + 1], u, f_int, stress);
    }
  }
  ElementEnergies total;  // in chunk order, whatever the threads
  for (const ElementEnergies& e : block.chunk_energies) {
    total.strain += e.strain;
    total.hourglass += e.hourglass;
  }
  return total;
}

InvertedElement find_inverted_element(const ElementBlock& block, std::uint32_t element_begin,
                                      std::uint32_t element_end, const NodalVectors& x_ref,
                                      const NodalVectors& u) {
  EXDYN_ASSERT(element_begin <= element_end && element_end <= block.count);
  // Neighbours of each corner along xi, eta, zeta, and the sign that orients the
  // edge towards +xi, +eta, +zeta (VTK order: 0-3 at zeta = -1, 4-7 at zeta = +1).
  static constexpr int neighbour[8][3] = {{1, 3, 4}, {0, 2, 5}, {3, 1, 6}, {2, 0, 7},
                                          {5, 7, 0}, {4, 6, 1}, {7, 5, 2}, {6, 4, 3}};
  // -sx sy sz of the corner at (sx, sy, sz): +1 where all three edges already point the + way.
  static constexpr double orientation[8] = {1.0, -1.0, 1.0, -1.0, -1.0, 1.0, -1.0, 1.0};
  double smallest_ratio = std::numeric_limits<double>::infinity();  // det J / ||J||_F^2, m
  for (std::uint32_t e = element_begin; e < element_end; ++e) {
    const std::uint32_t* nodes = block.connectivity + 8 * static_cast<std::size_t>(e);
    const ElementVectors x0 = gather(x_ref, nodes);
    const ElementVectors du = gather(u, nodes);
    std::array<double, 8> x, y, z;
    for (int k = 0; k < 8; ++k) x[k] = x0.x[k] + du.x[k], y[k] = x0.y[k] + du.y[k], z[k] = x0.z[k] + du.z[k];
    for (int a = 0; a < 8; ++a) {
      const int i = neighbour[a][0], j = neighbour[a][1], k = neighbour[a][2];
      const double ax = x[i] - x[a], ay = y[i] - y[a], az = z[i] - z[a];
      const double bx = x[j] - x[a], by = y[j] - y[a], bz = z[j] - z[a];
      const double cx = x[k] - x[a], cy = y[k] - y[a], cz = z[k] - z[a];
      const double det =
          orientation[a] * (ax * (by * cz - bz * cy) - ay * (bx * cz - bz * cx) + az * (bx * cy - by * cx));
      if (!(det > 0.0)) return {true, block.first_element + e, a, det, 0.0};
      const double frobenius2 =
          ax * ax + ay * ay + az * az + bx * bx + by * by + bz * bz + cx * cx + cy * cy + cz * cz;
      smallest_ratio = std::min(smallest_ratio, det / frobenius2);
    }
  }
  InvertedElement none;
  none.safety_radius = smallest_ratio / (2.0 * std::sqrt(3.0));
  return none;
}

InvertedElement find_inverted_element(const ElementBlock& block, const NodalVectors& x_ref,
                                      const NodalVectors& u) {
  return find_inverted_element(block, 0, block.count, x_ref, u);
}

bool uses_parallelepiped_kernel(const ElementBlock& block) {
  if (block.reference.empty()) return false;
  const ReferenceLayout layout = layout_of(block);
  return layout == ReferenceLayout::hex8_parallelepiped || layout == ReferenceLayout::hex8r_parallelepiped;
}

double critical_time_step(const ElementBlock& block, const NodalVectors& x_ref) {
  const double wave_speed = block.material.dilatational_wave_speed();  // c1 = sqrt((lambda + 2 mu) / rho)
  double shortest = std::numeric_limits<double>::infinity();
  for (std::uint32_t e = 0; e < block.count; ++e) {
    const ElementVectors x = gather(x_ref, block.connectivity + 8 * static_cast<std::size_t>(e));
    shortest = std::min(shortest, hex8::characteristic_length(x));
  }
  return shortest / wave_speed;
}

void add_lumped_mass(const ElementBlock& block, const NodalVectors& x_ref, std::vector<double>& mass) {
  EXDYN_ASSERT(mass.size() == x_ref.size());
  const double rho = block.material.density;
  for (std::uint32_t e = 0; e < block.count; ++e) {
    const std::uint32_t* nodes = block.connectivity + 8 * static_cast<std::size_t>(e);
    const std::array<double, 8> integral = hex8::shape_function_integrals(gather(x_ref, nodes));
    for (int k = 0; k < 8; ++k) mass[nodes[k]] += rho * integral[k];  // m_I += rho integral N_I dV
  }
}

}  // namespace exdyn::element
