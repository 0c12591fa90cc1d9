#pragma once
// argil::io, the entry header: CAD exchange (STEP, IGES), native JSON, meshes.

#include "argil/io/atomic_write.hpp"  // IWYU pragma: export
#include "argil/io/cad_exchange.hpp"  // IWYU pragma: export
#include "argil/io/json_format.hpp"   // IWYU pragma: export
#include "argil/io/mesh_export.hpp"   // IWYU pragma: export
#include "argil/io/model.hpp"         // IWYU pragma: export
#include "argil/io/model_files.hpp"   // IWYU pragma: export
#include "argil/io/tessellate.hpp"    // IWYU pragma: export
#include "argil/io/trim_curve.hpp"    // IWYU pragma: export
