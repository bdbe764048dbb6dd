#include "model/single_surface_setup.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <string>
#include <utility>

#include "common/errors.hpp"
#include "contact/edge_contact.hpp"
#include "mesh/mesh.hpp"
#include "model/opened_faces.hpp"

namespace exdyn::solver {

input::ContactOptions resolved_surface_options(const Model& model, const input::ContactOptions& options) {
  input::ContactOptions resolved = options;
  // A face that folds (a Gmsh part's whole boundary) as its sides, each a face.
  resolved.slave.clear();
  for (const input::FaceRef& f : options.slave) {
    const std::size_t sides = f.fold_side < 0 ? contact_face(model, f, {}).sides.size() : 1;
    for (std::size_t k = 0; k < sides; ++k) {
      input::FaceRef side = f;
      if (sides > 1) side.fold_side = static_cast<int>(k);
      resolved.slave.push_back(side);
    }
  }
  resolved.master = resolved.slave;
  bool eight_node_segments = false;
  for (const input::FaceRef& f : resolved.slave)
    eight_node_segments = eight_node_segments || model.mesh.parts.at(std::size_t(f.part)).order == 2;
  resolved.slave_points = input::resolved_slave_points(options.slave_points, eight_node_segments);
  if (options.surface_all) {  // and the faces erosion can open
    const std::vector<input::FaceRef> opening = opening_faces(model, resolved.slave);
    EXDYN_ASSERT(opening.empty() || resolved.slave_points != input::SlavePoints::mortar);  // the validator's
    resolved.slave.insert(resolved.slave.end(), opening.begin(), opening.end());
    resolved.master = resolved.slave;
  }
  return resolved;
}

mesh::KeepSegment off_held_planes(const Model& model) {
  return [&model](const mesh::FaceSegment& segment) {
    const NodalVectors& x = model.mesh.x_ref;
    for (int c = 0; c < 3; ++c) {
      const std::vector<double>& coordinate = x.component(c);
      const double x0 = coordinate[segment.nodes[0]];
      bool held_plane = true;
      for (int k = 0; k < segment.node_count && held_plane; ++k) {
        const std::uint32_t node = segment.nodes[std::size_t(k)];
        held_plane = held_at_rest(model, c, node) &&
                     std::abs(coordinate[node] - x0) <= 1.0e-12 * std::max({std::abs(x0), 1.0e-3});
      }
      if (held_plane) return false;
    }
    return true;
  };
}

std::vector<PassGeometry> surface_face_geometries(const input::Deck& deck, const Model& model,
                                                  const input::ContactOptions& options,
                                                  const std::function<void(PassGeometry&)>& set_stiffness) {
  std::vector<PassGeometry> faces;
  const mesh::KeepSegment keep = off_held_planes(model);
  for (const input::FaceRef& f : options.slave) {  // the first face's master side is the surface's
    PassGeometry g = pass_geometry(deck, model, options, {f}, options.slave, keep, faces.empty());
    set_stiffness(g);
    if (!faces.empty()) {  // (assigning {} would keep the capacity)
      std::vector<contact::SegmentNodes>().swap(g.surfaces.segments);
      std::vector<double>().swap(g.surfaces.master_area_per_mass);
      std::vector<std::uint32_t>().swap(g.place.segment_ids);
    }
    faces.push_back(std::move(g));
  }
  return faces;
}

namespace {

std::size_t index_of(const std::vector<std::uint32_t>& sorted, std::uint32_t value) {
  return static_cast<std::size_t>(std::lower_bound(sorted.begin(), sorted.end(), value) - sorted.begin());
}

// Node mode: each node's sides (the faces it lies on, in face order) with their
// stiffness, its smallest normal length, and its corners (the segments at it).
void add_node_sides(const std::vector<PassGeometry>& faces, const std::vector<std::size_t>& segment_face,
                    contact::ContactSurfaces& s) {
  const std::size_t n = s.slave_nodes.size();
  std::vector<std::vector<std::uint32_t>> node_faces(n);
  s.side_begin.assign(n + 1, 0);
  s.normal_length.assign(n, std::numeric_limits<double>::infinity());
  s.stiffness.assign(n, 0.0);
  std::vector<std::vector<double>> stiffness(n);
  for (std::size_t k = 0; k < faces.size(); ++k) {
    const contact::ContactSurfaces& face = faces[k].surfaces;
    for (std::size_t i = 0; i < face.slave_nodes.size(); ++i) {
      const std::size_t p = index_of(s.slave_nodes, face.slave_nodes[i]);
      node_faces[p].push_back(static_cast<std::uint32_t>(k));
      stiffness[p].push_back(face.stiffness[i]);
      s.normal_length[p] = std::min(s.normal_length[p], face.normal_length[i]);
    }
  }
  for (std::size_t p = 0; p < n; ++p) {
    if (node_faces[p].size() > contact::max_node_sides)
      throw InputError("a node of a contact surface lies on " + std::to_string(node_faces[p].size()) +
                       " of its faces; a single surface takes at most " +
                       std::to_string(contact::max_node_sides) + " faces at a node: list fewer faces");
    s.side_begin[p + 1] = s.side_begin[p] + static_cast<std::uint32_t>(node_faces[p].size());
    s.side_stiffness.insert(s.side_stiffness.end(), stiffness[p].begin(), stiffness[p].end());
    s.stiffness[p] = stiffness[p].front();
  }
  // The corners, sorted by node.
  std::vector<std::vector<contact::NodeCorner>> corners(n);
  for (std::size_t seg = 0; seg < s.segments.size(); ++seg) {
    const contact::SegmentNodes& ids = s.segments[seg];
    for (int i = 0; i < contact::node_count(ids.type); ++i) {
      const std::size_t p = index_of(s.slave_nodes, ids.nodes[std::size_t(i)]);
      if (p == n || s.slave_nodes[p] != ids.nodes[std::size_t(i)])
        continue;  // a node of another rank's points
      const auto& on = node_faces[p];
      const auto side = std::find(on.begin(), on.end(), static_cast<std::uint32_t>(segment_face[seg]));
      if (side == on.end()) continue;
      corners[p].push_back({static_cast<std::uint32_t>(seg), static_cast<std::uint8_t>(i),
                            static_cast<std::uint8_t>(side - on.begin())});
    }
  }
  s.corner_begin.assign(n + 1, 0);
  for (std::size_t p = 0; p < n; ++p) {
    s.corner_begin[p + 1] = s.corner_begin[p] + static_cast<std::uint32_t>(corners[p].size());
    s.node_corners.insert(s.node_corners.end(), corners[p].begin(), corners[p].end());
  }
}

}  // namespace

std::vector<std::array<std::int32_t, 4>> edge_neighbours(const std::vector<contact::SegmentNodes>& segments,
                                                         const std::vector<std::uint8_t>& live) {
  std::map<std::pair<std::uint32_t, std::uint32_t>, std::vector<std::int32_t>> at_edge;
  auto edge_key = [](const contact::SegmentNodes& ids, std::size_t e) {
    const std::uint32_t a = ids.nodes[contact::edge_corners[e][0]],
                        b = ids.nodes[contact::edge_corners[e][1]];
    return std::make_pair(std::min(a, b), std::max(a, b));
  };
  for (std::size_t seg = 0; seg < segments.size(); ++seg)
    if (live.empty() || live[seg] != 0)
      for (std::size_t e = 0; e < 4; ++e) at_edge[edge_key(segments[seg], e)].push_back(std::int32_t(seg));
  std::vector<std::array<std::int32_t, 4>> neighbours(segments.size());
  for (std::size_t seg = 0; seg < segments.size(); ++seg)
    for (std::size_t e = 0; e < 4; ++e) {
      const auto& sharing = at_edge[edge_key(segments[seg], e)];
      neighbours[seg][e] = sharing.size() == 1   ? -1
                           : sharing.size() == 2 ? (sharing[0] == std::int32_t(seg) ? sharing[1] : sharing[0])
                                                 : -2;
    }
  return neighbours;
}

PassGeometry merge_surface_faces(const Model& model, const input::ContactOptions& options,
                                 std::vector<PassGeometry>& faces) {
  EXDYN_ASSERT(!faces.empty());
  PassGeometry g;
  auto& s = g.surfaces;
  const contact::ContactSurfaces& whole = faces.front().surfaces;  // its master side is the surface
  s.single_surface = true;
  s.quadrature = whole.quadrature;
  s.mortar = whole.mortar;
  s.triangle_points = whole.triangle_points;
  s.master_area_per_mass = whole.master_area_per_mass;
  s.segments = whole.segments;
  s.edges = whole.edges;
  s.moving_nodes = whole.moving_nodes;
  g.place.segment_ids = faces.front().place.segment_ids;
  g.modulus = faces.front().modulus;
  g.smallest_length = faces.front().smallest_length;
  // Each segment's face, and whether each face lies on the first face's part.
  std::vector<std::size_t> segment_face;
  const int first_part = options.slave.front().part;
  const mesh::KeepSegment keep = off_held_planes(model);
  std::uint64_t first_point = 0;  // of the face, in the whole surface
  for (std::size_t k = 0; k < faces.size(); ++k) {
    const input::FaceRef& f = options.slave[k];
    const mesh::Face face = contact_face(model, f, keep);
    segment_face.insert(segment_face.end(), face.segments.size(), k);
    const auto first = static_cast<std::uint8_t>(f.part == first_part);
    s.first_part_segment.insert(s.first_part_segment.end(), face.segments.size(), first);
    const contact::ContactSurfaces& own = faces[k].surfaces;
    s.slave_nodes.insert(s.slave_nodes.end(), own.slave_nodes.begin(), own.slave_nodes.end());
    if (s.mortar) {  // face k's slave segments after the earlier faces', keyed by their index
      s.slave_segments.insert(s.slave_segments.end(), own.slave_segments.begin(), own.slave_segments.end());
      for (auto field : {&contact::ContactSurfaces::segment_kappa, &contact::ContactSurfaces::segment_length,
                         &contact::ContactSurfaces::slave_area_per_mass})
        (s.*field).insert((s.*field).end(), (own.*field).begin(), (own.*field).end());
      s.first_part_point.insert(s.first_part_point.end(), own.slave_segments.size(), first);
      for (std::uint32_t key : faces[k].place.point_keys)
        g.place.point_keys.push_back(static_cast<std::uint32_t>(first_point + key));
      first_point += face.whole_count();
      continue;
    }
    if (!s.quadrature) continue;
    // Gauss points: face k's after the earlier faces'; its slave segments are its
    // master segments, in the same order.
    const auto segment_offset = static_cast<std::uint32_t>(s.slave_segments.size());
    s.slave_segments.insert(s.slave_segments.end(), own.slave_segments.begin(), own.slave_segments.end());
    for (contact::QuadraturePoint q : own.quadrature_points) {
      q.segment += segment_offset;
      s.quadrature_points.push_back(q);
    }
    s.stiffness.insert(s.stiffness.end(), own.stiffness.begin(), own.stiffness.end());
    s.face_kappa.insert(s.face_kappa.end(), own.face_kappa.begin(), own.face_kappa.end());
    s.normal_length.insert(s.normal_length.end(), own.normal_length.begin(), own.normal_length.end());
    s.first_part_point.insert(s.first_part_point.end(), own.quadrature_points.size(), first);
    for (std::uint32_t key : faces[k].place.point_keys)
      g.place.point_keys.push_back(static_cast<std::uint32_t>(first_point + key));
    const auto side_points = std::uint64_t(
        options.quadrature.value_or(model.mesh.parts.at(std::size_t(f.part)).order == 2 ? 3 : 2));
    first_point += face.whole_count() * side_points * side_points;
  }
  EXDYN_ASSERT(segment_face.size() == s.segments.size());
  if (!s.face_kappa.empty()) {  // each face's kappa for each face as the master side
    s.face_count = faces.size();
    EXDYN_ASSERT(s.face_kappa.size() == s.slave_segments.size() * s.face_count);
    s.segment_face.assign(segment_face.begin(), segment_face.end());
  }
  s.edge_neighbours = edge_neighbours(s.segments);
  std::sort(s.slave_nodes.begin(), s.slave_nodes.end());
  s.slave_nodes.erase(std::unique(s.slave_nodes.begin(), s.slave_nodes.end()), s.slave_nodes.end());
  if (!s.quadrature && !s.mortar) {
    add_node_sides(faces, segment_face, s);
    // A node lies on the first part when any face of it there holds it.
    s.first_part_point.assign(s.slave_nodes.size(), 0);
    for (std::size_t k = 0; k < faces.size(); ++k)
      if (options.slave[k].part == first_part)
        for (std::uint32_t node : faces[k].surfaces.slave_nodes)
          s.first_part_point[index_of(s.slave_nodes, node)] = 1;
  }
  return g;
}

}  // namespace exdyn::solver
