// The gather -> kernel -> scatter loops over a range of a block's elements, for the
// element families (hex8_family.cpp, hex20_family.cpp): one element at a time
// (element_loop) or a pack of elements in the vector lanes (element_pack_loop);
// templates on the number of nodes and the value type, so a family writes only its kernel.
// Every node index is asserted within the nodal vectors: the sanitizer build compiles the
// families without instrumentation (src/element/CMakeLists.txt), and the asserts (off
// under NDEBUG) keep their every read and write of nodal data checked there.
#pragma once

#include <array>
#include <cassert>
#include <cstdint>
#include <cstring>
#include <limits>
#include <type_traits>

#include "common/nodal_vectors.hpp"
#include "common/simd_pack.hpp"
#include "element/corner_pack.hpp"
#include "element/element_block.hpp"
#include "element/node_values.hpp"

namespace exdyn::element {

template <int Nodes, class Vectors>
inline void gather(const NodalVectors& v, const std::uint32_t* nodes, Vectors& local) {
  const double* x = v.x.data();
  const double* y = v.y.data();
  const double* z = v.z.data();
  for (int k = 0; k < Nodes; ++k) {
    const std::uint32_t n = nodes[k];
    assert(n < v.size());
    local.x[k] = x[n];
    local.y[k] = y[n];
    local.z[k] = z[n];
  }
}

template <int Nodes, class Vectors>
inline void scatter_add(const Vectors& local, const std::uint32_t* nodes, NodalVectors& v) {
  double* x = v.x.data();
  double* y = v.y.data();
  double* z = v.z.data();
  for (int k = 0; k < Nodes; ++k) {
    const std::uint32_t n = nodes[k];
    assert(n < v.size());
    x[n] += local.x[k];
    y[n] += local.y[k];
    z[n] += local.z[k];
  }
}

// The element loop, one instantiation per kernel: kernel(reference, u, f, stress)
// returns the element's energies; `stride` doubles of reference data per element.
template <int Nodes, class Vectors, class Kernel>
ElementEnergies element_loop(const ElementBlock& block, std::uint32_t begin, std::uint32_t end,
                             const double* reference, std::size_t stride, const NodalVectors& u,
                             NodalVectors& f_int, double* stress, Kernel kernel) {
  ElementEnergies total;
  for (std::uint32_t e = begin; e < end; ++e) {
    const std::uint32_t* nodes = block.connectivity + Nodes * static_cast<std::size_t>(e);
    Vectors u_local{typename Vectors::Uninitialized{}};  // written whole by gather
    gather<Nodes>(u, nodes, u_local);
    Vectors f_local{typename Vectors::Uninitialized{}};  // the kernel writes every entry
    material::SymTensor element_stress;
    const ElementEnergies energies = kernel(reference + stride * e, u_local, f_local, element_stress);
    scatter_add<Nodes>(f_local, nodes, f_int);
    total.strain += energies.strain;
    total.hourglass += energies.hourglass;
    if (stress != nullptr) {
      double* out = stress + 6 * (static_cast<std::size_t>(block.first_element) + e);
      for (int k = 0; k < 6; ++k) out[k] = element_stress[k];
    }
  }
  return total;
}

// --- packs of elements: Lanes elements in the lanes of Pack<Lanes> (common/simd_pack.hpp)

// The gather of a pack: lane l from element l's nodes.
template <int Nodes, int Lanes>
NodeValues<Nodes, Pack<Lanes>> gather_pack(const NodalVectors& v,
                                           const std::uint32_t* const (&nodes)[Lanes]) {
  NodeValues<Nodes, Pack<Lanes>> local{
      typename NodeValues<Nodes, Pack<Lanes>>::Uninitialized{}};  // every entry written below
  const double* x = v.x.data();
  const double* y = v.y.data();
  const double* z = v.z.data();
  for (int k = 0; k < Nodes; ++k) {
    for (int lane = 0; lane < Lanes; ++lane) {
      const std::uint32_t n = nodes[lane][k];
      assert(n < v.size());
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
NodeValues<8, Pack<Lanes>> gather_row_pack(const NodalVectors& v, const std::uint32_t* nodes) {
  NodeValues<8, Pack<Lanes>> local{
      typename NodeValues<8, Pack<Lanes>>::Uninitialized{}};  // every entry written below
  for (int k = 0; k < 8; ++k) {
    assert(nodes[k] + Lanes <= v.size());
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
void scatter_add_row_pack(const NodeValues<8, Pack<Lanes>>& local, const std::uint32_t* nodes,
                          NodalVectors& v) {
  using Real = Pack<Lanes>;
  const IntPack<Lanes> shift = up_one_lane<Lanes>();
  constexpr int row_edges[4][2] = {{0, 1}, {3, 2}, {4, 5}, {7, 6}};
  const std::array<const std::array<Real, 8>*, 3> forces{&local.x, &local.y, &local.z};
  const std::array<double*, 3> out{v.x.data(), v.y.data(), v.z.data()};
  for (const auto& edge : row_edges) {
    const std::uint32_t n = nodes[edge[0]];
    assert(n + Lanes < v.size());
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

template <int Nodes, class Real>
void scatter_add_lane(const NodeValues<Nodes, Real>& local, int lane, const std::uint32_t* nodes,
                      NodalVectors& v) {
  double* x = v.x.data();
  double* y = v.y.data();
  double* z = v.z.data();
  for (int k = 0; k < Nodes; ++k) {
    const std::uint32_t n = nodes[k];
    assert(n < v.size());
    x[n] += lane_value(local.x[std::size_t(k)], lane);
    y[n] += lane_value(local.y[std::size_t(k)], lane);
    z[n] += lane_value(local.z[std::size_t(k)], lane);
  }
}

// The corner checks of block.corner_request on the pack of elements first .. first +
// Lanes - 1 (nodes: their connectivity; a row pack's x_ref loads as whole vectors):
// x = x_ref + u, the sum corner_checks.cpp's pass forms, into `checks`.
template <int Lanes>
void add_pack_corners(PackCorners<Lanes>& checks, const ElementBlock& block,
                      const NodeValues<8, Pack<Lanes>>& u_local, const std::uint32_t* const (&nodes)[Lanes],
                      bool row, std::uint32_t first, std::uint32_t end) {
  using Real = Pack<Lanes>;
  const CornerRequest& request = block.corner_request;
  const NodalVectors& x_ref = *request.x_ref;
  NodeValues<8, Real> x{typename NodeValues<8, Real>::Uninitialized{}};  // every entry written below
  for (int k = 0; k < 8; ++k) {
    Real rx, ry, rz;
    if (row) {
      rx = load<Real>(x_ref.x.data() + nodes[0][k], 0), ry = load<Real>(x_ref.y.data() + nodes[0][k], 0),
      rz = load<Real>(x_ref.z.data() + nodes[0][k], 0);
    } else {
      for (int lane = 0; lane < Lanes; ++lane) {
        const std::uint32_t n = nodes[lane][k];
        assert(n < x_ref.size());
        rx[lane] = x_ref.x[n], ry[lane] = x_ref.y[n], rz[lane] = x_ref.z[n];
      }
    }
    x.x[k] = rx + u_local.x[k], x.y[k] = ry + u_local.y[k], x.z[k] = rz + u_local.z[k];
  }
  checks.add(x, block, first, end, request.step, request.inversion);
}

// The energy that leaves with an element that failed at the last step, in the pass
// after (ElementFailure): its energy U + H at u^{n+1} less dt/2 f^{n+1}.v^{n+1/2}, J.
template <int Nodes, class Real>
double failed_energy(const ElementBlock& block, const NodeValues<Nodes, Real>& f, int lane,
                     const std::uint32_t* nodes, double energy) {
  const NodalVectors& v = *block.failure.velocity;
  double power = 0.0;  // f.v, W
  for (int k = 0; k < Nodes; ++k) {
    const std::uint32_t n = nodes[k];
    assert(n < v.size());
    power += lane_value(f.x[std::size_t(k)], lane) * v.x[n] + lane_value(f.y[std::size_t(k)], lane) * v.y[n] +
             lane_value(f.z[std::size_t(k)], lane) * v.z[n];
  }
  return energy - 0.5 * block.material_state.dt * power;
}

// Holds what an element marked distorted in this pass carries (ElementFailure::held).
template <int Nodes, class Real>
void hold_distorted(const ElementBlock& block, const NodeValues<Nodes, Real>& f, int lane,
                    std::uint32_t element, double energy) {
  double* held = block.failure.held.data() + ElementFailure::held_size(Nodes) * element;
  held[0] = energy;
  for (int k = 0; k < Nodes; ++k) {
    held[1 + 3 * k] = lane_value(f.x[std::size_t(k)], lane);
    held[2 + 3 * k] = lane_value(f.y[std::size_t(k)], lane);
    held[3 + 3 * k] = lane_value(f.z[std::size_t(k)], lane);
  }
}

// The energy that leaves with an element held at its last step: U^n + H^n + dt/2
// f^n.v^{n+1/2}, J; NaN where none was held.
template <int Nodes>
double held_energy(const ElementBlock& block, std::uint32_t element, const std::uint32_t* nodes) {
  const ElementFailure& failure = block.failure;
  if (failure.held.empty()) return std::numeric_limits<double>::quiet_NaN();
  const double* held = failure.held.data() + ElementFailure::held_size(Nodes) * element;
  const NodalVectors& v = *failure.velocity;
  double power = 0.0;  // f^n.v^{n+1/2}, W
  for (int k = 0; k < Nodes; ++k) {
    const std::uint32_t n = nodes[k];
    assert(n < v.size());
    power += held[1 + 3 * k] * v.x[n] + held[2 + 3 * k] * v.y[n] + held[3 + 3 * k] * v.z[n];
  }
  return held[0] + 0.5 * block.material_state.dt * power;
}

// The element loop over packs of Lanes consecutive elements: kernel(pack, u, f, stress)
// on the elements Lanes pack .. Lanes pack + Lanes - 1 at once returns their energies
// (strain, hourglass, and plastic work for the kernels of a material law); it finds the pack's reference data
// itself. Lanes outside [begin, end) are computed but neither scattered nor counted; the lanes past the
// block's last element take its first lane's nodes (hex8 layouts pad their reference
// data with zeros there). The forces are added lane by lane, in element order (a row
// pack, 8-node elements only: summed along its row edges first); the same order for
// any number of threads. Corners (8 nodes): the loop also runs the checks of
// block.corner_request on x = x_ref + u of each pack (corner_pack.hpp) when one is set,
// and [begin, end) must then be one chunk: its result goes to block.chunk_checks.
template <int Nodes, int Lanes, bool Corners = false, class Kernel>
ElementEnergies element_pack_loop(const ElementBlock& block, std::uint32_t begin, std::uint32_t end,
                                  const NodalVectors& u, NodalVectors& f_int, double* stress, Kernel kernel) {
  using Real = Pack<Lanes>;
  using Vectors = NodeValues<Nodes, Real>;
  static_assert(!Corners || Nodes == 8);
  ElementEnergies total;
  if (begin >= end) return total;
  const CornerRequest& request = block.corner_request;
  const bool corners = Corners && request.x_ref != nullptr;
  PackCorners<Lanes> checks(block, begin);
  for (std::uint32_t pack = begin / Lanes; pack <= (end - 1) / Lanes; ++pack) {
    std::uint32_t element[Lanes];
    const std::uint32_t* nodes[Lanes];
    for (int lane = 0; lane < Lanes; ++lane) {
      element[lane] = Lanes * pack + std::uint32_t(lane);
      const std::uint32_t present = element[lane] < block.count ? element[lane] : Lanes * pack;
      nodes[lane] = block.connectivity + Nodes * static_cast<std::size_t>(present);
    }
    // Erosion (ElementFailure): a pack holding an element that is not alive.
    const std::uint8_t* status = block.failure.any_not_alive ? block.failure.status.data() : nullptr;
    bool all_alive = true;
    if (status != nullptr)
      for (int lane = 0; lane < Lanes; ++lane)
        all_alive =
            all_alive && (element[lane] >= block.count || status[element[lane]] == ElementStatus::alive);
    // A whole row pack inside the range: vector gather and scatter.
    bool row = false;
    Vectors u_local{typename Vectors::Uninitialized{}};
    if constexpr (Nodes == 8) {
      row = !block.row_pack.empty() && block.row_pack[pack] != 0 && element[0] >= begin &&
            element[Lanes - 1] < end && all_alive;
      u_local = row ? gather_row_pack<Lanes>(u, nodes[0]) : gather_pack<Nodes, Lanes>(u, nodes);
    } else {
      u_local = gather_pack<Nodes, Lanes>(u, nodes);
    }
    // An eroded element runs in its reference shape (u = 0): it stays finite however
    // its nodes move, and its corners set no step and invert never.
    if (!all_alive)
      for (int lane = 0; lane < Lanes; ++lane)
        if (element[lane] < block.count && status[element[lane]] == ElementStatus::eroded)
          for (int k = 0; k < Nodes; ++k) u_local.x[k][lane] = u_local.y[k][lane] = u_local.z[k][lane] = 0.0;
    if constexpr (Corners) {
      if (corners) add_pack_corners<Lanes>(checks, block, u_local, nodes, row, Lanes * pack, end);
    }
    Vectors f_local{typename Vectors::Uninitialized{}};  // written whole by the kernel
    std::array<Real, 6> element_stress;
    const auto energies = kernel(pack, u_local, f_local, element_stress);
    if constexpr (Nodes == 8) {
      if (row) scatter_add_row_pack<Lanes>(f_local, nodes[0], f_int);
    }
    for (int lane = 0; lane < Lanes; ++lane) {
      if (element[lane] < begin || element[lane] >= end) continue;
      if (!all_alive && status[element[lane]] != ElementStatus::alive) {
        if (status[element[lane]] == ElementStatus::failed) {
          const double held = held_energy<Nodes>(block, element[lane], nodes[lane]);
          total.eroded += held == held
                              ? held
                              : failed_energy(block, f_local, lane, nodes[lane],
                                              lane_value(energies[0], lane) + lane_value(energies[1], lane));
        }
        if (stress != nullptr) {
          double* out = stress + 6 * (static_cast<std::size_t>(block.first_element) + element[lane]);
          for (int k = 0; k < 6; ++k) out[k] = 0.0;
        }
        continue;
      }
      if (!row) scatter_add_lane(f_local, lane, nodes[lane], f_int);
      if (!block.failure.held.empty() && block.failure.distorted[element[lane]] != 0)
        hold_distorted(block, f_local, lane, element[lane],
                       lane_value(energies[0], lane) + lane_value(energies[1], lane));
      total.strain += lane_value(energies[0], lane);
      total.hourglass += lane_value(energies[1], lane);
      if constexpr (std::tuple_size_v < std::decay_t < decltype(energies) >>> 2)
        total.plastic += lane_value(energies[2], lane);
      if (stress != nullptr) {
        double* out = stress + 6 * (static_cast<std::size_t>(block.first_element) + element[lane]);
        for (int k = 0; k < 6; ++k) out[k] = lane_value(element_stress[std::size_t(k)], lane);
      }
    }
  }
  if (corners) {
    const std::size_t chunk = chunk_index(block, begin);
    assert(block.chunk_begin[chunk] == begin && block.chunk_begin[chunk + 1] == end);
    block.chunk_checks[chunk] = checks.finish(request.inversion);
  }
  return total;
}

// An element that failed its reference check: bad input (the mesh, not the run).
[[noreturn]] void throw_inverted(std::uint32_t global_element, double det_jacobian);

}  // namespace exdyn::element
