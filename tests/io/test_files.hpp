#pragma once
// Files for the IO tests: the shared real CAD data, a fresh temporary folder per
// test, and whole-file reads and writes for building bad inputs from good ones.

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <string>

namespace argil::test {

/// tests/data (bearing.iges, screw.step and the other test inputs); set by CMake.
inline std::filesystem::path shared_data(const std::string& name) {
  return std::filesystem::path(ARGIL_SHARED_DATA_DIR) / name;
}

/// The repository root, for the bundled examples.
inline std::filesystem::path source_file(const std::string& relative) {
  return std::filesystem::path(ARGIL_SOURCE_DIR) / relative;
}

/// A folder under the system temp folder, removed with its content on scope exit.
class TempDir {
 public:
  TempDir() {
    std::random_device seed;
    path_ = std::filesystem::temp_directory_path() /
            ("argil-io-test-" + std::to_string(::getpid()) + "-" + std::to_string(seed()));
    std::filesystem::create_directories(path_);
  }
  ~TempDir() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;

  std::filesystem::path operator/(const std::string& name) const { return path_ / name; }
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

inline std::string read_bytes(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream content;
  content << in.rdbuf();
  return content.str();
}

inline void write_bytes(const std::filesystem::path& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary | std::ios::trunc) << bytes;
}

}  // namespace argil::test
