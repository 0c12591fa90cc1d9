#pragma once
// All-or-nothing file writes: content goes to a temporary file in the target's
// folder, which replaces the target by rename() only when complete. A failure
// removes the temporary and leaves an existing target byte for byte intact.

#include <filesystem>
#include <functional>
#include <string_view>

#include "argil/core/base/status.hpp"

namespace argil::io {

/// Writes the file at `temporary_path`, which does not exist yet and lives in the
/// target's folder. Returns an error (naming the target) when it did not write
/// the complete content.
using FileWriter = std::function<Status(const std::filesystem::path& temporary_path)>;

/// Runs `write` on a fresh temporary file next to `target`, then renames it over
/// `target`. Same folder, so the rename is atomic on POSIX file systems.
Status write_atomically(const std::filesystem::path& target, const FileWriter& write);

/// write_atomically() for content already in memory.
Status write_bytes_atomically(const std::filesystem::path& target, std::string_view bytes);

}  // namespace argil::io
