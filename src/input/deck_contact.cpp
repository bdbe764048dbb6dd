// The deck's contact pairs (penalty, global and local search settings, friction), its
// rigid walls and its loads.
#include <algorithm>
#include <map>
#include <string>
#include <vector>

#include "input/deck_validator.hpp"
#include "input/text_tools.hpp"

namespace exdyn::input::deck {

PenaltyOptions DeckValidator::penalty(const YAML::Node& node, const std::string& path) const {
  PenaltyOptions result;
  if (node.IsNull()) return result;
  check_map(node, path, {"scale", "stiffness", "damping"});
  const YAML::Node scale = optional(node, "scale");
  const YAML::Node stiffness = optional(node, "stiffness");
  if (scale.IsDefined())
    result.scale = number_where(scale, child_path(path, "scale"), "a number > 0", positive);
  if (stiffness.IsDefined()) {
    const std::string stiffness_path = child_path(path, "stiffness");
    result.stiffness = number_where(
        stiffness, stiffness_path,
        "a number > 0 (force per length; pressure per length with slave_points: quadrature)", positive);
    if (scale.IsDefined())
      fail(stiffness, stiffness_path,
           "give either scale (times the automatic stiffness) or stiffness (a fixed value), not both; "
           "scale is given " +
               position_text(scale, child_path(path, "scale")));
  }
  if (const YAML::Node damping = optional(node, "damping"); damping.IsDefined())
    result.damping = number_where(damping, child_path(path, "damping"), "a number >= 0", non_negative);
  return result;
}

// The name of entry `index` of the list at `path` (a contact pair, a rigid wall): it names
// an HDF5 group of the results (`group`, docs/output.md), so it has no '/', and no two
// entries share it.
std::string DeckValidator::group_name(const YAML::Node& entry, const std::string& path, std::size_t index,
                                      const std::string& what, const std::string& group,
                                      std::map<std::string, std::size_t>& index_by_name) const {
  const std::string entry_path = child_path(path, index);
  const std::string name_path = child_path(entry_path, "name");
  const YAML::Node name_node = required(entry, entry_path, "name");
  const std::string name = text(name_node, name_path, "a " + what + " name");
  if (name.find('/') != std::string::npos || name == "." || name == "..")
    fail(name_node, name_path,
         "expected a " + what + " name without '/' (it names the group " + group + " of the results), got '" +
             name + "'");
  const auto [first, inserted] = index_by_name.emplace(name, index);
  if (!inserted)
    fail(name_node, name_path,
         what + " name '" + name + "' is used twice (first by " + child_path(path, first->second) + ")");
  return name;
}

SlavePoints DeckValidator::slave_points(const YAML::Node& node, const std::string& path) const {
  return all_slave_points[choice(node, path, "slave points", names_of(all_slave_points))];
}

// {coefficient: mu} or {static: mu_s, dynamic: mu_d, decay: d}.
FrictionOptions DeckValidator::friction(const YAML::Node& node, const std::string& path) const {
  check_map(node, path, {"coefficient", "static", "dynamic", "decay"});
  FrictionOptions result;
  const YAML::Node coefficient = optional(node, "coefficient");
  const YAML::Node static_node = optional(node, "static");
  const YAML::Node dynamic_node = optional(node, "dynamic");
  if (coefficient.IsDefined()) {
    if (static_node.IsDefined() || dynamic_node.IsDefined())
      fail(coefficient, child_path(path, "coefficient"),
           "give either coefficient (mu_s = mu_d) or static and dynamic, not both");
    result.static_coefficient = result.dynamic_coefficient =
        number_where(coefficient, child_path(path, "coefficient"), "a number >= 0", non_negative);
  } else {
    if (!static_node.IsDefined() && !dynamic_node.IsDefined())
      fail(node, path, "expected {coefficient: mu} or {static: mu_s, dynamic: mu_d, decay: d}");
    const std::string static_path = child_path(path, "static"), dynamic_path = child_path(path, "dynamic");
    result.static_coefficient =
        number_where(required(node, path, "static"), static_path, "a number >= 0", non_negative);
    result.dynamic_coefficient =
        number_where(required(node, path, "dynamic"), dynamic_path, "a number >= 0", non_negative);
    if (result.dynamic_coefficient > result.static_coefficient)
      fail(dynamic_node, dynamic_path,
           "expected mu_d <= mu_s (the static coefficient, " + format_number(result.static_coefficient) +
               "), got " + describe(dynamic_node));
  }
  if (const YAML::Node decay = optional(node, "decay"); decay.IsDefined())
    result.decay = number_where(decay, child_path(path, "decay"), "a number >= 0 (s/m)", non_negative);
  return result;
}

std::vector<RigidWallOptions> DeckValidator::rigid_walls(const YAML::Node& node, const std::string& path,
                                                         const std::vector<PartOptions>& parts) const {
  std::vector<RigidWallOptions> result;
  if (node.IsNull()) return result;
  check_sequence(node, path, "a list of rigid walls");
  std::map<std::string, std::size_t> index_by_name;
  for (std::size_t w = 0; w < node.size(); ++w) {
    const std::string wall_path = child_path(path, w);
    const YAML::Node entry = node[w];
    check_map(entry, wall_path, {"name", "point", "normal", "slave", "slave_points", "friction", "velocity"});
    RigidWallOptions wall;
    wall.name = group_name(entry, path, w, "rigid wall", "/history/wall/NAME", index_by_name);
    wall.point = vector3(required(entry, wall_path, "point"), child_path(wall_path, "point"));
    const YAML::Node normal = required(entry, wall_path, "normal");
    wall.normal = vector3(normal, child_path(wall_path, "normal"));
    if (!(wall.normal[0] * wall.normal[0] + wall.normal[1] * wall.normal[1] +
              wall.normal[2] * wall.normal[2] >
          0.0))
      fail(normal, child_path(wall_path, "normal"), "expected a non-zero normal, got " + describe(normal));
    wall.slave = face_list(required(entry, wall_path, "slave"), child_path(wall_path, "slave"), parts);
    if (const YAML::Node points = optional(entry, "slave_points"); points.IsDefined()) {
      wall.slave_points = slave_points(points, child_path(wall_path, "slave_points"));
      // Mortar cuts slave segments by master segments; a wall has none, and on its
      // plane the Gauss points of the slave segments are already exact.
      if (wall.slave_points == SlavePoints::mortar)
        fail(points, child_path(wall_path, "slave_points"),
             "expected auto, nodes or quadrature: a rigid wall has no segments to cut the slave segments "
             "by (mortar); against its plane the slave segments' Gauss points (quadrature) are exact");
    }
    if (const YAML::Node friction_node = optional(entry, "friction"); friction_node.IsDefined())
      wall.friction = friction(friction_node, child_path(wall_path, "friction"));
    if (const YAML::Node velocity = optional(entry, "velocity"); velocity.IsDefined())
      wall.velocity = vector3(velocity, child_path(wall_path, "velocity"));
    result.push_back(std::move(wall));
  }
  return result;
}

std::vector<LoadOptions> DeckValidator::loads(const YAML::Node& node, const std::string& path,
                                              const std::vector<PartOptions>& parts) const {
  std::vector<LoadOptions> result;
  if (node.IsNull()) return result;
  check_sequence(node, path, "a list of loads like [{gravity: [0, 0, -9.81]}]");
  std::vector<std::string> part_names;
  for (const PartOptions& part : parts) part_names.push_back(part.name);
  for (std::size_t i = 0; i < node.size(); ++i) {
    const std::string load_path = child_path(path, i);
    const YAML::Node entry = node[i];
    check_map(entry, load_path, {"gravity", "parts"});
    LoadOptions load;
    load.gravity = vector3(required(entry, load_path, "gravity"), child_path(load_path, "gravity"));
    if (const YAML::Node list = optional(entry, "parts"); list.IsDefined()) {
      const std::string parts_path = child_path(load_path, "parts");
      check_sequence(list, parts_path, "a list of part names");
      for (std::size_t k = 0; k < list.size(); ++k)
        load.parts.push_back(
            static_cast<int>(choice(list[k], child_path(parts_path, k), "part", part_names)));
    }
    result.push_back(std::move(load));
  }
  return result;
}

GlobalSearchOptions DeckValidator::global_search(const YAML::Node& node, const std::string& path) const {
  GlobalSearchOptions result;
  if (node.IsNull()) return result;
  check_map(node, path, {"cell_size"});
  if (const YAML::Node cell_size = optional(node, "cell_size"); cell_size.IsDefined()) {
    if (cell_size.IsScalar() && !is_quoted(cell_size) && cell_size.Scalar() == "auto") return result;
    result.cell_size =
        number_where(cell_size, child_path(path, "cell_size"), "a number > 0 or auto", positive);
  }
  return result;
}

LocalSearchOptions DeckValidator::local_search(const YAML::Node& node, const std::string& path) const {
  LocalSearchOptions result;
  if (node.IsNull()) return result;
  check_map(node, path, {"method", "tolerance", "max_iterations", "initial_guess", "fallback"});
  if (const YAML::Node method = optional(node, "method"); method.IsDefined())
    result.method =
        contact::search_method_names[choice(method, child_path(path, "method"), "local search method",
                                            names_of(contact::search_method_names))]
            .first;
  if (const YAML::Node tolerance = optional(node, "tolerance"); tolerance.IsDefined())
    result.tolerance = number_where(tolerance, child_path(path, "tolerance"), "a number > 0", positive);
  if (const YAML::Node iterations = optional(node, "max_iterations"); iterations.IsDefined())
    result.max_iterations =
        integer_where(iterations, child_path(path, "max_iterations"), "an integer >= 1", 1);
  if (const YAML::Node guess = optional(node, "initial_guess"); guess.IsDefined())
    result.initial_guess =
        contact::initial_guess_names[choice(guess, child_path(path, "initial_guess"), "initial guess",
                                            names_of(contact::initial_guess_names))]
            .first;
  if (const YAML::Node fallback = optional(node, "fallback"); fallback.IsDefined()) {
    std::vector<std::string> names = names_of(contact::search_method_names);
    names.push_back("none");
    const std::size_t k = choice(fallback, child_path(path, "fallback"), "fallback method", names);
    result.fallback = k < contact::search_method_names.size()
                          ? std::optional(contact::search_method_names[k].first)
                          : std::nullopt;
  }
  return result;
}

std::vector<ContactOptions> DeckValidator::contact_pairs(const YAML::Node& node, const std::string& path,
                                                         const std::vector<PartOptions>& parts) const {
  std::vector<ContactOptions> result;
  if (node.IsNull()) return result;
  check_sequence(node, path, "a list of contact pairs");
  std::map<std::string, std::size_t> index_by_name;
  for (std::size_t c = 0; c < node.size(); ++c) {
    const std::string pair_path = child_path(path, c);
    const YAML::Node entry = node[c];
    check_map(entry, pair_path,
              {"name", "slave", "master", "surface", "two_pass", "slave_points", "quadrature", "penalty",
               "search", "local_search", "friction"});
    ContactOptions pair;
    pair.name = group_name(entry, path, c, "contact pair", "/history/contact/NAME", index_by_name);
    if (const YAML::Node surface = optional(entry, "surface"); surface.IsDefined()) {
      // Single-surface contact: the surface is both sides, so naming a side is a contradiction.
      for (const char* side : {"slave", "master"})
        if (const YAML::Node named = optional(entry, side); named.IsDefined())
          fail(named, child_path(pair_path, side),
               std::string("a contact entry with `surface` (single-surface contact) names no `") + side +
                   "`: give either `surface` or both `slave` and `master`");
      const std::string surface_path = child_path(pair_path, "surface");
      pair.single_surface = true;
      if (surface.IsScalar() && !is_quoted(surface) && surface.Scalar() == "all")
        pair.surface_all =
            true;  // the faces follow from the parts and boundary conditions (deck_validator.cpp)
      else if (surface.IsScalar())
        fail(
            surface, surface_path,
            "expected `all` or a non-empty list of face names like [tube.surface], got " + describe(surface));
      else
        pair.slave = face_list(surface, surface_path, parts);
      pair.master = pair.slave;
    } else {
      pair.slave = face_list(required(entry, pair_path, "slave"), child_path(pair_path, "slave"), parts);
      pair.master = face_list(required(entry, pair_path, "master"), child_path(pair_path, "master"), parts);
    }
    if (const YAML::Node two_pass = optional(entry, "two_pass"); two_pass.IsDefined()) {
      const bool both = boolean(two_pass, child_path(pair_path, "two_pass"));
      if (!pair.single_surface) pair.two_pass = both;  // a surface is both sides already
    }
    if (const YAML::Node points = optional(entry, "slave_points"); points.IsDefined())
      pair.slave_points = slave_points(points, child_path(pair_path, "slave_points"));
    // Accepted with slave_points: nodes too (unused there), so that batch runs can
    // switch the slave points with --set alone.
    // With mortar, the points of the rule on each triangle of a piece.
    if (const YAML::Node quadrature = optional(entry, "quadrature"); quadrature.IsDefined()) {
      const std::string quadrature_path = child_path(pair_path, "quadrature");
      if (pair.slave_points == SlavePoints::mortar) {
        const std::string expected =
            "1, 3, 6 or 7 (with slave_points: mortar, the points of the rule on each triangle of a piece)";
        pair.quadrature = integer_where(quadrature, quadrature_path, expected, 1);
        if (std::find(mortar_triangle_points.begin(), mortar_triangle_points.end(), *pair.quadrature) ==
            mortar_triangle_points.end())
          fail(quadrature, quadrature_path, "expected " + expected + ", got " + describe(quadrature));
      } else {
        const std::string expected = "an integer from 1 to " + std::to_string(max_quadrature) +
                                     " (Gauss points per direction on each slave segment)";
        pair.quadrature = integer_where(quadrature, quadrature_path, expected, 1);
        if (*pair.quadrature > max_quadrature)
          fail(quadrature, quadrature_path, "expected " + expected + ", got " + describe(quadrature));
      }
    }
    if (const YAML::Node penalty_node = optional(entry, "penalty"); penalty_node.IsDefined())
      pair.penalty = penalty(penalty_node, child_path(pair_path, "penalty"));
    if (const YAML::Node search = optional(entry, "search"); search.IsDefined())
      pair.search = global_search(search, child_path(pair_path, "search"));
    if (const YAML::Node local = optional(entry, "local_search"); local.IsDefined())
      pair.local_search = local_search(local, child_path(pair_path, "local_search"));
    if (const YAML::Node friction_node = optional(entry, "friction"); friction_node.IsDefined())
      pair.friction = friction(friction_node, child_path(pair_path, "friction"));
    result.push_back(std::move(pair));
  }
  return result;
}

}  // namespace exdyn::input::deck
