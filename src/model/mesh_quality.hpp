// The shape quality and volume of each part of a mesh (element/quality.hpp), for
// `exdyn check` and the mesh tests.
#pragma once

#include <cstdint>
#include <vector>

#include "mesh/mesh.hpp"

namespace exdyn::solver {

struct PartQuality {
  double smallest_scaled_jacobian = 0.0;  // over the part's elements (element/quality.hpp)
  std::uint32_t worst_element = 0;        // global element index where it is smallest
  double volume = 0.0;                    // sum of the element volumes, m^3
};

std::vector<PartQuality> mesh_quality(const mesh::Mesh& mesh);

}  // namespace exdyn::solver
