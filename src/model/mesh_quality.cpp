#include "model/mesh_quality.hpp"

#include <array>
#include <limits>

#include "element/quality.hpp"

namespace exdyn::solver {

std::vector<PartQuality> mesh_quality(const mesh::Mesh& mesh) {
  std::vector<PartQuality> result;
  for (const mesh::PartRange& part : mesh.parts) {
    PartQuality q;
    q.smallest_scaled_jacobian = std::numeric_limits<double>::infinity();
    for (std::uint32_t e = part.first_element; e < part.first_element + part.element_count; ++e) {
      std::array<std::array<double, 3>, 20> x{};
      const std::uint32_t* nodes = mesh.element_nodes(e);
      for (int i = 0; i < part.nodes_per_element; ++i)
        x[std::size_t(i)] = {mesh.x_ref.x[nodes[i]], mesh.x_ref.y[nodes[i]], mesh.x_ref.z[nodes[i]]};
      const element::ElementQuality eq = element::element_quality(x.data(), part.nodes_per_element);
      q.volume += eq.volume;
      if (eq.scaled_jacobian < q.smallest_scaled_jacobian) {
        q.smallest_scaled_jacobian = eq.scaled_jacobian;
        q.worst_element = e;
      }
    }
    result.push_back(q);
  }
  return result;
}

}  // namespace exdyn::solver
