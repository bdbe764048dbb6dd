// The passes over the corners of the current configuration (corner_checks.hpp).
#include "element/corner_checks.hpp"

#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>
#include <cstddef>
#include <limits>
#include <vector>

#include "common/errors.hpp"
#include "common/parallel.hpp"
#include "common/simd_pack.hpp"
#include "element/corner_pack.hpp"
#include "element/element_isa.hpp"
#include "element/element_loop.hpp"
#include "element/hex8_constitutive.hpp"

namespace exdyn::element {

namespace {

// The corners x_ref + u of the pack of Lanes elements from `first` on; lanes past the
// block's end repeat its last element. A row pack (ElementBlock::row_pack) gathers
// with vector loads: the same sums.
template <int Lanes>
BasicElementVectors<Pack<Lanes>> gather_corners(const ElementBlock& block, const NodalVectors& x_ref,
                                                const NodalVectors& u, std::uint32_t first, bool row) {
  using Real = Pack<Lanes>;
  BasicElementVectors<Real> x{typename BasicElementVectors<Real>::Uninitialized{}};
  if (row) {
    const std::uint32_t* nodes = block.connectivity + 8 * std::size_t(first);
    for (int k = 0; k < 8; ++k) {
      const std::size_t n = nodes[k];
      assert(n + Lanes <= x_ref.size() && x_ref.size() == u.size());
      x.x[k] = load<Real>(x_ref.x.data() + n, 0) + load<Real>(u.x.data() + n, 0);
      x.y[k] = load<Real>(x_ref.y.data() + n, 0) + load<Real>(u.y.data() + n, 0);
      x.z[k] = load<Real>(x_ref.z.data() + n, 0) + load<Real>(u.z.data() + n, 0);
    }
    return x;
  }
  for (int lane = 0; lane < Lanes; ++lane) {
    const std::uint32_t e = std::min(first + std::uint32_t(lane), block.count - 1);
    const std::uint32_t* nodes = block.connectivity + std::size_t(block.nodes_per_element) * e;
    for (int k = 0; k < 8; ++k) {
      const std::uint32_t n = nodes[k];
      assert(n < x_ref.size() && x_ref.size() == u.size());
      x.x[k][lane] = x_ref.x[n] + u.x[n], x.y[k][lane] = x_ref.y[n] + u.y[n],
      x.z[k][lane] = x_ref.z[n] + u.z[n];
    }
  }
  return x;
}

// An eroded element's corners in its reference shape (ElementFailure), as the
// element pass has them: it sets no step of its own and never inverts.
template <int Lanes>
void reference_shape_of_eroded(const ElementBlock& block, const NodalVectors& x_ref, std::uint32_t first,
                               BasicElementVectors<Pack<Lanes>>& x) {
  for (int lane = 0; lane < Lanes; ++lane) {
    const std::uint32_t e = std::min(first + std::uint32_t(lane), block.count - 1);
    if (block.failure.status[e] != ElementStatus::eroded) continue;
    const std::uint32_t* nodes = block.connectivity + std::size_t(block.nodes_per_element) * e;
    for (int k = 0; k < 8; ++k)
      x.x[k][lane] = x_ref.x[nodes[k]], x.y[k][lane] = x_ref.y[nodes[k]], x.z[k][lane] = x_ref.z[nodes[k]];
  }
}

// The elements [begin, end) of a chunk (begin a multiple of Lanes) in packs of Lanes.
template <int Lanes, bool Step, bool Inversion>
CornerChecks corner_packs(const ElementBlock& block, const NodalVectors& x_ref, const NodalVectors& u,
                          std::uint32_t begin, std::uint32_t end) {
  PackCorners<Lanes> corners(block, begin);
  const bool rows = block.row_pack.size() == (std::size_t(block.count) + Lanes - 1) / Lanes;
  for (std::uint32_t first = begin; first < end; first += Lanes) {
    BasicElementVectors<Pack<Lanes>> x =
        gather_corners<Lanes>(block, x_ref, u, first, rows && block.row_pack[first / Lanes] != 0);
    if (block.failure.any_not_alive) reference_shape_of_eroded<Lanes>(block, x_ref, first, x);
    corners.add(x, block, first, end, Step, Inversion);
  }
  return corners.finish(Inversion);
}

using CornerFn = CornerChecks (*)(const ElementBlock&, const NodalVectors&, const NodalVectors&,
                                  std::uint32_t, std::uint32_t);

template <CornerFn F>
[[gnu::flatten]] CornerChecks corners_x86_64_v2(const ElementBlock& b, const NodalVectors& x,
                                                const NodalVectors& u, std::uint32_t begin,
                                                std::uint32_t end) {
  return F(b, x, u, begin, end);
}
template <CornerFn F>
[[gnu::target("arch=x86-64-v3"), gnu::flatten]] CornerChecks corners_x86_64_v3(const ElementBlock& b,
                                                                               const NodalVectors& x,
                                                                               const NodalVectors& u,
                                                                               std::uint32_t begin,
                                                                               std::uint32_t end) {
  return F(b, x, u, begin, end);
}
template <CornerFn F>
[[gnu::target("arch=x86-64-v4"), gnu::flatten]] CornerChecks corners_x86_64_v4(const ElementBlock& b,
                                                                               const NodalVectors& x,
                                                                               const NodalVectors& u,
                                                                               std::uint32_t begin,
                                                                               std::uint32_t end) {
  return F(b, x, u, begin, end);
}

// The pass of the element loops' ISA and pack width (element_isa.hpp).
template <bool Step, bool Inversion>
CornerFn corners_for_isa() {
  switch (selected_isa()) {
    case Isa::x86_64_v4:
      return corners_x86_64_v4<corner_packs<8, Step, Inversion>>;
    case Isa::x86_64_v3:
      return corners_x86_64_v3<corner_packs<4, Step, Inversion>>;
    case Isa::x86_64_v2:
      break;
  }
  return corners_x86_64_v2<corner_packs<2, Step, Inversion>>;
}

// The pass over every chunk of the block on the threads (static, as the element pass:
// each thread reads the nodes it updates), then the chunks in order: the first smallest step and the first
// inverted element of the block, whatever the threads.
// The chunks' results in chunk order: the first smallest step and the first inverted
// element of the block, whatever the threads.
CornerChecks reduce_chunks(const ElementBlock& block) {
  CornerChecks result;
  result.step = {std::numeric_limits<double>::infinity(), block.first_element};
  result.inverted.safety_radius = std::numeric_limits<double>::infinity();
  if (block.count == 0) return result;
  const std::vector<CornerChecks>& chunks = block.chunk_checks;
  result.step = chunks.front().step;
  for (const CornerChecks& chunk : chunks) {
    if (chunk.step.dt < result.step.dt) result.step = chunk.step;
    if (result.inverted.found) continue;
    if (chunk.inverted.found)
      result.inverted = chunk.inverted;
    else
      result.inverted.safety_radius = std::min(result.inverted.safety_radius, chunk.inverted.safety_radius);
  }
  if (result.inverted.found) result.inverted.safety_radius = 0.0;
  return result;
}

// The pass over every chunk of the block on the threads (static, as the element pass:
// each thread reads the nodes it updates), reduced in chunk order.
template <bool Step, bool Inversion>
CornerChecks corner_pass(const ElementBlock& block, const NodalVectors& x_ref, const NodalVectors& u) {
  if (block.count == 0) return reduce_chunks(block);
  const CornerFn pass = corners_for_isa<Step, Inversion>();
  std::vector<CornerChecks>& chunks = block.chunk_checks;
  const auto count = static_cast<std::ptrdiff_t>(block.chunk_begin.size() - 1);
  EXDYN_ASSERT(chunks.size() == std::size_t(count));
  parallel_for_static(count, [&](std::ptrdiff_t c) {
    chunks[std::size_t(c)] =
        pass(block, x_ref, u, block.chunk_begin[std::size_t(c)], block.chunk_begin[std::size_t(c) + 1]);
  });
  return reduce_chunks(block);
}

}  // namespace

CurrentStep current_time_step(const ElementBlock& block, const NodalVectors& x_ref, const NodalVectors& u) {
  return corner_pass<true, false>(block, x_ref, u).step;
}

InvertedElement find_inverted_element(const ElementBlock& block, const NodalVectors& x_ref,
                                      const NodalVectors& u) {
  return corner_pass<false, true>(block, x_ref, u).inverted;
}

CornerChecks check_corners(const ElementBlock& block, const NodalVectors& x_ref, const NodalVectors& u) {
  return corner_pass<true, true>(block, x_ref, u);
}

void request_corner_checks(const ElementBlock& block, const NodalVectors& x_ref, bool step, bool inversion) {
  EXDYN_ASSERT(block.corners_in_pass && (step || inversion));
  block.corner_request = {&x_ref, step, inversion};
}

CornerChecks corner_checks_of_pass(const ElementBlock& block) {
  EXDYN_ASSERT(block.corner_request.x_ref != nullptr);
  block.corner_request = {};
  return reduce_chunks(block);
}

InvertedElement find_inverted_element(const ElementBlock& block, std::uint32_t element_begin,
                                      std::uint32_t element_end, const NodalVectors& x_ref,
                                      const NodalVectors& u) {
  EXDYN_ASSERT(element_begin <= element_end && element_end <= block.count);
  double smallest_ratio = std::numeric_limits<double>::infinity();  // det J / ||J||_F^2, m
  for (std::uint32_t e = element_begin; e < element_end; ++e) {
    if (block.failure.any_not_alive && block.failure.status[e] == ElementStatus::eroded) continue;
    const std::uint32_t* nodes = block.connectivity + std::size_t(block.nodes_per_element) * e;
    NodeValues<8> x0, du;  // the corners
    gather<8>(x_ref, nodes, x0);
    gather<8>(u, nodes, du);
    std::array<double, 8> x, y, z;
    for (int k = 0; k < 8; ++k) x[k] = x0.x[k] + du.x[k], y[k] = x0.y[k] + du.y[k], z[k] = x0.z[k] + du.z[k];
    for (int a = 0; a < 8; ++a) {
      const int i = corner::neighbour[a][0], j = corner::neighbour[a][1], k = corner::neighbour[a][2];
      const double ax = x[i] - x[a], ay = y[i] - y[a], az = z[i] - z[a];
      const double bx = x[j] - x[a], by = y[j] - y[a], bz = z[j] - z[a];
      const double cx = x[k] - x[a], cy = y[k] - y[a], cz = z[k] - z[a];
      const double det = corner::orientation[a] *
                         (ax * (by * cz - bz * cy) - ay * (bx * cz - bz * cx) + az * (bx * cy - by * cx));
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

}  // namespace exdyn::element
