#include "mesh/interior_faces.hpp"

#include <algorithm>
#include <array>

namespace exdyn::mesh {

std::vector<BrickFace> part_brick_faces(const Mesh& mesh, int part) {
  const PartRange& range = mesh.parts.at(std::size_t(part));
  std::vector<BrickFace> faces;
  faces.reserve(6 * std::size_t(range.element_count));
  for (std::uint32_t e = range.first_element; e < range.first_element + range.element_count; ++e) {
    const std::uint32_t* nodes = mesh.element_nodes(e);
    for (int f = 0; f < 6; ++f) {
      BrickFace face{};
      for (int k = 0; k < 4; ++k) face.corners[std::size_t(k)] = nodes[brick_faces[f][k]];
      std::sort(face.corners.begin(), face.corners.end());
      face.where = 6 * std::uint64_t(e) + std::uint64_t(f);
      faces.push_back(face);
    }
  }
  std::sort(faces.begin(), faces.end(), [](const BrickFace& a, const BrickFace& b) {
    return a.corners != b.corners ? a.corners < b.corners : a.where < b.where;
  });
  return faces;
}

std::vector<Face> interior_faces(const Mesh& mesh, int part) {
  const std::vector<BrickFace> faces = part_brick_faces(mesh, part);
  std::array<std::vector<std::uint64_t>, 6> shared;  // the where of each shared face, by local face
  for (std::size_t i = 0; i < faces.size();) {
    std::size_t j = i + 1;
    while (j < faces.size() && faces[j].corners == faces[i].corners) ++j;
    if (j - i == 2)
      for (std::size_t k = i; k < j; ++k) shared[faces[k].where % 6].push_back(faces[k].where);
    i = j;
  }
  const int segment_nodes = mesh.parts.at(std::size_t(part)).order == 2 ? 8 : 4;
  std::vector<Face> result(6);
  for (int local_face = 0; local_face < 6; ++local_face) {
    std::vector<std::uint64_t>& wheres = shared[std::size_t(local_face)];
    if (wheres.empty()) continue;
    std::sort(wheres.begin(), wheres.end());
    Face& face = result[std::size_t(local_face)];
    double length_sum = 0.0;
    for (const std::uint64_t where : wheres) {
      const std::uint32_t* nodes = mesh.element_nodes(std::size_t(where / 6));
      FaceSegment segment;
      segment.node_count = segment_nodes;
      for (int k = 0; k < segment_nodes; ++k)
        segment.nodes[std::size_t(k)] = nodes[brick_faces[local_face][k]];
      face.segments.push_back(segment);
      std::array<std::array<double, 3>, 8> corners{};
      for (std::size_t k = 0; k < 8; ++k)
        for (int c = 0; c < 3; ++c) corners[k][std::size_t(c)] = mesh.x_ref.component(c)[nodes[k]];
      length_sum += brick_normal_length(local_face, corners);
    }
    finish_face(face, length_sum);
  }
  return result;
}

bool outward_of(const Mesh& mesh, std::uint64_t where, const std::uint32_t* corners) {
  const std::uint32_t* nodes = mesh.element_nodes(std::size_t(where / 6));
  const int* f = brick_faces[where % 6];
  for (int shift = 0; shift < 4; ++shift) {
    bool same = true;
    for (int k = 0; k < 4 && same; ++k) same = nodes[f[(k + shift) % 4]] == corners[k];
    if (same) return true;
  }
  return false;
}

}  // namespace exdyn::mesh
