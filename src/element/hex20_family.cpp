// The 20-node families: hex20 (3x3x3 Gauss points) and hex20r (2x2x2), with HRZ
// lumped mass and the element eigenvalue time step (docs/theory.md, "hex20").
//
// Two layouts of the reference data:
//  - general: per element, the inverse Jacobian and w det J at every Gauss point
//    (hex20::make_reference); shared, the table of dN/dxi at the Gauss points.
//    The kernel is hex20::internal_forces, on packs of 2, 4 or 8 elements (the ISA's
//    vector width: element_pack_loop).
//  - affine (every element a parallelepiped with straight edges, as in a box part):
//    the element's response is linear with a constant Jacobian, so elements with the
//    same Jacobian share one matrix [K; S] (66 x 60): f = K u, mean stress = S u. It is
//    built by applying the general kernel to the 60 unit displacements of one element
//    of the group, so it is the same quadrature to round-off. The loop multiplies it by
//    the displacements of up to `batch` elements at once (a small matrix product,
//    3,960 multiply-adds per element instead of about 11,600 at 27 Gauss points), the
//    elements in the vector lanes of the ISA.
#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <vector>

#include "common/errors.hpp"
#include "element/element_family.hpp"
#include "element/element_isa.hpp"
#include "element/element_loop.hpp"
#include "element/hex20.hpp"
#include "element/hex20_constitutive.hpp"
#include "element/hex20_matrix.hpp"

namespace exdyn::element {
namespace {

using hex20::ElementVectors20;

using hex20_setup::dofs;
using hex20_setup::element_matrix;
using hex20_setup::element_step;
using hex20_setup::matrix_rows;
using hex20_setup::matrix_size;
constexpr int batch = 8;                // elements per matrix product
constexpr std::size_t max_groups = 64;  // distinct Jacobians kept before falling back to the general layout

ElementVectors20 gather20(const NodalVectors& v, const std::uint32_t* nodes) {
  ElementVectors20 local{ElementVectors20::Uninitialized{}};
  gather<20>(v, nodes, local);
  return local;
}

// Gauss points per direction of a formulation.
int gauss_per_direction(const ElementBlock& block) {
  return block.formulation == input::Formulation::hex20 ? 3 : 2;
}

// --- general layout

// Packs of Lanes elements: their reference data (element after element in
// block.reference, as element_matrix and the time step read them) interleaved into a
// local buffer, then the kernel on the whole pack. The copy is 10 G + 1 loads per
// element against about 430 G multiply-adds of the kernel.
template <int GaussPoints, int Lanes>
ElementEnergies general_loop(const ElementBlock& block, std::uint32_t begin, std::uint32_t end,
                             const NodalVectors& u, NodalVectors& f_int, double* stress) {
  using Real = Pack<Lanes>;
  constexpr int stride = hex20::reference_size(GaussPoints);
  const double lambda = block.material.lambda, mu = block.material.mu;
  const double* table = block.shared.data();
  const double* data = block.reference.data();
  const std::uint32_t count = block.count;
  return element_pack_loop<20, Lanes>(
      block, begin, end, u, f_int, stress,
      [lambda, mu, table, data, count](std::uint32_t pack, const NodeValues<20, Real>& u_local,
                                       NodeValues<20, Real>& f_local, std::array<Real, 6>& s) {
        double interleaved[stride * Lanes];
        for (int lane = 0; lane < Lanes; ++lane) {
          const std::uint32_t element = Lanes * pack + std::uint32_t(lane);
          // Lanes past the block's end repeat the pack's first element (not scattered).
          const double* mine = data + std::size_t(stride) * (element < count ? element : Lanes * pack);
          for (int k = 0; k < stride; ++k) interleaved[Lanes * k + lane] = mine[k];
        }
        return std::array<Real, 2>{
            hex20::internal_forces(GaussPoints, table, interleaved, lambda, mu, u_local, f_local, s), Real{}};
      });
}

// The loop of a material law (constitutive.hpp): the general layout, the law at every
// Gauss point, the point states in the block.
template <class Flow, bool Finite, int GaussPoints, int Lanes>
ElementEnergies law_loop_20(const ElementBlock& block, std::uint32_t begin, std::uint32_t end,
                            const NodalVectors& u, NodalVectors& f_int, double* stress) {
  using Real = Pack<Lanes>;
  constexpr int stride = hex20::reference_size(GaussPoints);
  const Flow& flow = flow_of<Flow>(block.law);
  const material::ElasticConstants elastic = block.material;
  const double dt = block.material_state.dt;
  const double* table = block.shared.data();
  const double* data = block.reference.data();
  const std::uint32_t count = block.count;
  return element_pack_loop<20, Lanes>(
      block, begin, end, u, f_int, stress,
      [&](std::uint32_t pack, const NodeValues<20, Real>& u_local, NodeValues<20, Real>& f_local,
          std::array<Real, 6>& s) {
        double interleaved[stride * Lanes];
        for (int lane = 0; lane < Lanes; ++lane) {
          const std::uint32_t element = Lanes * pack + std::uint32_t(lane);
          const double* mine = data + std::size_t(stride) * (element < count ? element : Lanes * pack);
          for (int k = 0; k < stride; ++k) interleaved[Lanes * k + lane] = mine[k];
        }
        const PackStates<Flow, Lanes> states(block, pack, GaussPoints);
        const ConstitutiveResult<Real> r = hex20::constitutive_forces<Flow, Finite, GaussPoints>(
            table, interleaved, elastic, flow, u_local, f_local, states.old_state, states.new_state, dt);
        s = r.mean_stress;
        store_plastic_strain(block, pack, r.eps_p);
        return std::array<Real, 3>{r.internal, Real{}, r.plastic};
      });
}

// --- affine layout

// F (66 x batch) = [K; S] (66 x 60, row-major) U (60 x batch): Rows rows at a time, the
// batch's 8 columns in packs of Lanes (8 / Lanes packs per row), so Rows x 8 / Lanes
// independent sums hide the multiply-add latency. Rows divides 66.
template <int Lanes>
void multiply(const double* matrix, const double (&u)[dofs][batch], double (&f)[matrix_rows][batch]) {
  using Real = Pack<Lanes>;
  constexpr int packs = batch / Lanes;
  constexpr int rows_at_once = Lanes == 2 ? 2 : 6;
  static_assert(batch % Lanes == 0 && matrix_rows % rows_at_once == 0);
  for (int r = 0; r < matrix_rows; r += rows_at_once) {
    Real sum[rows_at_once][packs] = {};
    for (int c = 0; c < dofs; ++c) {
      Real column[packs];
      for (int p = 0; p < packs; ++p) column[p] = load<Real>(&u[c][Lanes * p], 0);
      for (int i = 0; i < rows_at_once; ++i) {
        const double k = matrix[dofs * (r + i) + c];
        for (int p = 0; p < packs; ++p) sum[i][p] += k * column[p];
      }
    }
    for (int i = 0; i < rows_at_once; ++i)
      for (int p = 0; p < packs; ++p) store(&f[r + i][Lanes * p], sum[i][p]);
  }
}

template <int Lanes>
ElementEnergies affine_loop(const ElementBlock& block, std::uint32_t begin, std::uint32_t end,
                            const NodalVectors& u, NodalVectors& f_int, double* stress) {
  ElementEnergies total;
  alignas(64) double u_batch[dofs][batch];
  alignas(64) double f_batch[matrix_rows][batch];
  const double* ux = u.x.data();
  const double* uy = u.y.data();
  const double* uz = u.z.data();
  double* fx = f_int.x.data();
  double* fy = f_int.y.data();
  double* fz = f_int.z.data();
  for (std::uint32_t e = begin; e < end;) {
    // A run of up to `batch` consecutive elements that share one matrix.
    const std::uint32_t group = block.reference_index[e];
    int count = 1;
    while (count < batch && e + std::uint32_t(count) < end &&
           block.reference_index[e + std::uint32_t(count)] == group)
      ++count;
    for (int slot = 0; slot < batch; ++slot) {
      if (slot >= count) {  // unused columns: zeros, computed and dropped
        for (int c = 0; c < dofs; ++c) u_batch[c][slot] = 0.0;
        continue;
      }
      const std::uint32_t* nodes = block.connectivity + 20 * (std::size_t(e) + std::size_t(slot));
      for (int k = 0; k < 20; ++k) {
        const std::uint32_t n = nodes[k];
        assert(n < u.size());  // element_loop.hpp: the sanitizer build does not instrument this file
        u_batch[k][slot] = ux[n];
        u_batch[20 + k][slot] = uy[n];
        u_batch[40 + k][slot] = uz[n];
      }
    }
    multiply<Lanes>(block.shared.data() + std::size_t(matrix_size) * group, u_batch, f_batch);
    for (int slot = 0; slot < count; ++slot) {
      const std::uint32_t* nodes = block.connectivity + 20 * (std::size_t(e) + std::size_t(slot));
      double energy = 0.0;
      for (int k = 0; k < 20; ++k) {
        const std::uint32_t n = nodes[k];
        assert(n < f_int.size());
        fx[n] += f_batch[k][slot];
        fy[n] += f_batch[20 + k][slot];
        fz[n] += f_batch[40 + k][slot];
      }
      for (int c = 0; c < dofs; ++c) energy += u_batch[c][slot] * f_batch[c][slot];
      total.strain += 0.5 * energy;  // u.f / 2
      if (stress != nullptr) {
        double* out = stress + 6 * (std::size_t(block.first_element) + e + std::uint32_t(slot));
        for (int k = 0; k < 6; ++k) out[k] = f_batch[dofs + k][slot];
      }
    }
    e += std::uint32_t(count);
  }
  return total;
}

// Same Jacobian to round-off: the inverse Jacobian and w det J at the first Gauss
// point agree to 1e-12 of their size (an affine element's are the same at every point).
bool same_jacobian(const double* a, const double* b) {
  double size = 0.0, difference = 0.0;
  for (int k = 0; k < 9; ++k)
    size = std::max(size, std::abs(a[k])), difference = std::max(difference, std::abs(a[k] - b[k]));
  return difference <= 1e-12 * size && std::abs(a[9] - b[9]) <= 1e-12 * std::abs(a[9]);
}

// A group's first element as ElementVectors20 (ElementBlock::group_points' layout).
ElementVectors20 group_element(const std::array<double, 60>& points) {
  ElementVectors20 x{ElementVectors20::Uninitialized{}};
  for (int k = 0; k < 20; ++k)
    x.x[k] = points[std::size_t(k)], x.y[k] = points[std::size_t(20 + k)],
    x.z[k] = points[std::size_t(40 + k)];
  return x;
}

// Elements [0, count) grouped by Jacobian in order (`reference(e)` their reference
// data): an element joins the previous element's group or else the first whose
// first element it matches (same_jacobian), or starts a group. `first` are the
// groups' first elements: max_groups + 1 of them when there are more (no affine layout).
template <class Reference>
void group_by_jacobian(std::uint32_t count, Reference reference, std::vector<std::uint32_t>& index,
                       std::vector<std::uint32_t>& first) {
  index.resize(count);
  for (std::uint32_t e = 0; e < count && first.size() <= max_groups; ++e) {
    const double* mine = reference(e);
    std::size_t g = 0;
    // The previous element's group first: runs of equal elements are the rule.
    if (e > 0 && same_jacobian(reference(first[index[e - 1]]), mine))
      g = index[e - 1];
    else
      for (g = 0; g < first.size(); ++g)
        if (same_jacobian(reference(first[g]), mine)) break;
    if (g == first.size()) first.push_back(e);
    index[e] = static_cast<std::uint32_t>(g);
  }
}

template <int GaussPerDirection>
void prepare(ElementBlock& block, const NodalVectors& x_ref) {
  constexpr int gauss_points = GaussPerDirection * GaussPerDirection * GaussPerDirection;
  constexpr int stride = hex20::reference_size(gauss_points);
  const hex20::GaussRule rule = hex20::gauss_rule(GaussPerDirection);
  std::vector<double> table(std::size_t(hex20::table_stride) * gauss_points);
  hex20::derivative_table(rule, table.data());

  block.reference.assign(std::size_t(stride) * block.count, 0.0);
  block.reference_per_element = std::size_t(stride);  // 0 below when the block keeps only shared matrices
  bool affine = block.whole.parallelepipeds;          // a rank's part takes the whole block's layout
  for (std::uint32_t e = 0; e < block.count; ++e) {
    const ElementVectors20 x = gather20(x_ref, block.connectivity + 20 * std::size_t(e));
    const double smallest =
        hex20::make_reference(x, rule, table.data(), block.reference.data() + std::size_t(stride) * e);
    if (!(smallest > 0.0)) throw_inverted(block.first_element + e, smallest);
    affine = affine && hex20::is_affine(x);
  }
  // Group the elements by Jacobian (a box part: one group, or one per grading step),
  // each group's reference data from its first element: this block's, or the whole
  // block's where this is a rank's part of it (group_points given).
  std::vector<double> group_reference;  // per group
  if (affine && block.whole.group_points.empty()) {
    std::vector<std::uint32_t> first;
    group_by_jacobian(
        block.count, [&](std::uint32_t e) { return block.reference.data() + std::size_t(stride) * e; },
        block.reference_index, first);
    affine = first.size() <= max_groups;
    for (const std::uint32_t e : first) {
      const double* data = block.reference.data() + std::size_t(stride) * e;
      group_reference.insert(group_reference.end(), data, data + stride);
      const ElementVectors20 x = gather20(x_ref, block.connectivity + 20 * std::size_t(e));
      std::array<double, 60>& points = block.group_points.emplace_back();
      for (int k = 0; k < 20; ++k)
        points[std::size_t(k)] = x.x[k], points[std::size_t(20 + k)] = x.y[k],
        points[std::size_t(40 + k)] = x.z[k];
    }
  } else if (affine) {
    block.group_points = block.whole.group_points;
    affine = block.group_points.size() <= max_groups;
    group_reference.resize(std::size_t(stride) * block.group_points.size());
    for (std::size_t g = 0; g < block.group_points.size(); ++g)
      hex20::make_reference(group_element(block.group_points[g]), rule, table.data(),
                            group_reference.data() + std::size_t(stride) * g);
    block.reference_index.resize(block.count);
    for (std::uint32_t e = 0; e < block.count && affine; ++e) {
      const double* mine = block.reference.data() + std::size_t(stride) * e;
      std::size_t g = 0;
      if (e > 0 &&
          same_jacobian(group_reference.data() + std::size_t(stride) * block.reference_index[e - 1], mine))
        g = block.reference_index[e - 1];
      else
        while (g < block.group_points.size() &&
               !same_jacobian(group_reference.data() + std::size_t(stride) * g, mine))
          ++g;
      if (g == block.group_points.size())
        throw std::logic_error("hex20 prepare: an element matches none of the whole block's Jacobians");
      block.reference_index[e] = static_cast<std::uint32_t>(g);
    }
  }
  if (!block.law.linear_small()) {  // the law's loop on the general layout
    block.constant_jacobian = false;
    block.reference_index.clear();
    block.group_points.clear();
    block.shared = std::move(table);
    const Isa isa = selected_isa();
    block.loop = law_loop(block.law, [isa]<class Flow, bool Finite>() {
      return packed_for_isa<law_loop_20<Flow, Finite, gauss_points, 2>,
                            law_loop_20<Flow, Finite, gauss_points, 4>,
                            law_loop_20<Flow, Finite, gauss_points, 8>>(isa);
    });
    return;
  }
  block.constant_jacobian = affine;
  if (affine) {
    block.shared.assign(std::size_t(matrix_size) * block.group_points.size(), 0.0);
    for (std::size_t g = 0; g < block.group_points.size(); ++g)
      element_matrix(gauss_points, table.data(), group_reference.data() + std::size_t(stride) * g,
                     block.material.lambda, block.material.mu,
                     block.shared.data() + std::size_t(matrix_size) * g);
    block.reference.clear();
    block.reference.shrink_to_fit();
    block.reference_per_element = 0;
    block.loop = packed_for_isa<affine_loop<2>, affine_loop<4>, affine_loop<8>>(selected_isa());
  } else {
    block.reference_index.clear();
    block.group_points.clear();
    block.shared = std::move(table);
    block.loop = packed_for_isa<general_loop<gauss_points, 2>, general_loop<gauss_points, 4>,
                                general_loop<gauss_points, 8>>(selected_isa());
  }
}

void add_hrz_mass(const ElementBlock& block, const NodalVectors& x_ref, std::vector<double>& mass) {
  const double rho = block.material.density;
  for (std::uint32_t e = 0; e < block.count; ++e) {
    const std::uint32_t* nodes = block.connectivity + 20 * std::size_t(e);
    const std::array<double, 20> m = hex20::hrz_masses(gather20(x_ref, nodes), rho);
    for (int k = 0; k < 20; ++k) {
      assert(nodes[k] < mass.size());
      mass[nodes[k]] += m[k];
    }
  }
}

// The element eigenvalue rule: min over elements of 2 / omega_max(element). The mesh's
// highest frequency is at most the largest element's (its Rayleigh quotient is a
// ratio of sums of element terms), so Courant <= 1 is stable for the undamped mesh.
// An affine block needs one eigenvalue per group of equal elements.
double element_eigenvalue_step(const ElementBlock& block, const NodalVectors& x_ref) {
  const int per_direction = gauss_per_direction(block);
  const int gauss_points = per_direction * per_direction * per_direction;
  const hex20::GaussRule rule = hex20::gauss_rule(per_direction);
  std::vector<double> table(std::size_t(hex20::table_stride) * std::size_t(gauss_points));
  hex20::derivative_table(rule, table.data());
  double smallest = std::numeric_limits<double>::infinity();
  const auto count = static_cast<std::ptrdiff_t>(block.count);
  if (block.constant_jacobian) {  // each group's step from its first element (ElementBlock::group_points)
    for (std::size_t g = 0; g < block.group_points.size(); ++g)
      smallest = std::min(smallest, element_step(block.shared.data() + std::size_t(matrix_size) * g,
                                                 hex20::hrz_masses(group_element(block.group_points[g]),
                                                                   block.material.density)));
    return smallest;
  }
#pragma omp parallel for schedule(dynamic, 16) reduction(min : smallest)
  for (std::ptrdiff_t k = 0; k < count; ++k) {
    const auto e = static_cast<std::size_t>(k);
    std::vector<double> matrix(static_cast<std::size_t>(matrix_size));
    element_matrix(gauss_points, table.data(),
                   block.reference.data() + std::size_t(hex20::reference_size(gauss_points)) * e,
                   block.material.lambda, block.material.mu, matrix.data());
    const std::array<double, 20> m =
        hex20::hrz_masses(gather20(x_ref, block.connectivity + 20 * e), block.material.density);
    smallest = std::min(smallest, element_step(matrix.data(), m));
  }
  return smallest;
}

template <int GaussPerDirection>
std::vector<std::uint32_t> group_starts(std::uint32_t count, const std::uint32_t* connectivity,
                                        const NodalVectors& x_ref) {
  constexpr int gauss_points = GaussPerDirection * GaussPerDirection * GaussPerDirection;
  constexpr int stride = hex20::reference_size(gauss_points);
  const hex20::GaussRule rule = hex20::gauss_rule(GaussPerDirection);
  std::vector<double> table(std::size_t(hex20::table_stride) * gauss_points);
  hex20::derivative_table(rule, table.data());
  std::vector<double> reference(std::size_t(stride) * count);
  for (std::uint32_t e = 0; e < count; ++e) {
    const ElementVectors20 x = gather20(x_ref, connectivity + 20 * std::size_t(e));
    if (!hex20::is_affine(x)) return {};
    hex20::make_reference(x, rule, table.data(), reference.data() + std::size_t(stride) * e);
  }
  std::vector<std::uint32_t> index, first;
  group_by_jacobian(
      count, [&](std::uint32_t e) { return reference.data() + std::size_t(stride) * e; }, index, first);
  return first;
}

WholeBlock hex20_layout(std::uint32_t count, const std::uint32_t* connectivity, const NodalVectors& x_ref) {
  WholeBlock layout;
  for (std::uint32_t e = 0; e < count && layout.parallelepipeds; ++e)
    layout.parallelepipeds = hex20::is_affine(gather20(x_ref, connectivity + 20 * std::size_t(e)));
  return layout;
}

}  // namespace

std::vector<std::uint32_t> jacobian_group_starts(input::Formulation formulation, std::uint32_t count,
                                                 const std::uint32_t* connectivity,
                                                 const NodalVectors& x_ref) {
  switch (formulation) {
    case input::Formulation::hex20:
      return group_starts<3>(count, connectivity, x_ref);
    case input::Formulation::hex20r:
      return group_starts<2>(count, connectivity, x_ref);
    default:
      return {};
  }
}

const ElementFamily hex20_family{"hex20",     20, prepare<3>, add_hrz_mass, element_eigenvalue_step,
                                 hex20_layout};
const ElementFamily hex20r_family{"hex20r",    20, prepare<2>, add_hrz_mass, element_eigenvalue_step,
                                  hex20_layout};

}  // namespace exdyn::element
