// Test helper: a fresh directory under the system's temporary directory,
// removed when the object goes out of scope.
#pragma once

#include <filesystem>
#include <random>
#include <string>

namespace exdyn::testing {

class TempDir {
 public:
  explicit TempDir(const std::string& prefix = "exdyn_test") {
    std::random_device device;
    path_ = std::filesystem::temp_directory_path() / (prefix + "_" + std::to_string(device()));
    std::filesystem::create_directories(path_);
  }
  ~TempDir() {
    std::error_code ignored;
    std::filesystem::remove_all(path_, ignored);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  const std::filesystem::path& path() const { return path_; }
  std::string file(const std::string& name) const { return (path_ / name).string(); }

 private:
  std::filesystem::path path_;
};

}  // namespace exdyn::testing
