#include "contact/bucket_search.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace exdyn::contact {

namespace {

bool inside(const Box& box, double x, double y, double z) {
  return x >= box.lo[0] && x <= box.hi[0] && y >= box.lo[1] && y <= box.hi[1] && z >= box.lo[2] &&
         z <= box.hi[2];
}

// The grid: origin, cell edge and cell counts per axis.
struct Grid {
  std::array<double, 3> origin{};
  double inverse_cell = 1.0;
  std::array<std::int64_t, 3> cells{1, 1, 1};

  std::int64_t clamp_index(double coordinate, int axis) const {
    const double t = std::floor((coordinate - origin[axis]) * inverse_cell);
    if (!(t >= 0.0)) return 0;  // also NaN
    return std::min<std::int64_t>(static_cast<std::int64_t>(std::min(t, 9.0e18)), cells[axis] - 1);
  }
  std::uint32_t cell_of(double x, double y, double z) const {
    return static_cast<std::uint32_t>(clamp_index(x, 0) +
                                      cells[0] * (clamp_index(y, 1) + cells[1] * clamp_index(z, 2)));
  }
};

bool on(const std::vector<std::uint8_t>& mask, std::size_t i) { return mask.empty() || mask[i] != 0; }

Grid make_grid(const NodalVectors& points, const std::vector<Box>& boxes, double cell_size,
               const std::vector<std::uint8_t>& point_on, const std::vector<std::uint8_t>& box_on) {
  Grid grid;
  std::array<double, 3> lo{}, hi{};
  lo.fill(std::numeric_limits<double>::infinity());
  hi.fill(-std::numeric_limits<double>::infinity());
  // The grid covers the points only: a box part outside it cannot hold a point.
  for (int c = 0; c < 3; ++c) {
    const std::vector<double>& coordinate = points.component(c);
    for (std::size_t p = 0; p < coordinate.size(); ++p)
      if (on(point_on, p)) {
        lo[c] = std::min(lo[c], coordinate[p]);
        hi[c] = std::max(hi[c], coordinate[p]);
      }
  }
  double mean_extent = 0.0;
  std::size_t box_count = 0;
  for (std::size_t b = 0; b < boxes.size(); ++b)
    if (on(box_on, b)) {
      mean_extent += std::max({boxes[b].hi[0] - boxes[b].lo[0], boxes[b].hi[1] - boxes[b].lo[1],
                               boxes[b].hi[2] - boxes[b].lo[2]});
      ++box_count;
    }
  mean_extent /= static_cast<double>(std::max<std::size_t>(box_count, 1));
  double edge = cell_size > 0.0 ? cell_size : mean_extent;
  const double span = std::max({hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2], 0.0});
  if (!(edge > 0.0) || !std::isfinite(edge)) edge = span > 0.0 ? span : 1.0;
  // At most about 4 cells per item keeps the memory and the cell sweep linear.
  const double max_cells = 4.0 * static_cast<double>(points.size() + boxes.size()) + 64.0;
  for (;;) {
    double total = 1.0;
    for (int c = 0; c < 3; ++c) total *= std::floor((hi[c] - lo[c]) / edge) + 1.0;
    if (total <= max_cells) break;
    edge *= 1.5;
  }
  grid.origin = lo;
  grid.inverse_cell = 1.0 / edge;
  for (int c = 0; c < 3; ++c)
    grid.cells[c] = static_cast<std::int64_t>(std::floor((hi[c] - lo[c]) / edge)) + 1;
  return grid;
}

}  // namespace

void bucket_search(const NodalVectors& points, const std::vector<Box>& boxes, double cell_size,
                   BucketWorkspace& w, std::vector<CandidatePair>& pairs,
                   const std::vector<std::uint8_t>& point_on, const std::vector<std::uint8_t>& box_on) {
  pairs.clear();
  const std::size_t n_points = points.size();
  if (n_points == 0 || boxes.empty()) return;
  if (!point_on.empty() && std::find(point_on.begin(), point_on.end(), 1) == point_on.end()) return;
  const Grid grid = make_grid(points, boxes, cell_size, point_on, box_on);
  const std::size_t n_cells = static_cast<std::size_t>(grid.cells[0] * grid.cells[1] * grid.cells[2]);

  // The cells a box overlaps (clamped to the grid; none if the box misses it).
  auto cell_range = [&](const Box& box, std::array<std::int64_t, 3>& first,
                        std::array<std::int64_t, 3>& last) {
    for (int c = 0; c < 3; ++c) {
      const double grid_lo = grid.origin[c];
      const double grid_hi = grid_lo + static_cast<double>(grid.cells[c]) / grid.inverse_cell;
      if (box.hi[c] < grid_lo || box.lo[c] > grid_hi) return false;
      first[c] = grid.clamp_index(box.lo[c], c);
      last[c] = grid.clamp_index(box.hi[c], c);
    }
    return true;
  };
  auto for_each_cell = [&](const Box& box, auto&& visit) {
    std::array<std::int64_t, 3> first{}, last{};
    if (!cell_range(box, first, last)) return;
    for (std::int64_t k = first[2]; k <= last[2]; ++k)
      for (std::int64_t j = first[1]; j <= last[1]; ++j)
        for (std::int64_t i = first[0]; i <= last[0]; ++i)
          visit(static_cast<std::size_t>(i + grid.cells[0] * (j + grid.cells[1] * k)));
  };

  // Counting sort of the boxes by cell: cell_boxes[cell_start[c] ... cell_start[c+1]),
  // in increasing box order within a cell because the boxes are visited in order.
  w.cell_start.assign(n_cells + 1, 0);
  for (std::size_t b = 0; b < boxes.size(); ++b)
    if (on(box_on, b)) for_each_cell(boxes[b], [&](std::size_t cell) { ++w.cell_start[cell + 1]; });
  for (std::size_t c = 0; c < n_cells; ++c) w.cell_start[c + 1] += w.cell_start[c];
  w.cell_boxes.resize(w.cell_start[n_cells]);
  for (std::size_t b = 0; b < boxes.size(); ++b)
    if (on(box_on, b))
      for_each_cell(boxes[b], [&](std::size_t cell) {
        // cell_start[cell] serves as the fill cursor and ends at the next cell's start.
        w.cell_boxes[w.cell_start[cell]++] = static_cast<std::uint32_t>(b);
      });
  for (std::size_t c = n_cells; c > 0; --c) w.cell_start[c] = w.cell_start[c - 1];
  w.cell_start[0] = 0;

  // Each point tests the boxes of its own cell: the pairs come out sorted by
  // point, then by segment, with no further sort.
  for (std::size_t p = 0; p < n_points; ++p) {
    if (!on(point_on, p)) continue;
    const double x = points.x[p], y = points.y[p], z = points.z[p];
    const std::uint32_t cell = grid.cell_of(x, y, z);
    for (std::uint32_t at = w.cell_start[cell]; at < w.cell_start[cell + 1]; ++at) {
      const std::uint32_t b = w.cell_boxes[at];
      if (inside(boxes[b], x, y, z)) pairs.push_back({static_cast<std::uint32_t>(p), b});
    }
  }
}

void brute_force_search(const NodalVectors& points, const std::vector<Box>& boxes,
                        std::vector<CandidatePair>& pairs) {
  pairs.clear();
  for (std::size_t p = 0; p < points.size(); ++p)
    for (std::size_t s = 0; s < boxes.size(); ++s)
      if (inside(boxes[s], points.x[p], points.y[p], points.z[p]))
        pairs.push_back({static_cast<std::uint32_t>(p), static_cast<std::uint32_t>(s)});
}

}  // namespace exdyn::contact
