#include "argil/io/base/atomic_write.hpp"

#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <string>
#include <system_error>
#include <vector>

namespace argil::io {
namespace {

Status io_failure(const std::filesystem::path& target, const std::string& what) {
  return Status::error(StatusCode::io_error, target.string() + ": " + what);
}

}  // namespace

Status write_atomically(const std::filesystem::path& target, const FileWriter& write) {
  if (target.empty()) return Status::error(StatusCode::invalid_argument, "empty output path");
  std::error_code ec;
  if (std::filesystem::is_directory(target, ec)) return io_failure(target, "is a folder");
  const std::filesystem::path folder =
      target.parent_path().empty() ? std::filesystem::path(".") : target.parent_path();
  // mkstemp reserves a unique name, so concurrent writers never share a temporary.
  // Appends, not operator+ on a literal: GCC 12 -O3 warns falsely (-Wrestrict) on the latter.
  std::string hidden_name(".");
  hidden_name += target.filename().string();
  hidden_name += ".tmp-XXXXXX";
  std::string pattern = (folder / hidden_name).string();
  std::vector<char> name(pattern.begin(), pattern.end());
  name.push_back('\0');
  const int fd = ::mkstemp(name.data());
  if (fd < 0) {
    return io_failure(target, std::string("cannot create a temporary file in ") + folder.string() +
                                  ": " + std::strerror(errno));
  }
  // mkstemp creates mode 0600; give the file the permissions a plain fopen would.
  const mode_t mask = ::umask(0);
  ::umask(mask);
  ::fchmod(fd, 0666 & ~mask);
  ::close(fd);
  const std::filesystem::path temporary(name.data());
  Status status;
  try {
    status = write(temporary);
  } catch (const std::exception& e) {
    status = io_failure(target, std::string("writer failed: ") + e.what());
  } catch (...) {
    status = io_failure(target, "writer failed with an unknown exception");
  }
  if (status.ok() && !std::filesystem::exists(temporary, ec)) {
    status = io_failure(target, "writer produced no file");
  }
  if (status.ok() && std::rename(temporary.c_str(), target.c_str()) != 0) {
    status = io_failure(target, std::string("cannot replace the file: ") + std::strerror(errno));
  }
  if (!status.ok()) std::filesystem::remove(temporary, ec);
  return status;
}

Status write_bytes_atomically(const std::filesystem::path& target, std::string_view bytes) {
  return write_atomically(target, [&](const std::filesystem::path& temporary) -> Status {
    std::FILE* file = std::fopen(temporary.c_str(), "wb");
    if (file == nullptr) return io_failure(target, std::strerror(errno));
    const bool written = std::fwrite(bytes.data(), 1, bytes.size(), file) == bytes.size();
    // fclose flushes: its failure (disk full) means the content is incomplete.
    const bool closed = std::fclose(file) == 0;
    if (!written || !closed) return io_failure(target, "write failed (disk full?)");
    return Status::success();
  });
}

}  // namespace argil::io
