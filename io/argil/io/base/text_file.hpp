#pragma once
// Whole-file reads for the loaders (the read side of atomic_write.hpp).

#include <filesystem>
#include <string>

#include "argil/core/base/status.hpp"

namespace argil::io {

/// The file's bytes, or an io_error naming the file ("cannot open (missing
/// file?)" or "read failed").
Result<std::string> read_text_file(const std::filesystem::path& path);

}  // namespace argil::io
