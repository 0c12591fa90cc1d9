// argil view INPUT [--out FILE] [--scene SCENE] [--every N] [--scale MM]
// [--chord MM]: writes the interactive 3D page of a sculpt run's output folder
// (replayed from its recorded.csv) or of a model file.
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "argil/io/base/atomic_write.hpp"
#include "argil/io/files/model_files.hpp"
#include "argil/sculpt/view/session_replay.hpp"
#include "argil/sculpt/view/view_page.hpp"
#include "commands.hpp"

namespace argil::cli {
namespace {

/// The page of INPUT: a run's folder is replayed, a file is read as a model.
Result<std::string> page_of(const std::filesystem::path& input, const Arguments& a,
                            sculpt::ViewPageOptions& options, std::string& what) {
  if (std::filesystem::is_directory(input)) {
    sculpt::ReplayOptions replay_options{.folder = input,
                                         .scene = a.text("--scene").value_or(""),
                                         .every = a.index("--every").value_or(0)};
    Result<sculpt::SessionReplay> replay = sculpt::replay_session(replay_options);
    if (!replay.ok()) return replay.status();
    options.title = input.filename().empty() ? input.parent_path().filename().string()
                                             : input.filename().string();
    what = std::to_string(replay.value().frames.size()) + " frames of " +
           std::to_string(replay.value().time.size()) + " ticks";
    return sculpt::session_view_page(replay.value(), options);
  }
  Result<io::Model> model = io::read_model(input);
  if (!model.ok()) return model.status();
  options.title = input.filename().string();
  what = std::to_string(model.value().faces.size()) + " faces";
  return sculpt::model_view_page(model.value(), input.string(), options);
}

}  // namespace

const CommandDeclaration& view_command() {
  static const CommandDeclaration spec{
      .name = "view",
      .operands = {"INPUT"},
      .summary = "write an interactive 3D page of a sculpt run or a model file",
      .description =
          "INPUT is the output folder of a finished `argil sculpt` run (its run is\n"
          "replayed from recorded.csv against the scene named in summary.json) or a\n"
          "model file (.step, .iges, .json). The page is one HTML file that opens\n"
          "from disk with no network: the surfaces lit, before and after, coloured\n"
          "by signed deviation; the tool, its path and the force on a timeline; a\n"
          "click reads a face's (u, v) and gives a script keyframe.",
      .options = {{.name = "--out",
                   .argument = "FILE",
                   .kind = ValueKind::text,
                   .description = "the page to write",
                   .default_text = "INPUT/view.html for a run, INPUT's stem.html here for a model"},
                  {.name = "--scene",
                   .argument = "SCENE",
                   .kind = ValueKind::text,
                   .description = "the run's scene, when summary.json's path does not reach it",
                   .default_text = "summary.json's \"scene\""},
                  {.name = "--every",
                   .argument = "N",
                   .kind = ValueKind::index,
                   .description = "a timeline frame every N ticks (and at every stroke's end)",
                   .default_text = "about 60 frames"},
                  {.name = "--scale",
                   .argument = "S",
                   .kind = ValueKind::number,
                   .description = "fixed deviation colour scale (+-S)",
                   .range = kPositiveFinite,
                   .unit = "mm",
                   .default_text = "the largest movement"},
                  {.name = "--chord",
                   .argument = "C",
                   .kind = ValueKind::number,
                   .description = "chord tolerance of the page's meshes",
                   .range = kPositiveFinite,
                   .unit = "mm",
                   .default_text = "5e-4 of the models' size"}},
  };
  return spec;
}

int run_view(const std::vector<std::string>& args) {
  const ParseResult parsed = parse_arguments(view_command(), args);
  if (!parsed.arguments) return parsed.exit_status;
  const Arguments& a = *parsed.arguments;
  const std::filesystem::path input = a.operands[0];
  if (a.index("--every") && *a.index("--every") == 0) {
    return usage_error(view_command(), "--every must be at least 1");
  }
  if (!std::filesystem::exists(input)) {
    std::fprintf(stderr, "argil view: %s: no such file or folder\n", input.c_str());
    return kExitFailure;
  }
  sculpt::ViewPageOptions options;
  options.chord_tolerance_mm = a.number("--chord").value_or(0.0);
  if (a.number("--scale")) options.scale_mm = *a.number("--scale");
  std::string what;
  const Result<std::string> page = page_of(input, a, options, what);
  if (!page.ok()) {
    std::fprintf(stderr, "argil view: %s\n", page.status().message.c_str());
    return kExitFailure;
  }
  const std::filesystem::path out = a.text("--out") ? std::filesystem::path(*a.text("--out"))
                                    : std::filesystem::is_directory(input)
                                        ? input / "view.html"
                                        : std::filesystem::path(input.stem().string() + ".html");
  if (const Status written = io::write_bytes_atomically(out, page.value()); !written.ok()) {
    std::fprintf(stderr, "argil view: %s\n", written.message.c_str());
    return kExitFailure;
  }
  std::printf("wrote %s (%s, %.1f MB): open it in a browser\n",
              std::filesystem::absolute(out).lexically_normal().c_str(), what.c_str(),
              static_cast<double>(page.value().size()) / 1e6);
  return kExitOk;
}

}  // namespace argil::cli
