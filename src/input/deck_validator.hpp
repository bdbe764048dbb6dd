// The deck reader's private parts, shared by the files that read one section of
// the deck each (deck_validator.cpp: structure and values, deck_parts.cpp:
// materials, parts, faces and boundary conditions, deck_contact.cpp, deck_time_output.cpp)
// and by deck_reader.cpp (overrides, documents) and deck_writer.cpp (to_yaml).
// Only the input/ folder includes it: it is the only YAML code of the program.
#pragma once

#include <yaml-cpp/yaml.h>

#include <array>
#include <cstddef>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "common/errors.hpp"
#include "input/deck_reader.hpp"
#include "input/options.hpp"

namespace exdyn::input::deck {

inline constexpr std::string_view command_line_file = "<command line>";

// ---------------------------------------------------------------------------
// Names of the choices, in the order docs/input.md lists them.

inline constexpr std::array<MaterialModel, 3> all_material_models{
    MaterialModel::linear_elastic, MaterialModel::elastic_plastic, MaterialModel::johnson_cook};
inline constexpr std::array<Kinematics, 3> all_kinematics{Kinematics::automatic, Kinematics::small,
                                                          Kinematics::finite};
inline constexpr std::array<Formulation, 4> all_formulations{Formulation::hex8, Formulation::hex8r,
                                                             Formulation::hex20, Formulation::hex20r};
inline constexpr std::array<HourglassModel, 2> all_hourglass_models{HourglassModel::assumed_strain,
                                                                    HourglassModel::flanagan_belytschko};
inline constexpr std::array<SlavePoints, 4> all_slave_points{SlavePoints::automatic, SlavePoints::nodes,
                                                             SlavePoints::quadrature, SlavePoints::mortar};
inline constexpr std::array<PartFace, 6> box_faces{PartFace::xmin, PartFace::xmax, PartFace::ymin,
                                                   PartFace::ymax, PartFace::zmin, PartFace::zmax};
inline constexpr std::array<Geometry, 4> all_geometries{Geometry::box, Geometry::cylinder, Geometry::sphere,
                                                        Geometry::mesh};
inline constexpr std::array<PartFace, 3> cut_faces{PartFace::cut_x, PartFace::cut_y, PartFace::cut_z};
inline constexpr std::array<std::string_view, 3> component_names{"x", "y", "z"};

std::vector<std::string> top_level_keys();

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

std::string child_path(const std::string& path, std::string_view key);
std::string child_path(const std::string& path, std::size_t index);
std::string format_key_path(const std::vector<PathSegment>& segments);
[[noreturn]] void fail_argument(const std::string& argument, const std::string& message);
// Grammar: name ('[' digits ']')* ('.' name ('[' digits ']')*)*. A name is any run
// of characters other than `.`, `[`, `]` (material names may hold anything else).
std::vector<PathSegment> parse_key_path(const std::string& text);
std::string trim(std::string_view text);

// ---------------------------------------------------------------------------
// Scalars. yaml-cpp keeps every scalar as text; the number syntax is YAML 1.2's
// (an optional sign, digits, a point, an exponent), read with from_chars.

bool is_quoted(const YAML::Node& node);
std::optional<double> parse_double(std::string_view text);
std::optional<long long> parse_integer(std::string_view text);
bool looks_like_yaml_keyword(std::string_view text);
// A short description of a node for "expected ..., got <this>".
std::string describe(const YAML::Node& node);

inline bool positive(double value) { return value > 0.0; }
inline bool non_negative(double value) { return value >= 0.0; }
inline bool poissons_ratio_range(double value) { return value > -1.0 && value < 0.5; }

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
  void plasticity(const YAML::Node& body, const std::string& path, MaterialOptions& material) const;
  void failure(const YAML::Node& body, const std::string& path, MaterialOptions& material) const;
  std::array<Vec3, 2> angular_velocity(const YAML::Node& node, const std::string& path) const;
  std::vector<PartOptions> parts(const YAML::Node& node, const std::string& path,
                                 const std::vector<MaterialOptions>& materials) const;
  std::array<int, 3> keep_cuts(const YAML::Node& node, const std::string& path, int axis) const;
  MeshFileOptions mesh_file(const YAML::Node& node, const std::string& path) const;
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
  FrictionOptions friction(const YAML::Node& node, const std::string& path) const;
  std::string group_name(const YAML::Node& entry, const std::string& path, std::size_t index,
                         const std::string& what, const std::string& group,
                         std::map<std::string, std::size_t>& index_by_name) const;
  SlavePoints slave_points(const YAML::Node& node, const std::string& path) const;
  std::vector<RigidWallOptions> rigid_walls(const YAML::Node& node, const std::string& path,
                                            const std::vector<PartOptions>& parts) const;
  std::vector<LoadOptions> loads(const YAML::Node& node, const std::string& path,
                                 const std::vector<PartOptions>& parts) const;
  GlobalSearchOptions global_search(const YAML::Node& node, const std::string& path) const;
  LocalSearchOptions local_search(const YAML::Node& node, const std::string& path) const;
  ThermalSoftening thermal_softening(const YAML::Node& node, const std::string& path) const;
  TimeOptions time(const YAML::Node& node, const std::string& path) const;
  // time.erode needs a part that can fail, and every such part under finite strain.
  void check_erode(const YAML::Node& node, const Deck& deck) const;
  OutputOptions output(const YAML::Node& node, const std::string& path) const;
  GuardOptions guards(const YAML::Node& node, const std::string& path) const;
  CheckpointOptions checkpoint(const YAML::Node& node, const std::string& path) const;

  std::string source_name_;
  const std::vector<Override>& overrides_;
  // The physical volume and surface names of each mesh file read so far (parts that
  // share a file read it once).
  mutable std::map<std::string, std::array<std::vector<std::string>, 2>> mesh_names_;
  std::vector<std::string> override_paths_;  // normalised, parallel to overrides_
};

}  // namespace exdyn::input::deck
