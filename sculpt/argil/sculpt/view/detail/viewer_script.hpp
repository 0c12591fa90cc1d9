#pragma once
// The viewer page's script: web/viewer bundled with three.js by esbuild at
// build time and linked into the program, so `argil view` writes a page that
// needs no network and no file beside it.

#include <string_view>

namespace argil::sculpt::detail {

/// The bundled script (an IIFE); empty when this build has none (web/'s
/// packages were not installed when it was configured).
std::string_view viewer_script();

}  // namespace argil::sculpt::detail
