#pragma once
// Argil's native surface format: JSON with a versioned schema (docs/formats.md).
// Doubles are written in shortest round-trip form and read back bit-exactly.

#include <filesystem>
#include <string>
#include <string_view>

#include "argil/core/base/status.hpp"
#include "argil/io/model/model.hpp"

namespace argil::io {

/// The "format" value of an argil surface file.
inline constexpr std::string_view kJsonFormatName = "argil.surfaces";
/// The schema version this build writes; it reads this and every earlier one
/// (version 1: faces only; 2 adds the topology and the reader's warnings).
inline constexpr int kJsonFormatVersion = 2;

/// Parses a document. `source_name` (usually the file path) starts every error
/// message, followed by the field path, e.g. "faces[3].surface.knots_u[7]".
/// Rejects non-finite numbers (NaN, Infinity, null where a number belongs), wrong
/// counts, unknown versions, and any face that fails validate_face().
Result<Model> parse_json(std::string_view text, const std::string& source_name = "<json>");

/// Reads and parses a file.
Result<Model> read_json(const std::filesystem::path& path);

/// Serialises a model; fails (naming the face) if a face does not validate,
/// since the result could not be read back.
Result<std::string> to_json(const Model& model);

/// to_json() written atomically to `path`.
Status write_json(const Model& model, const std::filesystem::path& path);

}  // namespace argil::io
