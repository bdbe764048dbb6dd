// A rank's nodes from the parts: masses, initial velocities, fixed components, the
// contact faces near it and a 20-node block's groups (setup_parts.hpp).
#include <algorithm>
#include <array>
#include <cstring>
#include <functional>
#include <limits>
#include <map>
#include <memory>
#include <numeric>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <unordered_map>

#include "common/errors.hpp"
#include "element/corner_checks.hpp"
#include "element/element_family.hpp"
#include "material/elastic.hpp"
#include "material/material_law.hpp"
#include "mesh/mapped.hpp"
#include "mesh/mesh.hpp"
#include "model/memory_estimate.hpp"
#include "ranks/load_balance.hpp"
#include "ranks/setup_parts.hpp"

namespace exdyn::solver::setup {

// The lumped masses of `nodes` (global ids, ascending), kg: each from the elements
// around it, in ascending order, by the family's rule (element::add_lumped_mass), so
// every node gets one process's additions in one process's order.
std::vector<double> masses_of(const input::Deck& deck, const SetupParts& deck_parts,
                              const std::vector<std::uint32_t>& nodes) {
  std::vector<std::uint32_t> elements;  // global ids
  for (const std::uint32_t g : nodes) {
    const SetupPart& part = deck_parts.part_of_node(g);
    for (const std::uint32_t e : part.elements_around(g)) elements.push_back(part.first_element + e);
  }
  std::sort(elements.begin(), elements.end());
  elements.erase(std::unique(elements.begin(), elements.end()), elements.end());
  std::vector<std::uint32_t> halo;  // the nodes of those elements, ascending
  for (const std::uint32_t e : elements) {
    const SetupPart& part = deck_parts.part_of_element(e);
    for (const std::uint32_t g : part.element_nodes(e - part.first_element)) halo.push_back(g);
  }
  std::sort(halo.begin(), halo.end());
  halo.erase(std::unique(halo.begin(), halo.end()), halo.end());
  auto index = [&](std::uint32_t g) {
    return std::uint32_t(std::lower_bound(halo.begin(), halo.end(), g) - halo.begin());
  };
  const NodalVectors x = deck_parts.points(halo);
  std::vector<double> mass(halo.size(), 0.0);
  for (std::size_t first = 0; first < elements.size();) {  // a block of each part's elements
    const SetupPart& part = deck_parts.part_of_element(elements[first]);
    std::size_t last = first;
    std::vector<std::uint32_t> connectivity;
    for (; last < elements.size() && elements[last] < part.first_element + part.element_count; ++last)
      for (const std::uint32_t g : part.element_nodes(elements[last] - part.first_element))
        connectivity.push_back(index(g));
    const input::MaterialOptions& m = deck.materials.at(std::size_t(part.options->material_index));
    element::ElementBlock block;  // what the lumping reads: the family, density and nodes
    block.formulation = part.options->formulation;
    block.family = &element::element_family(block.formulation);
    block.nodes_per_element = part.nodes_per_element;
    block.material = material::elastic_constants(m.youngs_modulus, m.poissons_ratio, m.density);
    block.count = std::uint32_t(last - first);
    block.connectivity = connectivity.data();
    element::add_lumped_mass(block, x, mass);
    first = last;
  }
  std::vector<double> result(nodes.size());
  for (std::size_t k = 0; k < nodes.size(); ++k) result[k] = mass[index(nodes[k])];
  return result;
}

// initial_velocity's values for `nodes` (global ids) of a model of them (their
// coordinates and fixed components), node by node.
NodalVectors initial_velocities(const SetupParts& deck_parts, const std::vector<std::uint32_t>& nodes,
                                const Model& m) {
  NodalVectors v(nodes.size());
  const NodalVectors& x = m.mesh.x_ref;
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    const std::array<double, 3> vi =
        part_initial_velocity(*deck_parts.part_of_node(nodes[i]).options, {x.x[i], x.y[i], x.z[i]});
    v.x[i] = vi[0], v.y[i] = vi[1], v.z[i] = vi[2];
  }
  apply_prescribed_velocity(m, v);
  return v;
}

// Keeps the face segments with a node among `nodes` (global ids, ascending).
mesh::KeepSegment touching(const std::vector<std::uint32_t>& nodes) {
  return [&nodes](const mesh::FaceSegment& segment) {
    for (int k = 0; k < segment.node_count; ++k)
      if (std::binary_search(nodes.begin(), nodes.end(), segment.nodes[std::size_t(k)])) return true;
    return false;
  };
}

// The fixed components of each of `nodes` (global ids, ascending): the indices into
// `nodes` of those on a face of a boundary condition fixing component c (build_model's
// rule: every node of the face, mid-side nodes included), from the faces' segments
// touching `nodes`.
PrescribedMotion fixed_of(const input::Deck& deck, const SetupParts& deck_parts,
                          const std::vector<std::uint32_t>& nodes) {
  std::vector<std::vector<std::uint32_t>> condition_nodes;  // global ids among `nodes`
  for (const auto& bc : deck.boundary_conditions) {
    std::vector<std::uint32_t>& mine = condition_nodes.emplace_back();
    for (const input::FaceRef& f : bc.faces) {
      const mesh::Face face = deck_parts.list.at(std::size_t(f.part)).face(f, touching(nodes));
      for (const std::uint32_t g : face.nodes)
        if (std::binary_search(nodes.begin(), nodes.end(), g)) mine.push_back(g);
    }
  }
  PrescribedMotion motion = prescribed_motion(deck, condition_nodes);
  const auto index = [&](std::uint32_t g) {
    return std::uint32_t(std::lower_bound(nodes.begin(), nodes.end(), g) - nodes.begin());
  };
  for (std::size_t c = 0; c < 3; ++c) {
    for (std::uint32_t& g : motion.nodes[c]) g = index(g);
    for (BoundaryNodes& condition : motion.boundary)
      for (std::uint32_t& g : condition.nodes[c]) g = index(g);
  }
  return motion;
}

SurfaceModel surface_model(const input::Deck& deck, const SetupParts& deck_parts, const NearRank* near) {
  SurfaceModel out;
  Model& m = out.model;
  std::vector<input::FaceRef> faces;
  for (const input::ContactOptions& pair : deck.contact) {
    faces.insert(faces.end(), pair.slave.begin(), pair.slave.end());
    faces.insert(faces.end(), pair.master.begin(), pair.master.end());
  }
  for (const input::RigidWallOptions& wall : deck.rigid_walls)
    faces.insert(faces.end(), wall.slave.begin(), wall.slave.end());
  mesh::KeepSegment keep;
  if (near) keep = touching(near->nodes);
  for (const SetupPart& part : deck_parts.list) {
    // The part's faces as a mapped or imported part has them (face_of finds them by
    // name or by physical surface), first in global ids.
    mesh::PartRange& range = m.mesh.parts.emplace_back(part.range());
    range.normal_lengths = part.built    ? part.built->parts[0].normal_lengths
                           : part.mapped ? std::array<double, 6>{}  // add_mapped_part sets none
                                         : mesh::box_normal_lengths(*part.options);
    for (const input::FaceRef& f : faces) {
      if (f.part != part.index) continue;
      const bool physical = f.side == input::PartFace::physical;
      const auto surface = std::size_t(f.surface);
      if (physical ? surface < range.physical_faces.size() && range.physical_faces[surface].whole_count() > 0
                   : std::any_of(range.faces.begin(), range.faces.end(),
                                 [&](const auto& face) { return face.first == f.side; }))
        continue;
      mesh::Face face = part.face(f, keep);
      out.nodes.insert(out.nodes.end(), face.nodes.begin(), face.nodes.end());
      if (physical) {
        if (range.physical_faces.size() <= surface) range.physical_faces.resize(surface + 1);
        range.physical_faces[surface] = std::move(face);
      } else {
        range.faces.emplace_back(f.side, std::move(face));
      }
    }
  }
  std::sort(out.nodes.begin(), out.nodes.end());
  out.nodes.erase(std::unique(out.nodes.begin(), out.nodes.end()), out.nodes.end());
  auto index = [&](std::uint32_t g) {
    return std::uint32_t(std::lower_bound(out.nodes.begin(), out.nodes.end(), g) - out.nodes.begin());
  };
  auto renumber = [&](mesh::Face& face) {
    for (std::uint32_t& g : face.nodes) g = index(g);
    for (mesh::FaceSegment& segment : face.segments)
      for (int k = 0; k < segment.node_count; ++k)
        segment.nodes[std::size_t(k)] = index(segment.nodes[std::size_t(k)]);
  };
  for (mesh::PartRange& range : m.mesh.parts) {
    for (auto& named : range.faces) renumber(named.second);
    for (mesh::Face& face : range.physical_faces) renumber(face);
  }
  m.mesh.x_ref = deck_parts.points(out.nodes);
  if (!near) {
    m.mass = masses_of(deck, deck_parts, out.nodes);
    PrescribedMotion motion = fixed_of(deck, deck_parts, out.nodes);
    m.fixed_nodes = std::move(motion.nodes);
    m.fixed_velocity = std::move(motion.velocity);
  } else {
    out.held.resize(out.nodes.size());
    m.mass.assign(out.nodes.size(), std::numeric_limits<double>::infinity());
    for (std::size_t k = 0; k < out.nodes.size(); ++k) {
      const auto at = std::lower_bound(near->nodes.begin(), near->nodes.end(), out.nodes[k]);
      if (at == near->nodes.end() || *at != out.nodes[k]) continue;
      out.held[k] = 1;
      m.mass[k] = near->model.mass[std::size_t(at - near->nodes.begin())];
    }
    for (std::size_t c = 0; c < 3; ++c)
      for (std::size_t k = 0; k < near->model.fixed_nodes[c].size(); ++k) {
        const std::uint32_t i = near->model.fixed_nodes[c][k];
        if (!std::binary_search(out.nodes.begin(), out.nodes.end(), near->nodes[i])) continue;
        m.fixed_nodes[c].push_back(index(near->nodes[i]));
        m.fixed_velocity[c].push_back(near->model.fixed_velocity[c][k]);
      }
  }
  m.inverse_mass.resize(m.mass.size());
  for (std::size_t i = 0; i < m.mass.size(); ++i) m.inverse_mass[i] = 1.0 / m.mass[i];
  return out;
}

// The whole block's groups of equal Jacobians of a 20-node part (ElementBlock::
// group_points), on every rank: each rank's own group starts (`count` elements here,
// their global ids `global`) are candidates, and the groups start at those of the
// candidates, in global order, that start one among them all; their points come with
// them from the ranks that hold them, so every rank has the whole block's bits.
// Collective over comm.
std::vector<std::array<double, 60>> whole_block_groups(const SetupPart& part, std::uint32_t count,
                                                       const std::uint32_t* connectivity,
                                                       const NodalVectors& x_ref, const std::uint32_t* global,
                                                       const mpi::Communicator& comm) {
  const input::Formulation formulation = part.options->formulation;
  // Each rank's group starts (global ids) with their nodes' coordinates, x of the 20,
  // then y, then z; every rank's, rank after rank.
  std::vector<std::uint32_t> mine;
  std::vector<double> my_points;
  for (const std::uint32_t e : element::jacobian_group_starts(formulation, count, connectivity, x_ref)) {
    mine.push_back(global[e]);
    for (int a = 0; a < 3; ++a)
      for (std::size_t k = 0; k < 20; ++k) my_points.push_back(x_ref.component(a)[connectivity[20 * e + k]]);
  }
  const std::vector<std::uint32_t> gathered = mpi::all_gather_varying(comm, mine);
  const std::vector<double> gathered_points = mpi::all_gather_varying(comm, my_points);
  // The candidates in global order, once each.
  std::vector<std::size_t> by_id(gathered.size());
  std::iota(by_id.begin(), by_id.end(), std::size_t(0));
  std::sort(by_id.begin(), by_id.end(),
            [&](std::size_t a, std::size_t b) { return gathered[a] < gathered[b]; });
  by_id.erase(std::unique(by_id.begin(), by_id.end(),
                          [&](std::size_t a, std::size_t b) { return gathered[a] == gathered[b]; }),
              by_id.end());
  NodalVectors points(20 * by_id.size());
  std::vector<std::uint32_t> order(20 * by_id.size());  // 0, 1, ... into the points
  std::iota(order.begin(), order.end(), 0u);
  for (std::size_t c = 0; c < by_id.size(); ++c)
    for (int a = 0; a < 3; ++a)
      for (std::size_t k = 0; k < 20; ++k)
        points.component(a)[20 * c + k] = gathered_points[60 * by_id[c] + 20 * std::size_t(a) + k];
  std::vector<std::array<double, 60>> groups;
  for (const std::uint32_t c :
       element::jacobian_group_starts(formulation, std::uint32_t(by_id.size()), order.data(), points)) {
    std::array<double, 60>& group = groups.emplace_back();
    for (std::size_t k = 0; k < 20; ++k)
      for (std::size_t a = 0; a < 3; ++a) group[20 * a + k] = points.component(int(a))[20 * c + k];
  }
  return groups;
}

}  // namespace exdyn::solver::setup
