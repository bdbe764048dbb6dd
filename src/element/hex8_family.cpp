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
#include <cmath>
#include <cstring>
#include <limits>

#include "common/errors.hpp"
#include "element/element_family.hpp"
#include "element/element_isa.hpp"
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

template <int Lanes>
BasicElementVectors<Pack<Lanes>> gather_pack(const NodalVectors& v,
                                             const std::uint32_t* const (&nodes)[Lanes]) {
  BasicElementVectors<Pack<Lanes>> local{
      typename BasicElementVectors<Pack<Lanes>>::Uninitialized{}};  // every entry written below
  const double* x = v.x.data();
  const double* y = v.y.data();
  const double* z = v.z.data();
  for (int k = 0; k < 8; ++k) {
    for (int lane = 0; lane < Lanes; ++lane) {
      const std::uint32_t n = nodes[lane][k];
      local.x[k][lane] = x[n];
      local.y[k][lane] = y[n];
      local.z[k][lane] = z[n];
    }
  }
  return local;
}

// The lane indices for __builtin_shuffle that move every lane up by one and the zero
// of the second operand into lane 0.
template <int Lanes>
constexpr IntPack<Lanes> up_one_lane() {
  IntPack<Lanes> indices{};
  indices[0] = Lanes;
  for (int lane = 1; lane < Lanes; ++lane) indices[lane] = lane - 1;
  return indices;
}

// The gather of a row pack (ElementBlock::row_pack): node k of the Lanes elements are
// the consecutive nodes from nodes[k] on, one unaligned vector load per component.
template <int Lanes>
BasicElementVectors<Pack<Lanes>> gather_row_pack(const NodalVectors& v, const std::uint32_t* nodes) {
  BasicElementVectors<Pack<Lanes>> local{
      typename BasicElementVectors<Pack<Lanes>>::Uninitialized{}};  // every entry written below
  for (int k = 0; k < 8; ++k) {
    local.x[k] = load<Pack<Lanes>>(v.x.data() + nodes[k], 0);
    local.y[k] = load<Pack<Lanes>>(v.y.data() + nodes[k], 0);
    local.z[k] = load<Pack<Lanes>>(v.z.data() + nodes[k], 0);
  }
  return local;
}

// The scatter of a row pack: along each row edge (a, b = a + 1 in node numbers), lane l
// adds f_a to node n + l and f_b to node n + l + 1 (n: node a of lane 0). So node
// n + l receives f_a of lane l plus f_b of lane l - 1: summed in the registers (f_b
// moved up one lane), then one vector load-add-store and the last lane's f_b alone.
template <int Lanes>
void scatter_add_row_pack(const BasicElementVectors<Pack<Lanes>>& local, const std::uint32_t* nodes,
                          NodalVectors& v) {
  using Real = Pack<Lanes>;
  const IntPack<Lanes> shift = up_one_lane<Lanes>();
  constexpr int row_edges[4][2] = {{0, 1}, {3, 2}, {4, 5}, {7, 6}};
  const std::array<const std::array<Real, 8>*, 3> forces{&local.x, &local.y, &local.z};
  const std::array<double*, 3> out{v.x.data(), v.y.data(), v.z.data()};
  for (const auto& edge : row_edges) {
    const std::uint32_t n = nodes[edge[0]];
    for (int c = 0; c < 3; ++c) {
      const Real f_a = (*forces[std::size_t(c)])[std::size_t(edge[0])];
      const Real f_b = (*forces[std::size_t(c)])[std::size_t(edge[1])];
      double* p = out[std::size_t(c)] + n;
      Real sum = load<Real>(p, 0) + (f_a + __builtin_shuffle(f_b, Real{}, shift));
      std::memcpy(p, &sum, sizeof sum);
      p[Lanes] += f_b[Lanes - 1];
    }
  }
}

template <class Real>
double lane_value(const Real& pack, int lane) {
  return pack[lane];
}

template <class Real>
void scatter_add_lane(const BasicElementVectors<Real>& local, int lane, const std::uint32_t* nodes,
                      NodalVectors& v) {
  double* x = v.x.data();
  double* y = v.y.data();
  double* z = v.z.data();
  for (int k = 0; k < 8; ++k) {
    const std::uint32_t n = nodes[k];
    x[n] += lane_value(local.x[std::size_t(k)], lane);
    y[n] += lane_value(local.y[std::size_t(k)], lane);
    z[n] += lane_value(local.z[std::size_t(k)], lane);
  }
}

// The element loop over packs of Lanes consecutive elements: kernel(reference, u, f,
// stress) on the pack at once returns their energies (strain, hourglass). Lanes
// outside [begin, end) are computed but neither scattered nor counted; the lanes past
// the block's last element take its first lane's nodes (their reference data are zero).
// The forces are added lane by lane, in element order (a row pack: summed along its row
// edges first); the same order for any number of threads.
template <int Lanes, class Kernel>
ElementEnergies element_pack_loop(const ElementBlock& block, std::uint32_t begin, std::uint32_t end,
                                  std::size_t stride, const NodalVectors& u, NodalVectors& f_int,
                                  double* stress, Kernel kernel) {
  using Real = Pack<Lanes>;
  ElementEnergies total;
  if (begin >= end) return total;
  const double* reference = block.reference.data();
  for (std::uint32_t pack = begin / Lanes; pack <= (end - 1) / Lanes; ++pack) {
    std::uint32_t element[Lanes];
    const std::uint32_t* nodes[Lanes];
    for (int lane = 0; lane < Lanes; ++lane) {
      element[lane] = Lanes * pack + std::uint32_t(lane);
      const std::uint32_t present = element[lane] < block.count ? element[lane] : Lanes * pack;
      nodes[lane] = block.connectivity + 8 * static_cast<std::size_t>(present);
    }
    // A whole row pack inside the range: vector gather and scatter.
    const bool row = !block.row_pack.empty() && block.row_pack[pack] != 0 && element[0] >= begin &&
                     element[Lanes - 1] < end;
    const BasicElementVectors<Real> u_local =
        row ? gather_row_pack<Lanes>(u, nodes[0]) : gather_pack<Lanes>(u, nodes);
    BasicElementVectors<Real> f_local{typename BasicElementVectors<Real>::Uninitialized{}};  // written whole
    std::array<Real, 6> element_stress;
    const std::array<Real, 2> energies =
        kernel(reference + Lanes * stride * pack, u_local, f_local, element_stress);
    if (row) scatter_add_row_pack<Lanes>(f_local, nodes[0], f_int);
    for (int lane = 0; lane < Lanes; ++lane) {
      if (element[lane] < begin || element[lane] >= end) continue;
      if (!row) scatter_add_lane(f_local, lane, nodes[lane], f_int);
      total.strain += lane_value(energies[0], lane);
      total.hourglass += lane_value(energies[1], lane);
      if (stress != nullptr) {
        double* out = stress + 6 * (static_cast<std::size_t>(block.first_element) + element[lane]);
        for (int k = 0; k < 6; ++k) out[k] = lane_value(element_stress[std::size_t(k)], lane);
      }
    }
  }
  return total;
}

// --- the four loops, one per layout

template <int Lanes>
ElementEnergies hex8_general_loop(const ElementBlock& block, std::uint32_t begin, std::uint32_t end,
                                  const NodalVectors& u, NodalVectors& f_int, double* stress) {
  using Real = Pack<Lanes>;
  const double lambda = block.material.lambda, mu = block.material.mu;
  return element_pack_loop<Lanes>(
      block, begin, end, hex8::reference_size, u, f_int, stress,
      [lambda, mu](const double* reference, const BasicElementVectors<Real>& u_local,
                   BasicElementVectors<Real>& f_local, std::array<Real, 6>& s) {
        return std::array<Real, 2>{hex8::internal_forces(reference, lambda, mu, u_local, f_local, s), Real{}};
      });
}

template <int Lanes, bool AxisAligned>
ElementEnergies hex8_parallelepiped_loop(const ElementBlock& block, std::uint32_t begin, std::uint32_t end,
                                         const NodalVectors& u, NodalVectors& f_int, double* stress) {
  using Real = Pack<Lanes>;
  const double lambda = block.material.lambda, mu = block.material.mu;
  return element_pack_loop<Lanes>(
      block, begin, end, hex8::parallelepiped_reference_size, u, f_int, stress,
      [lambda, mu](const double* reference, const BasicElementVectors<Real>& u_local,
                   BasicElementVectors<Real>& f_local, std::array<Real, 6>& s) {
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
  return element_pack_loop<Lanes>(
      block, begin, end, stride, u, f_int, stress,
      [lambda, mu](const double* reference, const BasicElementVectors<Real>& u_local,
                   BasicElementVectors<Real>& f_local, std::array<Real, 6>& s) {
        const hex8r::BasicEnergies<Real> e =
            Parallelepiped ? hex8r::parallelepiped_internal_forces(reference, lambda, mu, u_local, f_local, s)
                           : hex8r::internal_forces(reference, lambda, mu, u_local, f_local, s);
        return std::array<Real, 2>{e.strain, e.hourglass};
      });
}

// The pack width of an ISA's loops: one 128-, 256- or 512-bit register of doubles.
int lanes_for(Isa isa) { return isa == Isa::x86_64_v4 ? 8 : isa == Isa::x86_64_v3 ? 4 : 2; }

// The loop for `isa`, from its versions for packs of 2, 4 and 8.
template <ElementLoopFn Loop2, ElementLoopFn Loop4, ElementLoopFn Loop8>
ElementLoopFn packed_for_isa(Isa isa) {
  switch (isa) {
    case Isa::x86_64_v4:
      return for_isa<Loop8>(isa);
    case Isa::x86_64_v3:
      return for_isa<Loop4>(isa);
    case Isa::x86_64_v2:
      break;
  }
  return for_isa<Loop2>(isa);
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
  static_assert(hex8::reference_size >= hex8r::reference_size &&
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
bool all_axis_aligned(const ElementBlock& block, const NodalVectors& x_ref) {
  std::array<double, hex8::parallelepiped_reference_size> reference{};
  for (std::uint32_t e = 0; e < block.count; ++e) {
    hex8::make_parallelepiped_reference(gather8(x_ref, block.connectivity + 8 * static_cast<std::size_t>(e)),
                                        reference.data());
    if (!hex8::is_axis_aligned(reference.data())) return false;
  }
  return true;
}

bool all_parallelepipeds(const ElementBlock& block, const NodalVectors& x_ref) {
  for (std::uint32_t e = 0; e < block.count; ++e)
    if (!hex8::is_parallelepiped(gather8(x_ref, block.connectivity + 8 * static_cast<std::size_t>(e))))
      return false;
  return true;
}

// The constant-Jacobian kernels when every element is a parallelepiped, their
// axis-aligned form when every one also has its edges along x, y, z (the structured
// boxes of this program), the general ones otherwise.
void prepare_hex8(ElementBlock& block, const NodalVectors& x_ref) {
  const Isa isa = selected_isa();
  block.constant_jacobian = all_parallelepipeds(block, x_ref);
  if (block.constant_jacobian) {
    block.axis_aligned = all_axis_aligned(block, x_ref);
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
  block.constant_jacobian = all_parallelepipeds(block, x_ref);
  const double mu = block.material.mu, coefficient = block.hourglass_coefficient;
  if (block.constant_jacobian) {
    block.loop = packed_for_isa<hex8r_loop<true, 2>, hex8r_loop<true, 4>, hex8r_loop<true, 8>>(isa);
    fill_reference(block, x_ref, hex8r::parallelepiped_reference_size, lanes_for(isa),
                   [mu, coefficient](const ElementVectors& x, double* r) {
                     return hex8r::make_parallelepiped_reference(x, mu, coefficient, r);
                   });
  } else {
    block.loop = packed_for_isa<hex8r_loop<false, 2>, hex8r_loop<false, 4>, hex8r_loop<false, 8>>(isa);
    fill_reference(block, x_ref, hex8r::reference_size, lanes_for(isa),
                   [mu, coefficient](const ElementVectors& x, double* r) {
                     return hex8r::make_reference(x, mu, coefficient, r);
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
