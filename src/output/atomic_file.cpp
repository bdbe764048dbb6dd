#include "output/atomic_file.hpp"

#include <cerrno>
#include <cstring>
#include <fstream>
#include <stdexcept>
#include <string>
#include <system_error>

namespace exdyn::output {

void write_file_atomically(const std::filesystem::path& path, const std::vector<std::string_view>& parts) {
  std::filesystem::path temporary = path;
  temporary += ".tmp";
  auto fail = [&](const std::string& what) {
    std::error_code ignored;
    std::filesystem::remove(temporary, ignored);
    throw std::runtime_error("cannot write " + path.string() + ": " + what);
  };
  {
    std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
    if (!out) fail("cannot create " + temporary.string() + " (" + std::strerror(errno) + ")");
    for (std::string_view part : parts) out.write(part.data(), static_cast<std::streamsize>(part.size()));
    out.close();
    if (!out) fail("write to " + temporary.string() + " failed (disk full?)");
  }
  std::error_code error;
  std::filesystem::rename(temporary, path, error);
  if (error) fail("rename of " + temporary.string() + " failed (" + error.message() + ")");
}

}  // namespace exdyn::output
