// Reads the `exdyn project` cases file (../shared/spec/cli.md). With
// deck_reader.cpp, the only place that touches the YAML library.
//
//   cases:
//     - id: 0                 # integer; optional, defaults to the case's index
//       segment: quad8        # quad4 | quad8
//       nodes: [[x,y,z], ...] # 4 (quad4) or 8 (quad8) points
//       point: [x, y, z]      # the slave point
//       initial_guess: [a, b] # optional
//
// Every error is an InputError "file:line:col: cases[3].nodes: what was expected".
#include "input/project_cases.hpp"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

#include "common/errors.hpp"

namespace exdyn::input {
namespace {

class CasesReader {
 public:
  explicit CasesReader(std::string source) : source_(std::move(source)) {}

  SourceLocation where(const YAML::Node& node) const {
    const YAML::Mark mark = node.Mark();
    if (mark.is_null()) return {source_, 0, 0};
    return {source_, mark.line + 1, mark.column + 1};
  }
  [[noreturn]] void fail(const YAML::Node& node, const std::string& key, const std::string& message) const {
    throw InputError(where(node), key, message);
  }

  std::vector<ProjectCase> read(const YAML::Node& root) const {
    if (!root || root.IsNull()) fail(root, "cases", "the file is empty: expected a map with the key `cases`");
    if (!root.IsMap()) fail(root, "", "expected a map with the key `cases`, got " + kind(root));
    for (const auto& entry : root) {
      const std::string key = key_name(entry.first, "");
      if (key != "cases") fail(entry.first, key, "unknown key (expected `cases`)");
    }
    const YAML::Node cases = root["cases"];
    if (!cases) fail(root, "cases", "missing key: expected a list of cases");
    if (!cases.IsSequence()) fail(cases, "cases", "expected a list of cases, got " + kind(cases));
    std::vector<ProjectCase> out;
    out.reserve(cases.size());
    for (std::size_t i = 0; i < cases.size(); ++i) out.push_back(read_case(cases[i], i));
    return out;
  }

 private:
  static std::string kind(const YAML::Node& node) {
    switch (node.Type()) {
      case YAML::NodeType::Null:
        return "nothing";
      case YAML::NodeType::Scalar:
        return "'" + node.Scalar() + "'";
      case YAML::NodeType::Sequence:
        return "a list";
      case YAML::NodeType::Map:
        return "a map";
      default:
        return "an undefined value";
    }
  }

  // A map key must be a scalar: `? [a]: 1` or `? {a: 1}: 2` makes a list or map the key.
  std::string key_name(const YAML::Node& key, const std::string& path) const {
    if (!key.IsScalar()) fail(key, path, "expected a key name, got " + kind(key));
    return key.Scalar();
  }

  ProjectCase read_case(const YAML::Node& node, std::size_t index) const {
    const std::string path = "cases[" + std::to_string(index) + "]";
    if (!node.IsMap())
      fail(node, path,
           "expected a map with keys id, segment, nodes, point, initial_guess; got " + kind(node));
    static const std::array<std::string_view, 5> keys{"id", "segment", "nodes", "point", "initial_guess"};
    for (const auto& entry : node) {
      const std::string key = key_name(entry.first, path);
      if (std::find(keys.begin(), keys.end(), key) == keys.end()) {
        fail(entry.first, path + "." + key,
             "unknown key" + suggestion(key, keys) + " (expected id, segment, nodes, point, initial_guess)");
      }
    }
    ProjectCase c;
    c.id = static_cast<long>(index);
    if (const YAML::Node id = node["id"]) c.id = read_integer(id, path + ".id");

    const YAML::Node segment = node["segment"];
    if (!segment) fail(node, path + ".segment", "missing key: expected quad4 or quad8");
    if (!segment.IsScalar())
      fail(segment, path + ".segment", "expected quad4 or quad8, got " + kind(segment));
    std::array<std::string_view, contact::segment_type_names.size()> type_names{};
    for (std::size_t k = 0; k < type_names.size(); ++k) type_names[k] = contact::segment_type_names[k].second;
    const auto type = contact::from_name(contact::segment_type_names, segment.Scalar());
    if (!type) {
      fail(segment, path + ".segment",
           "unknown segment type '" + segment.Scalar() + "'" + suggestion(segment.Scalar(), type_names) +
               " (expected quad4 or quad8)");
    }
    c.segment = *type;
    const std::size_t count = c.segment == contact::SegmentType::quad4 ? 4 : 8;

    const YAML::Node nodes = node["nodes"];
    if (!nodes)
      fail(node, path + ".nodes",
           "missing key: expected a list of " + std::to_string(count) + " points [x, y, z]");
    if (!nodes.IsSequence())
      fail(nodes, path + ".nodes", "expected a list of points [x, y, z], got " + kind(nodes));
    if (nodes.size() != count) {
      fail(nodes, path + ".nodes",
           "expected " + std::to_string(count) + " points for a " + segment.Scalar() + " segment, got " +
               std::to_string(nodes.size()));
    }
    for (std::size_t k = 0; k < count; ++k)
      c.nodes.push_back(read_vector<3>(nodes[k], path + ".nodes[" + std::to_string(k) + "]"));

    const YAML::Node point = node["point"];
    if (!point) fail(node, path + ".point", "missing key: expected the slave point [x, y, z]");
    c.point = read_vector<3>(point, path + ".point");
    if (const YAML::Node guess = node["initial_guess"])
      c.initial_guess = read_vector<2>(guess, path + ".initial_guess");
    return c;
  }

  template <std::size_t N>
  std::array<double, N> read_vector(const YAML::Node& node, const std::string& path) const {
    const std::string expected = "expected a list of " + std::to_string(N) + " numbers";
    if (!node.IsSequence()) fail(node, path, expected + ", got " + kind(node));
    if (node.size() != N) fail(node, path, expected + ", got " + std::to_string(node.size()) + " values");
    std::array<double, N> out{};
    for (std::size_t k = 0; k < N; ++k) out[k] = read_number(node[k], path + "[" + std::to_string(k) + "]");
    return out;
  }

  double read_number(const YAML::Node& node, const std::string& path) const {
    if (!node.IsScalar()) fail(node, path, "expected a number, got " + kind(node));
    const std::string& text = node.Scalar();
    std::istringstream in(text);
    in.imbue(std::locale::classic());
    double value = 0.0;
    in >> value;
    if (in.fail() || !(in >> std::ws).eof() || !std::isfinite(value))
      fail(node, path, "expected a finite number, got '" + text + "'");
    return value;
  }

  long read_integer(const YAML::Node& node, const std::string& path) const {
    if (!node.IsScalar()) fail(node, path, "expected an integer, got " + kind(node));
    const std::string& text = node.Scalar();
    std::size_t used = 0;
    long value = 0;
    try {
      value = std::stol(text, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used == 0 || used != text.size()) fail(node, path, "expected an integer, got '" + text + "'");
    return value;
  }

  // " (did you mean 'x'?)" for the nearest name by edit distance, if near.
  template <std::size_t N>
  static std::string suggestion(const std::string& text, const std::array<std::string_view, N>& names) {
    std::size_t best = std::string::npos;
    std::string_view best_name;
    for (const std::string_view name : names) {
      const std::size_t d = edit_distance(text, name);
      if (d < best) best = d, best_name = name;
    }
    if (best_name.empty() || best > std::max<std::size_t>(2, best_name.size() / 2)) return "";
    return " (did you mean '" + std::string(best_name) + "'?)";
  }
  static std::size_t edit_distance(std::string_view a, std::string_view b) {
    std::vector<std::size_t> row(b.size() + 1);
    for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
    for (std::size_t i = 1; i <= a.size(); ++i) {
      std::size_t diagonal = row[0];
      row[0] = i;
      for (std::size_t j = 1; j <= b.size(); ++j) {
        const std::size_t up = row[j];
        row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0u : 1u)});
        diagonal = up;
      }
    }
    return row[b.size()];
  }

  std::string source_;
};

}  // namespace

std::vector<ProjectCase> parse_project_cases(const std::string& text, const std::string& source_name) {
  YAML::Node root;
  try {
    root = YAML::Load(text);
  } catch (const YAML::Exception& error) {
    const SourceLocation where{source_name, error.mark.is_null() ? 0 : error.mark.line + 1,
                               error.mark.is_null() ? 0 : error.mark.column + 1};
    throw InputError(where, "", "not valid YAML: " + error.msg);
  }
  return CasesReader(source_name).read(root);
}

std::vector<ProjectCase> read_project_cases(const std::string& path) {
  std::ifstream file(path, std::ios::binary);
  if (!file) throw InputError(SourceLocation{path, 0, 0}, "", "cannot open the cases file");
  std::ostringstream text;
  text << file.rdbuf();
  return parse_project_cases(text.str(), path);
}

}  // namespace exdyn::input
