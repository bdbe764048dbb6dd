#include "model/memory_estimate.hpp"

#include <algorithm>
#include <array>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <limits>
#include <sstream>
#include <string>

#include "common/errors.hpp"
#include "common/nodal_vectors.hpp"
#include "element/hex20.hpp"
#include "element/hex8.hpp"
#include "element/hex8_parallelepiped.hpp"
#include "element/hex8r.hpp"

namespace exdyn::solver {

// The counts of memory_estimate.hpp, from the types they come from.
static_assert(sizeof(double) == 8 && sizeof(std::uint32_t) == 4 && sizeof(std::int32_t) == 4);
static_assert(bytes_per_node == (3 + 2 + 6 * 3 + 1 + 2 + 3 + (4 * 3 + 1)) * sizeof(double));
static_assert(bytes_per_element_besides_reference == 8 * sizeof(std::uint32_t) + sizeof(std::int32_t) +
                                                         2 * (6 + 1) * sizeof(double) +
                                                         8 * sizeof(std::int64_t));

std::uint64_t bytes_per_element(const input::PartOptions& part) {
  if (input::is_quadratic(part.formulation)) {
    // hex20_family.cpp: the general reference data of every element (kept for a
    // distorted part, replaced by a few shared matrices for a box), 20 node ids, the
    // int64 connectivity written to HDF5 and the group index of each element.
    const int gauss_points = part.formulation == input::Formulation::hex20 ? 27 : 8;
    return 20 * sizeof(std::uint32_t) + sizeof(std::int32_t) + 2 * (6 + 1) * sizeof(double) +
           20 * sizeof(std::int64_t) + sizeof(std::uint32_t) +
           8 * static_cast<std::uint64_t>(element::hex20::reference_size(gauss_points));
  }
  // The layouts hex8_family.cpp chooses: a regular box is made of parallelepipeds; a
  // distorted box and a mapped part are not.
  const bool hex8 = part.formulation == input::Formulation::hex8;
  const bool general = part.perturbation_fraction > 0.0 || part.geometry != input::Geometry::box;
  const int reference_doubles = general
                                    ? (hex8 ? element::hex8::reference_size : element::hex8r::reference_size)
                                    : (hex8 ? element::hex8::parallelepiped_reference_size
                                            : element::hex8r::parallelepiped_reference_size);
  return bytes_per_element_besides_reference + 8 * static_cast<std::uint64_t>(reference_doubles);
}

namespace {

constexpr std::uint64_t saturated = std::numeric_limits<std::uint64_t>::max();
constexpr std::uint64_t max_nodes = std::numeric_limits<std::uint32_t>::max();    // 32-bit node ids
constexpr std::uint64_t max_elements = std::numeric_limits<std::int32_t>::max();  // mesh::build_mesh's limit

// a * b and a + b, UINT64_MAX when the result does not fit.
std::uint64_t product(std::uint64_t a, std::uint64_t b) {
  std::uint64_t result = 0;
  return __builtin_mul_overflow(a, b, &result) ? saturated : result;
}
std::uint64_t sum(std::uint64_t a, std::uint64_t b) {
  std::uint64_t result = 0;
  return __builtin_add_overflow(a, b, &result) ? saturated : result;
}

// A part's element counts; the deck reader gives 1 <= n <= INT_MAX, a negative n
// (a deck not from the reader) counts as 0.
// A cylinder or sphere counts as the box of its bounding grid: (n_around + 2 n_radius)
// across the section (at least the n_around^2 + 4 n_around n_radius elements of the
// O-grid, docs/input.md), n_axis along a cylinder, halved per `keep` cut: an upper
// bound, which is what a refusal needs.
std::array<int, 3> element_counts(const input::PartOptions& part) {
  std::array<int, 3> n = part.elements;
  for (int& value : n) value = std::max(value, 0);
  if (part.geometry == input::Geometry::box) return n;
  const long long across = std::min<long long>(std::numeric_limits<int>::max(), n[0] + 2LL * n[1]);
  n = {static_cast<int>(across), static_cast<int>(across),
       part.geometry == input::Geometry::cylinder ? n[2] : static_cast<int>(across)};
  for (const int keep : part.keep)
    if (keep != 0) n[0] = (n[0] + 1) / 2;
  return n;
}

// n[0] * n[1] * n[2] with n[k] + offset (offset 1: grid points), exact or saturated.
std::uint64_t grid_count(const std::array<int, 3>& n, int offset) {
  std::uint64_t count = 1;
  for (const int value : n)
    count = product(count, static_cast<std::uint64_t>(value) + static_cast<std::uint64_t>(offset));
  return count;
}
double grid_count_real(const std::array<int, 3>& n, int offset) {
  return (double(n[0]) + offset) * (double(n[1]) + offset) * (double(n[2]) + offset);
}

// Nodes of a part: the grid points, and for a 20-node part the mid-edge points
// (nx (ny+1) (nz+1) and its two permutations), exact or saturated.
std::uint64_t node_count(const input::PartOptions& part, const std::array<int, 3>& n) {
  std::uint64_t count = grid_count(n, 1);
  if (!input::is_quadratic(part.formulation)) return count;
  for (int axis = 0; axis < 3; ++axis) {
    std::array<int, 3> edges = n;
    for (int other = 0; other < 3; ++other)
      if (other != axis) edges[static_cast<std::size_t>(other)] += 1;
    count = sum(count, grid_count(edges, 0));
  }
  return count;
}
double node_count_real(const input::PartOptions& part, const std::array<int, 3>& n) {
  double count = grid_count_real(n, 1);
  if (input::is_quadratic(part.formulation))
    count += double(n[0]) * (n[1] + 1.0) * (n[2] + 1.0) + (n[0] + 1.0) * double(n[1]) * (n[2] + 1.0) +
             (n[0] + 1.0) * (n[1] + 1.0) * double(n[2]);
  return count;
}

// "123456" when exact, "about 1e+15" when it saturated 64 bits.
std::string format_count(std::uint64_t count, double real) {
  if (count != saturated) return std::to_string(count);
  char text[32];
  std::snprintf(text, sizeof text, "about %.3g", real);
  return text;
}

// "1.5 GiB", "437 PiB"
std::string format_bytes(double bytes) {
  static constexpr const char* units[] = {"B", "KiB", "MiB", "GiB", "TiB", "PiB", "EiB"};
  std::size_t unit = 0;
  while (unit + 1 < std::size(units) && bytes >= 1024.0) bytes /= 1024.0, ++unit;
  char text[48];
  std::snprintf(text, sizeof text, "%.3g %s", bytes, units[unit]);
  return text;
}

}  // namespace

MemoryEstimate estimate_memory(const input::Deck& deck) {
  MemoryEstimate estimate;
  for (const input::PartOptions& part : deck.parts) {
    const std::array<int, 3> n = element_counts(part);
    estimate.nodes = sum(estimate.nodes, node_count(part, n));
    estimate.elements = sum(estimate.elements, grid_count(n, 0));
    estimate.bytes += node_count_real(part, n) * double(bytes_per_node) +
                      grid_count_real(n, 0) * double(bytes_per_element(part));
  }
  // The faces erosion can open, once for each part a surface that follows it holds.
  std::vector<std::uint8_t> opening(deck.parts.size(), 0);
  for (const input::ContactOptions& pair : deck.contact)
    if (input::follows_erosion(deck, pair))
      for (const input::FaceRef& face : pair.slave) {
        const input::PartOptions& part = deck.parts[std::size_t(face.part)];
        if (opening[std::size_t(face.part)] != 0 ||
            deck.materials[std::size_t(part.material_index)].failure == input::FailureModel::none)
          continue;
        opening[std::size_t(face.part)] = 1;
        estimate.bytes += grid_count_real(element_counts(part), 0) * double(bytes_per_opening_element);
      }
  return estimate;
}

std::optional<std::uint64_t> available_memory(const std::string& meminfo_path) {
  std::ifstream file(meminfo_path);
  std::string line;
  while (std::getline(file, line)) {
    // "MemAvailable:   12345678 kB"
    std::istringstream fields(line);
    std::string key, unit;
    std::uint64_t value = 0;
    if (!(fields >> key) || key != "MemAvailable:") continue;
    if (!(fields >> value >> unit) || unit != "kB") return std::nullopt;
    return product(value, 1024);
  }
  return std::nullopt;
}

void check_mesh_size(const input::Deck& deck, std::optional<std::uint64_t> available_bytes,
                     MachineShare share) {
  const MemoryEstimate estimate = estimate_memory(deck);
  const bool too_many_nodes = estimate.nodes > max_nodes;
  const bool too_many_elements = estimate.elements > max_elements;
  const double need = estimate.bytes * double(share.ranks_here) / double(share.ranks);  // here
  const bool too_large = available_bytes && need > double(*available_bytes);
  if (!too_many_nodes && !too_many_elements && !too_large) return;

  double nodes_real = 0.0, elements_real = 0.0;
  std::uint64_t least = saturated, most = 0;  // bytes per element over the parts
  std::string parts;
  for (std::size_t p = 0; p < deck.parts.size(); ++p) {
    const input::PartOptions& part = deck.parts[p];
    const std::array<int, 3> n = element_counts(part);
    nodes_real += node_count_real(part, n);
    elements_real += grid_count_real(n, 0);
    least = std::min(least, bytes_per_element(part));
    most = std::max(most, bytes_per_element(part));
    parts += (p == 0 ? "" : ", ") + std::string("parts[") + std::to_string(p) + "] '" + part.name + "' " +
             std::to_string(n[0]) + " x " + std::to_string(n[1]) + " x " + std::to_string(n[2]) + " = " +
             format_count(grid_count(n, 0), grid_count_real(n, 0)) + " elements";
  }
  std::string message = "the mesh is too large: " + parts + "; in all " +
                        format_count(estimate.elements, elements_real) + " elements and " +
                        format_count(estimate.nodes, nodes_real) + " nodes";
  if (too_many_nodes || too_many_elements)
    message += ", more than the " + std::to_string(max_nodes) + " nodes and " + std::to_string(max_elements) +
               " elements that the 32-bit indices of the mesh can number";
  if (share.ranks > 1)
    message += "; the " + std::to_string(share.ranks_here) + " of its " + std::to_string(share.ranks) +
               " ranks on this machine would need about " + format_bytes(need) + " of memory, " +
               format_bytes(estimate.bytes) + " in all (";
  else
    message += "; the run would need about " + format_bytes(estimate.bytes) + " of memory (";
  message += std::string() + std::to_string(bytes_per_node) + " B per node, " +
             (least == most ? "" : std::to_string(least) + " to ") + std::to_string(most) +
             " B per element) and " +
             (available_bytes ? format_bytes(double(*available_bytes)) + " are available (MemAvailable)"
                              : std::string("the available memory is unknown"));
  throw InputError(SourceLocation{deck.source_file, 0, 0}, "parts", message);
}

void check_mesh_size(const input::Deck& deck, MachineShare share) {
  check_mesh_size(deck, available_memory(), share);
}

}  // namespace exdyn::solver
