// argil convert IN OUT [--tolerance T]: formats chosen by extension.
#include <cstdio>
#include <string>
#include <vector>

#include "argil/io/files/model_files.hpp"
#include "commands.hpp"

namespace argil::cli {
namespace {

// Mesh chord tolerance when none is given: fine enough to look smooth, coarse
// enough to keep meshes of whole models to a few hundred thousand triangles.
constexpr double kDefaultRelativeChordTolerance = 1e-3;

}  // namespace

const CommandDeclaration& convert_command() {
  static const CommandDeclaration spec{
      .name = "convert",
      .operands = {"IN", "OUT"},
      .summary = "convert a model between STEP, IGES, JSON and meshes",
      .description =
          "Formats follow the extensions: STEP (.step .stp), IGES (.iges .igs) and argil\n"
          "JSON (.json) in and out; meshes (.stl .obj .ply .glb) out only.",
      .options = {{.name = "--tolerance",
                   .argument = "T",
                   .kind = ValueKind::number,
                   .description = "mesh chord tolerance, the largest distance from a triangle to "
                                  "the surface (meshes only)",
                   .range = kPositiveFinite,
                   .unit = "mm",
                   .default_text = "1e-3 of the model's size"}},
  };
  return spec;
}

int run_convert(const std::vector<std::string>& args) {
  const ParseResult parsed = parse_arguments(convert_command(), args);
  if (!parsed.arguments) return parsed.exit_status;
  const std::vector<std::string>& paths = parsed.arguments->operands;
  const double tolerance_mm = parsed.arguments->number("--tolerance").value_or(0.0);
  const Result<io::Model> read = io::read_model(paths[0]);
  if (!read.ok()) {
    std::fprintf(stderr, "argil convert: %s\n", read.status().message.c_str());
    return kExitFailure;
  }
  io::WriteOptions options;
  options.tessellation.chord_tolerance_mm =
      tolerance_mm > 0.0 ? tolerance_mm
                         : kDefaultRelativeChordTolerance * io::model_box(read.value()).diagonal();
  std::vector<std::string> warnings;
  options.cad.warnings = &warnings;
  const Status written = io::write_model(read.value(), paths[1], options);
  if (!written.ok()) {
    std::fprintf(stderr, "argil convert: %s\n", written.message.c_str());
    return kExitFailure;
  }
  for (const std::string& w : warnings)
    std::fprintf(stderr, "argil convert: warning: %s\n", w.c_str());
  std::printf("converted %s -> %s (%zu faces)\n", paths[0].c_str(), paths[1].c_str(),
              read.value().faces.size());
  return kExitOk;
}

}  // namespace argil::cli
