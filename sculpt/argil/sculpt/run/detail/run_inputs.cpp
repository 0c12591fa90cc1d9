#include "argil/sculpt/run/detail/run_inputs.hpp"

#include "argil/core/base/number_text.hpp"

#include <cmath>
#include <cstdio>

#include "argil/io/base/text_file.hpp"

namespace argil::sculpt::detail {
namespace {

// Longest run: about 2.8 hours at 1 kHz; samples and log rows are kept in memory.
constexpr double kMaxTicks = 1e7;

Status check_script_fits(const RunInputs& in) {
  if (in.scene.tool_index(in.script.tool) < 0) {
    return Status::error(StatusCode::invalid_argument, in.script_path.string() + ": tool: \"" +
                                                           in.script.tool + "\" is not a tool of " +
                                                           in.scene_path.string());
  }
  for (std::size_t k = 0; k < in.script.keyframes.size(); ++k) {
    const Keyframe& f = in.script.keyframes[k];
    if (f.event == ScriptEvent::tool && in.scene.tool_index(f.tool) < 0) {
      return Status::error(StatusCode::invalid_argument,
                           in.script_path.string() + ": keyframes[" + std::to_string(k) +
                               "].event: tool \"" + f.tool + "\" is not a tool of " +
                               in.scene_path.string());
    }
  }
  const double ticks = in.script.keyframes.back().t * in.scene.haptic_rate;
  if (ticks > kMaxTicks) {
    return Status::error(
        StatusCode::invalid_argument,
        in.script_path.string() + ": keyframes[" + std::to_string(in.script.keyframes.size() - 1) +
            "].t: the script lasts " + number_text(in.script.keyframes.back().t) + " s, " +
            limit_text(ticks, LimitSide::lower) + " ticks at " + number_text(in.scene.haptic_rate) +
            " Hz (at most " + number_text(kMaxTicks) + " ticks)");
  }
  return Status::success();
}

std::string scene_name_of(const std::filesystem::path& scene_path) {
  if (scene_path.stem().string() != "scene") return scene_path.stem().string();
  // The folder's name, also for a bare "scene.json" (the working folder).
  std::error_code error;
  const std::filesystem::path absolute = std::filesystem::absolute(scene_path, error);
  return (error ? scene_path : absolute).parent_path().filename().string();
}

}  // namespace

Result<RunInputs> load_run_inputs(const RunOptions& options) {
  RunInputs in;
  in.scene_path = options.scene;
  Result<Scene> scene = read_scene(options.scene);
  if (!scene.ok()) return scene.status();
  in.scene = std::move(scene).value();
  Result<std::string> scene_bytes = io::read_text_file(options.scene);
  if (!scene_bytes.ok()) return scene_bytes.status();
  in.scene_bytes = std::move(scene_bytes).value();
  if (options.tolerance) {
    if (!std::isfinite(*options.tolerance) || *options.tolerance <= 0.0) {
      return Status::error(StatusCode::invalid_argument,
                           "tolerance: must be a positive finite number [mm], got " +
                               std::to_string(*options.tolerance));
    }
    in.scene.tolerance = *options.tolerance;
  }
  in.script_path = options.script.empty() ? in.scene.script : options.script;
  if (in.script_path.empty()) {
    return Status::error(
        StatusCode::invalid_argument,
        options.scene.string() + ": no script: none given and the scene sets no \"script\"");
  }
  Result<Script> script = read_script(in.script_path);
  if (!script.ok()) return script.status();
  in.script = std::move(script).value();
  if (const Status fits = check_script_fits(in); !fits.ok()) return fits;
  Result<std::string> script_bytes = io::read_text_file(in.script_path);
  if (!script_bytes.ok()) return script_bytes.status();
  in.script_bytes = std::move(script_bytes).value();
  in.scene_name = scene_name_of(options.scene);
  in.out = options.out.empty() ? std::filesystem::path("out") / in.scene_name : options.out;
  in.outputs = options.outputs.value_or(in.scene.outputs);
  return in;
}

}  // namespace argil::sculpt::detail
