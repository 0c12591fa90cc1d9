// libFuzzer target: arbitrary bytes through the scene loader
// (argil::sculpt::parse_scene, which read_scene() calls with the file's content).
// Rejection must be a clean Status with a message; an accepted scene must
// parse again to the same tool and model counts (parsing is a pure function).
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string_view>

#include "argil/sculpt/scene/scene.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  const auto scene = argil::sculpt::parse_scene(text, "<fuzz>", "/nonexistent-base");
  if (!scene.ok()) {
    if (scene.status().message.empty()) {
      std::fprintf(stderr, "argil fuzz check failed: scene rejection without a message\n");
      std::abort();
    }
    return 0;
  }
  const auto again = argil::sculpt::parse_scene(text, "<fuzz>", "/nonexistent-base");
  if (!again.ok() || again.value().models.size() != scene.value().models.size() ||
      again.value().tools.size() != scene.value().tools.size()) {
    std::fprintf(stderr, "argil fuzz check failed: scene parsing is not repeatable\n");
    std::abort();
  }
  return 0;
}
