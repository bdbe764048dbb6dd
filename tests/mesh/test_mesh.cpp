#include <gtest/gtest.h>

#include <array>
#include <cmath>

#include "mesh/mesh.hpp"

namespace {

using exdyn::input::BoxSide;

exdyn::input::Deck two_part_deck() {
  exdyn::input::Deck deck;
  exdyn::input::PartOptions a;
  a.name = "a";
  a.box_min = {0, 0, 0};
  a.box_max = {3, 2, 1};
  a.elements = {3, 2, 1};
  exdyn::input::PartOptions b = a;
  b.name = "b";
  b.box_min = {3, 0, 0};
  b.box_max = {4, 1, 1};
  b.elements = {2, 3, 4};
  deck.parts = {a, b};
  return deck;
}

std::array<double, 3> point(const exdyn::mesh::Mesh& mesh, std::uint32_t node) { return mesh.x_ref.at(node); }

std::array<double, 3> cross(const std::array<double, 3>& a, const std::array<double, 3>& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
std::array<double, 3> minus(const std::array<double, 3>& a, const std::array<double, 3>& b) {
  return {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
}

TEST(Mesh, CountsNodesAndElementsPerPartWithoutSharing) {
  const auto mesh = exdyn::mesh::build_mesh(two_part_deck());
  EXPECT_EQ(mesh.node_count(), 4u * 3 * 2 + 3u * 4 * 5);
  EXPECT_EQ(mesh.element_count(), 6u + 24u);
  EXPECT_EQ(mesh.connectivity.size(), 8 * mesh.element_count());
  ASSERT_EQ(mesh.parts.size(), 2u);
  EXPECT_EQ(mesh.parts[1].first_node, 24u);
  EXPECT_EQ(mesh.parts[1].first_element, 6u);
  EXPECT_EQ(mesh.element_part[5], 0);
  EXPECT_EQ(mesh.element_part[6], 1);
}

TEST(Mesh, LastGridNodeLandsExactlyOnBoxMax) {
  exdyn::input::Deck deck = two_part_deck();
  deck.parts[0].box_min = {-2.5e-3, 0, 0};
  deck.parts[0].box_max = {0, 2.5e-5, 2.5e-3};
  deck.parts[0].elements = {100, 1, 100};
  const auto mesh = exdyn::mesh::build_mesh(deck);
  const auto face = exdyn::mesh::face_of(mesh, 0, BoxSide::xmax);
  for (auto node : face.nodes) EXPECT_EQ(mesh.x_ref.x[node], 0.0);
}

TEST(Mesh, ElementsFollowVtkHexahedronOrder) {
  // VTK order: (e1 x e3) . e4 > 0 for the edges from node 0 of a right-handed brick.
  const auto mesh = exdyn::mesh::build_mesh(two_part_deck());
  for (std::size_t e = 0; e < mesh.element_count(); ++e) {
    const std::uint32_t* n = &mesh.connectivity[8 * e];
    const auto x0 = point(mesh, n[0]);
    const auto e1 = minus(point(mesh, n[1]), x0), e3 = minus(point(mesh, n[3]), x0), e4 = minus(point(mesh, n[4]), x0);
    const auto c = cross(e1, e3);
    EXPECT_GT(c[0] * e4[0] + c[1] * e4[1] + c[2] * e4[2], 0.0) << "element " << e;
    // node 2 is opposite node 0 on the bottom face, node 6 opposite node 0 in the brick
    const auto x6 = point(mesh, n[6]);
    EXPECT_GT(x6[0], x0[0]);
    EXPECT_GT(x6[1], x0[1]);
    EXPECT_GT(x6[2], x0[2]);
  }
}

TEST(Mesh, EveryFaceQuadNormalPointsOutOfThePart) {
  const auto mesh = exdyn::mesh::build_mesh(two_part_deck());
  const std::array<std::pair<BoxSide, std::array<double, 3>>, 6> sides{{{BoxSide::xmin, {-1, 0, 0}},
                                                                         {BoxSide::xmax, {1, 0, 0}},
                                                                         {BoxSide::ymin, {0, -1, 0}},
                                                                         {BoxSide::ymax, {0, 1, 0}},
                                                                         {BoxSide::zmin, {0, 0, -1}},
                                                                         {BoxSide::zmax, {0, 0, 1}}}};
  for (int part = 0; part < 2; ++part)
    for (const auto& [side, outward] : sides) {
      const auto face = exdyn::mesh::face_of(mesh, part, side);
      const auto& n = mesh.parts[static_cast<std::size_t>(part)].elements;
      const int axis = static_cast<int>(side) / 2;
      const int a = (axis + 1) % 3, b = (axis + 2) % 3;
      EXPECT_EQ(face.nodes.size(), std::size_t((n[a] + 1) * (n[b] + 1)));
      EXPECT_EQ(face.quads.size(), std::size_t(n[a] * n[b]));
      for (const auto& q : face.quads) {
        const auto normal = cross(minus(point(mesh, q[1]), point(mesh, q[0])), minus(point(mesh, q[3]), point(mesh, q[0])));
        const double length = std::sqrt(normal[0] * normal[0] + normal[1] * normal[1] + normal[2] * normal[2]);
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(normal[c] / length, outward[c], 1e-14);
      }
      const double plane = point(mesh, face.nodes[0])[axis];
      for (auto node : face.nodes) EXPECT_EQ(point(mesh, node)[axis], plane);
    }
}

}  // namespace
