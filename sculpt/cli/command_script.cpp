// argil script SCENE OUT --face N --uv "U,V ..." [--model M] [--tool T] [--depth D]
// [--speed S] [--approach A] [--hold H]: a press (one point) or a drag (several)
// on a face of a scene's model, written as a script `argil sculpt` reads.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "argil/core/base/number_text.hpp"
#include "argil/io/files/model_files.hpp"
#include "argil/sculpt/scene/scene.hpp"
#include "argil/sculpt/script/stroke_script.hpp"
#include "commands.hpp"

namespace argil::cli {
namespace {

constexpr Interval kNonNegativeFinite{0.0, std::numeric_limits<double>::infinity(),
                                      IntervalEnds::open_high};

/// A whole word as a finite number.
std::optional<double> number_of(const std::string& word) {
  if (word.empty()) return std::nullopt;
  char* end = nullptr;
  const double value = std::strtod(word.c_str(), &end);
  if (end != word.c_str() + word.size() || !std::isfinite(value)) return std::nullopt;
  return value;
}

/// "0.2,0.5 0.4,0.5": (u, v) pairs separated by spaces or semicolons.
std::optional<std::vector<Eigen::Vector2d>> parse_points(const std::string& text) {
  std::string spaced = text;
  for (char& c : spaced)
    if (c == ';') c = ' ';
  std::istringstream words(spaced);
  std::vector<Eigen::Vector2d> points;
  for (std::string word; words >> word;) {
    const std::size_t comma = word.find(',');
    if (comma == std::string::npos) return std::nullopt;
    const std::optional<double> u = number_of(word.substr(0, comma));
    const std::optional<double> v = number_of(word.substr(comma + 1));
    if (!u || !v) return std::nullopt;
    points.emplace_back(*u, *v);
  }
  if (points.empty()) return std::nullopt;
  return points;
}

/// The scene model called `name`, or its first deformable one.
const sculpt::ModelOptions* find_model(const sculpt::Scene& scene, const std::string& name) {
  for (const sculpt::ModelOptions& m : scene.models)
    if (name.empty() ? m.deformable : m.name == name) return &m;
  return nullptr;
}

}  // namespace

const CommandDeclaration& script_command() {
  static const CommandDeclaration spec{
      .name = "script",
      .operands = {"SCENE", "OUT"},
      .summary = "write a press or drag script from a place on a face of a scene's model",
      .description =
          "One (u, v) makes a press along the face's outward normal; two or more make a\n"
          "drag (a carve) through them along the surface, the tool held at the depth.\n"
          "(u, v) are the face's surface parameters, as a picked point gives them;\n"
          "OUT is .json or .csv. The tool must be a sphere or a point.",
      .options = {{.name = "--face",
                   .argument = "N",
                   .kind = ValueKind::index,
                   .description = "face index in the model's file (as argil info lists them)"},
                  {.name = "--uv",
                   .argument = "\"U,V ...\"",
                   .kind = ValueKind::text,
                   .description = "the place: one (u, v) to press, several to drag through"},
                  {.name = "--model",
                   .argument = "M",
                   .kind = ValueKind::text,
                   .description = "the scene model",
                   .default_text = "the first deformable model"},
                  {.name = "--tool",
                   .argument = "T",
                   .kind = ValueKind::text,
                   .description = "the scene tool the script holds",
                   .default_text = "the scene's first tool"},
                  {.name = "--depth",
                   .argument = "D",
                   .kind = ValueKind::number,
                   .description = "how far the tool goes below the surface",
                   .range = kPositiveFinite,
                   .unit = "mm",
                   .default_text = "1"},
                  {.name = "--speed",
                   .argument = "S",
                   .kind = ValueKind::number,
                   .description = "device speed",
                   .range = kPositiveFinite,
                   .unit = "mm/s",
                   .default_text = "10"},
                  {.name = "--approach",
                   .argument = "A",
                   .kind = ValueKind::number,
                   .description = "start and end this far above the surface",
                   .range = kPositiveFinite,
                   .unit = "mm",
                   .default_text = "10"},
                  {.name = "--hold",
                   .argument = "H",
                   .kind = ValueKind::number,
                   .description = "how long a press rests at its depth",
                   .range = kNonNegativeFinite,
                   .unit = "s",
                   .default_text = "0.5"}},
  };
  return spec;
}

int run_script(const std::vector<std::string>& args) {
  const ParseResult parsed = parse_arguments(script_command(), args);
  if (!parsed.arguments) return parsed.exit_status;
  const Arguments& a = *parsed.arguments;
  const std::string& scene_path = a.operands[0];
  const std::string& out_path = a.operands[1];
  if (!a.index("--face")) return usage_error(script_command(), "--face is required");
  if (!a.text("--uv")) return usage_error(script_command(), "--uv is required");
  const std::optional<std::vector<Eigen::Vector2d>> points = parse_points(*a.text("--uv"));
  if (!points) {
    return usage_error(script_command(), "--uv \"" + *a.text("--uv") +
                                             "\" is not a list of U,V pairs (\"0.2,0.5 0.4,0.5\")");
  }
  const Result<sculpt::Scene> scene = sculpt::read_scene(scene_path);
  if (!scene.ok()) {
    std::fprintf(stderr, "argil script: %s\n", scene.status().message.c_str());
    return kExitFailure;
  }
  const std::string model_name = a.text("--model").value_or("");
  const sculpt::ModelOptions* model = find_model(scene.value(), model_name);
  if (model == nullptr) {
    std::fprintf(
        stderr, "argil script: %s: no %s\n", scene_path.c_str(),
        model_name.empty() ? "deformable model" : ("model \"" + model_name + "\"").c_str());
    return kExitFailure;
  }
  const std::string tool_name = a.text("--tool").value_or("");
  const int tool_index = scene.value().tool_index(tool_name);
  if (tool_index < 0) {
    std::fprintf(stderr, "argil script: %s: no tool \"%s\"\n", scene_path.c_str(),
                 tool_name.c_str());
    return kExitFailure;
  }
  const sculpt::ToolOptions& tool = scene.value().tools[static_cast<std::size_t>(tool_index)];
  if (tool.type == sculpt::ToolType::bspline) {
    std::fprintf(stderr,
                 "argil script: %s: tool \"%s\" is a B-spline surface; scripts are generated "
                 "for sphere and point tools only\n",
                 scene_path.c_str(), tool.name.c_str());
    return kExitFailure;
  }
  const auto face = static_cast<std::size_t>(*a.index("--face"));
  if (!model->faces.empty() && std::find(model->faces.begin(), model->faces.end(),
                                         static_cast<int>(face)) == model->faces.end()) {
    std::fprintf(stderr, "argil script: %s: model \"%s\" does not hold face %zu of %s\n",
                 scene_path.c_str(), model->name.c_str(), face, model->file.c_str());
    return kExitFailure;
  }
  const Result<io::Model> read = io::read_model(model->file);
  if (!read.ok()) {
    std::fprintf(stderr, "argil script: %s\n", read.status().message.c_str());
    return kExitFailure;
  }
  if (face >= read.value().faces.size()) {
    std::fprintf(stderr, "argil script: %s has %zu faces; there is no face %zu\n",
                 model->file.c_str(), read.value().faces.size(), face);
    return kExitFailure;
  }
  sculpt::StrokeRequest request;
  request.uv = *points;
  request.depth_mm = a.number("--depth").value_or(1.0);
  request.speed_mm_s = a.number("--speed").value_or(10.0);
  request.approach_mm = a.number("--approach").value_or(10.0);
  request.hold_s = a.number("--hold").value_or(0.5);
  request.tool_offset_mm = tool.type == sculpt::ToolType::sphere ? tool.radius : 0.0;
  request.tool = tool.name;
  // Keyframe chords short against the tool, so the device follows the surface.
  const double step_mm = tool.type == sculpt::ToolType::sphere ? 0.25 * tool.radius : 0.5;
  const std::string label = model->file.string() + " face " + std::to_string(face);
  const Result<sculpt::Script> script =
      sculpt::stroke_script(read.value().faces[face], request, label, step_mm);
  if (!script.ok()) {
    std::fprintf(stderr, "argil script: %s\n", script.status().message.c_str());
    return kExitFailure;
  }
  if (const Status written = sculpt::write_script(script.value(), out_path); !written.ok()) {
    std::fprintf(stderr, "argil script: %s\n", written.message.c_str());
    return kExitFailure;
  }
  const std::vector<sculpt::Keyframe>& k = script.value().keyframes;
  std::printf("wrote %s: a %s on model \"%s\" face %zu with tool \"%s\", %zu keyframes, %s s\n",
              out_path.c_str(), points->size() == 1 ? "press" : "drag", model->name.c_str(), face,
              tool.name.c_str(), k.size(), approx_text(k.back().t).c_str());
  return kExitOk;
}

}  // namespace argil::cli
