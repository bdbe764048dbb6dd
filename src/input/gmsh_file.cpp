#include "input/gmsh_file.hpp"

#include <dlfcn.h>

#include <filesystem>
#include <fstream>
#include <mutex>
#include <utility>

#include "common/parallel.hpp"

namespace exdyn::input {

namespace {

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

using ReadFn = void (*)(const char* file, GmshMesh* mesh, std::string* error);

// The reader module (gmsh_reader.cpp), loaded once and kept: where the build put it,
// else beside the executable. A module that cannot be loaded is an error of the
// installation, named with the loader's reason.
ReadFn reader(const SourceLocation& where, const std::string& key_path) {
  static std::mutex mutex;
  static ReadFn read = nullptr;
  const std::lock_guard<std::mutex> lock(mutex);
  if (read != nullptr) return read;
  std::string reasons;
  std::error_code ignored;
  const std::filesystem::path beside =
      std::filesystem::read_symlink("/proc/self/exe", ignored).parent_path() / EXDYN_GMSH_READER_NAME;
  for (const std::string& path : {std::string(EXDYN_GMSH_READER), beside.string()}) {
    void* module = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (module == nullptr) {
      reasons += std::string(reasons.empty() ? "" : "; ") + dlerror();
      continue;
    }
    read = reinterpret_cast<ReadFn>(dlsym(module, "exdyn_read_gmsh_file"));
    if (read != nullptr) return read;
    reasons += "; " + path + " has no exdyn_read_gmsh_file";
  }
  throw InputError(
      where, key_path,
      "cannot load exdyn's Gmsh reader, which reads mesh files (" + reasons +
          "): rebuild exdyn (scripts/build.sh) or install libgmsh-dev (scripts/install_deps.sh)");
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

  const ReadFn read = reader(where, key_path);
  GmshMesh result;
  result.file = file;
  std::string error;
  // gmsh::initialize sets OpenMP's thread count to General.NumThreads (1): without
  // setting it back, every later parallel region of a deck with a mesh file would run
  // on one thread, whatever --threads asked for.
  const int threads = max_threads();
  read(file.c_str(), &result, &error);
  set_threads(threads);
  if (!error.empty()) fail("Gmsh cannot read '" + file + "': " + error);
  if (result.node_tags.empty()) fail("'" + file + "' has no nodes: is it a mesh (gmsh -3)?");
  return result;
}

}  // namespace exdyn::input
