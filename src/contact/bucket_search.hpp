// Global contact search: which (slave point, master segment) pairs are close
// enough to need a local search. A uniform bucket grid, filled by a counting
// sort, so the cost is linear in the number of points, segments and pairs.
//
// A pair is a candidate when the point lies inside the segment's axis-aligned
// bounding box inflated by the capture distance. A point within distance d of a
// segment lies inside its box inflated by d, so with capture distance
// d_c = d_contact + margin every pair that comes within d_contact stays a
// candidate until some node has moved more than margin / 2 (ContactCandidates).
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "common/nodal_vectors.hpp"
#include "contact/segment.hpp"

namespace exdyn::contact {

struct Box {
  std::array<double, 3> lo{};
  std::array<double, 3> hi{};
};

struct CandidatePair {
  std::uint32_t point = 0;    // index into the list of slave points
  std::uint32_t segment = 0;  // index into the list of segments
  friend bool operator==(const CandidatePair&, const CandidatePair&) = default;
};

// Working arrays of the bucket grid, kept between searches so that a search
// allocates nothing once they have grown to size.
struct BucketWorkspace {
  std::vector<std::uint32_t> cell_start;  // CSR offsets of the boxes overlapping each cell
  std::vector<std::uint32_t> cell_boxes;  // box ids, grouped by cell, increasing within a cell
};

// Bounding box of each quadrilateral segment, inflated by `capture` (m) in every
// direction. position(node) gives a node's current coordinates as {x, y, z}.
template <class PositionFn>
void segment_boxes(PositionFn position, const std::vector<std::array<std::uint32_t, 4>>& segments,
                   double capture, std::vector<Box>& boxes) {
  boxes.resize(segments.size());
  for (std::size_t s = 0; s < segments.size(); ++s) {
    const std::array<double, 3> first = position(segments[s][0]);
    Box box{first, first};
    for (int i = 1; i < 4; ++i) {
      const std::array<double, 3> x = position(segments[s][i]);
      for (int c = 0; c < 3; ++c) {
        box.lo[c] = x[c] < box.lo[c] ? x[c] : box.lo[c];
        box.hi[c] = x[c] > box.hi[c] ? x[c] : box.hi[c];
      }
    }
    for (int c = 0; c < 3; ++c) {
      box.lo[c] -= capture;
      box.hi[c] += capture;
    }
    boxes[s] = box;
  }
}

// Bounding box of each segment of 4 or 8 nodes including its bulge (segment_box),
// inflated by `capture` (m). position(node) gives a node's current coordinates.
template <class PositionFn>
void segment_boxes(PositionFn position, const std::vector<SegmentNodes>& segments, double capture,
                   std::vector<Box>& boxes) {
  boxes.resize(segments.size());
  for (std::size_t s = 0; s < segments.size(); ++s) {
    Segment segment;
    segment.type = segments[s].type;
    for (int i = 0; i < node_count(segment.type); ++i) {
      const std::array<double, 3> x = position(segments[s].nodes[static_cast<std::size_t>(i)]);
      segment.nodes[static_cast<std::size_t>(i)] = {x[0], x[1], x[2]};
    }
    const SegmentBox box = segment_box(segment);
    boxes[s] = Box{{box.lo.x - capture, box.lo.y - capture, box.lo.z - capture},
                   {box.hi.x + capture, box.hi.y + capture, box.hi.z + capture}};
  }
}

// Every (point, segment) pair with the point inside the segment's box, sorted by
// point then segment. `points` holds the slave points' coordinates.
// cell_size <= 0 chooses the cell edge automatically (the mean box extent,
// enlarged if needed so that the grid has at most about 4 cells per item).
// point_on, box_on (empty: all): the points and boxes that take part (a surface that
// erosion changes, ContactSurfaces::point_live and segment_live); the others are left
// out of the grid.
void bucket_search(const NodalVectors& points, const std::vector<Box>& boxes, double cell_size,
                   BucketWorkspace& workspace, std::vector<CandidatePair>& pairs,
                   const std::vector<std::uint8_t>& point_on = {},
                   const std::vector<std::uint8_t>& box_on = {});

// The same set by testing every pair (the reference for tests).
void brute_force_search(const NodalVectors& points, const std::vector<Box>& boxes,
                        std::vector<CandidatePair>& pairs);

}  // namespace exdyn::contact
