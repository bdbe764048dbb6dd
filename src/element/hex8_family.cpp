// The 8-node families: hex8 (2x2x2 Gauss points) and hex8r (one point with
// hourglass stiffness), each with a general kernel and a constant-Jacobian one
// for parallelepipeds (docs/theory.md, "Element library").
//
// Reference data layouts: every layout but the general hex8 one stores element
// pairs (2p, 2p+1) interleaved value by value, [.., value k of 2p, value k of 2p+1, ..],
// for the kernels that run on two elements at once (Pack2); an odd last element is
// paired with zeros. (The general hex8 kernel vectorises over its 8 Gauss points instead.)
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "common/errors.hpp"
#include "element/element_family.hpp"
#include "element/element_loop.hpp"
#include "element/hex8.hpp"
#include "element/hex8r.hpp"

namespace exdyn::element {
namespace {

ElementVectors gather8(const NodalVectors& v, const std::uint32_t* nodes) {
  ElementVectors local{ElementVectors::Uninitialized{}};  // every entry written below
  gather<8>(v, nodes, local);
  return local;
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
  const double* reference = block.reference.data();
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

// --- the four loops, one per layout

ElementEnergies hex8_general_loop(const ElementBlock& block, std::uint32_t begin, std::uint32_t end,
                                  const NodalVectors& u, NodalVectors& f_int, double* stress) {
  const double lambda = block.material.lambda, mu = block.material.mu;
  return element_loop<8, ElementVectors>(
      block, begin, end, block.reference.data(), hex8::reference_size, u, f_int, stress,
      [lambda, mu](const double* reference, const ElementVectors& u_local, ElementVectors& f_local,
                   material::SymTensor& s) {
        return ElementEnergies{hex8::internal_forces(reference, lambda, mu, u_local, f_local, s), 0.0};
      });
}

ElementEnergies hex8_parallelepiped_loop(const ElementBlock& block, std::uint32_t begin, std::uint32_t end,
                                         const NodalVectors& u, NodalVectors& f_int, double* stress) {
  const double lambda = block.material.lambda, mu = block.material.mu;
  return element_pair_loop(block, begin, end, hex8::parallelepiped_reference_size, u, f_int, stress,
                           [lambda, mu](const double* reference, const BasicElementVectors<Pack2>& u_local,
                                        BasicElementVectors<Pack2>& f_local, std::array<Pack2, 6>& s) {
                             return std::array<Pack2, 2>{hex8::parallelepiped_internal_forces(
                                                             reference, lambda, mu, u_local, f_local, s),
                                                         Pack2{0.0, 0.0}};
                           });
}

// The two hex8r loops: the same pair loop around the general or the
// constant-Jacobian one-point kernel.
template <bool Parallelepiped>
ElementEnergies hex8r_loop(const ElementBlock& block, std::uint32_t begin, std::uint32_t end,
                           const NodalVectors& u, NodalVectors& f_int, double* stress) {
  const double lambda = block.material.lambda, mu = block.material.mu;
  const std::size_t stride = Parallelepiped ? hex8r::parallelepiped_reference_size : hex8r::reference_size;
  return element_pair_loop(
      block, begin, end, stride, u, f_int, stress,
      [lambda, mu](const double* reference, const BasicElementVectors<Pack2>& u_local,
                   BasicElementVectors<Pack2>& f_local, std::array<Pack2, 6>& s) {
        const hex8r::BasicEnergies<Pack2> e =
            Parallelepiped ? hex8r::parallelepiped_internal_forces(reference, lambda, mu, u_local, f_local, s)
                           : hex8r::internal_forces(reference, lambda, mu, u_local, f_local, s);
        return std::array<Pack2, 2>{e.strain, e.hourglass};
      });
}

// Precomputes the reference data of every element with make(x, reference) (which
// returns the smallest det J), stride doubles each, pairs interleaved when `paired`.
template <class Make>
void fill_reference(ElementBlock& block, const NodalVectors& x_ref, std::size_t stride, bool paired,
                    Make make) {
  const std::size_t stored = paired ? 2 * ((static_cast<std::size_t>(block.count) + 1) / 2) : block.count;
  block.reference.assign(stride * stored, 0.0);
  static_assert(hex8::reference_size >= hex8r::reference_size &&
                hex8::reference_size >= hex8r::parallelepiped_reference_size &&
                hex8::reference_size >= hex8::parallelepiped_reference_size);
  std::array<double, hex8::reference_size> scratch{};  // one element's data, the largest layout
  for (std::uint32_t e = 0; e < block.count; ++e) {
    const ElementVectors x = gather8(x_ref, block.connectivity + 8 * static_cast<std::size_t>(e));
    double* reference = paired ? scratch.data() : block.reference.data() + stride * e;
    const double min_det_jacobian = make(x, reference);
    if (!(min_det_jacobian > 0.0)) throw_inverted(block.first_element + e, min_det_jacobian);
    if (paired) {
      double* pair_data = block.reference.data() + 2 * stride * (e / 2);
      for (std::size_t k = 0; k < stride; ++k) pair_data[2 * k + e % 2] = scratch[k];
    }
  }
}

bool all_parallelepipeds(const ElementBlock& block, const NodalVectors& x_ref) {
  for (std::uint32_t e = 0; e < block.count; ++e)
    if (!hex8::is_parallelepiped(gather8(x_ref, block.connectivity + 8 * static_cast<std::size_t>(e))))
      return false;
  return true;
}

// The constant-Jacobian kernels when every element is a parallelepiped (the
// structured boxes of this program), the general ones otherwise.
void prepare_hex8(ElementBlock& block, const NodalVectors& x_ref) {
  block.constant_jacobian = all_parallelepipeds(block, x_ref);
  if (block.constant_jacobian) {
    block.loop = hex8_parallelepiped_loop;
    fill_reference(
        block, x_ref, hex8::parallelepiped_reference_size, true,
        [](const ElementVectors& x, double* r) { return hex8::make_parallelepiped_reference(x, r); });
  } else {
    block.loop = hex8_general_loop;
    fill_reference(block, x_ref, hex8::reference_size, false,
                   [](const ElementVectors& x, double* r) { return hex8::make_reference(x, r); });
  }
}

void prepare_hex8r(ElementBlock& block, const NodalVectors& x_ref) {
  block.constant_jacobian = all_parallelepipeds(block, x_ref);
  const double mu = block.material.mu, coefficient = block.hourglass_coefficient;
  if (block.constant_jacobian) {
    block.loop = hex8r_loop<true>;
    fill_reference(block, x_ref, hex8r::parallelepiped_reference_size, true,
                   [mu, coefficient](const ElementVectors& x, double* r) {
                     return hex8r::make_parallelepiped_reference(x, mu, coefficient, r);
                   });
  } else {
    block.loop = hex8r_loop<false>;
    fill_reference(block, x_ref, hex8r::reference_size, true,
                   [mu, coefficient](const ElementVectors& x, double* r) {
                     return hex8r::make_reference(x, mu, coefficient, r);
                   });
  }
}

// Row-sum lumping: m_I += rho integral of N_I dV (positive for every trilinear brick).
void add_row_sum_mass(const ElementBlock& block, const NodalVectors& x_ref, std::vector<double>& mass) {
  EXDYN_ASSERT(mass.size() == x_ref.size());
  const double rho = block.material.density;
  for (std::uint32_t e = 0; e < block.count; ++e) {
    const std::uint32_t* nodes = block.connectivity + 8 * static_cast<std::size_t>(e);
    const std::array<double, 8> integral = hex8::shape_function_integrals(gather8(x_ref, nodes));
    for (int k = 0; k < 8; ++k) mass[nodes[k]] += rho * integral[k];
  }
}

// min over elements of L_e / c1 (L_e = volume / largest face area).
double characteristic_length_step(const ElementBlock& block, const NodalVectors& x_ref) {
  const double wave_speed = block.material.dilatational_wave_speed();  // c1 = sqrt((lambda + 2 mu) / rho)
  double shortest = std::numeric_limits<double>::infinity();
  for (std::uint32_t e = 0; e < block.count; ++e)
    shortest = std::min(shortest, hex8::characteristic_length(
                                      gather8(x_ref, block.connectivity + 8 * static_cast<std::size_t>(e))));
  return shortest / wave_speed;
}

}  // namespace

const ElementFamily hex8_family{"hex8", 8, prepare_hex8, add_row_sum_mass, characteristic_length_step};
const ElementFamily hex8r_family{"hex8r", 8, prepare_hex8r, add_row_sum_mass, characteristic_length_step};

}  // namespace exdyn::element
