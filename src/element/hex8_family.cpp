// The 8-node families: hex8 (2x2x2 Gauss points) and hex8r (one point with
// hourglass stiffness), each with a general kernel and a constant-Jacobian one
// for parallelepipeds (docs/theory.md, "Element library").
//
// Reference data layouts: every layout stores packs of L
// consecutive elements interleaved value by value, [.., value k of Lp, .., value k of
// Lp + L - 1, ..], for the kernels that run on L elements at once (Pack<L>: L = 2, 4
// or 8, one vector register of the ISA the block runs, element_isa.hpp); a last
// partial pack is padded with zeros.
#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>
#include <cstring>
#include <limits>

#include "common/errors.hpp"
#include "element/element_family.hpp"
#include "element/element_isa.hpp"
#include "element/element_loop.hpp"
#include "element/hex8.hpp"
#include "element/hex8_constitutive.hpp"
#include "element/hex8_parallelepiped.hpp"
#include "element/hex8r.hpp"

namespace exdyn::element {
namespace {

ElementVectors gather8(const NodalVectors& v, const std::uint32_t* nodes) {
  ElementVectors local{ElementVectors::Uninitialized{}};  // every entry written below
  gather<8>(v, nodes, local);
  return local;
}

// --- the four loops, one per layout

template <int Lanes>
ElementEnergies hex8_general_loop(const ElementBlock& block, std::uint32_t begin, std::uint32_t end,
                                  const NodalVectors& u, NodalVectors& f_int, double* stress) {
  using Real = Pack<Lanes>;
  const double lambda = block.material.lambda, mu = block.material.mu;
  const double* data = block.reference.data();
  return element_pack_loop<8, Lanes>(
      block, begin, end, u, f_int, stress,
      [lambda, mu, data](std::uint32_t pack, const BasicElementVectors<Real>& u_local,
                         BasicElementVectors<Real>& f_local, std::array<Real, 6>& s) {
        const double* reference = data + std::size_t(Lanes) * hex8::reference_size * pack;
        return std::array<Real, 2>{hex8::internal_forces(reference, lambda, mu, u_local, f_local, s), Real{}};
      });
}

template <int Lanes, bool AxisAligned>
ElementEnergies hex8_parallelepiped_loop(const ElementBlock& block, std::uint32_t begin, std::uint32_t end,
                                         const NodalVectors& u, NodalVectors& f_int, double* stress) {
  using Real = Pack<Lanes>;
  const double lambda = block.material.lambda, mu = block.material.mu;
  const double* data = block.reference.data();
  return element_pack_loop<8, Lanes>(
      block, begin, end, u, f_int, stress,
      [lambda, mu, data](std::uint32_t pack, const BasicElementVectors<Real>& u_local,
                         BasicElementVectors<Real>& f_local, std::array<Real, 6>& s) {
        const double* reference = data + std::size_t(Lanes) * hex8::parallelepiped_reference_size * pack;
        return std::array<Real, 2>{
            AxisAligned ? hex8::axis_aligned_internal_forces(reference, lambda, mu, u_local, f_local, s)
                        : hex8::parallelepiped_internal_forces(reference, lambda, mu, u_local, f_local, s),
            Real{}};
      });
}

// The two hex8r loops: the same pair loop around the general or the
// constant-Jacobian one-point kernel.
template <bool Parallelepiped, int Lanes>
ElementEnergies hex8r_loop(const ElementBlock& block, std::uint32_t begin, std::uint32_t end,
                           const NodalVectors& u, NodalVectors& f_int, double* stress) {
  using Real = Pack<Lanes>;
  const double lambda = block.material.lambda, mu = block.material.mu;
  const std::size_t stride = Parallelepiped ? hex8r::parallelepiped_reference_size : hex8r::reference_size;
  const double* data = block.reference.data();
  return element_pack_loop<8, Lanes>(
      block, begin, end, u, f_int, stress,
      [lambda, mu, data, stride](std::uint32_t pack, const BasicElementVectors<Real>& u_local,
                                 BasicElementVectors<Real>& f_local, std::array<Real, 6>& s) {
        const double* reference = data + std::size_t(Lanes) * stride * pack;
        const hex8r::BasicEnergies<Real> e =
            Parallelepiped ? hex8r::parallelepiped_internal_forces(reference, lambda, mu, u_local, f_local, s)
                           : hex8r::internal_forces(reference, lambda, mu, u_local, f_local, s);
        return std::array<Real, 2>{e.strain, e.hourglass};
      });
}

// The loops of a material law (constitutive.hpp): the general layouts, the law at
// every point, the point states in the block.
template <class Flow, bool Finite, int Lanes>
ElementEnergies hex8_law_loop(const ElementBlock& block, std::uint32_t begin, std::uint32_t end,
                              const NodalVectors& u, NodalVectors& f_int, double* stress) {
  using Real = Pack<Lanes>;
  const Flow& flow = flow_of<Flow>(block.law);
  const material::ElasticConstants elastic = block.material;
  const bool f_bar = block.law.f_bar;
  const double dt = block.material_state.dt;
  const double* data = block.reference.data();
  return element_pack_loop<8, Lanes, true>(
      block, begin, end, u, f_int, stress,
      [&](std::uint32_t pack, const BasicElementVectors<Real>& u_local, BasicElementVectors<Real>& f_local,
          std::array<Real, 6>& s) {
        const PackStates<Flow, Lanes> states(block, pack, 8);
        const ConstitutiveResult<Real> r = hex8::constitutive_forces<Flow, Finite>(
            data + std::size_t(Lanes) * hex8::reference_size * pack, elastic, flow, f_bar, u_local, f_local,
            states.old_state, states.new_state, dt);
        s = r.mean_stress;
        store_plastic_strain(block, pack, r.eps_p);
        return std::array<Real, 3>{r.internal, Real{}, r.plastic};
      });
}

// AssumedStrain: the rate-form kernel with the hourglass state (law_reference_size);
// otherwise Flanagan-Belytschko's total form (reference_size).
template <class Flow, bool Finite, bool AssumedStrain, int Lanes>
ElementEnergies hex8r_law_loop(const ElementBlock& block, std::uint32_t begin, std::uint32_t end,
                               const NodalVectors& u, NodalVectors& f_int, double* stress) {
  using Real = Pack<Lanes>;
  const Flow& flow = flow_of<Flow>(block.law);
  const material::ElasticConstants elastic = block.material;
  const double dt = block.material_state.dt;
  const double* data = block.reference.data();
  constexpr std::size_t stride = AssumedStrain ? hex8r::law_reference_size : hex8r::reference_size;
  return element_pack_loop<8, Lanes, true>(
      block, begin, end, u, f_int, stress,
      [&](std::uint32_t pack, const BasicElementVectors<Real>& u_local, BasicElementVectors<Real>& f_local,
          std::array<Real, 6>& s) {
        const PackStates<Flow, Lanes> states(block, pack, 1);
        Real hourglass{};
        const double* reference = data + std::size_t(Lanes) * stride * pack;
        ConstitutiveResult<Real> r;
        if constexpr (AssumedStrain) {
          MaterialState& m = block.material_state;
          const std::size_t offset = std::size_t(Lanes) * hex8r::hourglass_state_size * pack;
          r = hex8r::assumed_strain_forces<Flow, Finite>(
              reference, elastic, flow, u_local, f_local, states.old_state, states.new_state,
              m.hourglass[std::size_t(m.committed)].data() + offset,
              m.hourglass[std::size_t(m.committed ^ 1)].data() + offset, dt, hourglass);
        } else {
          r = hex8r::constitutive_forces<Flow, Finite>(reference, elastic, flow, u_local, f_local,
                                                       states.old_state, states.new_state, dt, hourglass);
        }
        s = r.mean_stress;
        store_plastic_strain(block, pack, r.eps_p);
        return std::array<Real, 3>{r.internal, hourglass, r.plastic};
      });
}

// Precomputes the reference data of every element with make(x, reference) (which
// returns the smallest det J), stride doubles each, interleaved by packs of `lanes`
// elements value by value ([.., value k of element Lp, .., of element Lp + L - 1, ..];
// lanes 1: one element after the other). A last partial pack is padded with zeros.
template <class Make>
void fill_reference(ElementBlock& block, const NodalVectors& x_ref, std::size_t stride, int lanes,
                    Make make) {
  const std::size_t width = static_cast<std::size_t>(lanes);
  const std::size_t stored = width * ((static_cast<std::size_t>(block.count) + width - 1) / width);
  block.reference.assign(stride * stored, 0.0);
  block.reference_per_element = stride;
  static_assert(hex8::reference_size >= hex8r::reference_size &&
                hex8::reference_size >= hex8r::law_reference_size &&
                hex8::reference_size >= hex8r::parallelepiped_reference_size &&
                hex8::reference_size >= hex8::parallelepiped_reference_size);
  std::array<double, hex8::reference_size> scratch{};  // one element's data, the largest layout
  for (std::uint32_t e = 0; e < block.count; ++e) {
    const ElementVectors x = gather8(x_ref, block.connectivity + 8 * static_cast<std::size_t>(e));
    double* reference = lanes > 1 ? scratch.data() : block.reference.data() + stride * e;
    const double min_det_jacobian = make(x, reference);
    if (!(min_det_jacobian > 0.0)) throw_inverted(block.first_element + e, min_det_jacobian);
    if (lanes > 1) {
      double* pack_data = block.reference.data() + width * stride * (e / width);
      for (std::size_t k = 0; k < stride; ++k) pack_data[width * k + e % width] = scratch[k];
    }
  }
}

// ElementBlock::row_pack for packs of `lanes` elements.
void mark_row_packs(ElementBlock& block, int lanes) {
  const std::uint32_t width = static_cast<std::uint32_t>(lanes);
  block.row_pack.assign((block.count + width - 1) / width, 0);
  for (std::uint32_t pack = 0; pack < block.count / width; ++pack) {
    const std::uint32_t* first = block.connectivity + 8 * static_cast<std::size_t>(width * pack);
    bool row = first[1] == first[0] + 1 && first[2] == first[3] + 1 && first[5] == first[4] + 1 &&
               first[6] == first[7] + 1;
    for (std::uint32_t lane = 1; lane < width && row; ++lane)
      for (int k = 0; k < 8; ++k) row = row && first[8 * lane + k] == first[k] + lane;
    block.row_pack[pack] = row ? 1 : 0;
  }
}

// True when every element is a parallelepiped with edges along x, y and z.
bool all_axis_aligned(std::uint32_t count, const std::uint32_t* connectivity, const NodalVectors& x_ref) {
  std::array<double, hex8::parallelepiped_reference_size> reference{};
  for (std::uint32_t e = 0; e < count; ++e) {
    hex8::make_parallelepiped_reference(gather8(x_ref, connectivity + 8 * static_cast<std::size_t>(e)),
                                        reference.data());
    if (!hex8::is_axis_aligned(reference.data())) return false;
  }
  return true;
}

bool all_parallelepipeds(std::uint32_t count, const std::uint32_t* connectivity, const NodalVectors& x_ref) {
  for (std::uint32_t e = 0; e < count; ++e)
    if (!hex8::is_parallelepiped(gather8(x_ref, connectivity + 8 * static_cast<std::size_t>(e))))
      return false;
  return true;
}

WholeBlock hex8_layout(std::uint32_t count, const std::uint32_t* connectivity, const NodalVectors& x_ref) {
  WholeBlock layout;
  layout.parallelepipeds = all_parallelepipeds(count, connectivity, x_ref);
  layout.axis_aligned = layout.parallelepipeds && all_axis_aligned(count, connectivity, x_ref);
  return layout;
}

// The constant-Jacobian kernels when every element is a parallelepiped, their
// axis-aligned form when every one also has its edges along x, y, z (the structured
// boxes of this program), the general ones otherwise.
void prepare_hex8(ElementBlock& block, const NodalVectors& x_ref) {
  const Isa isa = selected_isa();
  if (!block.law.linear_small()) {
    block.loop = law_loop(block.law, [isa]<class Flow, bool Finite>() {
      return packed_for_isa<hex8_law_loop<Flow, Finite, 2>, hex8_law_loop<Flow, Finite, 4>,
                            hex8_law_loop<Flow, Finite, 8>>(isa);
    });
    block.corners_in_pass = true;
    fill_reference(block, x_ref, hex8::reference_size, lanes_for(isa),
                   [](const ElementVectors& x, double* r) { return hex8::make_reference(x, r); });
    mark_row_packs(block, lanes_for(isa));
    return;
  }
  // A rank's part of a block takes the whole block's layout (ElementBlock::whole).
  block.constant_jacobian =
      block.whole.parallelepipeds && all_parallelepipeds(block.count, block.connectivity, x_ref);
  if (block.constant_jacobian) {
    block.axis_aligned = block.whole.axis_aligned && all_axis_aligned(block.count, block.connectivity, x_ref);
    block.loop = block.axis_aligned
                     ? packed_for_isa<hex8_parallelepiped_loop<2, true>, hex8_parallelepiped_loop<4, true>,
                                      hex8_parallelepiped_loop<8, true>>(isa)
                     : packed_for_isa<hex8_parallelepiped_loop<2, false>, hex8_parallelepiped_loop<4, false>,
                                      hex8_parallelepiped_loop<8, false>>(isa);
    fill_reference(
        block, x_ref, hex8::parallelepiped_reference_size, lanes_for(isa),
        [](const ElementVectors& x, double* r) { return hex8::make_parallelepiped_reference(x, r); });
  } else {
    block.loop = packed_for_isa<hex8_general_loop<2>, hex8_general_loop<4>, hex8_general_loop<8>>(isa);
    fill_reference(block, x_ref, hex8::reference_size, lanes_for(isa),
                   [](const ElementVectors& x, double* r) { return hex8::make_reference(x, r); });
  }
  mark_row_packs(block, lanes_for(isa));
}

void prepare_hex8r(ElementBlock& block, const NodalVectors& x_ref) {
  const Isa isa = selected_isa();
  block.constant_jacobian =
      block.whole.parallelepipeds && all_parallelepipeds(block.count, block.connectivity, x_ref);
  const material::ElasticConstants& elastic = block.material;
  const hex8r::Stabilization stabilization{
      block.hourglass.model, block.hourglass.coefficient,
      elastic.mu * (3.0 * elastic.lambda + 2.0 * elastic.mu) / (elastic.lambda + elastic.mu), elastic.mu};
  if (!block.law.linear_small()) {
    const bool assumed_strain = block.hourglass.model == input::HourglassModel::assumed_strain;
    block.constant_jacobian = false;
    block.loop = law_loop(block.law, [isa, assumed_strain]<class Flow, bool Finite>() {
      return assumed_strain ? packed_for_isa<hex8r_law_loop<Flow, Finite, true, 2>,
                                             hex8r_law_loop<Flow, Finite, true, 4>,
                                             hex8r_law_loop<Flow, Finite, true, 8>>(isa)
                            : packed_for_isa<hex8r_law_loop<Flow, Finite, false, 2>,
                                             hex8r_law_loop<Flow, Finite, false, 4>,
                                             hex8r_law_loop<Flow, Finite, false, 8>>(isa);
    });
    block.corners_in_pass = true;
    fill_reference(block, x_ref, assumed_strain ? hex8r::law_reference_size : hex8r::reference_size,
                   lanes_for(isa), [stabilization, assumed_strain](const ElementVectors& x, double* r) {
                     return hex8r::make_reference(x, stabilization, r, assumed_strain);
                   });
    mark_row_packs(block, lanes_for(isa));
    return;
  }
  if (block.constant_jacobian) {
    block.loop = packed_for_isa<hex8r_loop<true, 2>, hex8r_loop<true, 4>, hex8r_loop<true, 8>>(isa);
    fill_reference(block, x_ref, hex8r::parallelepiped_reference_size, lanes_for(isa),
                   [stabilization](const ElementVectors& x, double* r) {
                     return hex8r::make_parallelepiped_reference(x, stabilization, r);
                   });
  } else {
    block.loop = packed_for_isa<hex8r_loop<false, 2>, hex8r_loop<false, 4>, hex8r_loop<false, 8>>(isa);
    fill_reference(block, x_ref, hex8r::reference_size, lanes_for(isa),
                   [stabilization](const ElementVectors& x, double* r) {
                     return hex8r::make_reference(x, stabilization, r);
                   });
  }
  mark_row_packs(block, lanes_for(isa));
}

// Row-sum lumping: m_I += rho integral of N_I dV (positive for every trilinear brick).
void add_row_sum_mass(const ElementBlock& block, const NodalVectors& x_ref, std::vector<double>& mass) {
  EXDYN_ASSERT(mass.size() == x_ref.size());
  const double rho = block.material.density;
  for (std::uint32_t e = 0; e < block.count; ++e) {
    const std::uint32_t* nodes = block.connectivity + 8 * static_cast<std::size_t>(e);
    const std::array<double, 8> integral = hex8::shape_function_integrals(gather8(x_ref, nodes));
    for (int k = 0; k < 8; ++k) {
      assert(nodes[k] < mass.size());  // element_loop.hpp: the sanitizer build does not instrument this file
      mass[nodes[k]] += rho * integral[k];
    }
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

const ElementFamily hex8_family{"hex8",     8, prepare_hex8, add_row_sum_mass, characteristic_length_step,
                                hex8_layout};
const ElementFamily hex8r_family{"hex8r",    8, prepare_hex8r, add_row_sum_mass, characteristic_length_step,
                                 hex8_layout};

}  // namespace exdyn::element
