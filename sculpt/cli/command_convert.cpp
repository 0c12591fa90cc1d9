// argil convert IN OUT [--tolerance T]: formats chosen by extension.
#include <cstdio>
#include <string>
#include <vector>

#include "argil/core/base/number_text.hpp"
#include "argil/io/files/model_files.hpp"
#include "argil/io/mesh/mesh_export.hpp"
#include "commands.hpp"

namespace argil::cli {
namespace {

// Mesh chord tolerance when none is given: fine enough to look smooth, coarse
// enough to keep meshes of whole models to a few hundred thousand triangles.
constexpr double kDefaultRelativeChordTolerance = 1e-3;
// Largest mesh written without --force: about 50 MB as binary STL. A chord
// tolerance far below the model's detail reaches it long before anyone wants
// such a file (2.9 million triangles from a 62 mm screw at 0.1 um).
constexpr std::size_t kMaxTrianglesWithoutForce = 1'000'000;

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
                   .default_text = "1e-3 of the model's size"},
                  {.name = "--force",
                   .description = "write a mesh of more than " +
                                  std::to_string(kMaxTrianglesWithoutForce) + " triangles"}},
  };
  return spec;
}

int run_convert(const std::vector<std::string>& args) {
  const ParseResult parsed = parse_arguments(convert_command(), args);
  if (!parsed.arguments) return parsed.exit_status;
  const std::vector<std::string>& paths = parsed.arguments->operands;
  const double tolerance_mm = parsed.arguments->number("--tolerance").value_or(0.0);
  const bool mesh_output = io::mesh_format_for(paths[1]).has_value();
  if (!mesh_output && (tolerance_mm > 0.0 || parsed.arguments->flag("--force"))) {
    return usage_error(convert_command(),
                       std::string(tolerance_mm > 0.0 ? "--tolerance" : "--force") +
                           " applies to mesh outputs (.stl .obj .ply .glb) only; " + paths[1] +
                           " is written exactly, with no tessellation");
  }
  const Result<io::Model> read = io::read_model(paths[0]);
  if (!read.ok()) {
    std::fprintf(stderr, "argil convert: %s\n", read.status().message.c_str());
    return kExitFailure;
  }
  io::WriteOptions options;
  options.tessellation.chord_tolerance_mm =
      tolerance_mm > 0.0 ? tolerance_mm
                         : kDefaultRelativeChordTolerance * io::model_box(read.value()).diagonal();
  if (mesh_output && !parsed.arguments->flag("--force")) {
    // Refuse before the work: the estimate costs two coarse tessellations.
    const Result<std::size_t> estimate =
        io::estimate_triangle_count(read.value(), options.tessellation);
    if (estimate.ok() && estimate.value() > kMaxTrianglesWithoutForce) {
      std::fprintf(stderr,
                   "argil convert: %s: chord tolerance %s mm would give about %zu triangles, "
                   "more than the %zu written without --force (give a coarser --tolerance, "
                   "or --force)\n",
                   paths[1].c_str(), number_text(options.tessellation.chord_tolerance_mm).c_str(),
                   estimate.value(), kMaxTrianglesWithoutForce);
      return kExitFailure;
    }
    // The estimate may fall short: the tessellation itself stops at twice the limit.
    options.tessellation.max_triangles = 2 * kMaxTrianglesWithoutForce;
  }
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
