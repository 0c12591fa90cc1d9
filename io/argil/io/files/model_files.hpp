#pragma once
// Reading and writing models by file extension: the entry point the CLI and the
// sculpt layer use.

#include <filesystem>

#include "argil/core/base/status.hpp"
#include "argil/io/cad/cad_exchange.hpp"
#include "argil/io/mesh/tessellate.hpp"
#include "argil/io/model/model.hpp"

namespace argil::io {

/// Reads .step/.stp, .iges/.igs or .json (case-insensitive).
Result<Model> read_model(const std::filesystem::path& path);

/// What write_model() needs beyond the model.
struct WriteOptions {
  /// Used for mesh formats only.
  TessellationOptions tessellation;
  /// Used for STEP and IGES only, but for `cad.warnings`, which also receives
  /// a mesh's (TriangleMesh::warnings).
  CadWriteOptions cad;
};

/// Writes .step/.stp, .iges/.igs, .json, or a tessellation as .stl, .obj, .ply,
/// .glb. Atomic: on failure an existing file is left as it was.
Status write_model(const Model& model, const std::filesystem::path& path,
                   const WriteOptions& options = {});

/// The extensions read_model() and write_model() accept, for messages.
const char* supported_extensions();

}  // namespace argil::io
