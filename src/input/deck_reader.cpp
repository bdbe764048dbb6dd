// The deck reader: YAML text -> overrides applied to the tree -> validated Deck.
// Every error is an InputError naming the file, line, column and key path of the
// offending node (docs/input.md, "Errors"). The input/ folder holds the only YAML
// code of the program: this file (overrides, documents), deck_validator.cpp and
// one file per deck section, deck_writer.cpp (to_yaml), project_cases.cpp.
#include "input/deck_reader.hpp"

#include <yaml-cpp/eventhandler.h>
#include <yaml-cpp/yaml.h>

#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>
#include <string>
#include <system_error>
#include <vector>

#include "common/errors.hpp"
#include "input/deck_validator.hpp"
#include "input/text_tools.hpp"

namespace exdyn::input {
namespace {

using namespace deck;

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

namespace {

std::string scalar_text(const YAML::Node& node) {
  if (!node.IsDefined() || node.IsNull()) return "(none)";
  if (node.IsScalar()) return node.Scalar();
  YAML::Emitter out;
  out << YAML::Flow << node;
  return out.c_str();
}

bool may_change_at_restart(const std::string& path) {
  return path == "time.end_time" || path == "output" || path == "checkpoint";
}

// The first difference of two YAML trees in document order, "" when none.
std::string first_difference(const YAML::Node& a, const YAML::Node& b, const std::string& path) {
  if (may_change_at_restart(path)) return {};
  const auto differs = [&] {
    return path + " (the checkpoint's " + scalar_text(a) + ", the deck's " + scalar_text(b) + ")";
  };
  if (!a.IsDefined() || !b.IsDefined() || a.Type() != b.Type()) return differs();
  if (a.IsScalar()) return a.Scalar() == b.Scalar() ? std::string() : differs();
  if (a.IsSequence()) {
    if (a.size() != b.size()) return differs();
    for (std::size_t i = 0; i < a.size(); ++i)
      if (std::string d = first_difference(a[i], b[i], path + "[" + std::to_string(i) + "]"); !d.empty())
        return d;
    return {};
  }
  if (a.IsMap()) {
    for (const auto& entry : a) {
      const std::string key = entry.first.Scalar();
      if (std::string d = first_difference(entry.second, b[key], path.empty() ? key : path + "." + key);
          !d.empty())
        return d;
    }
    for (const auto& entry : b) {
      const std::string key = entry.first.Scalar();
      if (!a[key].IsDefined())
        if (std::string d = first_difference(a[key], entry.second, path.empty() ? key : path + "." + key);
            !d.empty())
          return d;
    }
  }
  return {};
}

}  // namespace

std::string restart_difference(const std::string& saved, const Deck& deck) {
  return first_difference(YAML::Load(saved), YAML::Load(to_yaml(deck)), "");
}

}  // namespace exdyn::input
