// shuffle_mesh IN.msh OUT.msh [SEED]: writes IN with the elements of every volume in a
// random order (a fixed seed: the same file each time), through the Gmsh library. The
// mesh-order benchmark (scripts/bench_mesh_order.sh) reads it to measure what the
// import's Hilbert order buys over the order a mesher happens to write.
#include <gmsh.h>

#include <cstdint>
#include <cstdio>
#include <numeric>
#include <string>
#include <utility>
#include <vector>

int main(int argc, char** argv) {
  if (argc < 3) {
    std::fprintf(stderr, "usage: shuffle_mesh IN.msh OUT.msh [SEED]\n");
    return 2;
  }
  std::uint64_t state = argc > 3 ? std::stoull(argv[3]) : 1;
  gmsh::initialize(0, nullptr, false);
  gmsh::option::setNumber("General.Terminal", 0);
  try {
    gmsh::open(argv[1]);
    gmsh::vectorpair volumes;
    gmsh::model::getEntities(volumes, 3);
    for (const auto& [dim, tag] : volumes) {
      std::vector<int> types;
      std::vector<std::vector<std::size_t>> tags, nodes;
      gmsh::model::mesh::getElements(types, tags, nodes, dim, tag);
      for (std::size_t t = 0; t < types.size(); ++t) {
        std::vector<std::size_t> order(tags[t].size());
        std::iota(order.begin(), order.end(), std::size_t(0));
        for (std::size_t i = order.size(); i > 1; --i) {  // Fisher-Yates, a 64-bit LCG
          state = state * 6364136223846793005ULL + 1442695040888963407ULL;
          std::swap(order[i - 1], order[(state >> 33) % i]);
        }
        gmsh::model::mesh::reorderElements(types[t], tag, order);
      }
    }
    gmsh::option::setNumber("Mesh.MshFileVersion", 4.1);
    gmsh::write(argv[2]);
  } catch (const std::string& message) {
    std::fprintf(stderr, "shuffle_mesh: %s\n", message.c_str());
    gmsh::finalize();
    return 1;
  }
  gmsh::finalize();
  return 0;
}
