// to_yaml: the resolved deck as YAML, every default filled in (`exdyn check`).
#include <algorithm>
#include <cmath>
#include <optional>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include "input/deck_reader.hpp"
#include "input/deck_validator.hpp"
#include "input/text_tools.hpp"

namespace exdyn::input {
namespace {

using namespace deck;

// ---------------------------------------------------------------------------
// Writing YAML: numbers in the shortest form that reads back to the same double.

std::string yaml_text(std::string_view value) {
  const bool plain_characters = !value.empty() && std::all_of(value.begin(), value.end(), [](char c) {
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' ||
           c == '-' || c == '.' || c == '/';
  });
  const bool plain =
      plain_characters && value.front() != '-' && !parse_double(value) && !looks_like_yaml_keyword(value);
  if (plain) return std::string(value);
  std::string quoted = "\"";
  for (const char c : value) {
    switch (c) {
      case '"':
        quoted += "\\\"";
        break;
      case '\\':
        quoted += "\\\\";
        break;
      case '\n':
        quoted += "\\n";
        break;
      case '\t':
        quoted += "\\t";
        break;
      default:
        if (static_cast<unsigned char>(c) < 0x20) {
          constexpr char hex[] = "0123456789abcdef";
          quoted += "\\x";
          quoted += hex[(c >> 4) & 0xf];
          quoted += hex[c & 0xf];
        } else {
          quoted += c;
        }
    }
  }
  return quoted + "\"";
}

std::string yaml_number(double value) {
  if (std::isnan(value)) return ".nan";
  if (std::isinf(value)) return value > 0 ? ".inf" : "-.inf";
  return format_number(value);
}

std::string yaml_vector(const Vec3& value) {
  return "[" + yaml_number(value[0]) + ", " + yaml_number(value[1]) + ", " + yaml_number(value[2]) + "]";
}

std::string yaml_faces(const Deck& deck, const std::vector<FaceRef>& faces) {
  std::vector<std::string> names;
  for (const FaceRef& reference : faces) names.push_back(yaml_text(face_name(deck, reference)));
  return "[" + join(names, ", ") + "]";
}

// "friction: {...}" on a line of its own at `indent`, or nothing when frictionless.
std::string yaml_friction(const std::optional<FrictionOptions>& friction, const std::string& indent) {
  if (!friction) return "";
  return indent + "friction: {static: " + yaml_number(friction->static_coefficient) +
         ", dynamic: " + yaml_number(friction->dynamic_coefficient) +
         ", decay: " + yaml_number(friction->decay) + "}\n";
}

// The plastic model's keys, ", key: value" each.
std::string plasticity_text(const MaterialOptions& material) {
  switch (material.model) {
    case MaterialModel::linear_elastic:
      return "";
    case MaterialModel::johnson_cook:
      return ", A: " + yaml_number(material.jc_a) + ", B: " + yaml_number(material.jc_b) +
             ", n: " + yaml_number(material.jc_n) + ", C: " + yaml_number(material.jc_c) +
             ", reference_strain_rate: " + yaml_number(material.reference_strain_rate) +
             (material.thermal_softening
                  ? ", thermal_softening: {m: " + yaml_number(material.thermal_softening->m) +
                        ", melting_temperature: " +
                        yaml_number(material.thermal_softening->melting_temperature) +
                        ", room_temperature: " + yaml_number(material.thermal_softening->room_temperature) +
                        ", specific_heat: " + yaml_number(material.thermal_softening->specific_heat) +
                        ", taylor_quinney: " + yaml_number(material.thermal_softening->taylor_quinney) + "}"
                  : std::string());
    case MaterialModel::elastic_plastic:
      break;
  }
  if (material.hardening.empty())
    return ", yield_stress: " + yaml_number(material.yield_stress) +
           ", hardening_modulus: " + yaml_number(material.hardening_modulus);
  std::vector<std::string> rows;
  for (const auto& row : material.hardening)
    rows.push_back("[" + yaml_number(row[0]) + ", " + yaml_number(row[1]) + "]");
  return ", hardening: [" + join(rows, ", ") + "]";
}

// ", failure: {...}" of a material that fails, or nothing.
std::string failure_text(const MaterialOptions& material) {
  switch (material.failure) {
    case FailureModel::none:
      return "";
    case FailureModel::plastic_strain:
      return ", failure: {plastic_strain: " + yaml_number(material.failure_strain) + "}";
    case FailureModel::johnson_cook:
      break;
  }
  std::vector<std::string> d;
  for (std::size_t k = 0; k < 5; ++k)
    d.push_back("D" + std::to_string(k + 1) + ": " + yaml_number(material.failure_d[k]));
  return ", failure: {johnson_cook: {" + join(d, ", ") + "}}";
}

}  // namespace

std::string to_yaml(const Deck& deck) {
  std::ostringstream out;
  out << "# The resolved deck" << (deck.source_file.empty() ? "" : " " + deck.source_file)
      << ", every default filled in.\n";
  out << "name: " << yaml_text(deck.name) << "\n";

  out << "materials:\n";
  for (const MaterialOptions& material : deck.materials)
    out << "  " << yaml_text(material.name) << ": {model: " << name(material.model)
        << ", density: " << yaml_number(material.density)
        << ", youngs_modulus: " << yaml_number(material.youngs_modulus)
        << ", poissons_ratio: " << yaml_number(material.poissons_ratio) << plasticity_text(material)
        << failure_text(material) << "}\n";

  out << "parts:\n";
  for (const PartOptions& part : deck.parts) {
    const bool sphere = part.geometry == Geometry::sphere;
    out << "  - name: " << yaml_text(part.name) << "\n";
    if (part.geometry == Geometry::mesh) {
      out << "    mesh: {file: " << yaml_text(part.mesh.path) << ", volume: " << yaml_text(part.mesh.volume)
          << ", reorder: " << (part.mesh.reorder ? "true" : "false") << "}\n";
    } else if (part.geometry == Geometry::box) {
      out << "    box: {min: " << yaml_vector(part.box_min) << ", max: " << yaml_vector(part.box_max)
          << "}\n";
    } else {
      std::vector<std::string> keep;
      for (std::size_t axis = 0; axis < 3; ++axis)
        if (part.keep[axis] != 0)
          keep.push_back(std::string(component_names[axis]) + (part.keep[axis] > 0 ? "+" : "-"));
      out << "    " << name(part.geometry) << ": {center: " << yaml_vector(part.center)
          << (sphere ? std::string() : ", axis: " + std::string(component_names[std::size_t(part.axis)]))
          << ", radius: " << yaml_number(part.radius)
          << (sphere ? std::string() : ", length: " + yaml_number(part.length)) << ", keep: ["
          << join(keep, ", ") << "]}\n";
    }
    if (part.geometry != Geometry::mesh) {
      out << "    elements: [" << part.elements[0] << ", " << part.elements[1];
      if (!sphere) out << ", " << part.elements[2];
      out << "]\n    grading: [" << yaml_number(part.grading[0]) << ", " << yaml_number(part.grading[1]);
      if (!sphere) out << ", " << yaml_number(part.grading[2]);
      out << "]\n";
    }
    out << "    material: " << yaml_text(part.material) << "\n"
        << "    formulation: " << name(part.formulation) << "\n"
        << (is_quadratic(part.formulation)
                ? std::string()
                : std::string("    hourglass: {model: ") + name(part.hourglass_model) +
                      ", coefficient: " + yaml_number(part.hourglass_coefficient) + "}\n")
        << "    initial_velocity: " << yaml_vector(part.initial_velocity) << "\n"
        << (part.initial_angular_velocity
                ? "    initial_angular_velocity: {axis_point: " +
                      yaml_vector((*part.initial_angular_velocity)[0]) +
                      ", omega: " + yaml_vector((*part.initial_angular_velocity)[1]) + "}\n"
                : std::string())
        << "    kinematics: " << name(part.kinematics) << "\n"
        << (part.formulation == Formulation::hex8
                ? std::string("    f_bar: ") + (part.f_bar ? "true" : "false") + "\n"
                : std::string())
        << (part.geometry == Geometry::box
                ? "    perturbation: {fraction: " + yaml_number(part.perturbation_fraction) +
                      ", seed: " + std::to_string(part.perturbation_seed) + "}\n"
                : std::string());
  }

  out << "boundary_conditions:" << (deck.boundary_conditions.empty() ? " []" : "") << "\n";
  for (const BoundaryConditionOptions& condition : deck.boundary_conditions) {
    std::vector<std::string> components;
    for (std::size_t axis = 0; axis < 3; ++axis)
      if (condition.fix[axis])
        components.emplace_back(condition.moving() ? std::string(component_names[axis]) + ": " +
                                                         yaml_number(condition.velocity[axis])
                                                   : std::string(component_names[axis]));
    out << "  - {faces: " << yaml_faces(deck, condition.faces)
        << (condition.moving() ? ", velocity: {" + join(components, ", ") + "}}\n"
                               : ", fix: [" + join(components, ", ") + "]}\n");
  }

  out << "contact:" << (deck.contact.empty() ? " []" : "") << "\n";
  for (const ContactOptions& pair : deck.contact) {
    const PenaltyOptions& penalty = pair.penalty;
    const LocalSearchOptions& local = pair.local_search;
    out << "  - name: " << yaml_text(pair.name) << "\n"
        << (pair.surface_all      ? "    surface: all\n"
            : pair.single_surface ? "    surface: " + yaml_faces(deck, pair.slave) + "\n"
                                  : "    slave: " + yaml_faces(deck, pair.slave) + "\n" +
                                        "    master: " + yaml_faces(deck, pair.master) + "\n" +
                                        "    two_pass: " + (pair.two_pass ? "true" : "false") + "\n")
        << "    slave_points: " << name(pair.slave_points) << "\n"
        << (pair.quadrature ? "    quadrature: " + std::to_string(*pair.quadrature) + "\n" : std::string())
        << "    penalty: {"
        << (penalty.stiffness ? "stiffness: " + yaml_number(*penalty.stiffness)
                              : "scale: " + yaml_number(penalty.scale))
        << ", damping: " << yaml_number(penalty.damping) << "}\n"
        << "    search: {cell_size: "
        << (pair.search.cell_size ? yaml_number(*pair.search.cell_size) : "auto") << "}\n"
        << "    local_search: {method: " << contact::name(local.method)
        << ", tolerance: " << yaml_number(local.tolerance) << ", max_iterations: " << local.max_iterations
        << ", initial_guess: " << contact::name(local.initial_guess)
        << ", fallback: " << (local.fallback ? contact::name(*local.fallback) : std::string_view("none"))
        << "}\n"
        << yaml_friction(pair.friction, "    ");
  }

  out << "rigid_walls:" << (deck.rigid_walls.empty() ? " []" : "") << "\n";
  for (const RigidWallOptions& wall : deck.rigid_walls)
    out << "  - name: " << yaml_text(wall.name) << "\n"
        << "    point: " << yaml_vector(wall.point) << "\n"
        << "    normal: " << yaml_vector(wall.normal) << "\n"
        << "    slave: " << yaml_faces(deck, wall.slave) << "\n"
        << "    slave_points: " << name(wall.slave_points) << "\n"
        << "    velocity: " << yaml_vector(wall.velocity) << "\n"
        << yaml_friction(wall.friction, "    ");

  out << "loads:" << (deck.loads.empty() ? " []" : "") << "\n";
  for (const LoadOptions& load : deck.loads) {
    std::vector<std::string> names;
    for (const int part : load.parts) names.push_back(yaml_text(deck.parts[std::size_t(part)].name));
    out << "  - {gravity: " << yaml_vector(load.gravity)
        << (names.empty() ? std::string() : ", parts: [" + join(names, ", ") + "]") << "}\n";
  }

  out << "time:\n"
      << "  end_time: " << yaml_number(deck.time.end_time) << "\n";
  if (deck.time.dt)
    out << "  dt: " << yaml_number(*deck.time.dt) << "\n";
  else
    out << "  courant: " << yaml_number(deck.time.courant) << "\n";
  out << "  min_dt_ratio: " << yaml_number(deck.time.min_dt_ratio) << "\n";
  if (deck.time.erode) out << "  erode: true\n";

  std::vector<std::string> fields;
  for (const OutputField field : deck.output.fields) fields.emplace_back(name(field));
  out << "output:\n"
      << "  directory: " << yaml_text(deck.output.directory) << "\n"
      << "  every: " << deck.output.every << "\n"
      << "  fields: [" << join(fields, ", ") << "]\n"
      << "  history_every: " << deck.output.history_every << "\n"
      << "  background: " << (deck.output.background ? "true" : "false") << "\n"
      << "guards:\n"
      << "  energy_growth: " << yaml_number(deck.guards.energy_growth) << "\n"
      << "  max_penetration: " << yaml_number(deck.guards.max_penetration) << "\n";
  if (deck.checkpoint.enabled()) {
    out << "checkpoint:\n";
    if (deck.checkpoint.every > 0) out << "  every: " << deck.checkpoint.every << "\n";
    if (deck.checkpoint.every_seconds > 0.0)
      out << "  every_seconds: " << yaml_number(deck.checkpoint.every_seconds) << "\n";
    out << "  keep: " << deck.checkpoint.keep << "\n";
  }
  return out.str();
}

}  // namespace exdyn::input
