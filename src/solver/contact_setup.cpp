#include "solver/contact_setup.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "common/errors.hpp"
#include "contact/penalty.hpp"
#include "material/elastic.hpp"

namespace exdyn::solver {

namespace {

// Element length normal to a face of a structured box part (m).
double normal_element_length(const input::PartOptions& part, input::BoxSide side) {
  const int axis = static_cast<int>(side) / 2;
  return (part.box_max[axis] - part.box_min[axis]) / part.elements[axis];
}

double dilatational_modulus(const input::Deck& deck, int part) {
  const auto& m =
      deck.materials[static_cast<std::size_t>(deck.parts[static_cast<std::size_t>(part)].material_index)];
  return material::elastic_constants(m.youngs_modulus, m.poissons_ratio, m.density).dilatational_modulus();
}

// Area (m^2) of a quadrilateral: |d1 x d2| / 2 with its diagonals (exact when planar).
double quad_area(const NodalVectors& x, const contact::Quad& q) {
  const contact::Vec3 d1{x.x[q[2]] - x.x[q[0]], x.y[q[2]] - x.y[q[0]], x.z[q[2]] - x.z[q[0]]};
  const contact::Vec3 d2{x.x[q[3]] - x.x[q[1]], x.y[q[3]] - x.y[q[1]], x.z[q[3]] - x.z[q[1]]};
  return 0.5 * contact::norm(contact::cross(d1, d2));
}

struct PassGeometry {
  contact::ContactSurfaces surfaces;
  std::vector<double> area;                                          // tributary area of each slave node, m^2
  double modulus = std::numeric_limits<double>::infinity();          // smallest M of the parts involved, Pa
  double smallest_length = std::numeric_limits<double>::infinity();  // m
};

PassGeometry pass_geometry(const input::Deck& deck, const Model& model,
                           const std::vector<input::FaceRef>& slave,
                           const std::vector<input::FaceRef>& master) {
  PassGeometry g;
  auto& s = g.surfaces;
  std::vector<mesh::Face> slave_faces;
  for (const auto& f : slave) {
    slave_faces.push_back(mesh::face_of(model.mesh, f.part, f.side));
    s.slave_nodes.insert(s.slave_nodes.end(), slave_faces.back().nodes.begin(),
                         slave_faces.back().nodes.end());
    g.modulus = std::min(g.modulus, dilatational_modulus(deck, f.part));
  }
  std::sort(s.slave_nodes.begin(), s.slave_nodes.end());
  s.slave_nodes.erase(std::unique(s.slave_nodes.begin(), s.slave_nodes.end()), s.slave_nodes.end());
  auto slave_index = [&](std::uint32_t node) {
    return static_cast<std::size_t>(std::lower_bound(s.slave_nodes.begin(), s.slave_nodes.end(), node) -
                                    s.slave_nodes.begin());
  };
  g.area.assign(s.slave_nodes.size(), 0.0);
  s.normal_length.assign(s.slave_nodes.size(), std::numeric_limits<double>::infinity());
  for (std::size_t i = 0; i < slave.size(); ++i) {
    const double length =
        normal_element_length(deck.parts[static_cast<std::size_t>(slave[i].part)], slave[i].side);
    g.smallest_length = std::min(g.smallest_length, length);
    for (const auto& quad : slave_faces[i].quads) {
      const double quarter = 0.25 * quad_area(model.mesh.x_ref, quad);
      for (std::uint32_t node : quad) g.area[slave_index(node)] += quarter;
    }
    for (std::uint32_t node : slave_faces[i].nodes) {
      double& l = s.normal_length[slave_index(node)];
      l = std::min(l, length);
    }
  }
  for (const auto& f : master) {
    const mesh::Face face = mesh::face_of(model.mesh, f.part, f.side);
    s.segments.insert(s.segments.end(), face.quads.begin(), face.quads.end());
    g.modulus = std::min(g.modulus, dilatational_modulus(deck, f.part));
    g.smallest_length = std::min(g.smallest_length,
                                 normal_element_length(deck.parts[static_cast<std::size_t>(f.part)], f.side));
  }
  s.moving_nodes = s.slave_nodes;
  for (const auto& quad : s.segments) s.moving_nodes.insert(s.moving_nodes.end(), quad.begin(), quad.end());
  std::sort(s.moving_nodes.begin(), s.moving_nodes.end());
  s.moving_nodes.erase(std::unique(s.moving_nodes.begin(), s.moving_nodes.end()), s.moving_nodes.end());
  return g;
}

// A fixed penalty stiffness that no contact could carry stably is bad input: even
// for the heaviest slave node of the pair, with the master side taken as rigid
// (inverse mass 1/m_s, the most favourable case), k exceeds the bound of
// penalty.hpp for this step, Courant number and damping.
void refuse_unstable_stiffness(const input::Deck& deck, const Model& model, const ContactPair& pair,
                               const input::ContactOptions& options, std::size_t index, double dt,
                               double courant) {
  double heaviest = 0.0;  // kg
  for (const auto& pass : pair.passes)
    for (const std::uint32_t node : pass.slave_nodes) heaviest = std::max(heaviest, model.mass[node]);
  const double bound = contact::stable_stiffness_bound(dt, courant, options.penalty.damping, 1.0 / heaviest);
  if (*options.penalty.stiffness <= bound) return;
  char text[400];
  std::snprintf(
      text, sizeof text,
      "%.4g N/m is above the stability bound of this mesh and time step: no contact of pair '%s' can be "
      "stable with k > %.4g N/m (dt = %.4g s, Courant %.3g, damping %.3g; docs/contact.md). Lower it, "
      "use penalty: {scale: s} (the automatic rule), or lower time.courant",
      *options.penalty.stiffness, pair.name.c_str(), bound, dt, courant, options.penalty.damping);
  throw InputError(SourceLocation{deck.source_file, 0, 0},
                   "contact[" + std::to_string(index) + "].penalty.stiffness", text);
}

}  // namespace

ContactModel build_contact(const input::Deck& deck, const Model& model, double dt, double critical_dt) {
  ContactModel contact;
  for (const auto& options : deck.contact) {
    ContactPair pair;
    pair.name = options.name;
    const int pass_count = options.two_pass ? 2 : 1;
    double smallest_length = std::numeric_limits<double>::infinity();
    for (int p = 0; p < pass_count; ++p) {
      PassGeometry g = p == 0 ? pass_geometry(deck, model, options.slave, options.master)
                              : pass_geometry(deck, model, options.master, options.slave);
      smallest_length = std::min(smallest_length, g.smallest_length);
      auto& s = g.surfaces;
      s.stiffness.resize(s.slave_nodes.size());
      for (std::size_t i = 0; i < s.slave_nodes.size(); ++i)
        s.stiffness[i] = options.penalty.stiffness
                             ? *options.penalty.stiffness
                             : options.penalty.scale *
                                   contact::automatic_stiffness(g.modulus, g.area[i], s.normal_length[i]);
      pair.passes.push_back(std::move(s));
    }
    if (options.penalty.stiffness)
      refuse_unstable_stiffness(deck, model, pair, options, contact.pairs.size(), dt, dt / critical_dt);
    auto& settings = pair.settings;
    settings.project = contact::select_method(options.local_search.method);
    settings.projection.method = options.local_search.method;
    settings.projection.tolerance = options.local_search.tolerance;
    settings.projection.max_iterations = options.local_search.max_iterations;
    settings.initial_guess = options.local_search.initial_guess;
    settings.damping_ratio = options.penalty.damping;
    settings.automatic_stiffness = !options.penalty.stiffness.has_value();
    settings.stiffness_scale = options.penalty.scale;
    settings.dt = dt;
    settings.courant = dt / critical_dt;
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
  std::sort(contact.nodes.begin(), contact.nodes.end());
  contact.nodes.erase(std::unique(contact.nodes.begin(), contact.nodes.end()), contact.nodes.end());
  return contact;
}

std::string ContactModel::pair_of(std::uint32_t node) const {
  for (const auto& pair : pairs)
    for (const auto& pass : pair.passes)
      if (std::binary_search(pass.slave_nodes.begin(), pass.slave_nodes.end(), node)) return pair.name;
  return "?";
}

}  // namespace exdyn::solver
