// Parts from Gmsh meshes (mesh/imported.hpp): the 20-node node order, the faces of
// physical surfaces, two volumes sharing nodes, the Hilbert order, and every way a mesh
// can be wrong, from what the Gmsh library returns.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <numeric>
#include <set>
#include <string>

#include "../fuzz/fuzz_mesh_input.hpp"
#include "common/parallel.hpp"
#include "input/deck_reader.hpp"
#include "input/gmsh_file.hpp"
#include "mesh/face_sides.hpp"
#include "mesh/imported.hpp"
#include "mesh/mesh.hpp"

namespace exdyn::mesh {
namespace {

const std::string meshes = std::string(EXDYN_SOURCE_DIR) + "/input/meshes/";

input::PartOptions mesh_part(const std::string& volume, input::Formulation formulation,
                             std::vector<std::string> surfaces = {}, bool reorder = true) {
  input::PartOptions part;
  part.name = volume;
  part.geometry = input::Geometry::mesh;
  part.formulation = formulation;
  part.mesh.volume = volume;
  part.mesh.surfaces = std::move(surfaces);
  part.mesh.reorder = reorder;
  return part;
}

Mesh import(const input::GmshMesh& file, const input::PartOptions& part) {
  Mesh mesh;
  add_imported_part(mesh, part, 0, file, SourceLocation{"deck.yaml", 0, 0}, "parts[0].mesh");
  return mesh;
}

std::array<double, 3> point(const Mesh& mesh, std::uint32_t node) {
  return {mesh.x_ref.x[node], mesh.x_ref.y[node], mesh.x_ref.z[node]};
}

// (y1 - y0) x (y3 - y0) of a segment: its outward normal times twice an area.
std::array<double, 3> segment_normal(const Mesh& mesh, const FaceSegment& s) {
  const auto a = point(mesh, s.nodes[0]), b = point(mesh, s.nodes[1]), d = point(mesh, s.nodes[3]);
  const std::array<double, 3> u{b[0] - a[0], b[1] - a[1], b[2] - a[2]},
      v{d[0] - a[0], d[1] - a[1], d[2] - a[2]};
  return {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
}

TEST(GmshNodeOrder, TheTableMapsEveryVtkEdgeToTheGmshEdgeOfTheSameCorners) {
  // Gmsh's 20-node hexahedron (its documentation, "Node ordering"): edges 8..19.
  constexpr int gmsh_edges[12][2] = {{0, 1}, {0, 3}, {0, 4}, {1, 2}, {1, 5}, {2, 3},
                                     {2, 6}, {3, 7}, {4, 5}, {4, 7}, {5, 6}, {6, 7}};
  std::set<int> used;
  for (int v = 0; v < 20; ++v) {
    const int g = gmsh_hex20_node[std::size_t(v)];
    used.insert(g);
    if (v < 8) {
      EXPECT_EQ(g, v);
      continue;
    }
    // The VTK mid-edge node's corners: the corners at offset distance 1 from it.
    std::set<int> corners;
    for (int c = 0; c < 8; ++c) {
      int distance = 0;
      for (int k = 0; k < 3; ++k)
        distance += std::abs(brick_offsets[std::size_t(v)][std::size_t(k)] -
                             brick_offsets[std::size_t(c)][std::size_t(k)]);
      if (distance == 1) corners.insert(c);
    }
    EXPECT_EQ(corners, (std::set<int>{gmsh_edges[g - 8][0], gmsh_edges[g - 8][1]})) << "VTK node " << v;
  }
  EXPECT_EQ(used.size(), 20u);
}

// On a mesh Gmsh wrote (straight edges), each VTK mid-edge node lies at the middle of
// its two corners: the order the program reads is the order the library writes.
TEST(GmshNodeOrder, EveryMidEdgeNodeOfAGmshHex20MeshIsTheMiddleOfItsVtkEdge) {
  const auto file = input::read_gmsh(meshes + "plate_impact_hex20.msh", {}, "");
  const Mesh mesh = import(file, mesh_part("plate_a", input::Formulation::hex20, {}));
  ASSERT_EQ(mesh.element_count(), 2500u);
  double worst = 0.0;
  for (std::size_t e = 0; e < mesh.element_count(); ++e) {
    const std::uint32_t* nodes = mesh.element_nodes(e);
    for (int v = 8; v < 20; ++v) {
      std::array<double, 3> middle{};
      int found = 0;
      for (int c = 0; c < 8; ++c) {
        int distance = 0;
        for (int k = 0; k < 3; ++k)
          distance += std::abs(brick_offsets[std::size_t(v)][std::size_t(k)] -
                               brick_offsets[std::size_t(c)][std::size_t(k)]);
        if (distance != 1) continue;
        ++found;
        for (int k = 0; k < 3; ++k) middle[std::size_t(k)] += 0.5 * point(mesh, nodes[c])[std::size_t(k)];
      }
      ASSERT_EQ(found, 2);
      for (int k = 0; k < 3; ++k)
        worst = std::max(worst, std::abs(point(mesh, nodes[v])[std::size_t(k)] - middle[std::size_t(k)]));
    }
  }
  // Gmsh places a mid-edge node by the edge's parametrization, off the corners' mean by
  // round-off (measured 6.6e-17 m); a node of another edge would be half an element,
  // 1.25e-5 m, away.
  EXPECT_LE(worst, 1e-15);
}

TEST(ImportedFaces, PhysicalSurfacesBecomeOutwardFacesOfEachVolumeTheyBound) {
  const auto file = input::read_gmsh(meshes + "plate_impact_hex8.msh", {}, "");
  const std::vector<std::string> names{"front", "back", "bottom", "top", "interface", "left", "right"};
  for (const auto& [volume, outward_x] : {std::pair{"plate_a", 1.0}, std::pair{"plate_b", -1.0}}) {
    const Mesh mesh = import(file, mesh_part(volume, input::Formulation::hex8, names));
    const PartRange& part = mesh.parts[0];
    EXPECT_EQ(part.element_count, 10000u);
    EXPECT_EQ(part.node_count, 101u * 2u * 101u);
    ASSERT_EQ(part.physical_faces.size(), names.size());
    // The interface x = 0 bounds both plates, outward +x from plate_a and -x from plate_b.
    const Face& interface = part.physical_faces[4];
    ASSERT_EQ(interface.segments.size(), 100u);
    EXPECT_EQ(interface.nodes.size(), 2u * 101u);
    EXPECT_NEAR(interface.normal_length, 2.5e-5, 1e-15);
    for (const FaceSegment& s : interface.segments) {
      const auto n = segment_normal(mesh, s);
      EXPECT_GT(n[0] * outward_x, 0.0);
      EXPECT_NEAR(n[1], 0.0, 1e-20);
      for (int k = 0; k < 4; ++k) EXPECT_EQ(mesh.x_ref.x[s.nodes[std::size_t(k)]], 0.0);
    }
    // The face on the far side bounds only one of them.
    const bool a = std::string(volume) == "plate_a";
    EXPECT_EQ(part.physical_faces[5].segments.size(), a ? 100u : 0u);
    EXPECT_EQ(part.physical_faces[6].segments.size(), a ? 0u : 100u);
    for (const FaceSegment& s : part.physical_faces[0].segments) EXPECT_LT(segment_normal(mesh, s)[1], 0.0);
    for (const FaceSegment& s : part.physical_faces[1].segments) EXPECT_GT(segment_normal(mesh, s)[1], 0.0);
    // The whole boundary: 2 x 100 x 100 + 4 x 100 faces.
    EXPECT_EQ(face_of(mesh, 0, input::PartFace::surface).segments.size(), 20400u);
  }
}

// A Gmsh part's whole boundary folds at its edges: its sides (mesh/face_sides.hpp) are
// the pieces between them. The C of input/meshes/c_slot.geo (one brick thick): its
// boundary's sides are the 8 straight pieces of its outline (the base, the lower arm's
// end, the slot's three faces, the upper arm's end, the top, the back's outer face) and
// the front and the back planes, each physical surface that lies in one plane is
// one side with the same segments, the same mean normal length (bits) and its segments
// in the same order; a side cut (a rank's face) keeps its indices in the whole side.
TEST(ImportedFaces, AWholeBoundaryFoldsIntoSidesThatArePhysicalSurfaces) {
  for (const auto& [file_name, formulation] : {std::pair{"c_slot_hex8.msh", input::Formulation::hex8},
                                               std::pair{"c_slot_hex20.msh", input::Formulation::hex20}}) {
    const auto file = input::read_gmsh(meshes + file_name, {}, "");
    const std::vector<std::string> names{"slot_lower", "slot_upper", "slot_back", "lower_base", "upper_tip"};
    const Mesh mesh = import(file, mesh_part("c", formulation, names));
    const Face whole = face_of(mesh, 0, input::PartFace::surface);
    ASSERT_EQ(whole.sides.size(), 8u + 2u) << file_name;
    std::size_t segments = 0;
    for (std::size_t k = 0; k < whole.sides.size(); ++k) {
      input::FaceRef ref{0, input::PartFace::surface};
      ref.fold_side = int(k);
      const Face side = face_of(mesh, ref);
      EXPECT_EQ(side.whole_count(), whole.sides.count[k]);
      EXPECT_TRUE(side.sides.count.empty());  // a side is one side
      segments += side.segments.size();
      // Every segment of a side within 60 degrees of every neighbour's normal: here, one plane.
      const auto n0 = segment_normal(mesh, side.segments.front());
      for (const FaceSegment& s : side.segments) {
        const auto n = segment_normal(mesh, s);
        const double dot = n[0] * n0[0] + n[1] * n0[1] + n[2] * n0[2];
        EXPECT_GT(dot, 0.999 * std::sqrt((n[0] * n[0] + n[1] * n[1] + n[2] * n[2]) *
                                         (n0[0] * n0[0] + n0[1] * n0[1] + n0[2] * n0[2])));
      }
    }
    EXPECT_EQ(segments, whole.segments.size());
    for (std::size_t f = 0; f < names.size(); ++f) {
      const Face& physical = mesh.parts[0].physical_faces[f];
      EXPECT_TRUE(physical.sides.count.empty()) << names[f];  // flat: one side
      std::size_t matches = 0;
      for (std::size_t k = 0; k < whole.sides.size(); ++k) {
        input::FaceRef ref{0, input::PartFace::surface};
        ref.fold_side = int(k);
        const Face side = face_of(mesh, ref);
        if (side.segments.size() != physical.segments.size()) continue;
        bool same = true;
        for (std::size_t s = 0; s < side.segments.size() && same; ++s)
          same = side.segments[s].nodes == physical.segments[s].nodes;
        if (!same) continue;
        ++matches;
        EXPECT_EQ(side.normal_length, physical.normal_length) << names[f];
        EXPECT_EQ(side.nodes, physical.nodes) << names[f];
      }
      EXPECT_EQ(matches, 1u) << names[f];
    }
    // A side of a cut face: the cut's segments of that side, with their indices in the
    // whole side.
    const Face cut = cut_face(whole, [](const FaceSegment& s) { return s.nodes[0] % 2 == 0; });
    for (std::size_t k = 0; k < whole.sides.size(); ++k) {
      input::FaceRef ref{0, input::PartFace::surface};
      ref.fold_side = int(k);
      const Face side = face_of(mesh, ref);
      const Face side_cut = side_of(cut, k);
      EXPECT_EQ(side_cut.whole_count(), side.whole_count());
      EXPECT_EQ(side_cut.normal_length, side.normal_length);
      for (std::size_t s = 0; s < side_cut.segments.size(); ++s) {
        EXPECT_EQ(side_cut.segments[s].nodes, side.segments[side_cut.index_in_whole(s)].nodes);
        EXPECT_EQ(side_cut.segments[s].nodes[0] % 2, 0u);
      }
    }
  }
}

// A curved face whose segments turn less than the feature angle from one to the next is
// one side: the tube's (input/meshes/tube.geo, 24 segments a quarter turn) inner and
// outer faces are one side each; its ends and the symmetry planes are sides too.
TEST(ImportedFaces, ACurvedFaceIsOneSide) {
  const auto file = input::read_gmsh(meshes + "tube_crush_hex8.msh", {}, "");
  const Mesh mesh = import(file, mesh_part("tube", input::Formulation::hex8));
  const Face whole = face_of(mesh, 0, input::PartFace::surface);
  EXPECT_EQ(whole.sides.size(), 6u);  // inner, outer, two ends, two symmetry planes
}

// Two physical volumes that share the nodes of their common surface in the file are two
// bodies: each part has nodes of its own, and no element of one names a node of the other.
// The Gmsh library sets OpenMP's thread count to its own (one) when it starts: a
// reader that left it so ran every deck with a mesh file on one thread.
TEST(ImportedFaces, ReadingAFileKeepsTheThreadsThatWereAskedFor) {
  const int before = max_threads();
  if (set_threads(2) != 2 || max_threads() != 2) GTEST_SKIP() << "built without OpenMP";
  (void)input::read_gmsh(meshes + "tube_hex8.msh", {}, "");
  EXPECT_EQ(max_threads(), 2);
  set_threads(before);
}

TEST(ImportedFaces, TwoVolumesThatShareNodesInTheFileShareNoneAsParts) {
  const std::string deck_text = R"(name: two
materials:
  steel: {model: linear_elastic, density: 7800, youngs_modulus: 2.1e11, poissons_ratio: 0.3}
parts:
  - {name: a, mesh: {file: )" + meshes +
                                R"(plate_impact_hex8.msh, volume: plate_a}, material: steel}
  - {name: b, mesh: {file: )" + meshes +
                                R"(plate_impact_hex8.msh, volume: plate_b}, material: steel}
time: {end_time: 1.0e-9}
)";
  const Mesh mesh = build_mesh(input::parse_deck(deck_text, "two.yaml"));
  ASSERT_EQ(mesh.parts.size(), 2u);
  // The file has 101 x 2 x 201 nodes; the parts 2 x 101 x 2 x 101: the x = 0 layer twice.
  EXPECT_EQ(mesh.node_count(), 2u * 101u * 2u * 101u);
  const auto file = input::read_gmsh(meshes + "plate_impact_hex8.msh", {}, "");
  EXPECT_EQ(file.node_tags.size(), 201u * 2u * 101u);
  for (std::size_t e = 0; e < mesh.element_count(); ++e) {
    const PartRange& part = mesh.parts[std::size_t(mesh.element_part[e])];
    for (int k = 0; k < 8; ++k) {
      EXPECT_GE(mesh.element_nodes(e)[k], part.first_node);
      EXPECT_LT(mesh.element_nodes(e)[k], part.first_node + part.node_count);
    }
  }
}

TEST(HilbertOrder, ConsecutiveCellsOfTheCurveAreFaceNeighbours) {
  constexpr int n = 8;
  std::vector<std::pair<std::uint64_t, std::array<int, 3>>> cells;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      for (int k = 0; k < n; ++k)
        cells.push_back({hilbert_index({(i + 0.5) / n, (j + 0.5) / n, (k + 0.5) / n}), {i, j, k}});
  std::sort(cells.begin(), cells.end());
  for (std::size_t c = 1; c < cells.size(); ++c) {
    EXPECT_NE(cells[c].first, cells[c - 1].first);
    int distance = 0;
    for (int k = 0; k < 3; ++k)
      distance += std::abs(cells[c].second[std::size_t(k)] - cells[c - 1].second[std::size_t(k)]);
    EXPECT_EQ(distance, 1) << "cells " << c - 1 << " and " << c;
  }
}

// A mesh's elements in a random order: with `reorder` the part has the same elements and
// nodes, and its elements come in rows as a built-in box's do (element e + 1's node k is
// element e's node k plus one: the packed kernels then load a pack's nodes as vectors).
TEST(HilbertOrder, ReorderingAShuffledMeshPutsItsElementsInRows) {
  auto file = input::read_gmsh(meshes + "tube_hex8.msh", {}, "");
  input::GmshElements& hexes = file.volumes.at(0).elements.at(0);
  const std::size_t count = hexes.tags.size();
  std::vector<std::size_t> order(count);
  std::iota(order.begin(), order.end(), std::size_t(0));
  std::uint64_t state = 12345;
  for (std::size_t i = count - 1; i > 0; --i) {  // Fisher-Yates with a fixed LCG
    state = state * 6364136223846793005ULL + 1442695040888963407ULL;
    std::swap(order[i], order[std::size_t((state >> 33) % (i + 1))]);
  }
  const Mesh file_order = import(file, mesh_part("tube", input::Formulation::hex8, {}, false));
  input::GmshElements shuffled = hexes;
  for (std::size_t e = 0; e < count; ++e) {
    shuffled.tags[e] = hexes.tags[order[e]];
    std::copy_n(hexes.nodes.begin() + std::ptrdiff_t(8 * order[e]), 8,
                shuffled.nodes.begin() + std::ptrdiff_t(8 * e));
  }
  hexes = shuffled;
  // The share of consecutive elements that continue a row.
  auto in_rows = [](const Mesh& mesh) {
    std::size_t rows = 0;
    for (std::size_t e = 0; e + 1 < mesh.element_count(); ++e) {
      bool row = true;
      for (int k = 0; k < 8; ++k) row = row && mesh.element_nodes(e + 1)[k] == mesh.element_nodes(e)[k] + 1;
      rows += row ? 1 : 0;
    }
    return double(rows) / double(mesh.element_count() - 1);
  };
  const Mesh kept = import(file, mesh_part("tube", input::Formulation::hex8, {}, false));
  const Mesh ordered = import(file, mesh_part("tube", input::Formulation::hex8, {}, true));
  EXPECT_EQ(kept.element_count(), ordered.element_count());
  EXPECT_EQ(kept.node_count(), ordered.node_count());
  std::printf("elements continuing a row: Gmsh's order %.3f, shuffled %.3f, reordered %.3f\n",
              in_rows(file_order), in_rows(kept), in_rows(ordered));
  EXPECT_LT(in_rows(kept), 0.01);
  EXPECT_GT(in_rows(ordered), 0.9);
  // The same points, and every element keeps its positive orientation (import checks it).
  auto sorted_points = [](const Mesh& mesh) {
    std::vector<std::array<double, 3>> points;
    for (std::uint32_t n = 0; n < mesh.node_count(); ++n) points.push_back(point(mesh, n));
    std::sort(points.begin(), points.end());
    return points;
  };
  EXPECT_EQ(sorted_points(kept), sorted_points(ordered));
  EXPECT_EQ(face_of(kept, 0, input::PartFace::surface).segments.size(),
            face_of(ordered, 0, input::PartFace::surface).segments.size());
}

// Every one of the 24 rotations of a brick keeps it right-handed: the turned elements of
// the rows pass the import's corner-Jacobian check (a Gmsh hex20 mesh, reordered).
TEST(HilbertOrder, TurnedHex20ElementsStayRightHandedAndKeepTheirMidEdgeNodes) {
  const auto file = input::read_gmsh(meshes + "hertz_ball_coarse_hex20.msh", {}, "");
  const Mesh mesh = import(file, mesh_part("ball", input::Formulation::hex20, {}, true));
  double worst = 0.0;  // a mid-edge node off its edge's middle, over the element size
  for (std::size_t e = 0; e < mesh.element_count(); ++e) {
    const std::uint32_t* nodes = mesh.element_nodes(e);
    for (int v = 8; v < 20; ++v) {
      std::array<double, 3> middle{};
      for (int c = 0; c < 8; ++c) {
        int distance = 0;
        for (int k = 0; k < 3; ++k)
          distance += std::abs(brick_offsets[std::size_t(v)][std::size_t(k)] -
                               brick_offsets[std::size_t(c)][std::size_t(k)]);
        if (distance == 1)
          for (int k = 0; k < 3; ++k) middle[std::size_t(k)] += 0.5 * point(mesh, nodes[c])[std::size_t(k)];
      }
      for (int k = 0; k < 3; ++k)
        worst = std::max(worst, std::abs(point(mesh, nodes[v])[std::size_t(k)] - middle[std::size_t(k)]));
    }
  }
  // Curved edges on the sphere put mid-edge nodes off the chord's middle by the sagitta,
  // R (1 - cos(pi / 32)) = 48 um at most; a node of another edge is 1 mm or more away.
  EXPECT_LT(worst, 1e-4);
}

// ---------------------------------------------------------------- what the library returns, wrong

// One unit cube of 8-node hexahedra, tags 1..8, in the physical volume "v".
input::GmshMesh cube() {
  input::GmshMesh file;
  file.file = "cube.msh";
  const double corners[8][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
                                {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
  for (std::size_t i = 0; i < 8; ++i) {
    file.node_tags.push_back(i + 1);
    file.coordinates.insert(file.coordinates.end(), corners[i], corners[i] + 3);
  }
  input::GmshElements hexes;
  hexes.type = input::gmsh_type::hex8;
  hexes.name = "Hexahedron 8";
  hexes.dimension = 3;
  hexes.nodes_per_element = 8;
  hexes.tags = {7};
  hexes.nodes = {1, 2, 3, 4, 5, 6, 7, 8};
  file.volumes.push_back({"v", {hexes}});
  return file;
}

std::string import_error(const input::GmshMesh& file,
                         input::Formulation formulation = input::Formulation::hex8) {
  try {
    import(file, mesh_part("v", formulation));
  } catch (const InputError& error) {
    EXPECT_EQ(error.key_path(), "parts[0].mesh");
    return error.what();
  }
  return "no error";
}

TEST(ImportErrors, AGoodCubeIsAccepted) {
  const Mesh mesh = import(cube(), mesh_part("v", input::Formulation::hex8));
  EXPECT_EQ(mesh.element_count(), 1u);
  EXPECT_EQ(face_of(mesh, 0, input::PartFace::surface).segments.size(), 6u);
}

TEST(ImportErrors, EachWrongMeshIsNamedWithTheFileAndWhatIsWrong) {
  auto with = [](auto change) {
    input::GmshMesh file = cube();
    change(file);
    return file;
  };
  auto add_type = [](input::GmshMesh& file, int type, const char* name, std::size_t count) {
    input::GmshElements other;
    other.type = type;
    other.name = name;
    other.dimension = 3;
    other.tags.assign(count, 99);
    file.volumes[0].elements.push_back(other);
  };
  const std::pair<input::GmshMesh, std::string> cases[] = {
      {with([](auto& f) { f.volumes[0].name = "w"; }), "no physical volume 'v' of 'cube.msh'"},
      {with([&](auto& f) { add_type(f, 4, "Tetrahedron 4", 12); }),
       "has 12 tetrahedra ('Tetrahedron 4', Gmsh type 4)"},
      {with([&](auto& f) { add_type(f, 6, "Prism 6", 3); }), "has 3 prisms ('Prism 6', Gmsh type 6)"},
      {with([&](auto& f) { add_type(f, 7, "Pyramid 5", 2); }), "has 2 pyramids ('Pyramid 5', Gmsh type 7)"},
      {with([&](auto& f) { add_type(f, 12, "Hexahedron 27", 1); }),
       "has 1 27-node hexahedra ('Hexahedron 27', Gmsh type 12)"},
      {with([&](auto& f) { add_type(f, input::gmsh_type::hex20, "Hexahedron 20", 2); }),
       "mixes 1 8-node hexahedron and 2 20-node hexahedrons"},
      {with([](auto& f) { f.volumes[0].elements.clear(); }), "has no elements"},
      {with([](auto& f) { f.volumes[0].elements[0].nodes[6] = 42; }),
       "element 7 of the physical volume 'v' of 'cube.msh' names node 42, which the file does not have"},
      {with([](auto& f) { f.volumes[0].elements[0].nodes[6] = 1; }),
       "element 7 of the physical volume 'v' of "
       "'cube.msh' is degenerate: node 1 is two"},
      {with([](auto& f) { std::swap(f.volumes[0].elements[0].nodes[1], f.volumes[0].elements[0].nodes[3]); }),
       "element 7 of the physical volume 'v' of 'cube.msh' is inverted: the Jacobian at its corner node 1 is "
       "negative"},
      {with([](auto& f) {
         f.coordinates[3 * 6 + 2] = 0.0, f.coordinates[3 * 5 + 2] = 0.0, f.coordinates[3 * 4 + 2] = 0.0,
                               f.coordinates[3 * 7 + 2] = 0.0;
       }),
       "is degenerate: the Jacobian at its corner node 1 is zero"},
      {with([](auto& f) { f.coordinates[4] = std::nan(""); }), "at a coordinate that is not a finite number"},
      {with([](auto& f) { f.volumes[0].elements[0].nodes.pop_back(); }), "1 element with 7 node tags"},
      {with([](auto& f) { f.node_tags[1] = 1; }), "has node tag 1 twice"},
      {with([](auto& f) { f.coordinates.pop_back(); }), "gives 23 coordinates for 8 nodes"},
      {with([](auto& f) {  // the cube twice
         auto& hexes = f.volumes[0].elements[0];
         hexes.tags.push_back(8);
         const std::vector<std::size_t> same = hexes.nodes;
         hexes.nodes.insert(hexes.nodes.end(), same.begin(), same.end());
       }),
       "elements 7 and 8 of the physical volume 'v' of 'cube.msh' have the same nodes"},
      {with([](auto& f) {  // a second copy of the cube: every face shared by two, and one face by more
         auto& hexes = f.volumes[0].elements[0];
         hexes.tags.push_back(8);
         hexes.tags.push_back(9);
         const std::vector<std::size_t> same = hexes.nodes;
         hexes.nodes.insert(hexes.nodes.end(), same.begin(), same.end());
         hexes.nodes.insert(hexes.nodes.end(), same.begin(), same.end());
       }),
       "have the same nodes"},
  };
  for (const auto& [file, expected] : cases) {
    const std::string message = import_error(file);
    EXPECT_NE(message.find(expected), std::string::npos) << "expected '" << expected << "' in: " << message;
    EXPECT_NE(message.find("deck.yaml"), std::string::npos) << message;
  }
  EXPECT_NE(import_error(cube(), input::Formulation::hex20)
                .find("has 8-node hexahedra, but the part's formulation "
                      "hex20 takes 20-node ones"),
            std::string::npos);
}

TEST(ImportErrors, AFileThatIsNotAGmshMeshOrIsMissingIsNamed) {
  auto read_error = [](const std::string& path) {
    try {
      input::read_gmsh(path, SourceLocation{"deck.yaml", 3, 5}, "parts[0].mesh.file");
    } catch (const InputError& error) {
      return std::string(error.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(read_error("/no/such/file.msh").find("cannot read the mesh file '/no/such/file.msh'"),
            std::string::npos);
  const std::string deck = std::string(EXDYN_SOURCE_DIR) + "/input/plate_impact.yaml";
  const std::string not_a_mesh = read_error(deck);
  EXPECT_NE(not_a_mesh.find("is not a Gmsh mesh: its first line is '# The seed paper"), std::string::npos)
      << not_a_mesh;
  EXPECT_NE(not_a_mesh.find("deck.yaml:3:5: parts[0].mesh.file"), std::string::npos) << not_a_mesh;
}

// The fuzz target's generator and checks on 3,000 byte strings of a fixed generator (and
// the seeds and past findings of tests/fuzz/): every one is refused with an InputError or
// gives a part that keeps the import's promises; both kinds occur.
TEST(ImportFuzz, GeneratedBrokenMeshesAreRefusedOrKeepThePromises) {
  std::vector<std::string> inputs;
  for (const char* folder : {"seeds/mesh", "regressions/mesh"}) {
    const std::filesystem::path path = std::filesystem::path(EXDYN_SOURCE_DIR) / "tests/fuzz" / folder;
    if (!std::filesystem::exists(path)) continue;
    for (const auto& entry : std::filesystem::directory_iterator(path)) {
      std::ifstream file(entry.path(), std::ios::binary);
      inputs.emplace_back(std::istreambuf_iterator<char>(file), std::istreambuf_iterator<char>());
    }
  }
  std::uint64_t state = 2026;
  for (int i = 0; i < 3000; ++i) {
    std::string bytes;
    state = state * 6364136223846793005ULL + 1442695040888963407ULL;
    const int length = int((state >> 33) % 12);
    for (int k = 0; k < length; ++k) {
      state = state * 6364136223846793005ULL + 1442695040888963407ULL;
      bytes.push_back(static_cast<char>(state >> 56));
    }
    inputs.push_back(bytes);
  }
  int accepted = 0, refused = 0;
  for (const std::string& bytes : inputs) {
    try {
      const std::string problem = fuzz::check_mesh_input(bytes);
      EXPECT_EQ(problem, "") << "input of " << bytes.size() << " bytes";
      ++accepted;
    } catch (const InputError&) {
      ++refused;
    }
  }
  std::printf("generated meshes: %d accepted, %d refused with a message\n", accepted, refused);
  EXPECT_GT(accepted, 100);
  EXPECT_GT(refused, 100);
}

}  // namespace
}  // namespace exdyn::mesh
