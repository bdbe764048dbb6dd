#include "contact/bucket_search.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace exdyn::contact {

namespace {

bool inside(const Box& box, double x, double y, double z) {
  return x >= box.lo[0] && x <= box.hi[0] && y >= box.lo[1] && y <= box.hi[1] && z >= box.lo[2] && z <= box.hi[2];
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
    return static_cast<std::uint32_t>(clamp_index(x, 0) + cells[0] * (clamp_index(y, 1) + cells[1] * clamp_index(z, 2)));
  }
};

Grid make_grid(const NodalVectors& points, const std::vector<Box>& boxes, double cell_size) {
  Grid grid;
  std::array<double, 3> lo{}, hi{};
  lo.fill(std::numeric_limits<double>::infinity());
  hi.fill(-std::numeric_limits<double>::infinity());
  // The grid covers the points only: a box part outside it cannot hold a point.
  for (int c = 0; c < 3; ++c)
    for (double v : points.component(c)) {
      lo[c] = std::min(lo[c], v);
      hi[c] = std::max(hi[c], v);
    }
  double mean_extent = 0.0;
  for (const Box& b : boxes) mean_extent += std::max({b.hi[0] - b.lo[0], b.hi[1] - b.lo[1], b.hi[2] - b.lo[2]});
  mean_extent /= static_cast<double>(std::max<std::size_t>(boxes.size(), 1));
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
  for (int c = 0; c < 3; ++c) grid.cells[c] = static_cast<std::int64_t>(std::floor((hi[c] - lo[c]) / edge)) + 1;
  return grid;
}

}  // namespace

void bucket_search(const NodalVectors& points, const std::vector<Box>& boxes, double cell_size,
                   BucketWorkspace& w, std::vector<CandidatePair>& pairs) {
  pairs.clear();
  const std::size_t n_points = points.size();
  if (n_points == 0 || boxes.empty()) return;
  const Grid grid = make_grid(points, boxes, cell_size);
  const std::size_t n_cells = static_cast<std::size_t>(grid.cells[0] * grid.cells[1] * grid.cells[2]);

  // Counting sort of the points by cell: cell_points[cell_start[c] ... cell_start[c+1]).
  w.point_cell.resize(n_points);
  w.cell_start.assign(n_cells + 1, 0);
  for (std::size_t p = 0; p < n_points; ++p) {
    w.point_cell[p] = grid.cell_of(points.x[p], points.y[p], points.z[p]);
    ++w.cell_start[w.point_cell[p] + 1];
  }
  for (std::size_t c = 0; c < n_cells; ++c) w.cell_start[c + 1] += w.cell_start[c];
  w.cell_points.resize(n_points);
  {
    std::vector<std::uint32_t>& next = w.pair_count;  // reused as the fill cursor
    next.assign(w.cell_start.begin(), w.cell_start.end() - 1);
    for (std::size_t p = 0; p < n_points; ++p) w.cell_points[next[w.point_cell[p]]++] = static_cast<std::uint32_t>(p);
  }

  // Each box visits the cells it overlaps and tests their points.
  w.unsorted.clear();
  for (std::size_t s = 0; s < boxes.size(); ++s) {
    const Box& box = boxes[s];
    std::array<std::int64_t, 3> first{}, last{};
    bool outside = false;
    for (int c = 0; c < 3; ++c) {
      const double grid_lo = grid.origin[c], grid_hi = grid_lo + static_cast<double>(grid.cells[c]) / grid.inverse_cell;
      if (box.hi[c] < grid_lo || box.lo[c] > grid_hi) outside = true;
      first[c] = grid.clamp_index(box.lo[c], c);
      last[c] = grid.clamp_index(box.hi[c], c);
    }
    if (outside) continue;
    for (std::int64_t k = first[2]; k <= last[2]; ++k)
      for (std::int64_t j = first[1]; j <= last[1]; ++j)
        for (std::int64_t i = first[0]; i <= last[0]; ++i) {
          const std::size_t cell = static_cast<std::size_t>(i + grid.cells[0] * (j + grid.cells[1] * k));
          for (std::uint32_t at = w.cell_start[cell]; at < w.cell_start[cell + 1]; ++at) {
            const std::uint32_t p = w.cell_points[at];
            if (inside(box, points.x[p], points.y[p], points.z[p]))
              w.unsorted.push_back({p, static_cast<std::uint32_t>(s)});
          }
        }
  }

  // Counting sort by point; the segments of a point come out in increasing order
  // because the boxes were visited in increasing order.
  w.pair_count.assign(n_points + 1, 0);
  for (const CandidatePair& pair : w.unsorted) ++w.pair_count[pair.point + 1];
  for (std::size_t p = 0; p < n_points; ++p) w.pair_count[p + 1] += w.pair_count[p];
  pairs.resize(w.unsorted.size());
  for (const CandidatePair& pair : w.unsorted) pairs[w.pair_count[pair.point]++] = pair;
}

void brute_force_search(const NodalVectors& points, const std::vector<Box>& boxes, std::vector<CandidatePair>& pairs) {
  pairs.clear();
  for (std::size_t p = 0; p < points.size(); ++p)
    for (std::size_t s = 0; s < boxes.size(); ++s)
      if (inside(boxes[s], points.x[p], points.y[p], points.z[p]))
        pairs.push_back({static_cast<std::uint32_t>(p), static_cast<std::uint32_t>(s)});
}

}  // namespace exdyn::contact
