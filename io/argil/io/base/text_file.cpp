#include "argil/io/base/text_file.hpp"

#include <fstream>
#include <sstream>

namespace argil::io {

Result<std::string> read_text_file(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    return Status::error(StatusCode::io_error, path.string() + ": cannot open (missing file?)");
  }
  std::ostringstream content;
  content << in.rdbuf();
  if (in.bad()) return Status::error(StatusCode::io_error, path.string() + ": read failed");
  return content.str();
}

}  // namespace argil::io
