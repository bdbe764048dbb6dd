// The part of the mesh reader that calls the Gmsh library (input/gmsh_file.hpp), built
// as a module of its own (libexdyn_gmsh_reader.so) that exdyn loads only when a deck
// has a mesh file: loading the library and the ~120 libraries it needs (OpenCASCADE,
// FLTK, ...) took 0.1 s and 44 MB of every process, most of a small run's start-up.
#include <gmsh.h>

#include <exception>
#include <mutex>
#include <string>
#include <utility>
#include <vector>

#include "input/gmsh_file.hpp"

namespace exdyn::input {

namespace {

// The library keeps one global model: one reader at a time, each in its own session.
std::mutex gmsh_mutex;

class GmshSession {
 public:
  GmshSession() {
    gmsh::initialize(0, nullptr, false);  // no configuration files: the same result on every machine
    gmsh::option::setNumber("General.Terminal", 0);
    gmsh::option::setNumber("General.Verbosity", 1);  // errors only
    gmsh::logger::start();
  }
  ~GmshSession() {
    gmsh::logger::stop();
    gmsh::finalize();
  }
  GmshSession(const GmshSession&) = delete;
  GmshSession& operator=(const GmshSession&) = delete;
};

// The elements of every entity of physical group (dim, tag), merged by type.
GmshGroup read_group(int dim, int tag) {
  GmshGroup group;
  gmsh::model::getPhysicalName(dim, tag, group.name);
  if (group.name.empty()) group.name = std::to_string(tag);
  std::vector<int> entities;
  gmsh::model::getEntitiesForPhysicalGroup(dim, tag, entities);
  for (const int entity : entities) {
    std::vector<int> types;
    std::vector<std::vector<std::size_t>> tags, nodes;
    gmsh::model::mesh::getElements(types, tags, nodes, dim, entity);
    for (std::size_t t = 0; t < types.size(); ++t) {
      GmshElements* block = nullptr;
      for (GmshElements& known : group.elements)
        if (known.type == types[t]) block = &known;
      if (block == nullptr) {
        GmshElements added;
        added.type = types[t];
        int order = 0, primary_nodes = 0;
        std::vector<double> local_coordinates;
        gmsh::model::mesh::getElementProperties(types[t], added.name, added.dimension, order,
                                                added.nodes_per_element, local_coordinates, primary_nodes);
        group.elements.push_back(std::move(added));
        block = &group.elements.back();
      }
      block->tags.insert(block->tags.end(), tags[t].begin(), tags[t].end());
      block->nodes.insert(block->nodes.end(), nodes[t].begin(), nodes[t].end());
    }
  }
  return group;
}

}  // namespace

}  // namespace exdyn::input

// The module's one entry (gmsh_file.cpp loads it by this name): reads `file` into
// *mesh; on an error of the library, its message in *error (nothing thrown across).
extern "C" [[gnu::visibility("default")]] void exdyn_read_gmsh_file(const char* file,
                                                                    exdyn::input::GmshMesh* mesh,
                                                                    std::string* error) {
  using namespace exdyn::input;
  try {
    const std::lock_guard<std::mutex> lock(gmsh_mutex);
    GmshSession session;
    gmsh::open(file);
    std::vector<double> parametric;
    gmsh::model::mesh::getNodes(mesh->node_tags, mesh->coordinates, parametric, -1, -1, false, false);
    gmsh::vectorpair groups;
    gmsh::model::getPhysicalGroups(groups);
    for (const auto& [dim, tag] : groups) {
      if (dim == 3) mesh->volumes.push_back(read_group(dim, tag));
      if (dim == 2) mesh->surfaces.push_back(read_group(dim, tag));
    }
  } catch (const std::string& message) {  // how Gmsh 4.8 reports an error
    *error = message;
  } catch (const std::exception& e) {
    *error = e.what();
  }
}
