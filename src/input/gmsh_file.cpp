#include "input/gmsh_file.hpp"

#include <gmsh.h>

#include <fstream>
#include <mutex>
#include <utility>

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

// The first line that is not blank, without its line end.
std::string first_line(std::ifstream& in) {
  std::string line;
  while (std::getline(in, line)) {
    while (!line.empty() && (line.back() == '\r' || line.back() == ' ' || line.back() == '\t'))
      line.pop_back();
    if (!line.empty()) return line;
  }
  return {};
}

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

GmshMesh read_gmsh(const std::string& file, const SourceLocation& where, const std::string& key_path) {
  auto fail = [&](const std::string& message) { throw InputError(where, key_path, message); };
  // The library reads a missing file as an empty model and any other text as a .geo
  // script: check both here, where the message can say what is wrong.
  std::ifstream in(file);
  if (!in) fail("cannot read the mesh file '" + file + "': it does not exist or is not readable");
  const std::string head = first_line(in);
  if (head != "$MeshFormat" && head != "$NOD")
    fail("'" + file + "' is not a Gmsh mesh: its first line is '" + head.substr(0, 40) +
         "', not $MeshFormat (write it with gmsh -3 FILE.geo -o FILE.msh)");
  in.close();

  const std::lock_guard<std::mutex> lock(gmsh_mutex);
  GmshSession session;
  GmshMesh result;
  result.file = file;
  try {
    gmsh::open(file);
    std::vector<double> parametric;
    gmsh::model::mesh::getNodes(result.node_tags, result.coordinates, parametric, -1, -1, false, false);
    gmsh::vectorpair groups;
    gmsh::model::getPhysicalGroups(groups);
    for (const auto& [dim, tag] : groups) {
      if (dim == 3) result.volumes.push_back(read_group(dim, tag));
      if (dim == 2) result.surfaces.push_back(read_group(dim, tag));
    }
  } catch (const std::string& message) {  // how Gmsh 4.8 reports an error
    fail("Gmsh cannot read '" + file + "': " + message);
  } catch (const std::exception& error) {
    fail("Gmsh cannot read '" + file + "': " + error.what());
  }
  if (result.node_tags.empty()) fail("'" + file + "' has no nodes: is it a mesh (gmsh -3)?");
  return result;
}

}  // namespace exdyn::input
