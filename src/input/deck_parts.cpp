// The deck's materials, parts, face names and boundary conditions.
#include <algorithm>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "input/deck_validator.hpp"
#include "input/gmsh_file.hpp"
#include "input/text_tools.hpp"

namespace exdyn::input::deck {

std::string DeckValidator::run_name(const YAML::Node& node, const std::string& path) const {
  const std::string expected = "a name of letters, digits, _ and -";
  const std::string value = text(node, path, expected);
  const bool valid = std::all_of(value.begin(), value.end(), [](char c) {
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' || c == '-';
  });
  if (!valid) fail(node, path, "expected " + expected + ", got '" + value + "'");
  return value;
}

std::vector<MaterialOptions> DeckValidator::materials(const YAML::Node& node, const std::string& path) const {
  if (!node.IsMap() || node.size() == 0)
    fail(node, path,
         "expected a map of materials by name, e.g. {steel: {model: linear_elastic, ...}}; got " +
             describe(node));
  const std::vector<std::string> keys{"model",
                                      "density",
                                      "youngs_modulus",
                                      "poissons_ratio",
                                      "yield_stress",
                                      "hardening_modulus",
                                      "hardening",
                                      "A",
                                      "B",
                                      "n",
                                      "C",
                                      "reference_strain_rate",
                                      "thermal_softening",
                                      "failure"};
  std::vector<MaterialOptions> result;
  std::map<std::string, YAML::Node> seen;
  for (auto entry = node.begin(); entry != node.end(); ++entry) {
    const YAML::Node key_node = entry->first;
    const std::string name_path = path + "[" + std::to_string(result.size()) + "]";
    MaterialOptions material;
    material.name = text(key_node, name_path, "a material name");
    const std::string material_path = child_path(path, material.name);
    const auto [first, inserted] = seen.emplace(material.name, key_node);
    if (!inserted)
      fail(key_node, material_path,
           "material '" + material.name + "' is defined twice (first " +
               position_text(first->second, material_path) + ")");
    const YAML::Node body = entry->second;
    check_map(body, material_path, keys);
    material.model =
        all_material_models[choice(required(body, material_path, "model"), child_path(material_path, "model"),
                                   "material model", names_of(all_material_models))];
    material.density = number_where(required(body, material_path, "density"),
                                    child_path(material_path, "density"), "a number > 0", positive);
    material.youngs_modulus =
        number_where(required(body, material_path, "youngs_modulus"),
                     child_path(material_path, "youngs_modulus"), "a number > 0", positive);
    material.poissons_ratio = number_where(required(body, material_path, "poissons_ratio"),
                                           child_path(material_path, "poissons_ratio"),
                                           "a number in (-1, 0.5)", poissons_ratio_range);
    plasticity(body, material_path, material);
    failure(body, material_path, material);
    result.push_back(std::move(material));
  }
  return result;
}

// johnson_cook's {m, melting_temperature, room_temperature, specific_heat, taylor_quinney}.
ThermalSoftening DeckValidator::thermal_softening(const YAML::Node& node, const std::string& path) const {
  check_map(node, path, {"m", "melting_temperature", "room_temperature", "specific_heat", "taylor_quinney"});
  ThermalSoftening t;
  t.m =
      number_where(required(node, path, "m"), child_path(path, "m"), "a number > 0 (the exponent)", positive);
  if (const YAML::Node room = optional(node, "room_temperature"); room.IsDefined())
    t.room_temperature =
        number_where(room, child_path(path, "room_temperature"), "a number >= 0 (K)", non_negative);
  const YAML::Node melting = required(node, path, "melting_temperature");
  t.melting_temperature =
      number_where(melting, child_path(path, "melting_temperature"), "a number > 0 (K)", positive);
  if (!(t.melting_temperature > t.room_temperature))
    fail(melting, child_path(path, "melting_temperature"),
         "expected a temperature above room_temperature (" + format_number(t.room_temperature) + " K), got " +
             format_number(t.melting_temperature));
  t.specific_heat = number_where(required(node, path, "specific_heat"), child_path(path, "specific_heat"),
                                 "a number > 0 (J/(kg K))", positive);
  if (const YAML::Node chi = optional(node, "taylor_quinney"); chi.IsDefined())
    t.taylor_quinney = number_where(chi, child_path(path, "taylor_quinney"),
                                    "a number in [0, 1] (the share of plastic work that heats)",
                                    [](double value) { return value >= 0.0 && value <= 1.0; });
  return t;
}

// The keys of the plastic models; each is an error on a model it does not belong to.
void DeckValidator::plasticity(const YAML::Node& body, const std::string& path,
                               MaterialOptions& material) const {
  const std::vector<std::string> elastic_plastic_keys{"yield_stress", "hardening_modulus", "hardening"};
  const std::vector<std::string> johnson_cook_keys{
      "A", "B", "n", "C", "reference_strain_rate", "thermal_softening"};
  const auto refuse = [&](const std::vector<std::string>& keys, const char* owner) {
    for (const std::string& key : keys)
      if (const YAML::Node value = optional(body, key); value.IsDefined())
        fail(value, child_path(path, key),
             "'" + key + "' belongs to model " + owner + "; this material is " + name(material.model));
  };
  const auto number_at = [&](const std::string& key, const std::string& expected, bool (*accept)(double)) {
    return number_where(required(body, path, key), child_path(path, key), expected, accept);
  };
  switch (material.model) {
    case MaterialModel::linear_elastic:
      refuse(elastic_plastic_keys, "elastic_plastic");
      refuse(johnson_cook_keys, "johnson_cook");
      return;
    case MaterialModel::johnson_cook:
      refuse(elastic_plastic_keys, "elastic_plastic");
      material.jc_a = number_at("A", "a number > 0 (the initial yield stress)", positive);
      material.jc_b = number_at("B", "a number >= 0", non_negative);
      material.jc_n = number_at("n", "a number > 0 (the hardening exponent)", positive);
      if (const YAML::Node c = optional(body, "C"); c.IsDefined())
        material.jc_c = number_where(c, child_path(path, "C"), "a number >= 0", non_negative);
      if (const YAML::Node rate = optional(body, "reference_strain_rate"); rate.IsDefined())
        material.reference_strain_rate =
            number_where(rate, child_path(path, "reference_strain_rate"), "a number > 0 (1/s)", positive);
      if (const YAML::Node thermal = optional(body, "thermal_softening"); thermal.IsDefined())
        material.thermal_softening = thermal_softening(thermal, child_path(path, "thermal_softening"));
      return;
    case MaterialModel::elastic_plastic:
      break;
  }
  refuse(johnson_cook_keys, "johnson_cook");
  const YAML::Node table = optional(body, "hardening");
  const YAML::Node yield = optional(body, "yield_stress");
  const YAML::Node modulus = optional(body, "hardening_modulus");
  if (!table.IsDefined()) {
    material.yield_stress = number_at("yield_stress", "a number > 0 (the initial yield stress)", positive);
    if (modulus.IsDefined())
      material.hardening_modulus =
          number_where(modulus, child_path(path, "hardening_modulus"), "a number >= 0", non_negative);
    return;
  }
  const std::string table_path = child_path(path, "hardening");
  if (modulus.IsDefined())
    fail(modulus, child_path(path, "hardening_modulus"),
         "give either hardening_modulus (linear hardening) or a hardening table, not both");
  const std::string expected =
      "a list of rows [eps_p, sigma_y] starting at eps_p = 0, eps_p increasing, sigma_y > 0 and "
      "non-decreasing";
  check_sequence(table, table_path, expected);
  if (table.size() == 0) fail(table, table_path, "expected " + expected + ", got an empty list");
  if (table.size() > 32)
    fail(table, table_path, "a hardening table has at most 32 rows, got " + std::to_string(table.size()));
  for (std::size_t i = 0; i < table.size(); ++i) {
    const std::string row_path = child_path(table_path, i);
    check_sequence(table[i], row_path, expected);
    if (table[i].size() != 2)
      fail(table[i], row_path, "expected " + expected + ", got " + describe(table[i]));
    const double strain = number(table[i][0], child_path(row_path, 0), "a number (eps_p)");
    const double stress = number(table[i][1], child_path(row_path, 1), "a number (sigma_y)");
    if (i == 0 && strain != 0.0)
      fail(table[i][0], child_path(row_path, 0),
           "the hardening table starts at eps_p = 0, got " + format_number(strain));
    if (i > 0 && !(strain > material.hardening.back()[0]))
      fail(table[i][0], child_path(row_path, 0),
           "eps_p must increase strictly down the table, got " + format_number(strain) + " after " +
               format_number(material.hardening.back()[0]));
    if (!(stress > 0.0))
      fail(table[i][1], child_path(row_path, 1), "expected a yield stress > 0, got " + format_number(stress));
    if (i > 0 && stress < material.hardening.back()[1])
      fail(table[i][1], child_path(row_path, 1),
           "the hardening table decreases: sigma_y " + format_number(stress) + " after " +
               format_number(material.hardening.back()[1]) + " (softening is not supported)");
    material.hardening.push_back({strain, stress});
  }
  material.yield_stress = material.hardening.front()[1];
  if (yield.IsDefined() &&
      number(yield, child_path(path, "yield_stress"), "a number") != material.yield_stress)
    fail(yield, child_path(path, "yield_stress"),
         "yield_stress differs from the hardening table's first sigma_y (" +
             format_number(material.yield_stress) + "): give one of them");
}

std::array<Vec3, 2> DeckValidator::angular_velocity(const YAML::Node& node, const std::string& path) const {
  check_map(node, path, {"axis_point", "omega"});
  return {vector3(required(node, path, "axis_point"), child_path(path, "axis_point")),
          vector3(required(node, path, "omega"), child_path(path, "omega"))};
}

std::array<int, 3> DeckValidator::keep_cuts(const YAML::Node& node, const std::string& path, int axis) const {
  const std::string expected = "a list of half-spaces through the centre among x+, x-, y+, y-, z+, z-";
  check_sequence(node, path, expected);
  std::array<int, 3> keep{};
  const std::vector<std::string> names{"x+", "x-", "y+", "y-", "z+", "z-"};
  for (std::size_t i = 0; i < node.size(); ++i) {
    const std::string entry_path = child_path(path, i);
    const std::size_t found = choice(node[i], entry_path, "half-space", names);
    const std::size_t cut_axis = found / 2;
    if (keep[cut_axis] != 0)
      fail(node[i], entry_path, "the axis " + std::string(component_names[cut_axis]) + " is cut twice");
    if (static_cast<int>(cut_axis) == axis)
      fail(
          node[i], entry_path,
          "a cut across the cylinder's axis would keep all of it or nothing (the axis starts at the centre); "
          "set the length instead");
    keep[cut_axis] = found % 2 == 0 ? 1 : -1;
  }
  return keep;
}

MeshFileOptions DeckValidator::mesh_file(const YAML::Node& node, const std::string& path) const {
  check_map(node, path, {"file", "volume", "reorder"});
  MeshFileOptions result;
  const std::string file_path = child_path(path, "file");
  const YAML::Node file = required(node, path, "file");
  const std::string written = text(file, file_path, "the path of a Gmsh mesh file (.msh)");
  // Relative to the deck's folder, so a deck runs from anywhere.
  std::filesystem::path resolved(written);
  if (resolved.is_relative()) resolved = std::filesystem::path(source_name_).parent_path() / resolved;
  std::error_code error;
  const std::filesystem::path absolute = std::filesystem::absolute(resolved, error);
  result.path = (error ? resolved : absolute).lexically_normal().string();
  const std::string volume_path = child_path(path, "volume");
  const YAML::Node volume = required(node, path, "volume");
  result.volume = text(volume, volume_path, "the name of a physical volume of the mesh file");
  if (const YAML::Node reorder = optional(node, "reorder"); reorder.IsDefined())
    result.reorder = boolean(reorder, child_path(path, "reorder"));

  // The file's names, so that faces and volumes are checked here, at their line.
  auto names = mesh_names_.find(result.path);
  if (names == mesh_names_.end()) {
    const GmshMesh mesh = read_gmsh(result.path, locate(file, file_path), file_path);
    std::array<std::vector<std::string>, 2> read;
    for (const GmshGroup& group : mesh.volumes) read[0].push_back(group.name);
    for (const GmshGroup& group : mesh.surfaces) read[1].push_back(group.name);
    names = mesh_names_.emplace(result.path, std::move(read)).first;
  }
  const std::vector<std::string>& volumes = names->second[0];
  if (std::find(volumes.begin(), volumes.end(), result.volume) == volumes.end())
    fail(volume, volume_path,
         "'" + written + "' has no physical volume '" + result.volume + "'" +
             (volumes.empty()
                  ? std::string("; it has none (add Physical Volume(\"NAME\") = {...}; to the .geo)")
                  : suggestion(result.volume, volumes, "its physical volumes are")));
  for (const std::string& surface : names->second[1]) {
    if (surface == name(PartFace::surface))
      fail(file, file_path,
           "'" + written +
               "' has a physical surface named 'surface', the name of a mesh part's whole boundary: rename "
               "it");
    result.surfaces.push_back(surface);
  }
  return result;
}

PartOptions DeckValidator::part(const YAML::Node& node, const std::string& path,
                                const std::vector<MaterialOptions>& materials) const {
  check_map(
      node, path,
      {"name", "box", "cylinder", "sphere", "mesh", "elements", "grading", "material", "formulation",
       "hourglass", "initial_velocity", "initial_angular_velocity", "kinematics", "f_bar", "perturbation"});
  PartOptions result;
  result.name = text(required(node, path, "name"), child_path(path, "name"), "a part name");

  // Exactly one geometry key.
  std::vector<std::string> geometry_keys;
  for (const Geometry geometry : all_geometries)
    if (optional(node, name(geometry)).IsDefined()) geometry_keys.emplace_back(name(geometry));
  if (geometry_keys.empty())
    fail(node, path, "expected one geometry key: box, cylinder, sphere or mesh (docs/input.md)");
  if (geometry_keys.size() > 1)
    fail(node[geometry_keys[1]], child_path(path, geometry_keys[1]),
         "a part has exactly one geometry key; this one has " + join(geometry_keys, " and "));
  const std::string geometry_path = child_path(path, geometry_keys[0]);
  const YAML::Node geometry = node[geometry_keys[0]];
  if (geometry_keys[0] == "box") {
    check_map(geometry, geometry_path, {"min", "max"});
    result.box_min = vector3(required(geometry, geometry_path, "min"), child_path(geometry_path, "min"));
    const YAML::Node box_max = required(geometry, geometry_path, "max");
    result.box_max = vector3(box_max, child_path(geometry_path, "max"));
    for (std::size_t i = 0; i < 3; ++i) {
      if (result.box_max[i] > result.box_min[i]) continue;
      fail(box_max, child_path(geometry_path, "max"),
           "expected max > min in every component, got " + std::string(component_names[i]) + ": max " +
               format_number(result.box_max[i]) + " <= min " + format_number(result.box_min[i]));
    }
  } else if (geometry_keys[0] == "mesh") {
    result.geometry = Geometry::mesh;
    result.mesh = mesh_file(geometry, geometry_path);
  } else {
    result.geometry = geometry_keys[0] == "cylinder" ? Geometry::cylinder : Geometry::sphere;
    const bool cylinder = result.geometry == Geometry::cylinder;
    check_map(geometry, geometry_path,
              cylinder ? std::vector<std::string>{"center", "axis", "radius", "length", "keep"}
                       : std::vector<std::string>{"center", "radius", "keep"});
    result.center = vector3(required(geometry, geometry_path, "center"), child_path(geometry_path, "center"));
    result.radius = number_where(required(geometry, geometry_path, "radius"),
                                 child_path(geometry_path, "radius"), "a number > 0", positive);
    if (cylinder) {
      const std::vector<std::string> axes(component_names.begin(), component_names.end());
      result.axis = static_cast<int>(
          choice(required(geometry, geometry_path, "axis"), child_path(geometry_path, "axis"), "axis", axes));
      result.length = number_where(required(geometry, geometry_path, "length"),
                                   child_path(geometry_path, "length"), "a number > 0", positive);
    }
    if (const YAML::Node keep = optional(geometry, "keep"); keep.IsDefined() && !keep.IsNull())
      result.keep = keep_cuts(keep, child_path(geometry_path, "keep"), cylinder ? result.axis : -1);
  }

  if (result.geometry == Geometry::mesh) {
    for (const char* key : {"elements", "grading"})
      if (const YAML::Node given = optional(node, key); given.IsDefined())
        fail(given, child_path(path, key),
             std::string(key) +
                 " does not apply to a mesh part: its elements come from the file; remove the key");
  } else {
    const std::string elements_path = child_path(path, "elements");
    const YAML::Node elements = required(node, path, "elements");
    const std::size_t counts = result.geometry == Geometry::sphere ? 2 : 3;
    const std::string expected = result.geometry == Geometry::box ? "a list of 3 integers >= 1 [nx, ny, nz]"
                                 : result.geometry == Geometry::cylinder
                                     ? "a list of 3 integers >= 1 [n_around, "
                                       "n_radius, n_axis]"
                                     : "a list of 2 integers >= 1 [n_around, "
                                       "n_radius]";
    check_sequence(elements, elements_path, expected);
    if (elements.size() != counts)
      fail(elements, elements_path, "expected " + expected + ", got " + describe(elements));
    for (std::size_t i = 0; i < counts; ++i)
      result.elements[i] = integer_where(elements[i], child_path(elements_path, i), "an integer >= 1", 1);
    const bool cut = result.keep != std::array<int, 3>{};
    if (cut && result.elements[0] % 2 != 0)
      fail(elements[0], child_path(elements_path, 0),
           "n_around must be even when `keep` cuts the part: a cut runs along the middle grid line of the "
           "square core (docs/input.md), got " +
               std::to_string(result.elements[0]));

    if (const YAML::Node grading = optional(node, "grading"); grading.IsDefined() && !grading.IsNull()) {
      const std::string grading_path = child_path(path, "grading");
      const std::string grading_expected =
          "a list of " + std::to_string(counts) + " numbers > 0, one per count of `elements`";
      check_sequence(grading, grading_path, grading_expected);
      if (grading.size() != counts)
        fail(grading, grading_path, "expected " + grading_expected + ", got " + describe(grading));
      for (std::size_t i = 0; i < counts; ++i)
        result.grading[i] = number_where(grading[i], child_path(grading_path, i), "a number > 0", positive);
      if (result.geometry != Geometry::box && result.grading[0] != 1.0)
        fail(grading[0], child_path(grading_path, 0),
             "the elements around a cylinder or ball are equal: the grading along n_around must be 1, got " +
                 format_number(result.grading[0]));
    }
  }

  const std::string material_path = child_path(path, "material");
  const YAML::Node material = required(node, path, "material");
  result.material = text(material, material_path, "a material name");
  std::vector<std::string> material_names;
  for (const MaterialOptions& known : materials) material_names.push_back(known.name);
  const auto found = std::find(material_names.begin(), material_names.end(), result.material);
  if (found == material_names.end())
    fail(material, material_path,
         "unknown material '" + result.material + "'" +
             suggestion(result.material, material_names, "the materials are"));
  result.material_index = static_cast<int>(found - material_names.begin());

  if (const YAML::Node formulation = optional(node, "formulation"); formulation.IsDefined())
    result.formulation = all_formulations[choice(formulation, child_path(path, "formulation"), "formulation",
                                                 names_of(all_formulations))];

  // Accepted for hex8 too (and unused there), so that batch runs can switch between
  // hex8 and hex8r with --set without editing the hourglass block. A 20-node part has
  // no hourglass control: the key there is a mistake, not a setting to keep.
  if (const YAML::Node hourglass = optional(node, "hourglass");
      hourglass.IsDefined() && !hourglass.IsNull()) {
    const std::string hourglass_path = child_path(path, "hourglass");
    if (is_quadratic(result.formulation))
      fail(hourglass, hourglass_path,
           std::string("hourglass applies to hex8r parts (and is accepted, unused, on hex8); this part is ") +
               name(result.formulation) +
               ", whose Gauss points leave no hourglass mode to control: remove the key");
    check_map(hourglass, hourglass_path, {"model", "coefficient"});
    const YAML::Node model = optional(hourglass, "model");
    const YAML::Node coefficient = optional(hourglass, "coefficient");
    // `coefficient` alone keeps the meaning it had before `model`: Flanagan-Belytschko.
    if (model.IsDefined())
      result.hourglass_model = all_hourglass_models[choice(
          model, child_path(hourglass_path, "model"), "hourglass model", names_of(all_hourglass_models))];
    else if (coefficient.IsDefined())
      result.hourglass_model = HourglassModel::flanagan_belytschko;
    result.hourglass_coefficient = result.hourglass_model == HourglassModel::flanagan_belytschko ? 0.05 : 1.0;
    if (coefficient.IsDefined())
      result.hourglass_coefficient =
          number_where(coefficient, child_path(hourglass_path, "coefficient"), "a number >= 0", non_negative);
  }

  if (const YAML::Node velocity = optional(node, "initial_velocity"); velocity.IsDefined())
    result.initial_velocity = vector3(velocity, child_path(path, "initial_velocity"));
  if (const YAML::Node spin = optional(node, "initial_angular_velocity"); spin.IsDefined() && !spin.IsNull())
    result.initial_angular_velocity = angular_velocity(spin, child_path(path, "initial_angular_velocity"));
  if (const YAML::Node kinematics = optional(node, "kinematics"); kinematics.IsDefined())
    result.kinematics = all_kinematics[choice(kinematics, child_path(path, "kinematics"), "kinematics",
                                              names_of(all_kinematics))];
  if (const YAML::Node f_bar = optional(node, "f_bar"); f_bar.IsDefined()) {
    if (result.formulation != Formulation::hex8)
      fail(f_bar, child_path(path, "f_bar"),
           std::string("f_bar applies to hex8 parts under finite kinematics; this part is ") +
               name(result.formulation));
    result.f_bar = boolean(f_bar, child_path(path, "f_bar"));
  }

  if (const YAML::Node perturbation = optional(node, "perturbation");
      perturbation.IsDefined() && !perturbation.IsNull()) {
    const std::string perturbation_path = child_path(path, "perturbation");
    if (result.geometry != Geometry::box)
      fail(perturbation, perturbation_path,
           std::string("perturbation distorts the grid of a box part; this part is a ") +
               name(result.geometry));
    check_map(perturbation, perturbation_path, {"fraction", "seed"});
    if (const YAML::Node fraction = optional(perturbation, "fraction"); fraction.IsDefined()) {
      const std::string fraction_path = child_path(perturbation_path, "fraction");
      const std::string fraction_range = "a number in [0, 0.5) (a fraction of the element length h)";
      result.perturbation_fraction = number_where(fraction, fraction_path, fraction_range, non_negative);
      // Two neighbours moving toward each other by fraction h each close a gap of h.
      if (result.perturbation_fraction >= 0.5)
        fail(fraction, fraction_path,
             "expected " + fraction_range + ", got " + describe(fraction) +
                 ": at 0.5 or more a node can reach or pass its neighbour and invert elements");
    }
    if (const YAML::Node seed = optional(perturbation, "seed"); seed.IsDefined())
      result.perturbation_seed = static_cast<unsigned>(
          integer_where(seed, child_path(perturbation_path, "seed"), "an integer >= 0", 0));
  }
  return result;
}

std::vector<PartOptions> DeckValidator::parts(const YAML::Node& node, const std::string& path,
                                              const std::vector<MaterialOptions>& materials) const {
  check_sequence(node, path, "a list of parts");
  if (node.size() == 0) fail(node, path, "expected at least one part, got an empty list");
  std::vector<PartOptions> result;
  std::map<std::string, std::size_t> index_by_name;
  for (std::size_t p = 0; p < node.size(); ++p) {
    const std::string part_path = child_path(path, p);
    result.push_back(part(node[p], part_path, materials));
    const auto [first, inserted] = index_by_name.emplace(result.back().name, p);
    if (!inserted) {
      const std::string name_path = child_path(part_path, "name");
      const std::string first_path = child_path(child_path(path, first->second), "name");
      fail(node[p]["name"], name_path,
           "part name '" + result.back().name + "' is used twice (first by " +
               child_path(path, first->second) + ", " +
               position_text(node[first->second]["name"], first_path) + ")");
    }
  }
  return result;
}

FaceRef DeckValidator::face(const YAML::Node& node, const std::string& path,
                            const std::vector<PartOptions>& parts) const {
  const std::string value = text(node, path, "a face name <part>.<side>");
  std::vector<std::string> part_names;
  std::vector<std::string> face_names;
  for (const PartOptions& known : parts) {
    part_names.push_back(known.name);
    for (const std::string& side : side_names(known)) face_names.push_back(known.name + "." + side);
  }
  std::string hint = "; the faces are " + join(face_names, ", ");
  if (const std::optional<std::string> nearest = nearest_name(value, face_names))
    hint = "; did you mean '" + *nearest + "'?";
  // The side follows the last point, so part names may contain points.
  const std::size_t point = value.rfind('.');
  if (point == std::string::npos)
    fail(node, path, "expected a face name <part>.<side>, got '" + value + "'" + hint);
  const std::string part_name = value.substr(0, point);
  const std::string side_name = value.substr(point + 1);
  const auto part_found = std::find(part_names.begin(), part_names.end(), part_name);
  if (part_found == part_names.end())
    fail(node, path, "unknown part '" + part_name + "' in face '" + value + "'" + hint);
  const PartOptions& part = parts[static_cast<std::size_t>(part_found - part_names.begin())];
  const int part_index = static_cast<int>(part_found - part_names.begin());
  const std::vector<PartFace> sides = faces_of(part);
  const auto side_found =
      std::find_if(sides.begin(), sides.end(), [&](PartFace side) { return side_name == name(side); });
  if (side_found != sides.end()) return FaceRef{part_index, *side_found};
  const auto& surfaces = part.mesh.surfaces;
  if (const auto surface = std::find(surfaces.begin(), surfaces.end(), side_name);
      part.geometry == Geometry::mesh && surface != surfaces.end())
    return FaceRef{part_index, PartFace::physical, static_cast<int>(surface - surfaces.begin())};
  fail(node, path,
       "unknown side '" + side_name + "' of the " + name(part.geometry) + " part '" + part.name +
           "' in face '" + value + "'" + hint);
}

std::vector<FaceRef> DeckValidator::face_list(const YAML::Node& node, const std::string& path,
                                              const std::vector<PartOptions>& parts) const {
  const std::string expected = "a non-empty list of face names like [plate.xmin]";
  check_sequence(node, path, expected);
  if (node.size() == 0) fail(node, path, "expected " + expected + ", got an empty list");
  std::vector<FaceRef> result;
  for (std::size_t i = 0; i < node.size(); ++i) {
    const std::string face_path = child_path(path, i);
    const FaceRef reference = face(node[i], face_path, parts);
    const auto repeated = std::find(result.begin(), result.end(), reference);
    if (repeated != result.end()) fail(node[i], face_path, "face '" + node[i].Scalar() + "' is listed twice");
    result.push_back(reference);
  }
  return result;
}

std::vector<BoundaryConditionOptions> DeckValidator::boundary_conditions(
    const YAML::Node& node, const std::string& path, const std::vector<PartOptions>& parts) const {
  std::vector<BoundaryConditionOptions> result;
  if (node.IsNull()) return result;
  check_sequence(node, path, "a list of boundary conditions {faces: [...], fix: [...]} or {faces, velocity}");
  const std::vector<std::string> components(component_names.begin(), component_names.end());
  for (std::size_t b = 0; b < node.size(); ++b) {
    const std::string bc_path = child_path(path, b);
    const YAML::Node entry = node[b];
    check_map(entry, bc_path, {"faces", "fix", "velocity"});
    BoundaryConditionOptions condition;
    condition.faces = face_list(required(entry, bc_path, "faces"), child_path(bc_path, "faces"), parts);
    const YAML::Node fix = optional(entry, "fix");
    const YAML::Node velocity = optional(entry, "velocity");
    if (fix.IsDefined() && velocity.IsDefined())
      fail(velocity, child_path(bc_path, "velocity"),
           "give either fix (held at rest) or velocity (a prescribed motion), not both");
    if (!fix.IsDefined() && !velocity.IsDefined())
      fail(entry, bc_path,
           "expected fix: [components] or velocity: {component: value}, e.g. fix: [z] or velocity: {z: "
           "-10.0}");
    if (fix.IsDefined()) {
      const std::string fix_path = child_path(bc_path, "fix");
      const std::string expected = "a non-empty list of components among x, y, z";
      check_sequence(fix, fix_path, expected);
      if (fix.size() == 0) fail(fix, fix_path, "expected " + expected + ", got an empty list");
      for (std::size_t i = 0; i < fix.size(); ++i) {
        const std::string component_path = child_path(fix_path, i);
        const std::size_t axis = choice(fix[i], component_path, "component", components);
        if (condition.fix[axis])
          fail(fix[i], component_path, "component '" + components[axis] + "' is listed twice");
        condition.fix[axis] = true;
      }
    } else {
      const std::string velocity_path = child_path(bc_path, "velocity");
      const std::string expected =
          "a non-empty map of components among x, y, z to velocities, e.g. {z: -10.0}";
      if (!velocity.IsMap() || velocity.size() == 0)
        fail(velocity, velocity_path, "expected " + expected + ", got " + describe(velocity));
      check_map(velocity, velocity_path, components);
      for (std::size_t axis = 0; axis < 3; ++axis)
        if (const YAML::Node value = optional(velocity, components[axis]); value.IsDefined()) {
          condition.fix[axis] = true;
          condition.velocity[axis] =
              number(value, child_path(velocity_path, components[axis]), "a velocity (m/s)");
        }
    }
    result.push_back(std::move(condition));
  }
  return result;
}

}  // namespace exdyn::input::deck
