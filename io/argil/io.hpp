#pragma once
// argil::io, the entry header. Modules from the bottom up: base (atomic writes,
// whole-file reads), model (faces, trims, units), json (the native format), cad
// (STEP and IGES through OpenCASCADE), mesh (tessellation, STL/OBJ/PLY/glTF),
// files (read or write any model file by its extension).

#include "argil/core.hpp"  // IWYU pragma: export

// base
#include "argil/io/base/atomic_write.hpp"  // IWYU pragma: export
#include "argil/io/base/text_file.hpp"     // IWYU pragma: export
// model
#include "argil/io/model/model.hpp"       // IWYU pragma: export
#include "argil/io/model/topology.hpp"    // IWYU pragma: export
#include "argil/io/model/trim_curve.hpp"  // IWYU pragma: export
// json
#include "argil/io/json/json_format.hpp"    // IWYU pragma: export
#include "argil/io/json/json_literals.hpp"  // IWYU pragma: export
// cad
#include "argil/io/cad/cad_exchange.hpp"  // IWYU pragma: export
// mesh
#include "argil/io/mesh/mesh_export.hpp"  // IWYU pragma: export
#include "argil/io/mesh/tessellate.hpp"   // IWYU pragma: export
// files
#include "argil/io/files/model_files.hpp"  // IWYU pragma: export
