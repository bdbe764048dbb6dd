// The deck reader: YAML text -> overrides applied to the tree -> validated Deck.
// Every error is an InputError naming the file, line, column and key path of the
// offending node (docs/input.md, "Errors"). Only this file and project_cases.cpp
// include yaml-cpp.
#include "input/deck_reader.hpp"

#include <yaml-cpp/eventhandler.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstddef>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <optional>
#include <sstream>
#include <string>
#include <string_view>
#include <system_error>
#include <utility>
#include <vector>

#include "common/errors.hpp"
#include "input/text_tools.hpp"

namespace exdyn::input {
namespace {

constexpr std::string_view command_line_file = "<command line>";

// ---------------------------------------------------------------------------
// Names of the choices, in the order docs/input.md lists them.

constexpr std::array<MaterialModel, 1> all_material_models{MaterialModel::linear_elastic};
constexpr std::array<Formulation, 2> all_formulations{Formulation::hex8, Formulation::hex8r};
constexpr std::array<BoxSide, 6> all_box_sides{BoxSide::xmin, BoxSide::xmax, BoxSide::ymin,
                                               BoxSide::ymax, BoxSide::zmin, BoxSide::zmax};
constexpr std::array<std::string_view, 3> component_names{"x", "y", "z"};

std::vector<std::string> top_level_keys() {
  return {"name", "materials", "parts", "boundary_conditions", "contact", "time", "output", "guards"};
}

template <class Enum, std::size_t N>
std::vector<std::string> names_of(const std::array<Enum, N>& values) {
  std::vector<std::string> names;
  for (const Enum value : values) names.emplace_back(name(value));
  return names;
}

template <class Enum, std::size_t N>
std::vector<std::string> names_of(const std::array<std::pair<Enum, std::string_view>, N>& table) {
  std::vector<std::string> names;
  for (const auto& entry : table) names.emplace_back(entry.second);
  return names;
}

// ---------------------------------------------------------------------------
// Key paths: `parts[0].elements`, `contact[1].local_search.method`.

struct PathSegment {
  std::string key;                   // a map key, or
  std::optional<std::size_t> index;  // a list index
};

std::string child_path(const std::string& path, std::string_view key) {
  return path.empty() ? std::string(key) : path + "." + std::string(key);
}

std::string child_path(const std::string& path, std::size_t index) {
  return path + "[" + std::to_string(index) + "]";
}

std::string format_key_path(const std::vector<PathSegment>& segments) {
  std::string path;
  for (const PathSegment& segment : segments)
    path = segment.index ? child_path(path, *segment.index) : child_path(path, segment.key);
  return path;
}

[[noreturn]] void fail_argument(const std::string& argument, const std::string& message) {
  throw InputError(SourceLocation{std::string(command_line_file), 0, 0}, "--set " + argument, message);
}

// Grammar: name ('[' digits ']')* ('.' name ('[' digits ']')*)*. A name is any run
// of characters other than `.`, `[`, `]` (material names may hold anything else).
std::vector<PathSegment> parse_key_path(const std::string& text) {
  std::vector<PathSegment> segments;
  const std::size_t size = text.size();
  std::size_t i = 0;
  while (true) {
    const std::size_t name_start = i;
    while (i < size && text[i] != '.' && text[i] != '[' && text[i] != ']') ++i;
    if (i == name_start)
      fail_argument(text, "expected a key name at character " + std::to_string(i + 1) +
                              " of the key path (key paths look like time.courant or parts[0].elements)");
    segments.push_back({text.substr(name_start, i - name_start), std::nullopt});
    while (i < size && text[i] == '[') {
      const std::size_t digits_start = ++i;
      while (i < size && text[i] >= '0' && text[i] <= '9') ++i;
      std::size_t index = 0;
      const auto [end, error] = std::from_chars(text.data() + digits_start, text.data() + i, index);
      if (i == digits_start || i >= size || text[i] != ']' || error != std::errc{} || end != text.data() + i)
        fail_argument(text, "expected a list index like [0] at character " + std::to_string(digits_start) +
                                " of the key path");
      ++i;
      segments.push_back({std::string(), index});
    }
    if (i == size) break;
    if (text[i] != '.')
      fail_argument(text, "unexpected '" + std::string(1, text[i]) + "' at character " +
                              std::to_string(i + 1) + " of the key path");
    ++i;
  }
  return segments;
}

std::string trim(std::string_view text) {
  const auto first = text.find_first_not_of(" \t\r\n");
  if (first == std::string_view::npos) return {};
  const auto last = text.find_last_not_of(" \t\r\n");
  return std::string(text.substr(first, last - first + 1));
}

// ---------------------------------------------------------------------------
// Scalars. yaml-cpp keeps every scalar as text; the number syntax is YAML 1.2's
// (an optional sign, digits, a point, an exponent), read with from_chars.

bool is_quoted(const YAML::Node& node) { return node.Tag() == "!"; }

std::optional<double> parse_double(std::string_view text) {
  if (!text.empty() && text.front() == '+') text.remove_prefix(1);
  if (text.empty() || text.front() == '+') return std::nullopt;
  // A digit or a point must come first: from_chars alone would also take "inf" and "nan".
  const char first = text.front() == '-' && text.size() > 1 ? text[1] : text.front();
  if (!(first >= '0' && first <= '9') && first != '.') return std::nullopt;
  double value = 0.0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (error != std::errc{} || end != text.data() + text.size()) return std::nullopt;
  return value;
}

std::optional<long long> parse_integer(std::string_view text) {
  if (!text.empty() && text.front() == '+') text.remove_prefix(1);
  long long value = 0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (text.empty() || error != std::errc{} || end != text.data() + text.size()) return std::nullopt;
  return value;
}

bool looks_like_yaml_keyword(std::string_view text) {
  std::string lower(text);
  std::transform(lower.begin(), lower.end(), lower.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  for (std::string_view keyword : {"true", "false", "yes", "no", "on", "off", "null", "~", "y", "n"})
    if (lower == keyword) return true;
  return false;
}

// A short description of a node for "expected ..., got <this>".
std::string describe(const YAML::Node& node) {
  if (!node.IsDefined()) return "nothing";
  switch (node.Type()) {
    case YAML::NodeType::Null:
      return "an empty value";
    case YAML::NodeType::Scalar: {
      std::string text = node.Scalar();
      if (text.size() > 60) text = text.substr(0, 57) + "...";
      if (is_quoted(node)) return "the quoted string \"" + text + "\"";
      return text.empty() ? "an empty string" : text;
    }
    case YAML::NodeType::Sequence:
      return node.size() == 1 ? "a list of 1 entry" : "a list of " + std::to_string(node.size()) + " entries";
    case YAML::NodeType::Map:
      return "a map";
    case YAML::NodeType::Undefined:
      return "nothing";
  }
  return "an unknown node";
}

// ---------------------------------------------------------------------------
// Overrides: applied to the YAML tree, before validation, in the order given.

[[noreturn]] void fail_override(const Override& item, const std::string& message) {
  throw InputError(SourceLocation{std::string(command_line_file), 0, 0}, "--set " + item.key_path, message);
}

// `node` is a handle sharing the tree (yaml-cpp nodes are references), so
// assigning through it edits the deck. Missing map keys are created on the way.
void assign_at(YAML::Node node, const std::vector<PathSegment>& segments, std::size_t depth,
               const YAML::Node& value, const Override& item, const std::string& node_path) {
  const PathSegment& segment = segments[depth];
  const bool last = depth + 1 == segments.size();
  const std::string shown = node_path.empty() ? std::string("the deck") : node_path;
  if (segment.index) {
    if (!node.IsDefined())
      fail_override(
          item, shown + " is not in the deck, so it has no entry [" + std::to_string(*segment.index) + "]");
    if (!node.IsSequence())
      fail_override(item, shown + " is " + describe(node) + ", not a list, so it has no entry [" +
                              std::to_string(*segment.index) + "]");
    if (*segment.index >= node.size())
      fail_override(item, "index " + std::to_string(*segment.index) + " is out of range: " + shown + " has " +
                              std::to_string(node.size()) + (node.size() == 1 ? " entry" : " entries"));
    const std::string path = child_path(node_path, *segment.index);
    if (last) {
      node[*segment.index] = value;
      return;
    }
    assign_at(node[*segment.index], segments, depth + 1, value, item, path);
    return;
  }
  if (node.IsDefined() && !node.IsMap() && !node.IsNull()) {
    const std::string what = node.IsSequence()
                                 ? describe(node) + " (give an index, e.g. " + child_path(node_path, 0) + ")"
                                 : "the value " + describe(node);
    fail_override(item, shown + " is " + what + ", not a map, so it has no key '" + segment.key + "'");
  }
  const std::string path = child_path(node_path, segment.key);
  if (last) {
    node[segment.key] = value;
    return;
  }
  assign_at(node[segment.key], segments, depth + 1, value, item, path);
}

void apply_override(YAML::Node& root, const Override& item) {
  const std::vector<PathSegment> segments = parse_key_path(item.key_path);
  YAML::Node value;
  try {
    value = YAML::Load(item.value);
  } catch (const YAML::Exception& error) {
    fail_override(item, "cannot read the value '" + item.value + "' as YAML: " + error.msg);
  }
  assign_at(root, segments, 0, value, item, "");
}

// ---------------------------------------------------------------------------
// Validation: one method per section of the deck, each given its node and key path.

class DeckValidator {
 public:
  DeckValidator(std::string source_name, const std::vector<Override>& overrides)
      : source_name_(std::move(source_name)), overrides_(overrides) {
    for (const Override& item : overrides_)
      override_paths_.push_back(format_key_path(parse_key_path(item.key_path)));
  }

  Deck deck(const YAML::Node& root) const;

 private:
  // --- where a node stands, and failing there
  const Override* override_covering(const std::string& path) const;
  SourceLocation locate(const YAML::Node& node, const std::string& node_path) const;
  std::string position_text(const YAML::Node& node, const std::string& node_path) const;
  [[noreturn]] void fail_at(const YAML::Node& node, const std::string& node_path, const std::string& key_path,
                            const std::string& message) const;
  [[noreturn]] void fail(const YAML::Node& node, const std::string& path, const std::string& message) const {
    fail_at(node, path, path, message);
  }

  // --- structure
  void check_map(const YAML::Node& node, const std::string& path,
                 const std::vector<std::string>& allowed) const;
  YAML::Node required(const YAML::Node& map, const std::string& path, const std::string& key) const;
  static YAML::Node optional(const YAML::Node& map, const std::string& key);
  void check_sequence(const YAML::Node& node, const std::string& path, const std::string& expected) const;

  // --- values
  double number(const YAML::Node& node, const std::string& path, const std::string& expected) const;
  double number_where(const YAML::Node& node, const std::string& path, const std::string& expected,
                      bool (*accept)(double)) const;
  int integer_where(const YAML::Node& node, const std::string& path, const std::string& expected,
                    long long minimum) const;
  std::string text(const YAML::Node& node, const std::string& path, const std::string& expected) const;
  bool boolean(const YAML::Node& node, const std::string& path) const;
  std::size_t choice(const YAML::Node& node, const std::string& path, const std::string& what,
                     const std::vector<std::string>& names) const;
  Vec3 vector3(const YAML::Node& node, const std::string& path) const;

  // --- sections
  std::string run_name(const YAML::Node& node, const std::string& path) const;
  std::vector<MaterialOptions> materials(const YAML::Node& node, const std::string& path) const;
  std::vector<PartOptions> parts(const YAML::Node& node, const std::string& path,
                                 const std::vector<MaterialOptions>& materials) const;
  PartOptions part(const YAML::Node& node, const std::string& path,
                   const std::vector<MaterialOptions>& materials) const;
  FaceRef face(const YAML::Node& node, const std::string& path, const std::vector<PartOptions>& parts) const;
  std::vector<FaceRef> face_list(const YAML::Node& node, const std::string& path,
                                 const std::vector<PartOptions>& parts) const;
  std::vector<BoundaryConditionOptions> boundary_conditions(const YAML::Node& node, const std::string& path,
                                                            const std::vector<PartOptions>& parts) const;
  std::vector<ContactOptions> contact_pairs(const YAML::Node& node, const std::string& path,
                                            const std::vector<PartOptions>& parts) const;
  PenaltyOptions penalty(const YAML::Node& node, const std::string& path) const;
  GlobalSearchOptions global_search(const YAML::Node& node, const std::string& path) const;
  LocalSearchOptions local_search(const YAML::Node& node, const std::string& path) const;
  TimeOptions time(const YAML::Node& node, const std::string& path) const;
  OutputOptions output(const YAML::Node& node, const std::string& path) const;
  GuardOptions guards(const YAML::Node& node, const std::string& path) const;

  std::string source_name_;
  const std::vector<Override>& overrides_;
  std::vector<std::string> override_paths_;  // normalised, parallel to overrides_
};

// The last override that set this path or one of its parents, if any.
const Override* DeckValidator::override_covering(const std::string& path) const {
  for (std::size_t k = override_paths_.size(); k-- > 0;) {
    const std::string& set = override_paths_[k];
    if (path.size() < set.size() || path.compare(0, set.size(), set) != 0) continue;
    if (path.size() == set.size() || path[set.size()] == '.' || path[set.size()] == '[')
      return &overrides_[k];
  }
  return nullptr;
}

SourceLocation DeckValidator::locate(const YAML::Node& node, const std::string& node_path) const {
  if (override_covering(node_path) != nullptr) return {std::string(command_line_file), 0, 0};
  SourceLocation where{source_name_, 0, 0};
  if (node.IsDefined()) {
    const YAML::Mark mark = node.Mark();
    if (!mark.is_null() && mark.line >= 0) {
      where.line = mark.line + 1;  // yaml-cpp counts from 0
      where.column = mark.column + 1;
    }
  }
  return where;
}

std::string DeckValidator::position_text(const YAML::Node& node, const std::string& node_path) const {
  if (const Override* item = override_covering(node_path))
    return "by --set " + item->key_path + "=" + item->value;
  const SourceLocation where = locate(node, node_path);
  return where.line > 0 ? "at line " + std::to_string(where.line) : "above";
}

void DeckValidator::fail_at(const YAML::Node& node, const std::string& node_path, const std::string& key_path,
                            const std::string& message) const {
  std::string full_message = message;
  if (const Override* item = override_covering(node_path))
    full_message += " (from --set " + item->key_path + "=" + item->value + ")";
  throw InputError(locate(node, node_path), key_path, full_message);
}

void DeckValidator::check_map(const YAML::Node& node, const std::string& path,
                              const std::vector<std::string>& allowed) const {
  if (!node.IsMap())
    fail(node, path, "expected a map with keys " + join(allowed, ", ") + "; got " + describe(node));
  std::map<std::string, YAML::Node> seen;
  for (auto entry = node.begin(); entry != node.end(); ++entry) {
    const YAML::Node key_node = entry->first;
    if (!key_node.IsScalar()) fail(key_node, path, "expected a key name, got " + describe(key_node));
    const std::string key = key_node.Scalar();
    const std::string key_path = child_path(path, key);
    if (std::find(allowed.begin(), allowed.end(), key) == allowed.end())
      fail(key_node, key_path, "unknown key '" + key + "'" + suggestion(key, allowed, "the keys here are"));
    const auto [first, inserted] = seen.emplace(key, key_node);
    if (!inserted)
      fail(key_node, key_path,
           "key '" + key + "' is given twice (first " + position_text(first->second, key_path) + ")");
  }
}

YAML::Node DeckValidator::required(const YAML::Node& map, const std::string& path,
                                   const std::string& key) const {
  const YAML::Node value = optional(map, key);
  if (!value.IsDefined())
    fail_at(map, path, child_path(path, key),
            "missing required key '" + key + "'" + (path.empty() ? std::string() : " in " + path));
  return value;
}

YAML::Node DeckValidator::optional(const YAML::Node& map, const std::string& key) {
  // A const lookup never inserts; a missing key gives an undefined node.
  return map[key];
}

void DeckValidator::check_sequence(const YAML::Node& node, const std::string& path,
                                   const std::string& expected) const {
  if (!node.IsSequence()) fail(node, path, "expected " + expected + ", got " + describe(node));
}

double DeckValidator::number(const YAML::Node& node, const std::string& path,
                             const std::string& expected) const {
  std::optional<double> value;
  if (node.IsScalar() && !is_quoted(node)) value = parse_double(node.Scalar());
  if (!value || !std::isfinite(*value)) fail(node, path, "expected " + expected + ", got " + describe(node));
  return *value;
}

double DeckValidator::number_where(const YAML::Node& node, const std::string& path,
                                   const std::string& expected, bool (*accept)(double)) const {
  const double value = number(node, path, expected);
  if (!accept(value)) fail(node, path, "expected " + expected + ", got " + describe(node));
  return value;
}

int DeckValidator::integer_where(const YAML::Node& node, const std::string& path, const std::string& expected,
                                 long long minimum) const {
  if (!node.IsScalar() || is_quoted(node))
    fail(node, path, "expected " + expected + ", got " + describe(node));
  const std::optional<long long> value = parse_integer(node.Scalar());
  if (!value) {
    const std::optional<double> real = parse_double(node.Scalar());
    std::string why;
    if (real) why = *real == std::trunc(*real) ? " (out of range)" : " (not an integer)";
    fail(node, path, "expected " + expected + ", got " + describe(node) + why);
  }
  if (*value < minimum) fail(node, path, "expected " + expected + ", got " + describe(node));
  if (*value > std::numeric_limits<int>::max())
    fail(node, path,
         "expected " + expected + ", got " + describe(node) + " (larger than " +
             std::to_string(std::numeric_limits<int>::max()) + ")");
  return static_cast<int>(*value);
}

std::string DeckValidator::text(const YAML::Node& node, const std::string& path,
                                const std::string& expected) const {
  if (!node.IsScalar() || node.Scalar().empty())
    fail(node, path, "expected " + expected + ", got " + describe(node));
  return node.Scalar();
}

bool DeckValidator::boolean(const YAML::Node& node, const std::string& path) const {
  if (node.IsScalar() && !is_quoted(node)) {
    const std::string& value = node.Scalar();
    if (value == "true" || value == "True" || value == "TRUE") return true;
    if (value == "false" || value == "False" || value == "FALSE") return false;
  }
  fail(node, path, "expected true or false, got " + describe(node));
}

std::size_t DeckValidator::choice(const YAML::Node& node, const std::string& path, const std::string& what,
                                  const std::vector<std::string>& names) const {
  const std::string one_of = "one of " + join(names, ", ");
  if (!node.IsScalar() || is_quoted(node) || node.Scalar().empty())
    fail(node, path, "expected " + what + " (" + one_of + "), got " + describe(node));
  const std::string& value = node.Scalar();
  const auto found = std::find(names.begin(), names.end(), value);
  if (found == names.end())
    fail(node, path, "unknown " + what + " '" + value + "'" + suggestion(value, names, "expected"));
  return static_cast<std::size_t>(found - names.begin());
}

Vec3 DeckValidator::vector3(const YAML::Node& node, const std::string& path) const {
  const std::string expected = "a list of 3 numbers [x, y, z]";
  check_sequence(node, path, expected);
  if (node.size() != 3) fail(node, path, "expected " + expected + ", got " + describe(node));
  Vec3 value{};
  for (std::size_t i = 0; i < 3; ++i) value[i] = number(node[i], child_path(path, i), "a number");
  return value;
}

// ---------------------------------------------------------------------------

bool positive(double value) { return value > 0.0; }
bool non_negative(double value) { return value >= 0.0; }
bool poissons_ratio_range(double value) { return value > -1.0 && value < 0.5; }

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
  const std::vector<std::string> keys{"model", "density", "youngs_modulus", "poissons_ratio"};
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
    result.push_back(std::move(material));
  }
  return result;
}

PartOptions DeckValidator::part(const YAML::Node& node, const std::string& path,
                                const std::vector<MaterialOptions>& materials) const {
  check_map(node, path,
            {"name", "box", "elements", "material", "formulation", "hourglass", "initial_velocity",
             "perturbation"});
  PartOptions result;
  result.name = text(required(node, path, "name"), child_path(path, "name"), "a part name");

  const std::string box_path = child_path(path, "box");
  const YAML::Node box = required(node, path, "box");
  check_map(box, box_path, {"min", "max"});
  result.box_min = vector3(required(box, box_path, "min"), child_path(box_path, "min"));
  const YAML::Node box_max = required(box, box_path, "max");
  result.box_max = vector3(box_max, child_path(box_path, "max"));
  for (std::size_t i = 0; i < 3; ++i) {
    if (result.box_max[i] > result.box_min[i]) continue;
    fail(box_max, child_path(box_path, "max"),
         "expected max > min in every component, got " + std::string(component_names[i]) + ": max " +
             format_number(result.box_max[i]) + " <= min " + format_number(result.box_min[i]));
  }

  const std::string elements_path = child_path(path, "elements");
  const YAML::Node elements = required(node, path, "elements");
  const std::string expected = "a list of 3 integers >= 1 [nx, ny, nz]";
  check_sequence(elements, elements_path, expected);
  if (elements.size() != 3)
    fail(elements, elements_path, "expected " + expected + ", got " + describe(elements));
  for (std::size_t i = 0; i < 3; ++i)
    result.elements[i] = integer_where(elements[i], child_path(elements_path, i), "an integer >= 1", 1);

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

  // Accepted for hex8 too (and unused there), so that batch runs can switch the
  // formulation with --set without editing the hourglass block.
  if (const YAML::Node hourglass = optional(node, "hourglass");
      hourglass.IsDefined() && !hourglass.IsNull()) {
    const std::string hourglass_path = child_path(path, "hourglass");
    check_map(hourglass, hourglass_path, {"coefficient"});
    if (const YAML::Node coefficient = optional(hourglass, "coefficient"); coefficient.IsDefined())
      result.hourglass_coefficient =
          number_where(coefficient, child_path(hourglass_path, "coefficient"), "a number >= 0", non_negative);
  }

  if (const YAML::Node velocity = optional(node, "initial_velocity"); velocity.IsDefined())
    result.initial_velocity = vector3(velocity, child_path(path, "initial_velocity"));

  if (const YAML::Node perturbation = optional(node, "perturbation");
      perturbation.IsDefined() && !perturbation.IsNull()) {
    const std::string perturbation_path = child_path(path, "perturbation");
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
  const std::vector<std::string> sides = names_of(all_box_sides);
  const std::string value = text(node, path, "a face name <part>.<side>");
  std::vector<std::string> part_names;
  std::vector<std::string> face_names;
  for (const PartOptions& known : parts) {
    part_names.push_back(known.name);
    for (const std::string& side : sides) face_names.push_back(known.name + "." + side);
  }
  std::string hint = "; the parts are " + join(part_names, ", ") + " and the sides " + join(sides, ", ");
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
  const auto side_found = std::find(sides.begin(), sides.end(), side_name);
  if (side_found == sides.end())
    fail(node, path, "unknown side '" + side_name + "' in face '" + value + "'" + hint);
  return FaceRef{static_cast<int>(part_found - part_names.begin()),
                 all_box_sides[static_cast<std::size_t>(side_found - sides.begin())]};
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
  check_sequence(node, path, "a list of boundary conditions {faces: [...], fix: [...]}");
  for (std::size_t b = 0; b < node.size(); ++b) {
    const std::string bc_path = child_path(path, b);
    const YAML::Node entry = node[b];
    check_map(entry, bc_path, {"faces", "fix"});
    BoundaryConditionOptions condition;
    condition.faces = face_list(required(entry, bc_path, "faces"), child_path(bc_path, "faces"), parts);
    const std::string fix_path = child_path(bc_path, "fix");
    const YAML::Node fix = required(entry, bc_path, "fix");
    const std::string expected = "a non-empty list of components among x, y, z";
    check_sequence(fix, fix_path, expected);
    if (fix.size() == 0) fail(fix, fix_path, "expected " + expected + ", got an empty list");
    const std::vector<std::string> components(component_names.begin(), component_names.end());
    for (std::size_t i = 0; i < fix.size(); ++i) {
      const std::string component_path = child_path(fix_path, i);
      const std::size_t axis = choice(fix[i], component_path, "component", components);
      if (condition.fix[axis])
        fail(fix[i], component_path, "component '" + components[axis] + "' is listed twice");
      condition.fix[axis] = true;
    }
    result.push_back(std::move(condition));
  }
  return result;
}

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
    result.stiffness = number_where(stiffness, stiffness_path, "a number > 0 (force per length)", positive);
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
  check_map(node, path, {"method", "tolerance", "max_iterations", "initial_guess"});
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
    check_map(entry, pair_path, {"name", "slave", "master", "two_pass", "penalty", "search", "local_search"});
    ContactOptions pair;
    const std::string name_path = child_path(pair_path, "name");
    const YAML::Node name_node = required(entry, pair_path, "name");
    pair.name = text(name_node, name_path, "a contact pair name");
    const auto [first, inserted] = index_by_name.emplace(pair.name, c);
    if (!inserted)
      fail(name_node, name_path,
           "contact pair name '" + pair.name + "' is used twice (first by " +
               child_path(path, first->second) + ")");
    pair.slave = face_list(required(entry, pair_path, "slave"), child_path(pair_path, "slave"), parts);
    pair.master = face_list(required(entry, pair_path, "master"), child_path(pair_path, "master"), parts);
    if (const YAML::Node two_pass = optional(entry, "two_pass"); two_pass.IsDefined())
      pair.two_pass = boolean(two_pass, child_path(pair_path, "two_pass"));
    if (const YAML::Node penalty_node = optional(entry, "penalty"); penalty_node.IsDefined())
      pair.penalty = penalty(penalty_node, child_path(pair_path, "penalty"));
    if (const YAML::Node search = optional(entry, "search"); search.IsDefined())
      pair.search = global_search(search, child_path(pair_path, "search"));
    if (const YAML::Node local = optional(entry, "local_search"); local.IsDefined())
      pair.local_search = local_search(local, child_path(pair_path, "local_search"));
    result.push_back(std::move(pair));
  }
  return result;
}

TimeOptions DeckValidator::time(const YAML::Node& node, const std::string& path) const {
  check_map(node, path, {"end_time", "courant", "dt"});
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
  return result;
}

OutputOptions DeckValidator::output(const YAML::Node& node, const std::string& path) const {
  OutputOptions result;
  if (node.IsNull()) return result;
  check_map(node, path, {"directory", "every", "fields", "history_every"});
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

Deck DeckValidator::deck(const YAML::Node& root) const {
  if (!root.IsMap())
    fail(root, "",
         "expected the deck to be a map with keys " + join(top_level_keys(), ", ") + "; got " +
             describe(root));
  check_map(root, "", top_level_keys());
  Deck result;
  result.source_file = source_name_;
  result.name = run_name(required(root, "", "name"), "name");
  result.materials = materials(required(root, "", "materials"), "materials");
  result.parts = parts(required(root, "", "parts"), "parts", result.materials);
  if (const YAML::Node node = optional(root, "boundary_conditions"); node.IsDefined())
    result.boundary_conditions = boundary_conditions(node, "boundary_conditions", result.parts);
  if (const YAML::Node node = optional(root, "contact"); node.IsDefined())
    result.contact = contact_pairs(node, "contact", result.parts);
  result.time = time(required(root, "", "time"), "time");
  if (const YAML::Node node = optional(root, "output"); node.IsDefined())
    result.output = output(node, "output");
  if (const YAML::Node node = optional(root, "guards"); node.IsDefined())
    result.guards = guards(node, "guards");
  return result;
}

// ---------------------------------------------------------------------------
// Documents. yaml-cpp 0.7's LoadAll loops forever on a document that starts with
// ',' (jbeder/yaml-cpp#1040, fixed upstream by #1319), so the deck is read with
// Load (one document) and the documents are counted by a parser that stops at the
// first empty one, as that fix does.

class DocumentCounter final : public YAML::EventHandler {
 public:
  void OnDocumentStart(const YAML::Mark& mark) override {
    start = mark;
    events = 0;
    root_is_null = false;
  }
  void OnDocumentEnd() override {}
  void OnNull(const YAML::Mark&, YAML::anchor_t) override {
    if (events == 0) root_is_null = true;
    ++events;
  }
  void OnAlias(const YAML::Mark&, YAML::anchor_t) override { ++events; }
  void OnScalar(const YAML::Mark&, const std::string&, YAML::anchor_t, const std::string&) override {
    ++events;
  }
  void OnSequenceStart(const YAML::Mark&, const std::string&, YAML::anchor_t,
                       YAML::EmitterStyle::value) override {
    ++events;
  }
  void OnSequenceEnd() override {}
  void OnMapStart(const YAML::Mark&, const std::string&, YAML::anchor_t, YAML::EmitterStyle::value) override {
    ++events;
  }
  void OnMapEnd() override {}

  YAML::Mark start;
  int events = 0;
  bool root_is_null = false;
};

// Where the second non-empty document starts, if there is one.
std::optional<YAML::Mark> second_document(const std::string& text) {
  std::istringstream stream(text);
  YAML::Parser parser(stream);
  DocumentCounter counter;
  int documents = 0;
  while (parser.HandleNextDocument(counter)) {
    if (counter.events == 1 && counter.root_is_null) break;  // no progress is possible past this
    if (++documents == 2) return counter.start;
  }
  return std::nullopt;
}

// The first line that is not blank, a comment or a document marker.
struct FirstContent {
  int line = 0;  // 1-based
  int column = 0;
  std::string text;
};

std::optional<FirstContent> first_content(const std::string& text) {
  std::istringstream stream(text);
  std::string line;
  for (int number = 1; std::getline(stream, line); ++number) {
    const std::string content = trim(line);
    if (content.empty() || content.front() == '#' || content.front() == '%' || content == "---" ||
        content == "...")
      continue;
    const std::size_t column = line.find_first_not_of(" \t");
    return FirstContent{number, static_cast<int>(column) + 1,
                        content.size() > 40 ? content.substr(0, 37) + "..." : content};
  }
  return std::nullopt;
}

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

}  // namespace

// ---------------------------------------------------------------------------

Override parse_override(const std::string& argument) {
  const std::size_t equals = argument.find('=');
  if (equals == std::string::npos)
    fail_argument(argument,
                  "expected KEY=VALUE, e.g. --set time.courant=0.5 or --set parts[0].elements=[50,1,50]");
  Override result{trim(std::string_view(argument).substr(0, equals)),
                  trim(std::string_view(argument).substr(equals + 1))};
  if (result.key_path.empty()) fail_argument(argument, "expected KEY=VALUE, but the key before '=' is empty");
  if (result.value.empty()) fail_argument(argument, "expected KEY=VALUE, but the value after '=' is empty");
  parse_key_path(result.key_path);  // throws on a malformed path, naming the argument
  return result;
}

Deck parse_deck(const std::string& text, const std::string& source_name,
                const std::vector<Override>& overrides) {
  YAML::Node root;
  std::optional<YAML::Mark> second;
  try {
    root = YAML::Load(text);
    second = second_document(text);
  } catch (const YAML::Exception& error) {
    const SourceLocation where{source_name, error.mark.is_null() ? 0 : error.mark.line + 1,
                               error.mark.is_null() ? 0 : error.mark.column + 1};
    throw InputError(where, "", "YAML syntax error: " + error.msg);
  }
  if (root.IsNull()) {
    // Empty, or a document yaml-cpp could not start (it reads ", x" as null).
    const std::optional<FirstContent> content = first_content(text);
    if (!content)
      throw InputError(SourceLocation{source_name, 0, 0}, "",
                       "the deck is empty; expected a map with keys " + join(top_level_keys(), ", "));
    throw InputError(SourceLocation{source_name, content->line, content->column}, "",
                     "expected the deck to be a map with keys " + join(top_level_keys(), ", ") + "; got '" +
                         content->text + "'");
  }
  if (second)
    throw InputError(SourceLocation{source_name, second->line + 1, second->column + 1}, "",
                     "the file holds more than one YAML document (separated by ---); a deck is one document");
  const DeckValidator validator(source_name, overrides);
  if (root.IsMap())
    for (const Override& item : overrides) apply_override(root, item);
  return validator.deck(root);
}

Deck read_deck(const std::string& path, const std::vector<Override>& overrides) {
  std::error_code error;
  if (std::filesystem::is_directory(path, error))
    throw InputError(SourceLocation{path, 0, 0}, "", "cannot read the deck: it is a directory");
  std::ifstream file(path, std::ios::binary);
  if (!file)
    throw InputError(SourceLocation{path, 0, 0}, "", "cannot read the deck: no such file or no permission");
  std::ostringstream content;
  content << file.rdbuf();
  if (file.bad()) throw InputError(SourceLocation{path, 0, 0}, "", "cannot read the deck: read error");
  return parse_deck(content.str(), path, overrides);
}

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
        << ", poissons_ratio: " << yaml_number(material.poissons_ratio) << "}\n";

  out << "parts:\n";
  for (const PartOptions& part : deck.parts) {
    out << "  - name: " << yaml_text(part.name) << "\n"
        << "    box: {min: " << yaml_vector(part.box_min) << ", max: " << yaml_vector(part.box_max) << "}\n"
        << "    elements: [" << part.elements[0] << ", " << part.elements[1] << ", " << part.elements[2]
        << "]\n"
        << "    material: " << yaml_text(part.material) << "\n"
        << "    formulation: " << name(part.formulation) << "\n"
        << "    hourglass: {coefficient: " << yaml_number(part.hourglass_coefficient) << "}\n"
        << "    initial_velocity: " << yaml_vector(part.initial_velocity) << "\n"
        << "    perturbation: {fraction: " << yaml_number(part.perturbation_fraction)
        << ", seed: " << part.perturbation_seed << "}\n";
  }

  out << "boundary_conditions:" << (deck.boundary_conditions.empty() ? " []" : "") << "\n";
  for (const BoundaryConditionOptions& condition : deck.boundary_conditions) {
    std::vector<std::string> components;
    for (std::size_t axis = 0; axis < 3; ++axis)
      if (condition.fix[axis]) components.emplace_back(component_names[axis]);
    out << "  - {faces: " << yaml_faces(deck, condition.faces) << ", fix: [" << join(components, ", ")
        << "]}\n";
  }

  out << "contact:" << (deck.contact.empty() ? " []" : "") << "\n";
  for (const ContactOptions& pair : deck.contact) {
    const PenaltyOptions& penalty = pair.penalty;
    const LocalSearchOptions& local = pair.local_search;
    out << "  - name: " << yaml_text(pair.name) << "\n"
        << "    slave: " << yaml_faces(deck, pair.slave) << "\n"
        << "    master: " << yaml_faces(deck, pair.master) << "\n"
        << "    two_pass: " << (pair.two_pass ? "true" : "false") << "\n"
        << "    penalty: {"
        << (penalty.stiffness ? "stiffness: " + yaml_number(*penalty.stiffness)
                              : "scale: " + yaml_number(penalty.scale))
        << ", damping: " << yaml_number(penalty.damping) << "}\n"
        << "    search: {cell_size: "
        << (pair.search.cell_size ? yaml_number(*pair.search.cell_size) : "auto") << "}\n"
        << "    local_search: {method: " << contact::name(local.method)
        << ", tolerance: " << yaml_number(local.tolerance) << ", max_iterations: " << local.max_iterations
        << ", initial_guess: " << contact::name(local.initial_guess) << "}\n";
  }

  out << "time:\n"
      << "  end_time: " << yaml_number(deck.time.end_time) << "\n";
  if (deck.time.dt)
    out << "  dt: " << yaml_number(*deck.time.dt) << "\n";
  else
    out << "  courant: " << yaml_number(deck.time.courant) << "\n";

  std::vector<std::string> fields;
  for (const OutputField field : deck.output.fields) fields.emplace_back(name(field));
  out << "output:\n"
      << "  directory: " << yaml_text(deck.output.directory) << "\n"
      << "  every: " << deck.output.every << "\n"
      << "  fields: [" << join(fields, ", ") << "]\n"
      << "  history_every: " << deck.output.history_every << "\n"
      << "guards:\n"
      << "  energy_growth: " << yaml_number(deck.guards.energy_growth) << "\n"
      << "  max_penetration: " << yaml_number(deck.guards.max_penetration) << "\n";
  return out.str();
}

}  // namespace exdyn::input
