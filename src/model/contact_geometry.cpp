// A contact pass's geometry from the deck's faces (contact_geometry.hpp).
#include "model/contact_geometry.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <optional>

#include "common/errors.hpp"
#include "contact/edge_contact.hpp"
#include "contact/penalty.hpp"
#include "contact/quadrature.hpp"
#include "material/elastic.hpp"

namespace exdyn::solver {

double dilatational_modulus(const input::Deck& deck, int part) {
  const auto& m =
      deck.materials[static_cast<std::size_t>(deck.parts[static_cast<std::size_t>(part)].material_index)];
  return material::elastic_constants(m.youngs_modulus, m.poissons_ratio, m.density).dilatational_modulus();
}

namespace {

contact::SegmentNodes segment_nodes(const mesh::FaceSegment& face_segment) {
  contact::SegmentNodes segment;
  segment.type = face_segment.node_count == 8 ? contact::SegmentType::quad8 : contact::SegmentType::quad4;
  segment.nodes = face_segment.nodes;
  return segment;
}

contact::Segment reference_segment(const NodalVectors& x, const contact::SegmentNodes& ids) {
  contact::Segment segment;
  segment.type = ids.type;
  for (int i = 0; i < contact::node_count(ids.type); ++i) {
    const std::uint32_t n = ids.nodes[std::size_t(i)];
    segment.nodes[std::size_t(i)] = {x.x[n], x.y[n], x.z[n]};
  }
  return segment;
}

// |a1 x a2| at xi: the area element of the segment, m^2 per unit xi1 xi2.
double area_element(const contact::Segment& segment, contact::Xi xi) {
  const contact::SurfacePoint p = contact::evaluate(segment, xi);
  return contact::norm(contact::cross(p.a1, p.a2));
}

// The share of a segment's area (m^2) that each of its nodes carries for the
// automatic stiffness of slave nodes. quad4: a quarter of the area |d1 x d2| / 2 of
// its diagonals (exact when planar). quad8: the consistent nodal areas integral N_I dA
// are negative at the corners (-A/12 on a flat square), so the areas are lumped like
// the HRZ mass: integral N_I^2 dA, scaled to add up to the area (3x3 Gauss points).
std::array<double, 8> nodal_areas(const NodalVectors& x, const contact::SegmentNodes& ids) {
  std::array<double, 8> areas{};
  const contact::Segment segment = reference_segment(x, ids);
  if (ids.type == contact::SegmentType::quad4) {
    const contact::Vec3 d1 = segment.nodes[2] - segment.nodes[0], d2 = segment.nodes[3] - segment.nodes[1];
    const double quarter = 0.25 * 0.5 * contact::norm(contact::cross(d1, d2));
    for (int i = 0; i < 4; ++i) areas[std::size_t(i)] = quarter;
    return areas;
  }
  const contact::GaussLegendre rule = contact::gauss_legendre(3);
  double area = 0.0, sum = 0.0;
  std::array<double, 8> diagonal{};
  for (int i = 0; i < rule.count; ++i)
    for (int j = 0; j < rule.count; ++j) {
      const contact::Xi xi{rule.abscissa[std::size_t(i)], rule.abscissa[std::size_t(j)]};
      const double dA = rule.weight[std::size_t(i)] * rule.weight[std::size_t(j)] * area_element(segment, xi);
      const std::array<double, 8> N = contact::shape_functions(ids.type, xi);
      for (int k = 0; k < 8; ++k) diagonal[std::size_t(k)] += N[std::size_t(k)] * N[std::size_t(k)] * dA;
      area += dA;
    }
  for (double d : diagonal) sum += d;
  for (int k = 0; k < 8; ++k) areas[std::size_t(k)] = area * diagonal[std::size_t(k)] / sum;
  return areas;
}

}  // namespace

// What the surface does past each edge of each master segment (edge_contact.hpp): it
// goes on where the edge's two corner nodes bound another master segment too, or lie
// on a symmetry plane: both held in the same component a and at the same reference
// coordinate x_a (the cut faces of a half or quarter model), the mirror axis a.
namespace {

std::pair<std::uint32_t, std::uint32_t> edge_key(const contact::SegmentNodes& ids, int e) {
  const std::uint32_t a = ids.nodes[contact::edge_corners[e][0]], b = ids.nodes[contact::edge_corners[e][1]];
  return std::make_pair(std::min(a, b), std::max(a, b));
}

}  // namespace

std::vector<contact::SegmentEdges> segment_edges(const Model& model,
                                                 const std::vector<contact::SegmentNodes>& segments,
                                                 const std::vector<std::uint8_t>& live) {
  const NodalVectors& x = model.mesh.x_ref;
  auto mirror_axis = [&](std::uint32_t a, std::uint32_t b) {
    const std::array<const std::vector<double>*, 3> coordinate{&x.x, &x.y, &x.z};
    for (int c = 0; c < 3; ++c) {
      const double xa = (*coordinate[std::size_t(c)])[a], xb = (*coordinate[std::size_t(c)])[b];
      if (held_at_rest(model, c, a) && held_at_rest(model, c, b) &&
          std::abs(xa - xb) <= 1.0e-12 * std::max({std::abs(xa), std::abs(xb), 1.0e-3}))
        return c;
    }
    return -1;
  };
  std::vector<contact::SegmentEdges> edges(segments.size());
  for (std::size_t i = 0; i < segments.size(); ++i)
    for (int e = 0; e < 4; ++e) {
      const auto key = edge_key(segments[i], e);
      edges[i].mirror_axis[std::size_t(e)] = static_cast<std::int8_t>(mirror_axis(key.first, key.second));
    }
  continue_edges(segments, live, edges);
  return edges;
}

void continue_edges(const std::vector<contact::SegmentNodes>& segments, const std::vector<std::uint8_t>& live,
                    std::vector<contact::SegmentEdges>& edges) {
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> edge_count;
  for (std::size_t i = 0; i < segments.size(); ++i)
    if (live.empty() || live[i] != 0)
      for (int e = 0; e < 4; ++e) ++edge_count[edge_key(segments[i], e)];
  for (std::size_t i = 0; i < segments.size(); ++i) {
    edges[i].continued = 0;
    for (int e = 0; e < 4; ++e)
      if (edge_count[edge_key(segments[i], e)] > 1 || edges[i].mirror_axis[std::size_t(e)] >= 0)
        edges[i].continued |= static_cast<std::uint8_t>(1u << e);
  }
}

mesh::Face contact_face(const Model& model, const input::FaceRef& f, const mesh::KeepSegment& keep) {
  return keep ? mesh::cut_face(mesh::face_of(model.mesh, f), keep) : mesh::face_of(model.mesh, f);
}

namespace {

// The node count (4 or 8) of the segments of face f: of its first, or, cut to none
// (ContactScope), of its part's bricks.
int face_segment_nodes(const Model& model, const input::FaceRef& f, const mesh::Face& face) {
  if (!face.segments.empty()) return face.segments.front().node_count;
  return model.mesh.parts.at(static_cast<std::size_t>(f.part)).order == 2 ? 8 : 4;
}

// The Gauss points along each side of a slave segment of `nodes` nodes: the deck's
// quadrature, by default 2 on quad4 and 3 on quad8. Mortar takes the default for its
// spring areas (its `quadrature` is the points of a triangle).
int points_per_side(const input::ContactOptions& options, int nodes) {
  const int default_points = nodes == 4 ? 2 : 3;
  return options.slave_points == input::SlavePoints::mortar ? default_points
                                                            : options.quadrature.value_or(default_points);
}

// The Gauss points of slave segment `ids`: n x n, n = side_points (default 2 on quad4,
// 3 on quad8), weight w_i w_j |a1 x a2| on the reference segment, keyed from
// first_key in the whole pass.
void add_gauss_points(const NodalVectors& x, const contact::SegmentNodes& ids, int side_points,
                      std::uint64_t first_key, double length, PassGeometry& g) {
  auto& s = g.surfaces;
  const contact::GaussLegendre rule = contact::gauss_legendre(side_points);
  const contact::Segment segment = reference_segment(x, ids);
  const auto segment_index = static_cast<std::uint32_t>(s.slave_segments.size());
  s.slave_segments.push_back(ids);
  for (int b = 0; b < rule.count; ++b)
    for (int a = 0; a < rule.count; ++a) {
      contact::QuadraturePoint point;
      point.segment = segment_index;
      point.xi = {rule.abscissa[std::size_t(a)], rule.abscissa[std::size_t(b)]};
      point.weight =
          rule.weight[std::size_t(a)] * rule.weight[std::size_t(b)] * area_element(segment, point.xi);
      s.quadrature_points.push_back(point);
      g.place.point_keys.push_back(static_cast<std::uint32_t>(first_key + std::uint64_t(b * rule.count + a)));
      s.normal_length.push_back(length);
    }
}

// The master faces' segments, keyed by their index in the whole pass; the modulus and
// smallest length over them too. Returns whether a face has 8-node segments.
bool add_master_faces(const input::Deck& deck, const Model& model, const std::vector<input::FaceRef>& master,
                      const mesh::KeepSegment& keep, PassGeometry& g) {
  bool eight_node_segments = false;
  std::uint32_t first_segment = 0;  // of the face, in the whole pass
  for (const auto& f : master) {
    const mesh::Face face = contact_face(model, f, keep);
    eight_node_segments = eight_node_segments || face_segment_nodes(model, f, face) == 8;
    for (std::size_t k = 0; k < face.segments.size(); ++k) {
      g.surfaces.segments.push_back(segment_nodes(face.segments[k]));
      g.place.segment_ids.push_back(first_segment + face.index_in_whole(k));
    }
    first_segment += static_cast<std::uint32_t>(face.whole_count());
    g.master_face_end.push_back(g.surfaces.segments.size());
    g.modulus = std::min(g.modulus, dilatational_modulus(deck, f.part));
    g.smallest_length = std::min(g.smallest_length, face.normal_length);
  }
  return eight_node_segments;
}

}  // namespace

// The spring area of each of `nodes` (sorted) over `segments` (m^2): the sum over the
// n x n Gauss points of the segments at each node of |N_I| w sum_J |N_J|, n as
// points_per_side. What a node's springs act over, for the caps of penalty.hpp.
std::vector<double> spring_areas(const input::ContactOptions& options, const NodalVectors& x,
                                 const std::vector<contact::SegmentNodes>& segments,
                                 const std::vector<std::uint32_t>& nodes) {
  std::vector<double> area(nodes.size(), 0.0);
  for (const contact::SegmentNodes& ids : segments) {
    const contact::GaussLegendre rule =
        contact::gauss_legendre(points_per_side(options, contact::node_count(ids.type)));
    const contact::Segment segment = reference_segment(x, ids);
    for (int b = 0; b < rule.count; ++b)
      for (int a = 0; a < rule.count; ++a) {
        const contact::Xi xi{rule.abscissa[std::size_t(a)], rule.abscissa[std::size_t(b)]};
        const double weight =
            rule.weight[std::size_t(a)] * rule.weight[std::size_t(b)] * area_element(segment, xi);
        const std::array<double, 8> N = contact::shape_functions(ids.type, xi);
        double absolute_sum = 0.0;
        for (int k = 0; k < contact::node_count(ids.type); ++k) absolute_sum += std::abs(N[std::size_t(k)]);
        for (int k = 0; k < contact::node_count(ids.type); ++k) {
          const auto at = std::lower_bound(nodes.begin(), nodes.end(), ids.nodes[std::size_t(k)]);
          area[std::size_t(at - nodes.begin())] += std::abs(N[std::size_t(k)]) * weight * absolute_sum;
        }
      }
  }
  return area;
}

PassGeometry pass_geometry(const input::Deck& deck, const Model& model, const input::ContactOptions& options,
                           const std::vector<input::FaceRef>& slave,
                           const std::vector<input::FaceRef>& master, const mesh::KeepSegment& keep,
                           bool whole_master) {
  PassGeometry g;
  auto& s = g.surfaces;
  const NodalVectors& x = model.mesh.x_ref;
  std::vector<mesh::Face> slave_faces;
  bool eight_node_segments = false;
  for (const auto& f : slave) {
    slave_faces.push_back(contact_face(model, f, keep));
    eight_node_segments = eight_node_segments || face_segment_nodes(model, f, slave_faces.back()) == 8;
    s.slave_nodes.insert(s.slave_nodes.end(), slave_faces.back().nodes.begin(),
                         slave_faces.back().nodes.end());
    g.modulus = std::min(g.modulus, dilatational_modulus(deck, f.part));
  }
  const input::SlavePoints points = input::resolved_slave_points(options.slave_points, eight_node_segments);
  s.quadrature = points == input::SlavePoints::quadrature;
  s.mortar = points == input::SlavePoints::mortar;
  std::sort(s.slave_nodes.begin(), s.slave_nodes.end());
  s.slave_nodes.erase(std::unique(s.slave_nodes.begin(), s.slave_nodes.end()), s.slave_nodes.end());
  auto slave_index = [&](std::uint32_t node) {
    return static_cast<std::size_t>(std::lower_bound(s.slave_nodes.begin(), s.slave_nodes.end(), node) -
                                    s.slave_nodes.begin());
  };
  std::vector<double> node_length(s.slave_nodes.size(), std::numeric_limits<double>::infinity());
  g.area.assign(s.slave_nodes.size(), 0.0);
  std::uint64_t first_point = 0;  // of the face, in the whole pass
  for (std::size_t i = 0; i < slave.size(); ++i) {
    const mesh::Face& face = slave_faces[i];
    const double length = face.normal_length;
    g.smallest_length = std::min(g.smallest_length, length);
    for (std::uint32_t node : face.nodes) {
      double& l = node_length[slave_index(node)];
      l = std::min(l, length);
    }
    const int side_points = points_per_side(options, face_segment_nodes(model, slave[i], face));
    const auto segment_points = std::uint64_t(side_points * side_points);
    for (std::size_t at = 0; at < face.segments.size(); ++at) {
      const contact::SegmentNodes ids = segment_nodes(face.segments[at]);
      if (s.mortar) {  // the points are made each step; a segment's key is its index
        s.slave_segments.push_back(ids);
        s.segment_length.push_back(length);
        g.place.point_keys.push_back(static_cast<std::uint32_t>(first_point + face.index_in_whole(at)));
        continue;
      }
      if (!s.quadrature) {
        const std::array<double, 8> areas = nodal_areas(x, ids);
        for (int k = 0; k < contact::node_count(ids.type); ++k)
          g.area[slave_index(ids.nodes[std::size_t(k)])] += areas[std::size_t(k)];
        continue;
      }
      add_gauss_points(x, ids, side_points, first_point + face.index_in_whole(at) * segment_points, length,
                       g);
    }
    first_point += face.whole_count() * (s.mortar ? 1 : segment_points);
  }
  if (s.quadrature || s.mortar) g.spring_area = spring_areas(options, x, s.slave_segments, s.slave_nodes);
  if (!s.quadrature && !s.mortar) s.normal_length = node_length;
  eight_node_segments = add_master_faces(deck, model, master, keep, g) || eight_node_segments;
  // Mortar's triangle rule: the deck's, or by the faces of both sides.
  if (s.mortar)
    s.triangle_points =
        options.quadrature.value_or(input::mortar_default_triangle_points(eight_node_segments));
  if (!whole_master) return g;
  s.edges = segment_edges(model, s.segments);
  s.moving_nodes = s.slave_nodes;
  for (const auto& segment : s.segments)
    s.moving_nodes.insert(s.moving_nodes.end(), segment.nodes.begin(),
                          segment.nodes.begin() + contact::node_count(segment.type));
  std::sort(s.moving_nodes.begin(), s.moving_nodes.end());
  s.moving_nodes.erase(std::unique(s.moving_nodes.begin(), s.moving_nodes.end()), s.moving_nodes.end());
  return g;
}

}  // namespace exdyn::solver
