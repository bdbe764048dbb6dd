// The deck's time, output and guards sections.
#include <algorithm>
#include <string>
#include <vector>

#include "input/deck_validator.hpp"
#include "input/text_tools.hpp"

namespace exdyn::input::deck {

TimeOptions DeckValidator::time(const YAML::Node& node, const std::string& path) const {
  check_map(node, path, {"end_time", "courant", "dt", "min_dt_ratio", "erode"});
  TimeOptions result;
  result.end_time =
      number_where(required(node, path, "end_time"), child_path(path, "end_time"), "a number > 0", positive);
  const YAML::Node courant = optional(node, "courant");
  const YAML::Node dt = optional(node, "dt");
  if (courant.IsDefined())
    result.courant = number_where(courant, child_path(path, "courant"), "a number > 0", positive);
  if (dt.IsDefined()) {
    const std::string dt_path = child_path(path, "dt");
    result.dt = number_where(dt, dt_path, "a number > 0", positive);
    if (courant.IsDefined())
      fail(dt, dt_path,
           "give either courant (a fraction of the stable step) or dt (a fixed step), not both; courant is "
           "given " +
               position_text(courant, child_path(path, "courant")));
  }
  if (const YAML::Node ratio = optional(node, "min_dt_ratio"); ratio.IsDefined())
    result.min_dt_ratio = number_where(ratio, child_path(path, "min_dt_ratio"),
                                       "a number in (0, 1) (a fraction of the first step)",
                                       [](double value) { return value > 0.0 && value < 1.0; });
  if (const YAML::Node erode = optional(node, "erode"); erode.IsDefined()) {
    result.erode = boolean(erode, child_path(path, "erode"));
    if (result.erode && dt.IsDefined())
      fail(erode, child_path(path, "erode"),
           "erodes elements whose own stable step falls below min_dt_ratio of the first, which needs a step "
           "that follows the deformation: give courant, not dt");
  }
  return result;
}

void DeckValidator::check_erode(const YAML::Node& node, const Deck& deck) const {
  bool any = false;
  for (const PartOptions& part : deck.parts) {
    const MaterialOptions& material = deck.materials[std::size_t(part.material_index)];
    if (material.failure == FailureModel::none) continue;
    any = true;
    if (resolved_kinematics(part, material) != Kinematics::finite)
      fail(node, "time.erode",
           "part '" + part.name +
               "' can fail but runs small strain, whose step does not follow its elements: give it "
               "kinematics: finite");
  }
  if (!any)
    fail(node, "time.erode",
         "erodes elements of the parts that can fail, and no part's material has `failure`");
}

OutputOptions DeckValidator::output(const YAML::Node& node, const std::string& path) const {
  OutputOptions result;
  if (node.IsNull()) return result;
  check_map(node, path, {"directory", "every", "fields", "history_every", "background"});
  if (const YAML::Node directory = optional(node, "directory"); directory.IsDefined())
    result.directory = text(directory, child_path(path, "directory"), "a directory name");
  if (const YAML::Node every = optional(node, "every"); every.IsDefined())
    result.every = integer_where(every, child_path(path, "every"), "an integer >= 1", 1);
  if (const YAML::Node fields = optional(node, "fields"); fields.IsDefined()) {
    const std::string fields_path = child_path(path, "fields");
    const std::vector<std::string> field_names = names_of(all_output_fields);
    check_sequence(fields, fields_path, "a list of field names among " + join(field_names, ", "));
    result.fields.clear();
    for (std::size_t i = 0; i < fields.size(); ++i) {
      const std::string field_path = child_path(fields_path, i);
      const OutputField field = all_output_fields[choice(fields[i], field_path, "output field", field_names)];
      if (std::find(result.fields.begin(), result.fields.end(), field) != result.fields.end())
        fail(fields[i], field_path,
             "field '" + field_names[static_cast<std::size_t>(field)] + "' is listed twice");
      result.fields.push_back(field);
    }
  }
  if (const YAML::Node history = optional(node, "history_every"); history.IsDefined())
    result.history_every = integer_where(history, child_path(path, "history_every"), "an integer >= 1", 1);
  if (const YAML::Node background = optional(node, "background"); background.IsDefined())
    result.background = boolean(background, child_path(path, "background"));
  return result;
}

GuardOptions DeckValidator::guards(const YAML::Node& node, const std::string& path) const {
  GuardOptions result;
  if (node.IsNull()) return result;
  check_map(node, path, {"energy_growth", "max_penetration"});
  if (const YAML::Node growth = optional(node, "energy_growth"); growth.IsDefined())
    result.energy_growth =
        number_where(growth, child_path(path, "energy_growth"), "a number > 0 (a fraction)", positive);
  if (const YAML::Node penetration = optional(node, "max_penetration"); penetration.IsDefined())
    result.max_penetration = number_where(penetration, child_path(path, "max_penetration"),
                                          "a number > 0 (a fraction of the element length)", positive);
  return result;
}

CheckpointOptions DeckValidator::checkpoint(const YAML::Node& node, const std::string& path) const {
  CheckpointOptions result;
  if (node.IsNull()) return result;
  check_map(node, path, {"every", "every_seconds", "keep"});
  if (const YAML::Node every = optional(node, "every"); every.IsDefined())
    result.every = integer_where(every, child_path(path, "every"), "an integer >= 1 (steps)", 1);
  if (const YAML::Node seconds = optional(node, "every_seconds"); seconds.IsDefined())
    result.every_seconds =
        number_where(seconds, child_path(path, "every_seconds"), "a number > 0 (wall seconds)", positive);
  if (const YAML::Node keep = optional(node, "keep"); keep.IsDefined())
    result.keep = integer_where(keep, child_path(path, "keep"), "an integer >= 1", 1);
  if (!result.enabled())
    fail(node, path, "give every (steps) or every_seconds (wall seconds) between checkpoints, or both");
  return result;
}

}  // namespace exdyn::input::deck
