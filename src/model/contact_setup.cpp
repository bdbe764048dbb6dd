#include "model/contact_setup.hpp"

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
#include "model/contact_geometry.hpp"
#include "model/opened_faces.hpp"
#include "model/single_surface_setup.hpp"

namespace exdyn::solver {

namespace {

// The largest of a figure over the ranks (ContactScope::largest), or the figure.
double over_ranks(const ContactScope& scope, double figure) {
  return scope.largest ? scope.largest(figure) : figure;
}

// Whether node n's mass is this rank's (ContactScope::held).
bool held(const ContactScope& scope, std::uint32_t n) { return !scope.held || (*scope.held)[n] != 0; }

// The largest 1/m of the master nodes of segments [begin, end) of a pass, 1/kg (a halo
// node's 1/m is 0; each node is held by some rank).
double largest_master_inverse_mass(const Model& model, const contact::ContactSurfaces& s, std::size_t begin,
                                   std::size_t end, const ContactScope& scope) {
  double largest = 0.0;
  for (std::size_t seg = begin; seg < end; ++seg)
    for (int k = 0; k < contact::node_count(s.segments[seg].type); ++k)
      largest = std::max(largest, 1.0 / model.mass[s.segments[seg].nodes[std::size_t(k)]]);
  return over_ranks(scope, largest);
}

// The stiffness of each quadrature point, N/m: kappa (Pa/m) times its weight, kappa
// the deck's fixed value or the automatic scale 8 M / L capped per slave segment so
// that no slave node's springs together exceed the frequency caps of penalty.hpp:
// kappa a_I <= scale min(accurate, stable bound) for 1/m_I + the largest master 1/m,
// with a_I the node's spring area (PassGeometry::spring_area). A single surface's
// points also get the kappa for each of its faces as the master side
// (ContactSurfaces::face_kappa): a point takes the one of the segment it meets.
void quadrature_stiffness(const input::ContactOptions& options, const Model& model, PassGeometry& g,
                          double dt, double courant, const ContactScope& scope) {
  auto& s = g.surfaces;
  // Each slave segment's cap on kappa for the master inverse mass given.
  auto segment_caps = [&](double master_inverse_mass) {
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
    return segment_kappa;
  };
  auto automatic = [&](std::size_t p) {
    return options.penalty.scale * contact::automatic_pressure_stiffness(g.modulus, s.normal_length[p]);
  };
  const bool per_face = options.single_surface && !options.penalty.stiffness;
  std::vector<double> face_inverse_mass;  // the largest 1/m of each master face's nodes
  double master_inverse_mass = 0.0;
  if (per_face) {
    for (std::size_t f = 0, begin = 0; f < g.master_face_end.size(); begin = g.master_face_end[f++]) {
      face_inverse_mass.push_back(largest_master_inverse_mass(model, s, begin, g.master_face_end[f], scope));
      master_inverse_mass = std::max(master_inverse_mass, face_inverse_mass.back());
    }
  } else {
    master_inverse_mass = largest_master_inverse_mass(model, s, 0, s.segments.size(), scope);
  }
  const std::vector<double> segment_kappa = segment_caps(master_inverse_mass);
  s.stiffness.resize(s.quadrature_points.size());
  for (std::size_t p = 0; p < s.quadrature_points.size(); ++p) {
    const contact::QuadraturePoint& q = s.quadrature_points[p];
    const double kappa = options.penalty.stiffness ? *options.penalty.stiffness  // Pa/m
                                                   : std::min(automatic(p), segment_kappa[q.segment]);
    s.stiffness[p] = kappa * q.weight;
  }
  if (!per_face) return;
  // A slave segment's points share its face's length, so its automatic kappa.
  s.face_count = face_inverse_mass.size();
  s.face_kappa.assign(s.slave_segments.size() * s.face_count, 0.0);
  for (std::size_t f = 0; f < s.face_count; ++f) {
    const std::vector<double> caps = segment_caps(face_inverse_mass[f]);
    for (std::size_t p = 0; p < s.quadrature_points.size(); ++p) {
      const std::uint32_t seg = s.quadrature_points[p].segment;
      s.face_kappa[seg * s.face_count + f] = std::min(automatic(p), caps[seg]);
    }
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
  // a / m of a node (a halo node's mass is infinite: 0; its own rank has its figure).
  auto area_per_mass = [&](const std::vector<std::uint32_t>& nodes, const std::vector<double>& area,
                           std::uint32_t node) {
    const auto at = std::size_t(std::lower_bound(nodes.begin(), nodes.end(), node) - nodes.begin());
    return area[at] / model.mass[node];
  };
  auto segment_mean = [&](const contact::SegmentNodes& ids, const std::vector<std::uint32_t>& nodes,
                          const std::vector<double>& area) {
    double sum = 0.0;
    for (int k = 0; k < contact::node_count(ids.type); ++k)
      sum += area_per_mass(nodes, area, ids.nodes[std::size_t(k)]);
    return sum / contact::node_count(ids.type);
  };
  // The master nodes' spring areas over the master side, or, on a single surface, over
  // each face by itself (a node on two faces is pressed through one of them, as in a
  // pair on that face).
  std::vector<std::size_t> group_end{s.segments.size()};
  if (options.single_surface) group_end = g.master_face_end;
  double largest_master = 0.0;
  s.master_area_per_mass.clear();
  for (std::size_t group = 0, begin = 0; group < group_end.size(); begin = group_end[group++]) {
    const std::vector<contact::SegmentNodes> segments(s.segments.begin() + std::ptrdiff_t(begin),
                                                      s.segments.begin() + std::ptrdiff_t(group_end[group]));
    std::vector<std::uint32_t> master_nodes;
    for (const contact::SegmentNodes& ids : segments)
      master_nodes.insert(master_nodes.end(), ids.nodes.begin(),
                          ids.nodes.begin() + contact::node_count(ids.type));
    std::sort(master_nodes.begin(), master_nodes.end());
    master_nodes.erase(std::unique(master_nodes.begin(), master_nodes.end()), master_nodes.end());
    const std::vector<double> master_area = spring_areas(options, model.mesh.x_ref, segments, master_nodes);
    for (std::size_t i = 0; i < master_nodes.size(); ++i)
      largest_master = std::max(largest_master, master_area[i] / model.mass[master_nodes[i]]);
    for (const contact::SegmentNodes& ids : segments)
      s.master_area_per_mass.push_back(segment_mean(ids, master_nodes, master_area));
  }
  largest_master = over_ranks(scope, largest_master);
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
    // A single surface is one pass in which every contact is seen from both sides, as a
    // two-pass pair's: each of its springs carries half.
    const int pass_count = options.two_pass || options.single_surface ? 2 : 1;
    double smallest_length = std::numeric_limits<double>::infinity();
    std::vector<PassGeometry> geometry;
    if (options.single_surface) {
      const input::ContactOptions resolved = resolved_surface_options(model, options);
      geometry = surface_face_geometries(deck, model, resolved, [&](PassGeometry& face) {
        slave_point_stiffness(resolved, model, face, dt, dt / critical_dt, scope);
      });
    } else {
      for (int p = 0; p < pass_count; ++p) {
        geometry.push_back(p == 0 ? pass_geometry(deck, model, options, options.slave, options.master)
                                  : pass_geometry(deck, model, options, options.master, options.slave));
        slave_point_stiffness(options, model, geometry.back(), dt, dt / critical_dt, scope);
      }
    }
    for (const PassGeometry& g : geometry) smallest_length = std::min(smallest_length, g.smallest_length);
    if (options.penalty.stiffness)
      refuse_unstable_stiffness(deck, model, pair, geometry, options, contact.pairs.size(), dt,
                                dt / critical_dt, scope);
    if (options.single_surface) {
      PassGeometry surface = merge_surface_faces(model, resolved_surface_options(model, options), geometry);
      if (options.surface_all) find_segment_elements(model, surface.surfaces);
      geometry.clear();
      geometry.push_back(std::move(surface));
    }
    pair.slave_points = geometry.front().surfaces.mortar       ? input::SlavePoints::mortar
                        : geometry.front().surfaces.quadrature ? input::SlavePoints::quadrature
                                                               : input::SlavePoints::nodes;
    for (auto& g : geometry) {
      pair.passes.push_back(std::move(g.surfaces));
      pair.places.push_back(scope.held ? std::move(g.place) : PassPlace{});
    }
    auto& settings = pair.settings;
    settings.project = contact::select_method(options.local_search.method);
    if (const auto fallback = options.local_search.fallback;
        fallback && *fallback != options.local_search.method)
      settings.fallback = contact::select_method(*fallback);
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

double ContactPair::normal_force_sum() const {
  double sum = 0.0;
  for (const auto& state : states) sum += state.normal_force_sum;
  return sum;
}

double ContactPair::tangential_force_sum() const {
  double sum = 0.0;
  for (const auto& state : states) sum += state.tangential_force_sum;
  return sum;
}

long ContactPair::points_in_contact() const {
  long count = 0;
  for (const auto& state : states) count += state.points_in_contact;
  return count;
}

void ContactPair::follow_peaks() {
  max_force = std::max(max_force, contact::norm(slave_force()));
  if (const double sum = normal_force_sum(); sum > peak_normal_force_sum) {
    peak_normal_force_sum = sum;
    points_in_contact_at_peak = points_in_contact();
  }
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
