// Key paths, scalars, and the validator's structure and value checks; the
// top-level deck() that calls one reader per section (docs/input.md, "Errors").
#include "input/deck_validator.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <limits>
#include <map>
#include <string>
#include <system_error>
#include <vector>

#include "common/errors.hpp"
#include "input/text_tools.hpp"

namespace exdyn::input::deck {

std::vector<std::string> top_level_keys() {
  return {"name", "materials", "parts",  "boundary_conditions", "contact", "rigid_walls", "loads",
          "time", "output",    "guards", "checkpoint"};
}

// ---------------------------------------------------------------------------
// Key paths: `parts[0].elements`, `contact[1].local_search.method`.

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

// (the grammar is in deck_validator.hpp)
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
// DeckValidator: where a node stands, structure and values.
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
  if (const YAML::Node node = optional(root, "contact"); node.IsDefined()) {
    result.contact = contact_pairs(node, "contact", result.parts);
    // `surface: all`: every exterior face, which the boundary conditions decide.
    for (std::size_t c = 0; c < result.contact.size(); ++c) {
      ContactOptions& pair = result.contact[c];
      if (!pair.surface_all) continue;
      pair.slave = pair.master = exterior_faces(result);
      if (pair.slave.empty())
        fail(node[c]["surface"], child_path(child_path("contact", c), "surface"),
             "`all` finds no exterior face: every face of every part is held normal to itself by a boundary "
             "condition (a symmetry plane or a support)");
      if (follows_erosion(result, pair) && pair.slave_points == SlavePoints::mortar)
        fail(node[c]["slave_points"], child_path(child_path("contact", c), "slave_points"),
             "mortar does not follow the faces erosion opens, and a part of `surface: all` can fail: use "
             "nodes, "
             "quadrature or auto");
    }
  }
  if (const YAML::Node node = optional(root, "rigid_walls"); node.IsDefined())
    result.rigid_walls = rigid_walls(node, "rigid_walls", result.parts);
  if (const YAML::Node node = optional(root, "loads"); node.IsDefined())
    result.loads = loads(node, "loads", result.parts);
  result.time = time(required(root, "", "time"), "time");
  if (result.time.erode) check_erode(required(root, "", "time")["erode"], result);
  const YAML::Node output_node = optional(root, "output");
  if (output_node.IsDefined()) result.output = output(output_node, "output");
  const bool fails = std::any_of(result.materials.begin(), result.materials.end(),
                                 [](const MaterialOptions& m) { return m.failure != FailureModel::none; });
  if (fails &&
      !(output_node.IsDefined() && output_node.IsMap() && optional(output_node, "fields").IsDefined()))
    result.output.fields.insert(result.output.fields.end(), {OutputField::damage, OutputField::status});
  if (const YAML::Node node = optional(root, "guards"); node.IsDefined())
    result.guards = guards(node, "guards");
  if (const YAML::Node node = optional(root, "checkpoint"); node.IsDefined())
    result.checkpoint = checkpoint(node, "checkpoint");
  return result;
}

}  // namespace exdyn::input::deck
