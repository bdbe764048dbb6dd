// MappedLattice (mesh/mapped.hpp): the lattice of a mapped part numbered without storing
// it, from the block layouts of mesh/mapped_blocks.hpp.
#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

#include "common/errors.hpp"
#include "mesh/mapped.hpp"
#include "mesh/mapped_blocks.hpp"

namespace exdyn::mesh {

using namespace mapped;

struct MappedLattice::Layout {
  // Side s of a block is the lattice plane p_a = 0 (s = 2 a) or p_a = size_a - 1 (s = 2 a
  // + 1); glued to a side of block `other`, its point with in-side lattice coordinates
  // (u, v) along the axes a + 1 and a + 2 (mod 3) is the other's origin + u d1 + v d2.
  struct Glue {
    int other = -1;
    std::array<int, 3> origin{}, d1{}, d2{};
  };
  struct LatticeBlock {
    Block block;
    std::array<int, 3> size{};        // order n + 1 lattice points along each axis
    std::array<int, 3> lo{}, hi{};    // the kept elements: lo <= index < hi along each axis
    std::uint32_t first_element = 0;  // of the part
    std::uint32_t elements = 0;
    bool mirrored = false;  // a left-handed map: every element mirrored (add_mapped_part)
    std::array<Glue, 6> glue;
    std::array<std::vector<std::uint32_t>, 6> sides;  // node of each point of side s (no_node: none)
    std::size_t first_row = 0;                        // row (K, J) is first_row + K size_1 + J
  };
  struct Where {
    int block = 0;
    std::array<int, 3> p{};
  };

  input::PartOptions options;
  int order = 1, nodes_per_element = 8;
  std::vector<LatticeBlock> blocks;
  // The first node of each row of each block (rows of all blocks in order), then the
  // node count. A row off the block's sides has its points off the sides counted in
  // closed form, and its two end points (on sides I = 0 and I = end) in row_ends: bit
  // 1 and bit 2 set where each is numbered in this row.
  std::vector<std::uint32_t> row_start;
  std::vector<std::uint8_t> row_ends;
  std::uint32_t elements = 0;
  std::array<int, 20> mirror{};
  std::vector<std::pair<input::PartFace, Face>> faces;

  bool valid(const std::array<int, 3>& p) const {
    return (p[0] % order) + (p[1] % order) + (p[2] % order) <= 1;
  }
  bool on_side(const LatticeBlock& b, const std::array<int, 3>& p) const {
    for (std::size_t a = 0; a < 3; ++a)
      if (p[a] == 0 || p[a] == b.size[a] - 1) return true;
    return false;
  }
  static bool on(const LatticeBlock& b, int s, const std::array<int, 3>& p) {
    const auto a = std::size_t(s / 2);
    return p[a] == (s % 2 == 0 ? 0 : b.size[a] - 1);
  }
  static std::size_t side_index(const LatticeBlock& b, int s, const std::array<int, 3>& p) {
    const std::size_t a = std::size_t(s / 2), a1 = (a + 1) % 3, a2 = (a + 2) % 3;
    return std::size_t(p[a1]) + std::size_t(b.size[a1]) * std::size_t(p[a2]);
  }
  // True where a kept element of the block has the point (the kept box, closed).
  bool used_in(const LatticeBlock& b, const std::array<int, 3>& p) const {
    for (std::size_t a = 0; a < 3; ++a)
      if (b.lo[a] >= b.hi[a] || p[a] < order * b.lo[a] || p[a] > order * b.hi[a]) return false;
    return true;
  }
  Point point_at(int block, const std::array<int, 3>& p) const {
    const double o = order;
    return to_global(options, blocks[std::size_t(block)].block.at(p[0] / o, p[1] / o, p[2] / o));
  }
  // Every appearance of a point (one per block holding it), through the glued sides.
  int appearances(const Where& w, std::array<Where, 8>& out) const {
    int count = 0;
    out[std::size_t(count++)] = w;
    for (int at = 0; at < count; ++at) {
      const Where here = out[std::size_t(at)];
      const LatticeBlock& b = blocks[std::size_t(here.block)];
      for (int s = 0; s < 6; ++s) {
        const Glue& g = b.glue[std::size_t(s)];
        if (g.other < 0 || !on(b, s, here.p)) continue;
        const std::size_t a = std::size_t(s / 2), a1 = (a + 1) % 3, a2 = (a + 2) % 3;
        Where there{g.other, {}};
        for (std::size_t c = 0; c < 3; ++c)
          there.p[c] = g.origin[c] + here.p[a1] * g.d1[c] + here.p[a2] * g.d2[c];
        bool known = false;
        for (int k = 0; k < count; ++k) known = known || out[std::size_t(k)].block == there.block;
        if (!known) {
          EXDYN_ASSERT(count < 8);
          out[std::size_t(count++)] = there;
        }
      }
    }
    return count;
  }
  // The node of a point on a side of its block (no_node: no kept element has it).
  std::uint32_t side_node(const LatticeBlock& b, const std::array<int, 3>& p) const {
    for (int s = 0; s < 6; ++s)
      if (on(b, s, p)) return b.sides[std::size_t(s)][side_index(b, s, p)];
    return no_node;
  }
  // The points of a row: every I (step 1) or the even ones (step 2), or none (0).
  int row_step(int j, int k) const {
    const int odd = (j % order) + (k % order);
    return odd == 0 ? 1 : (odd == 1 ? 2 : 0);
  }
  // How many of the row's points I in [first, last] there are.
  static int count_in(int first, int last, int step) {
    if (step == 0 || last < first) return 0;
    return step == 1 ? last - first + 1 : last / 2 - (first + 1) / 2 + 1;
  }
  // The interior points of a row off the sides that kept elements have: I in [first, last].
  std::array<int, 2> used_interior(const LatticeBlock& b, int j, int k) const {
    if (!used_in(b, {order * b.lo[0], j, k})) return {1, 0};
    return {std::max(1, order * b.lo[0]), std::min(b.size[0] - 2, order * b.hi[0])};
  }
  std::uint32_t node(int block, const std::array<int, 3>& p) const {
    const LatticeBlock& b = blocks[std::size_t(block)];
    if (on_side(b, p)) return side_node(b, p);
    const std::size_t row = b.first_row + std::size_t(p[2]) * std::size_t(b.size[1]) + std::size_t(p[1]);
    const std::array<int, 2> interior = used_interior(b, p[1], p[2]);
    return row_start[row] + (row_ends[row] & 1) +
           std::uint32_t(count_in(interior[0], p[0] - 1, row_step(p[1], p[2])));
  }
  // Where node k first appears.
  Where where(std::uint32_t k) const {
    EXDYN_ASSERT(k < row_start.back());
    const std::size_t row =
        std::size_t(std::upper_bound(row_start.begin(), row_start.end(), k) - row_start.begin()) - 1;
    const auto it = std::upper_bound(blocks.begin(), blocks.end(), row,
                                     [](std::size_t r, const LatticeBlock& b) { return r < b.first_row; });
    const int block = int(it - blocks.begin()) - 1;
    const LatticeBlock& b = blocks[std::size_t(block)];
    const std::size_t r = row - b.first_row;
    const int j = int(r % std::size_t(b.size[1])), kk = int(r / std::size_t(b.size[1]));
    const int step = row_step(j, kk);
    std::uint32_t offset = k - row_start[row];
    if (j == 0 || kk == 0 || j == b.size[1] - 1 || kk == b.size[2] - 1) {
      for (int i = 0; i < b.size[0]; i += step)
        if (side_node(b, {i, j, kk}) == k) return {block, {i, j, kk}};
      EXDYN_ASSERT(false);
    }
    if (row_ends[row] & 1) {
      if (offset == 0) return {block, {0, j, kk}};
      --offset;
    }
    const std::array<int, 2> interior = used_interior(b, j, kk);
    if (offset < std::uint32_t(count_in(interior[0], interior[1], step))) {
      const int first = step == 2 ? interior[0] + interior[0] % 2 : interior[0];
      return {block, {first + step * int(offset), j, kk}};
    }
    EXDYN_ASSERT(row_ends[row] & 2);
    return {block, {b.size[0] - 1, j, kk}};
  }
  std::array<std::uint32_t, 20> element_nodes(std::uint32_t e) const {
    const auto it =
        std::upper_bound(blocks.begin(), blocks.end(), e,
                         [](std::uint32_t v, const LatticeBlock& b) { return v < b.first_element; });
    const int block = int(it - blocks.begin()) - 1;
    const LatticeBlock& b = blocks[std::size_t(block)];
    const std::uint32_t local = e - b.first_element;
    const auto ex = std::uint32_t(b.hi[0] - b.lo[0]), ey = std::uint32_t(b.hi[1] - b.lo[1]);
    const std::array<int, 3> ijk{b.lo[0] + int(local % ex), b.lo[1] + int((local / ex) % ey),
                                 b.lo[2] + int(local / (ex * ey))};
    std::array<std::uint32_t, 20> nodes{};
    for (int l = 0; l < nodes_per_element; ++l) {
      const auto& d = brick_offsets[std::size_t(b.mirrored ? mirror[std::size_t(l)] : l)];
      nodes[std::size_t(l)] =
          node(block, {order * ijk[0] + d[0] * order / 2, order * ijk[1] + d[1] * order / 2,
                       order * ijk[2] + d[2] * order / 2});
    }
    return nodes;
  }

  // The kept box of each block: add_mapped_part's test of each element's centroid,
  // which keeps a box (asserted).
  void find_kept_boxes() {
    for (std::size_t bi = 0; bi < blocks.size(); ++bi) {
      LatticeBlock& b = blocks[bi];
      const std::array<int, 3>& n = b.block.n;
      std::array<int, 3> lo = n, hi{};
      std::uint64_t kept = 0;
      for (int k = 0; k < n[2]; ++k)
        for (int j = 0; j < n[1]; ++j)
          for (int i = 0; i < n[0]; ++i) {
            Point centroid{};
            for (std::size_t l = 0; l < 8; ++l) {
              const auto& d = brick_offsets[l];
              const Point x = point_at(int(bi), {order * i + d[0] * order / 2, order * j + d[1] * order / 2,
                                                 order * k + d[2] * order / 2});
              for (std::size_t c = 0; c < 3; ++c) centroid[c] += x[c] / 8.0;
            }
            bool inside = true;
            for (std::size_t c = 0; c < 3; ++c)
              if (options.keep[c] != 0 && options.keep[c] * (centroid[c] - options.center[c]) <= 0.0)
                inside = false;
            if (!inside) continue;
            ++kept;
            const std::array<int, 3> ijk{i, j, k};
            for (std::size_t a = 0; a < 3; ++a)
              lo[a] = std::min(lo[a], ijk[a]), hi[a] = std::max(hi[a], ijk[a] + 1);
          }
      if (kept == 0) lo = hi = {};
      b.lo = lo, b.hi = hi;
      b.elements = std::uint32_t(kept);
      EXDYN_ASSERT(kept == std::uint64_t(hi[0] - lo[0]) * std::uint64_t(hi[1] - lo[1]) *
                               std::uint64_t(hi[2] - lo[2]));
      b.first_element = elements;
      elements += b.elements;
      if (kept == 0) continue;
      // add_mapped_part's sign of the corner Jacobian, of the first kept element.
      auto corner = [&](int l) {
        const auto& d = brick_offsets[std::size_t(l)];
        return point_at(int(bi),
                        {order * (lo[0] + d[0] / 2), order * (lo[1] + d[1] / 2), order * (lo[2] + d[2] / 2)});
      };
      const Point x0 = corner(0), x1 = corner(1), x3 = corner(3), x4 = corner(4);
      const Point e1{x1[0] - x0[0], x1[1] - x0[1], x1[2] - x0[2]},
          e2{x3[0] - x0[0], x3[1] - x0[1], x3[2] - x0[2]}, e3{x4[0] - x0[0], x4[1] - x0[1], x4[2] - x0[2]};
      b.mirrored = e1[0] * (e2[1] * e3[2] - e2[2] * e3[1]) - e1[1] * (e2[0] * e3[2] - e2[2] * e3[0]) +
                       e1[2] * (e2[0] * e3[1] - e2[1] * e3[0]) <
                   0.0;
    }
    EXDYN_ASSERT(elements == mapped_element_count(options));
  }

  // The glued sides: those whose four corners are another block's side's within
  // add_mapped_part's merging tolerance.
  void glue_sides() {
    const double tolerance = 1e-9 * options.radius;
    auto close = [&](const Point& x, const Point& y) {
      return std::abs(x[0] - y[0]) <= tolerance && std::abs(x[1] - y[1]) <= tolerance &&
             std::abs(x[2] - y[2]) <= tolerance;
    };
    // Side s's corner (u, v) in {0, 1}^2 as a lattice point.
    auto side_corner = [](const LatticeBlock& b, int s, int u, int v) {
      const std::size_t a = std::size_t(s / 2), a1 = (a + 1) % 3, a2 = (a + 2) % 3;
      std::array<int, 3> p{};
      p[a] = s % 2 == 0 ? 0 : b.size[a] - 1;
      p[a1] = u * (b.size[a1] - 1);
      p[a2] = v * (b.size[a2] - 1);
      return p;
    };
    for (std::size_t bi = 0; bi < blocks.size(); ++bi)
      for (int s = 0; s < 6; ++s) {
        LatticeBlock& b = blocks[bi];
        std::array<Point, 4> mine{};
        for (int c = 0; c < 4; ++c) mine[std::size_t(c)] = point_at(int(bi), side_corner(b, s, c % 2, c / 2));
        for (std::size_t oi = 0; oi < blocks.size() && b.glue[std::size_t(s)].other < 0; ++oi) {
          if (oi == bi) continue;
          const LatticeBlock& other = blocks[oi];
          for (int t = 0; t < 6; ++t) {
            std::array<std::array<int, 3>, 4> match{};
            int found = 0;
            for (int c = 0; c < 4; ++c)
              for (int d = 0; d < 4; ++d) {
                const std::array<int, 3> q = side_corner(other, t, d % 2, d / 2);
                if (close(mine[std::size_t(c)], point_at(int(oi), q))) {
                  match[std::size_t(c)] = q;
                  ++found;
                  break;
                }
              }
            if (found != 4) continue;
            const std::size_t a = std::size_t(s / 2), a1 = (a + 1) % 3, a2 = (a + 2) % 3;
            Glue& g = b.glue[std::size_t(s)];
            g.other = int(oi);
            g.origin = match[0];
            for (std::size_t c = 0; c < 3; ++c) {
              g.d1[c] = (match[1][c] - match[0][c]) / (b.size[a1] - 1);
              g.d2[c] = (match[2][c] - match[0][c]) / (b.size[a2] - 1);
            }
            break;
          }
        }
      }
  }

  // A point on a side: numbered here if this is its first appearance and a kept
  // element has it, else the node of its first appearance (or none); recorded in
  // every side of the block that holds it.
  void number_side_point(int block, const std::array<int, 3>& p, std::uint32_t& next, bool& numbered_here) {
    std::array<Where, 8> all{};
    const int count = appearances({block, p}, all);
    Where first = all[0];
    bool used = false;
    for (int k = 0; k < count; ++k) {
      const Where& w = all[std::size_t(k)];
      used = used || used_in(blocks[std::size_t(w.block)], w.p);
      if (w.block < first.block) first = w;
    }
    LatticeBlock& b = blocks[std::size_t(block)];
    std::uint32_t id = no_node;
    numbered_here = used && first.block == block;
    if (numbered_here)
      id = next++;
    else if (used)
      id = side_node(blocks[std::size_t(first.block)], first.p);
    for (int s = 0; s < 6; ++s)
      if (on(b, s, p)) b.sides[std::size_t(s)][side_index(b, s, p)] = id;
  }

  void number_points() {
    std::size_t rows = 0;
    for (LatticeBlock& b : blocks) {
      b.first_row = rows;
      rows += std::size_t(b.size[1]) * std::size_t(b.size[2]);
      for (int s = 0; s < 6; ++s) {
        const std::size_t a = std::size_t(s / 2);
        b.sides[std::size_t(s)].assign(std::size_t(b.size[(a + 1) % 3]) * std::size_t(b.size[(a + 2) % 3]),
                                       no_node);
      }
    }
    row_start.assign(rows + 1, 0);
    row_ends.assign(rows, 0);
    std::uint32_t next = 0;
    bool here = false;
    for (std::size_t bi = 0; bi < blocks.size(); ++bi) {
      const LatticeBlock& b = blocks[bi];
      for (int k = 0; k < b.size[2]; ++k)
        for (int j = 0; j < b.size[1]; ++j) {
          const std::size_t row = b.first_row + std::size_t(k) * std::size_t(b.size[1]) + std::size_t(j);
          row_start[row] = next;
          const int step = row_step(j, k);
          if (step == 0) continue;
          if (j == 0 || k == 0 || j == b.size[1] - 1 || k == b.size[2] - 1) {
            for (int i = 0; i < b.size[0]; i += step) number_side_point(int(bi), {i, j, k}, next, here);
            continue;
          }
          number_side_point(int(bi), {0, j, k}, next, here);
          if (here) row_ends[row] |= 1;
          const std::array<int, 2> interior = used_interior(b, j, k);
          next += std::uint32_t(count_in(interior[0], interior[1], step));
          number_side_point(int(bi), {b.size[0] - 1, j, k}, next, here);
          if (here) row_ends[row] |= 2;
        }
    }
    row_start[rows] = next;
  }

  // add_mapped_part's faces: the faces of the kept elements on their block's kept box
  // that no other kept element shares, in order of element and local face.
  void find_faces(int part_index) {
    std::vector<BrickFace> entries;
    for (std::size_t bi = 0; bi < blocks.size(); ++bi) {
      const LatticeBlock& b = blocks[bi];
      for (std::uint32_t local = 0; local < b.elements; ++local) {
        const auto ex = std::uint32_t(b.hi[0] - b.lo[0]), ey = std::uint32_t(b.hi[1] - b.lo[1]);
        const std::array<int, 3> ijk{b.lo[0] + int(local % ex), b.lo[1] + int((local / ex) % ey),
                                     b.lo[2] + int(local / (ex * ey))};
        bool outer = false;
        for (std::size_t a = 0; a < 3; ++a) outer = outer || ijk[a] == b.lo[a] || ijk[a] == b.hi[a] - 1;
        if (!outer) continue;
        const std::uint32_t e = b.first_element + local;
        for (int f = 0; f < 6; ++f) {
          std::array<std::array<int, 3>, 4> corner{};
          for (std::size_t k = 0; k < 4; ++k) {
            const int l = brick_faces[f][k];
            const auto& d = brick_offsets[std::size_t(b.mirrored ? mirror[std::size_t(l)] : l)];
            for (std::size_t a = 0; a < 3; ++a) corner[k][a] = order * ijk[a] + d[a] * order / 2;
          }
          bool on_box = false;
          for (std::size_t a = 0; a < 3; ++a) {
            const int v = corner[0][a];
            if ((v == order * b.lo[a] || v == order * b.hi[a]) && corner[1][a] == v && corner[2][a] == v &&
                corner[3][a] == v)
              on_box = true;
          }
          if (!on_box) continue;
          BrickFace entry{};
          for (std::size_t k = 0; k < 4; ++k) entry.corners[k] = node(int(bi), corner[k]);
          std::sort(entry.corners.begin(), entry.corners.end());
          entry.where = 6 * std::uint64_t(e) + std::uint64_t(f);
          entries.push_back(entry);
        }
      }
    }
    const std::vector<std::uint64_t> boundary = unshared_faces(std::move(entries));
    std::vector<OuterSegment> outer;
    outer.reserve(boundary.size());
    for (const std::uint64_t where_face : boundary) {
      const std::array<std::uint32_t, 20> nodes = element_nodes(std::uint32_t(where_face / 6));
      const int f = int(where_face % 6);
      std::array<std::array<double, 3>, 8> corners{};
      for (std::size_t k = 0; k < 8; ++k) corners[k] = point_of(nodes[k]);
      OuterSegment& segment = outer.emplace_back();
      segment.segment.node_count = nodes_per_element == 20 ? 8 : 4;
      for (int k = 0; k < segment.segment.node_count; ++k)
        segment.segment.nodes[std::size_t(k)] = nodes[std::size_t(brick_faces[f][k])];
      for (std::size_t k = 0; k < 4; ++k) segment.corners[k] = corners[std::size_t(brick_faces[f][k])];
      segment.normal_length = brick_normal_length(f, corners);
    }
    faces = named_faces(options, part_index, outer);
  }
  Point point_of(std::uint32_t k) const {
    const Where w = where(k);
    return point_at(w.block, w.p);
  }
};

MappedLattice::MappedLattice(const input::PartOptions& options, int part_index)
    : layout_(std::make_unique<Layout>()) {
  Layout& l = *layout_;
  l.options = options;
  l.order = input::is_quadratic(options.formulation) ? 2 : 1;
  l.nodes_per_element = l.order == 2 ? 20 : 8;
  l.mirror = mirror_xi();
  for (Block& block :
       options.geometry == input::Geometry::cylinder ? cylinder_blocks(options) : sphere_blocks(options)) {
    Layout::LatticeBlock& b = l.blocks.emplace_back();
    for (std::size_t c = 0; c < 3; ++c) b.size[c] = l.order * block.n[c] + 1;
    b.block = std::move(block);
  }
  l.find_kept_boxes();
  l.glue_sides();
  l.number_points();
  l.find_faces(part_index);
}

MappedLattice::MappedLattice(MappedLattice&&) noexcept = default;
MappedLattice& MappedLattice::operator=(MappedLattice&&) noexcept = default;
MappedLattice::~MappedLattice() = default;

std::uint32_t MappedLattice::node_count() const { return layout_->row_start.back(); }
std::uint32_t MappedLattice::element_count() const { return layout_->elements; }
int MappedLattice::order() const { return layout_->order; }
int MappedLattice::nodes_per_element() const { return layout_->nodes_per_element; }
std::array<std::uint32_t, 20> MappedLattice::element_nodes(std::uint32_t e) const {
  return layout_->element_nodes(e);
}
std::array<double, 3> MappedLattice::point(std::uint32_t k) const { return layout_->point_of(k); }
const std::vector<std::pair<input::PartFace, Face>>& MappedLattice::faces() const { return layout_->faces; }

std::vector<std::uint32_t> MappedLattice::elements_around(std::uint32_t k) const {
  const Layout& l = *layout_;
  std::array<Layout::Where, 8> all{};
  const int count = l.appearances(l.where(k), all);
  std::vector<std::uint32_t> out;
  const int o = l.order;
  for (int w = 0; w < count; ++w) {
    const Layout::Where& at = all[std::size_t(w)];
    const Layout::LatticeBlock& b = l.blocks[std::size_t(at.block)];
    std::array<int, 3> low{}, high{};
    for (std::size_t a = 0; a < 3; ++a) {
      low[a] = std::max(b.lo[a], at.p[a] % o == 0 ? at.p[a] / o - 1 : at.p[a] / o);
      high[a] = std::min(b.hi[a] - 1, at.p[a] / o);
    }
    const auto ex = std::uint32_t(b.hi[0] - b.lo[0]), ey = std::uint32_t(b.hi[1] - b.lo[1]);
    for (int kk = low[2]; kk <= high[2]; ++kk)
      for (int j = low[1]; j <= high[1]; ++j)
        for (int i = low[0]; i <= high[0]; ++i)
          out.push_back(b.first_element + std::uint32_t(i - b.lo[0]) +
                        ex * (std::uint32_t(j - b.lo[1]) + ey * std::uint32_t(kk - b.lo[2])));
  }
  std::sort(out.begin(), out.end());
  return out;
}

}  // namespace exdyn::mesh
