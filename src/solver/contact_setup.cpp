#include "solver/contact_setup.hpp"

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

namespace {

double dilatational_modulus(const input::Deck& deck, int part) {
  const auto& m =
      deck.materials[static_cast<std::size_t>(deck.parts[static_cast<std::size_t>(part)].material_index)];
  return material::elastic_constants(m.youngs_modulus, m.poissons_ratio, m.density).dilatational_modulus();
}

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

// What the surface does past each edge of each master segment (edge_contact.hpp): it
// goes on where the edge's two corner nodes bound another master segment too, or lie
// on a symmetry plane: both held in the same component a and at the same reference
// coordinate x_a (the cut faces of a half or quarter model), the mirror axis a.
std::vector<contact::SegmentEdges> segment_edges(const Model& model,
                                                 const std::vector<contact::SegmentNodes>& segments) {
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> edge_count;
  auto edge_key = [](const contact::SegmentNodes& ids, int e) {
    const std::uint32_t a = ids.nodes[contact::edge_corners[e][0]],
                        b = ids.nodes[contact::edge_corners[e][1]];
    return std::make_pair(std::min(a, b), std::max(a, b));
  };
  for (const auto& ids : segments)
    for (int e = 0; e < 4; ++e) ++edge_count[edge_key(ids, e)];
  const NodalVectors& x = model.mesh.x_ref;
  auto mirror_axis = [&](std::uint32_t a, std::uint32_t b) {
    const std::array<const std::vector<double>*, 3> coordinate{&x.x, &x.y, &x.z};
    for (int c = 0; c < 3; ++c) {
      const auto& fixed = model.fixed_nodes[std::size_t(c)];
      const double xa = (*coordinate[std::size_t(c)])[a], xb = (*coordinate[std::size_t(c)])[b];
      if (std::binary_search(fixed.begin(), fixed.end(), a) &&
          std::binary_search(fixed.begin(), fixed.end(), b) &&
          std::abs(xa - xb) <= 1.0e-12 * std::max({std::abs(xa), std::abs(xb), 1.0e-3}))
        return c;
    }
    return -1;
  };
  std::vector<contact::SegmentEdges> edges(segments.size());
  for (std::size_t i = 0; i < segments.size(); ++i)
    for (int e = 0; e < 4; ++e) {
      const auto key = edge_key(segments[i], e);
      const int axis = mirror_axis(key.first, key.second);
      edges[i].mirror_axis[std::size_t(e)] = static_cast<std::int8_t>(axis);
      if (edge_count[key] > 1 || axis >= 0) edges[i].continued |= static_cast<std::uint8_t>(1u << e);
    }
  return edges;
}

struct PassGeometry {
  contact::ContactSurfaces surfaces;
  std::vector<double> area;  // node mode: tributary area of each slave node, m^2
  // quadrature mode: for each slave node, sum over the points of its segments of
  // |N_I| weight sum_J |N_J|, m^2: the area over which its springs act (the cap).
  std::vector<double> spring_area;
  double modulus = std::numeric_limits<double>::infinity();          // smallest M of the parts involved, Pa
  double smallest_length = std::numeric_limits<double>::infinity();  // m
  PassPlace place;  // the points' and segments' places in the whole pass
};

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
                           const std::vector<input::FaceRef>& master) {
  PassGeometry g;
  auto& s = g.surfaces;
  const NodalVectors& x = model.mesh.x_ref;
  std::vector<mesh::Face> slave_faces;
  bool eight_node_segments = false;
  for (const auto& f : slave) {
    slave_faces.push_back(mesh::face_of(model.mesh, f));
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
      // Gauss points of the slave segment: n x n, n = quadrature (default 2 on
      // quad4, 3 on quad8), weight w_i w_j |a1 x a2| on the reference segment.
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
          g.place.point_keys.push_back(static_cast<std::uint32_t>(
              first_point + face.index_in_whole(at) * segment_points + std::uint64_t(b * rule.count + a)));
          s.normal_length.push_back(length);
        }
    }
    first_point += face.whole_count() * (s.mortar ? 1 : segment_points);
  }
  if (s.quadrature || s.mortar) g.spring_area = spring_areas(options, x, s.slave_segments, s.slave_nodes);
  if (!s.quadrature && !s.mortar) s.normal_length = node_length;
  std::uint32_t first_segment = 0;  // of the face, in the whole pass
  for (const auto& f : master) {
    const mesh::Face face = mesh::face_of(model.mesh, f);
    eight_node_segments = eight_node_segments || face_segment_nodes(model, f, face) == 8;
    for (std::size_t k = 0; k < face.segments.size(); ++k) {
      s.segments.push_back(segment_nodes(face.segments[k]));
      g.place.segment_ids.push_back(first_segment + face.index_in_whole(k));
    }
    first_segment += static_cast<std::uint32_t>(face.whole_count());
    g.modulus = std::min(g.modulus, dilatational_modulus(deck, f.part));
    g.smallest_length = std::min(g.smallest_length, face.normal_length);
  }
  // Mortar's triangle rule: the deck's, or by the faces of both sides.
  if (s.mortar)
    s.triangle_points =
        options.quadrature.value_or(input::mortar_default_triangle_points(eight_node_segments));
  s.edges = segment_edges(model, s.segments);
  s.moving_nodes = s.slave_nodes;
  for (const auto& segment : s.segments)
    s.moving_nodes.insert(s.moving_nodes.end(), segment.nodes.begin(),
                          segment.nodes.begin() + contact::node_count(segment.type));
  std::sort(s.moving_nodes.begin(), s.moving_nodes.end());
  s.moving_nodes.erase(std::unique(s.moving_nodes.begin(), s.moving_nodes.end()), s.moving_nodes.end());
  return g;
}

// The largest of a figure over the ranks (ContactScope::largest), or the figure.
double over_ranks(const ContactScope& scope, double figure) {
  return scope.largest ? scope.largest(figure) : figure;
}

// Whether node n's mass is this rank's (ContactScope::held).
bool held(const ContactScope& scope, std::uint32_t n) { return !scope.held || (*scope.held)[n] != 0; }

// The largest 1/m of the master nodes of a pass, 1/kg (a halo node's 1/m is 0; each
// node is held by some rank).
double largest_master_inverse_mass(const Model& model, const contact::ContactSurfaces& s,
                                   const ContactScope& scope) {
  double largest = 0.0;
  for (const auto& segment : s.segments)
    for (int k = 0; k < contact::node_count(segment.type); ++k)
      largest = std::max(largest, 1.0 / model.mass[segment.nodes[std::size_t(k)]]);
  return over_ranks(scope, largest);
}

// The stiffness of each quadrature point, N/m: kappa (Pa/m) times its weight, kappa
// the deck's fixed value or the automatic scale 8 M / L capped per slave segment so
// that no slave node's springs together exceed the frequency caps of penalty.hpp:
// kappa a_I <= scale min(accurate, stable bound) for 1/m_I + the largest master 1/m,
// with a_I the node's spring area (PassGeometry::spring_area).
void quadrature_stiffness(const input::ContactOptions& options, const Model& model, PassGeometry& g,
                          double dt, double courant, const ContactScope& scope) {
  auto& s = g.surfaces;
  const double master_inverse_mass = largest_master_inverse_mass(model, s, scope);
  std::vector<double> segment_kappa(s.slave_segments.size(), std::numeric_limits<double>::infinity());
  for (std::size_t seg = 0; seg < s.slave_segments.size(); ++seg) {
    const contact::SegmentNodes& ids = s.slave_segments[seg];
    for (int k = 0; k < contact::node_count(ids.type); ++k) {
      const std::uint32_t node = ids.nodes[std::size_t(k)];
      const std::size_t i = static_cast<std::size_t>(
          std::lower_bound(s.slave_nodes.begin(), s.slave_nodes.end(), node) - s.slave_nodes.begin());
      const double inverse_mass = 1.0 / model.mass[node] + master_inverse_mass;
      const double cap =
          options.penalty.scale *
          std::min(contact::accurate_stiffness_bound(dt, inverse_mass),
                   contact::stable_stiffness_bound(dt, courant, options.penalty.damping, inverse_mass));
      segment_kappa[seg] = std::min(segment_kappa[seg], cap / g.spring_area[i]);
    }
  }
  s.stiffness.resize(s.quadrature_points.size());
  for (std::size_t p = 0; p < s.quadrature_points.size(); ++p) {
    const contact::QuadraturePoint& q = s.quadrature_points[p];
    double kappa = 0.0;  // Pa/m
    if (options.penalty.stiffness)
      kappa = *options.penalty.stiffness;
    else
      kappa = std::min(
          options.penalty.scale * contact::automatic_pressure_stiffness(g.modulus, s.normal_length[p]),
          segment_kappa[q.segment]);
    s.stiffness[p] = kappa * q.weight;
  }
}

// Mortar (docs/contact.md, "Mortar"): per slave segment kappa (Pa/m), the deck's fixed
// value or the automatic 8 M / L capped like the quadrature points' but per unit area,
// so that it is the same on every segment of a uniform layer however the face is cut:
// kappa <= scale min(accurate, stable bound) for the inverse mass per area
// a_I / m_I + max_J a_J / m_J (m^2/kg) of each slave node I, J over the master nodes,
// a the spring areas; and the mean a / m of each slave and master segment's nodes, which
// sets the dashpot's reduced mass per area.
void mortar_stiffness(const input::ContactOptions& options, const Model& model, PassGeometry& g, double dt,
                      double courant, const ContactScope& scope) {
  auto& s = g.surfaces;
  std::vector<std::uint32_t> master_nodes;
  for (const contact::SegmentNodes& ids : s.segments)
    master_nodes.insert(master_nodes.end(), ids.nodes.begin(),
                        ids.nodes.begin() + contact::node_count(ids.type));
  std::sort(master_nodes.begin(), master_nodes.end());
  master_nodes.erase(std::unique(master_nodes.begin(), master_nodes.end()), master_nodes.end());
  const std::vector<double> master_area = spring_areas(options, model.mesh.x_ref, s.segments, master_nodes);
  // a / m of a node (a halo node's mass is infinite: 0; its own rank has its figure).
  auto area_per_mass = [&](const std::vector<std::uint32_t>& nodes, const std::vector<double>& area,
                           std::uint32_t node) {
    const auto at = std::size_t(std::lower_bound(nodes.begin(), nodes.end(), node) - nodes.begin());
    return area[at] / model.mass[node];
  };
  double largest_master = 0.0;
  for (std::size_t i = 0; i < master_nodes.size(); ++i)
    largest_master = std::max(largest_master, master_area[i] / model.mass[master_nodes[i]]);
  largest_master = over_ranks(scope, largest_master);
  auto segment_mean = [&](const contact::SegmentNodes& ids, const std::vector<std::uint32_t>& nodes,
                          const std::vector<double>& area) {
    double sum = 0.0;
    for (int k = 0; k < contact::node_count(ids.type); ++k)
      sum += area_per_mass(nodes, area, ids.nodes[std::size_t(k)]);
    return sum / contact::node_count(ids.type);
  };
  s.master_area_per_mass.clear();
  for (const contact::SegmentNodes& ids : s.segments)
    s.master_area_per_mass.push_back(segment_mean(ids, master_nodes, master_area));
  s.slave_area_per_mass.clear();
  s.segment_kappa.clear();
  for (std::size_t seg = 0; seg < s.slave_segments.size(); ++seg) {
    const contact::SegmentNodes& ids = s.slave_segments[seg];
    s.slave_area_per_mass.push_back(segment_mean(ids, s.slave_nodes, g.spring_area));
    double cap = std::numeric_limits<double>::infinity();
    for (int k = 0; k < contact::node_count(ids.type); ++k) {
      const double inverse =
          area_per_mass(s.slave_nodes, g.spring_area, ids.nodes[std::size_t(k)]) + largest_master;
      cap = std::min(
          cap, options.penalty.scale *
                   std::min(contact::accurate_stiffness_bound(dt, inverse),
                            contact::stable_stiffness_bound(dt, courant, options.penalty.damping, inverse)));
    }
    s.segment_kappa.push_back(options.penalty.stiffness
                                  ? *options.penalty.stiffness
                                  : std::min(options.penalty.scale * contact::automatic_pressure_stiffness(
                                                                         g.modulus, s.segment_length[seg]),
                                             cap));
  }
}

// The stiffness of each slave point of a pass, N/m (ContactSurfaces::stiffness).
void slave_point_stiffness(const input::ContactOptions& options, const Model& model, PassGeometry& g,
                           double dt, double courant, const ContactScope& scope) {
  auto& s = g.surfaces;
  if (s.quadrature) {
    quadrature_stiffness(options, model, g, dt, courant, scope);
    return;
  }
  if (s.mortar) {
    mortar_stiffness(options, model, g, dt, courant, scope);
    return;
  }
  s.stiffness.resize(s.slave_nodes.size());
  for (std::size_t i = 0; i < s.slave_nodes.size(); ++i)
    s.stiffness[i] =
        options.penalty.stiffness
            ? *options.penalty.stiffness
            : options.penalty.scale * contact::automatic_stiffness(g.modulus, g.area[i], s.normal_length[i]);
}

contact::FrictionLaw friction_law(const std::optional<input::FrictionOptions>& friction) {
  contact::FrictionLaw law;
  if (!friction) return law;
  law.enabled = true;
  law.static_coefficient = friction->static_coefficient;
  law.dynamic_coefficient = friction->dynamic_coefficient;
  law.decay = friction->decay;
  return law;
}

// The penalty settings of a pair or a wall: the automatic caps at step dt.
void set_penalty(const input::PenaltyOptions& penalty, double dt, double critical_dt,
                 contact::ContactPassSettings& settings) {
  settings.damping_ratio = penalty.damping;
  settings.automatic_stiffness = !penalty.stiffness.has_value();
  settings.stiffness_scale = penalty.scale;
  settings.dt = settings.set_for_dt = dt;
  settings.courant = dt / critical_dt;
}

// A rigid wall: its slave side as the slave side of a pass against the same faces (the
// mirror image's), for the stiffness rule; the segments are not needed after.
RigidWall build_wall(const input::Deck& deck, const Model& model, const input::RigidWallOptions& options,
                     double dt, double critical_dt, const ContactScope& scope) {
  input::ContactOptions as_pair;
  as_pair.slave = as_pair.master = options.slave;
  as_pair.slave_points = options.slave_points;
  PassGeometry g = pass_geometry(deck, model, as_pair, options.slave, options.slave);
  slave_point_stiffness(as_pair, model, g, dt, dt / critical_dt, scope);
  RigidWall wall;
  wall.name = options.name;
  if (scope.held) wall.place.point_keys = std::move(g.place.point_keys);
  wall.surfaces = std::move(g.surfaces);
  wall.surfaces.segments.clear();
  wall.surfaces.edges.clear();
  wall.surfaces.moving_nodes = wall.surfaces.slave_nodes;
  const contact::Vec3 normal{options.normal[0], options.normal[1], options.normal[2]};
  wall.plane.normal = (1.0 / contact::norm(normal)) * normal;
  wall.plane.point = {options.point[0], options.point[1], options.point[2]};
  wall.plane.velocity = {options.velocity[0], options.velocity[1], options.velocity[2]};
  set_penalty(as_pair.penalty, dt, critical_dt, wall.settings);
  wall.settings.pass_count = 2;  // the image pair's two passes
  wall.settings.friction = friction_law(options.friction);
  return wall;
}

// A fixed penalty stiffness that no contact could carry stably is bad input: even
// for the heaviest slave node of the pair, with the master side taken as rigid
// (inverse mass 1/m_s, the most favourable case), k exceeds the bound of
// penalty.hpp for this step, Courant number and damping.
void refuse_unstable_stiffness(const input::Deck& deck, const Model& model, const ContactPair& pair,
                               const std::vector<PassGeometry>& geometry,
                               const input::ContactOptions& options, std::size_t index, double dt,
                               double courant, const ContactScope& scope) {
  // Nodes: the bound of the heaviest slave node. Quadrature points: kappa a_I for the
  // node whose bound / a_I is largest, the most favourable.
  double bound = 0.0;
  for (const auto& g : geometry) {
    const auto& pass = g.surfaces;
    for (std::size_t i = 0; i < pass.slave_nodes.size(); ++i) {
      if (!held(scope, pass.slave_nodes[i])) continue;  // a halo node's sums are not whole here
      const double node_bound = contact::stable_stiffness_bound(dt, courant, options.penalty.damping,
                                                                1.0 / model.mass[pass.slave_nodes[i]]);
      bound = std::max(bound, pass.quadrature || pass.mortar ? node_bound / g.spring_area[i] : node_bound);
    }
  }
  bound = over_ranks(scope, bound);
  if (*options.penalty.stiffness <= bound) return;
  const bool quadrature = geometry.front().surfaces.quadrature || geometry.front().surfaces.mortar;
  const char* units = quadrature ? "Pa/m" : "N/m";
  char text[440];
  std::snprintf(
      text, sizeof text,
      "%.4g %s is above the stability bound of this mesh and time step: no contact of pair '%s' can be "
      "stable with %s > %.4g %s (dt = %.4g s, Courant %.3g, damping %.3g; docs/contact.md). Lower it, "
      "use penalty: {scale: s} (the automatic rule), or lower time.courant",
      *options.penalty.stiffness, units, pair.name.c_str(), quadrature ? "kappa" : "k", bound, units, dt,
      courant, options.penalty.damping);
  throw InputError(SourceLocation{deck.source_file, 0, 0},
                   "contact[" + std::to_string(index) + "].penalty.stiffness", text);
}

}  // namespace

ContactModel build_contact(const input::Deck& deck, const Model& model, double dt, double critical_dt,
                           const ContactScope& scope) {
  ContactModel contact;
  for (const auto& options : deck.contact) {
    ContactPair pair;
    pair.name = options.name;
    const int pass_count = options.two_pass ? 2 : 1;
    double smallest_length = std::numeric_limits<double>::infinity();
    std::vector<PassGeometry> geometry;
    for (int p = 0; p < pass_count; ++p) {
      geometry.push_back(p == 0 ? pass_geometry(deck, model, options, options.slave, options.master)
                                : pass_geometry(deck, model, options, options.master, options.slave));
      smallest_length = std::min(smallest_length, geometry.back().smallest_length);
      slave_point_stiffness(options, model, geometry.back(), dt, dt / critical_dt, scope);
    }
    if (options.penalty.stiffness)
      refuse_unstable_stiffness(deck, model, pair, geometry, options, contact.pairs.size(), dt,
                                dt / critical_dt, scope);
    pair.slave_points = geometry.front().surfaces.mortar       ? input::SlavePoints::mortar
                        : geometry.front().surfaces.quadrature ? input::SlavePoints::quadrature
                                                               : input::SlavePoints::nodes;
    for (auto& g : geometry) {
      pair.passes.push_back(std::move(g.surfaces));
      pair.places.push_back(scope.held ? std::move(g.place) : PassPlace{});
    }
    auto& settings = pair.settings;
    settings.project = contact::select_method(options.local_search.method);
    settings.projection.method = options.local_search.method;
    settings.projection.tolerance = options.local_search.tolerance;
    settings.projection.max_iterations = options.local_search.max_iterations;
    settings.initial_guess = options.local_search.initial_guess;
    set_penalty(options.penalty, dt, critical_dt, settings);
    settings.friction = friction_law(options.friction);
    settings.pass_count = pass_count;
    // Penetrations deeper than half an element are not searched for; a node that
    // moves half the margin triggers a new global search.
    settings.search_distance = 0.5 * smallest_length;
    settings.margin = 0.5 * smallest_length;
    settings.cell_size = options.search.cell_size.value_or(0.0);
    pair.states.resize(pair.passes.size());
    for (const auto& pass : pair.passes)
      contact.nodes.insert(contact.nodes.end(), pass.moving_nodes.begin(), pass.moving_nodes.end());
    contact.pairs.push_back(std::move(pair));
  }
  for (const auto& options : deck.rigid_walls) {
    contact.walls.push_back(build_wall(deck, model, options, dt, critical_dt, scope));
    const auto& slave_nodes = contact.walls.back().surfaces.slave_nodes;
    contact.nodes.insert(contact.nodes.end(), slave_nodes.begin(), slave_nodes.end());
  }
  std::sort(contact.nodes.begin(), contact.nodes.end());
  contact.nodes.erase(std::unique(contact.nodes.begin(), contact.nodes.end()), contact.nodes.end());
  return contact;
}

void follow_time_step(ContactModel& contact, double fall) {
  auto follow = [fall](contact::ContactPassSettings& settings) {
    settings.dt = settings.set_for_dt * fall;
    settings.stiffness_growth = 1.0 / (fall * fall);
  };
  for (ContactPair& pair : contact.pairs) follow(pair.settings);
  for (RigidWall& wall : contact.walls) follow(wall.settings);
}

// A pass state's slave-side vector, the first pass's less the second's (whose slave
// side is the pair's master side): the pair's force on its slave side.
contact::Vec3 ContactPair::first_pass_less_second(contact::Vec3 contact::ContactPassState::*member) const {
  contact::Vec3 force{};
  for (std::size_t p = 0; p < states.size(); ++p)
    force = p == 0 ? force + states[p].*member : force - states[p].*member;
  return force;
}

contact::Vec3 ContactPair::normal_force() const {
  return first_pass_less_second(&contact::ContactPassState::slave_normal_force);
}

contact::Vec3 ContactPair::tangential_force() const {
  return first_pass_less_second(&contact::ContactPassState::slave_tangential_force);
}

double ContactModel::friction_work() const {
  double work = 0.0;
  for (const ContactPair& pair : pairs)
    for (const auto& state : pair.states) work += state.friction_work;
  for (const RigidWall& wall : walls) work += wall.state.friction_work;
  return work;
}

contact::Vec3 ContactPair::slave_force() const {
  return first_pass_less_second(&contact::ContactPassState::slave_force);
}

double ContactPair::max_penetration() const {
  double deepest = 0.0;
  for (const auto& state : states) deepest = std::max(deepest, state.max_penetration);
  return deepest;
}

std::string ContactModel::deepest_contact() const {
  std::string name = "contact ?";
  double deepest = -1.0;
  for (const auto& pair : pairs)
    if (pair.statistics.max_penetration_over_h > deepest)
      deepest = pair.statistics.max_penetration_over_h, name = "contact pair " + pair.name;
  for (const auto& wall : walls)
    if (wall.statistics.max_penetration_over_h > deepest)
      deepest = wall.statistics.max_penetration_over_h, name = "rigid wall " + wall.name;
  return name;
}

}  // namespace exdyn::solver
