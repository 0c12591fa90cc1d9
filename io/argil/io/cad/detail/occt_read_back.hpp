#pragma once
// Internal to argil_io: a written STEP or IGES file read back by OpenCASCADE's
// own readers, the way a user of the file reads it, to check what it holds.

#include <TopoDS_Face.hxx>
#include <TopoDS_Shape.hxx>

#include <filesystem>
#include <vector>

#include "argil/core/base/status.hpp"
#include "argil/io/cad/cad_exchange.hpp"

namespace argil::io::detail {

/// The whole shape of the file, read and transferred with OpenCASCADE's
/// readers and settings (a null shape when it holds nothing).
/// Errors: the file cannot be read (io_error), naming nothing.
Result<TopoDS_Shape> read_back_shape(const std::filesystem::path& file, CadFormat format);

/// Every face of the file in TopExp_Explorer order (the order they were
/// written in), read and transferred with OpenCASCADE's readers and settings.
/// Errors: the file cannot be read (io_error), naming nothing (the caller names
/// the file).
Result<std::vector<TopoDS_Face>> read_back_faces(const std::filesystem::path& file,
                                                 CadFormat format);

/// For each face of `written`, in order, the faces of `back` that lie on the
/// same surface: as many poles spanning the same box, compared exactly (the
/// files carry 17 significant digits; IGES gives a reversed face the same poles
/// in mirrored order). A face the reader dropped has none, one it split several.
std::vector<std::vector<TopoDS_Face>> faces_on_same_surface(const std::vector<TopoDS_Face>& written,
                                                            const std::vector<TopoDS_Face>& back);

}  // namespace argil::io::detail
