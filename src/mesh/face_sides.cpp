#include "mesh/face_sides.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <map>
#include <utility>

#include "common/errors.hpp"

namespace exdyn::mesh {

namespace {

using Vec = std::array<double, 3>;

// (x2 - x0) x (x3 - x1): the segment's outward normal at its centre, times twice its
// area on a flat quadrilateral.
Vec centre_normal(const FaceSegment& segment, const NodalVectors& x) {
  auto point = [&](int k) {
    const std::uint32_t n = segment.nodes[std::size_t(k)];
    return Vec{x.x[n], x.y[n], x.z[n]};
  };
  const Vec a = point(2), b = point(3), c = point(0), d = point(1);
  const Vec d1{a[0] - c[0], a[1] - c[1], a[2] - c[2]}, d2{b[0] - d[0], b[1] - d[1], b[2] - d[2]};
  return {d1[1] * d2[2] - d1[2] * d2[1], d1[2] * d2[0] - d1[0] * d2[2], d1[0] * d2[1] - d1[1] * d2[0]};
}

// Whether normals a and b are at most feature_angle apart.
bool no_fold(const Vec& a, const Vec& b) {
  const double dot = a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
  const double norms =
      std::sqrt((a[0] * a[0] + a[1] * a[1] + a[2] * a[2]) * (b[0] * b[0] + b[1] * b[1] + b[2] * b[2]));
  return dot >= std::cos(feature_angle) * norms;
}

}  // namespace

FaceSides fold_sides(const std::vector<FaceSegment>& segments, const std::vector<double>& normal_length,
                     const NodalVectors& x) {
  EXDYN_ASSERT(normal_length.size() == segments.size());
  const std::size_t n = segments.size();
  std::vector<Vec> normal(n);
  std::map<std::pair<std::uint32_t, std::uint32_t>, std::vector<std::uint32_t>> at_edge;
  for (std::size_t s = 0; s < n; ++s) {
    normal[s] = centre_normal(segments[s], x);
    for (int e = 0; e < 4; ++e) {
      const std::uint32_t a = segments[s].nodes[std::size_t(e)],
                          b = segments[s].nodes[std::size_t((e + 1) % 4)];
      at_edge[{std::min(a, b), std::max(a, b)}].push_back(std::uint32_t(s));
    }
  }
  // Each side from its first segment in face order, across every edge that is no fold.
  constexpr std::uint32_t none = 0xffffffffu;
  FaceSides sides;
  sides.side.assign(n, none);
  std::uint32_t count = 0;
  std::vector<std::uint32_t> stack;
  for (std::size_t first = 0; first < n; ++first) {
    if (sides.side[first] != none) continue;
    sides.side[first] = count;
    stack.assign(1, std::uint32_t(first));
    while (!stack.empty()) {
      const std::uint32_t s = stack.back();
      stack.pop_back();
      for (int e = 0; e < 4; ++e) {
        const std::uint32_t a = segments[s].nodes[std::size_t(e)],
                            b = segments[s].nodes[std::size_t((e + 1) % 4)];
        for (const std::uint32_t t : at_edge[{std::min(a, b), std::max(a, b)}])
          if (sides.side[t] == none && no_fold(normal[s], normal[t])) {
            sides.side[t] = count;
            stack.push_back(t);
          }
      }
    }
    ++count;
  }
  if (count <= 1) return {};
  // Each segment's index in its side, and each side's count and mean normal length,
  // summed in face order (a physical surface that is one side sums the same lengths in
  // the same order: the same bits).
  sides.index.resize(n);
  sides.count.assign(count, 0);
  sides.normal_length.assign(count, 0.0);
  for (std::size_t s = 0; s < n; ++s) {
    sides.index[s] = std::uint32_t(sides.count[sides.side[s]]++);
    sides.normal_length[sides.side[s]] += normal_length[s];
  }
  for (std::uint32_t k = 0; k < count; ++k) sides.normal_length[k] /= static_cast<double>(sides.count[k]);
  return sides;
}

Face side_of(const Face& face, std::size_t k) {
  if (face.sides.count.empty()) return face;
  EXDYN_ASSERT(k < face.sides.count.size());
  Face side;  // one side: no sides of its own
  side.normal_length = face.sides.normal_length[k];
  side.whole_segments = face.sides.count[k];
  for (std::size_t s = 0; s < face.segments.size(); ++s) {
    const std::uint32_t whole = face.index_in_whole(s);
    if (face.sides.side[whole] != k) continue;
    side.segments.push_back(face.segments[s]);
    side.segment_index.push_back(face.sides.index[whole]);
  }
  nodes_of_segments(side);
  return side;
}

}  // namespace exdyn::mesh
