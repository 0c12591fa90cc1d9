#pragma once
// Internal to the runner: a run's inputs read and checked, before anything is
// written.

#include <filesystem>
#include <string>

#include "argil/core/base/status.hpp"
#include "argil/sculpt/run/session_runner.hpp"
#include "argil/sculpt/scene/scene.hpp"
#include "argil/sculpt/script/script.hpp"

namespace argil::sculpt::detail {

struct RunInputs {
  std::filesystem::path scene_path, script_path;
  Scene scene;  // with the tolerance override applied
  Script script;
  std::string scene_bytes, script_bytes;  // hashed into the journal header
  std::string scene_name;     // the scene file's stem, or its folder's name for scene.json
  std::filesystem::path out;  // the output folder
  OutputOptions outputs;      // what to write
};

/// Reads the scene and the script and checks that they fit together: the
/// script's tool is one of the scene's and the run stays within the ticks kept
/// in memory. Writes nothing.
Result<RunInputs> load_run_inputs(const RunOptions& options);

}  // namespace argil::sculpt::detail
