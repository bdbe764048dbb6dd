#include "model/model.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "common/errors.hpp"
#include "material/elastic.hpp"
#include "material/material_law.hpp"
#include "mesh/interior_faces.hpp"
#include "model/memory_estimate.hpp"
#include "model/opened_faces.hpp"

namespace exdyn::solver {

Model build_model(const input::Deck& deck) {
  check_mesh_size(deck);  // before anything of the mesh's size is allocated
  Model model;
  model.mesh = mesh::build_mesh(deck);
  const std::size_t node_count = model.mesh.node_count();
  model.mass.assign(node_count, 0.0);
  for (std::size_t p = 0; p < deck.parts.size(); ++p) {
    const input::PartOptions& part = deck.parts[p];
    const input::MaterialOptions& m = deck.materials.at(static_cast<std::size_t>(part.material_index));
    const mesh::PartRange& range = model.mesh.parts[p];
    model.blocks.push_back(element::make_element_block(
        part.formulation, material::elastic_constants(m.youngs_modulus, m.poissons_ratio, m.density),
        input::HourglassControl(part.hourglass_model, part.hourglass_coefficient), range.first_element,
        range.element_count, model.mesh.connectivity.data() + range.first_connectivity, model.mesh.x_ref,
        material::make_law(m, input::resolved_kinematics(part, m), part.f_bar)));
    element::add_lumped_mass(model.blocks.back(), model.mesh.x_ref, model.mass);
  }
  // The faces erosion can open, for the surfaces that follow it (model/opened_faces.hpp).
  for (const input::ContactOptions& pair : deck.contact)
    if (input::follows_erosion(deck, pair))
      for (const input::FaceRef& face : pair.slave) {
        mesh::PartRange& range = model.mesh.parts[std::size_t(face.part)];
        if (part_can_fail(model, face.part) && range.interior_faces.empty())
          range.interior_faces = mesh::interior_faces(model.mesh, face.part);
      }
  model.inverse_mass.resize(node_count);
  for (std::size_t i = 0; i < node_count; ++i) {
    EXDYN_ASSERT(model.mass[i] > 0.0);  // every node belongs to an element
    model.inverse_mass[i] = 1.0 / model.mass[i];
  }
  // Gravity: a body force rho g per unit volume, on the lumped mass m g per node (the
  // consistent load of a 20-node brick has the negative corner shares of its mass;
  // the lumped one the same total, docs/theory.md).
  if (!deck.loads.empty()) {
    model.load_acceleration.resize(node_count);
    for (const input::LoadOptions& load : deck.loads)
      for (std::size_t p = 0; p < deck.parts.size(); ++p) {
        if (!load.parts.empty() &&
            std::find(load.parts.begin(), load.parts.end(), int(p)) == load.parts.end())
          continue;
        const mesh::PartRange& range = model.mesh.parts[p];
        for (std::uint32_t i = range.first_node; i < range.first_node + range.node_count; ++i)
          for (int c = 0; c < 3; ++c) model.load_acceleration.component(c)[i] += load.gravity[std::size_t(c)];
      }
  }
  std::vector<std::vector<std::uint32_t>> condition_nodes;
  for (const auto& bc : deck.boundary_conditions) {
    std::vector<std::uint32_t>& nodes = condition_nodes.emplace_back();
    for (const auto& face_ref : bc.faces) {  // every node of the face, mid-side nodes included
      const mesh::Face face = mesh::face_of(model.mesh, face_ref);
      nodes.insert(nodes.end(), face.nodes.begin(), face.nodes.end());
    }
  }
  PrescribedMotion motion = prescribed_motion(deck, condition_nodes);
  if (!motion.conflict.empty()) throw InputError(motion.conflict);
  model.fixed_nodes = std::move(motion.nodes);
  model.fixed_velocity = std::move(motion.velocity);
  model.boundary = std::move(motion.boundary);
  return model;
}

PrescribedMotion prescribed_motion(const input::Deck& deck,
                                   const std::vector<std::vector<std::uint32_t>>& condition_nodes) {
  PrescribedMotion out;
  const auto& conditions = deck.boundary_conditions;
  out.boundary.resize(conditions.size());
  for (std::size_t c = 0; c < 3; ++c) {
    // (node, condition) of every prescribed component c, the earliest condition first.
    std::vector<std::pair<std::uint32_t, std::uint32_t>> claims;
    for (std::size_t b = 0; b < conditions.size(); ++b) {
      out.boundary[b].velocity[c] = conditions[b].fix[c] ? conditions[b].velocity[c] : 0.0;
      if (!conditions[b].fix[c]) continue;
      for (const std::uint32_t node : condition_nodes[b]) claims.emplace_back(node, std::uint32_t(b));
    }
    std::sort(claims.begin(), claims.end());
    claims.erase(std::unique(claims.begin(), claims.end()), claims.end());
    std::uint32_t owner = 0;  // the earliest condition at the current node
    for (std::size_t k = 0; k < claims.size(); ++k) {
      const auto [node, b] = claims[k];
      const double value = conditions[b].velocity[c];
      if (k > 0 && claims[k - 1].first == node) {  // a later condition at the same node
        const double earlier = conditions[owner].velocity[c];
        if (value != earlier && out.conflict.empty()) {
          char text[300];
          std::snprintf(text, sizeof text,
                        "boundary_conditions[%u] and boundary_conditions[%u] prescribe different %s "
                        "velocities (%.6g and %.6g m/s) at node %u, on faces they share",
                        unsigned(owner), unsigned(b),
                        c == 0   ? "x"
                        : c == 1 ? "y"
                                 : "z",
                        earlier, value, unsigned(node));
          out.conflict = text;
        }
        continue;
      }
      owner = b;
      out.nodes[c].push_back(node);
      out.velocity[c].push_back(value);
      out.boundary[b].nodes[c].push_back(node);
    }
  }
  return out;
}

std::array<double, 3> part_initial_velocity(const input::PartOptions& part, const std::array<double, 3>& x) {
  std::array<double, 3> v{part.initial_velocity[0], part.initial_velocity[1], part.initial_velocity[2]};
  // omega x (x - axis_point): a rigid rotation about the axis through axis_point.
  if (const auto& spin = part.initial_angular_velocity) {
    const input::Vec3& point = (*spin)[0];
    const input::Vec3& omega = (*spin)[1];
    const double r[3] = {x[0] - point[0], x[1] - point[1], x[2] - point[2]};
    v[0] += omega[1] * r[2] - omega[2] * r[1];
    v[1] += omega[2] * r[0] - omega[0] * r[2];
    v[2] += omega[0] * r[1] - omega[1] * r[0];
  }
  return v;
}

NodalVectors initial_velocity(const input::Deck& deck, const Model& model) {
  NodalVectors v(model.mesh.node_count());
  const NodalVectors& x = model.mesh.x_ref;
  for (std::size_t p = 0; p < deck.parts.size(); ++p) {
    const mesh::PartRange& range = model.mesh.parts[p];
    for (std::size_t i = range.first_node; i < range.first_node + range.node_count; ++i) {
      const std::array<double, 3> vi = part_initial_velocity(deck.parts[p], {x.x[i], x.y[i], x.z[i]});
      v.x[i] = vi[0], v.y[i] = vi[1], v.z[i] = vi[2];
    }
  }
  apply_prescribed_velocity(model, v);
  return v;
}

void apply_fixed_components(const Model& model, NodalVectors& field) {
  for (int c = 0; c < 3; ++c) {
    auto& component = field.component(c);
    for (const std::uint32_t node : model.fixed_nodes[c]) component[node] = 0.0;
  }
}

bool held_at_rest(const Model& model, int c, std::uint32_t node) {
  const std::vector<std::uint32_t>& nodes = model.fixed_nodes[std::size_t(c)];
  const auto at = std::lower_bound(nodes.begin(), nodes.end(), node);
  if (at == nodes.end() || *at != node) return false;
  const std::vector<double>& values = model.fixed_velocity[std::size_t(c)];
  return values.empty() || values[std::size_t(at - nodes.begin())] == 0.0;
}

void apply_prescribed_velocity(const Model& model, NodalVectors& velocity) {
  for (int c = 0; c < 3; ++c) {
    auto& component = velocity.component(c);
    const std::vector<std::uint32_t>& nodes = model.fixed_nodes[std::size_t(c)];
    const std::vector<double>& values = model.fixed_velocity[std::size_t(c)];
    for (std::size_t k = 0; k < nodes.size(); ++k) component[nodes[k]] = values.empty() ? 0.0 : values[k];
  }
}

double critical_time_step(const Model& model) {
  double dt = std::numeric_limits<double>::infinity();
  for (const auto& block : model.blocks)
    dt = std::min(dt, element::critical_time_step(block, model.mesh.x_ref));
  return dt;
}

TimeStepping time_stepping(const input::TimeOptions& time, double critical_dt) {
  TimeStepping result;
  result.dt = time.dt ? *time.dt : time.courant * critical_dt;
  // Steps to reach end_time; a ratio within round-off of an integer counts as
  // that integer (end_time = 448 dt must give 448 steps, not 449).
  const double ratio = time.end_time / result.dt;
  const double nearest = std::round(ratio);
  result.steps = static_cast<long>(
      std::abs(ratio - nearest) <= 1e-9 * std::max(1.0, ratio) ? nearest : std::ceil(ratio));
  result.steps = std::max(result.steps, 1L);
  return result;
}

}  // namespace exdyn::solver
