#include "argil/sculpt/view/detail/viewer_script.hpp"

// ARGIL_VIEWER_BUNDLE is the bundle's path, set by CMake, which also makes
// this file depend on it. .incbin copies its bytes into read-only data.
#ifdef ARGIL_VIEWER_BUNDLE
asm(".section .rodata\n"
    ".global argil_viewer_bundle_begin\n"
    "argil_viewer_bundle_begin:\n"
    ".incbin \"" ARGIL_VIEWER_BUNDLE
    "\"\n"
    ".global argil_viewer_bundle_end\n"
    "argil_viewer_bundle_end:\n"
    ".byte 0\n"
    ".previous\n");
extern "C" const char argil_viewer_bundle_begin[];
extern "C" const char argil_viewer_bundle_end[];
#endif

namespace argil::sculpt::detail {

std::string_view viewer_script() {
#ifdef ARGIL_VIEWER_BUNDLE
  return {argil_viewer_bundle_begin,
          static_cast<std::size_t>(argil_viewer_bundle_end - argil_viewer_bundle_begin)};
#else
  return {};
#endif
}

}  // namespace argil::sculpt::detail
