// argil convert IN OUT [--tolerance T]: formats chosen by extension.
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "argil/io/files/model_files.hpp"
#include "commands.hpp"

namespace argil::cli {
namespace {

// Mesh chord tolerance when none is given: fine enough to look smooth, coarse
// enough to keep meshes of whole models to a few hundred thousand triangles.
constexpr double kDefaultRelativeChordTolerance = 1e-3;

int usage() {
  std::fprintf(stderr, "usage: argil convert IN OUT [--tolerance T]   (T in mm, > 0)\n");
  return kExitUsage;
}

}  // namespace

int run_convert(const std::vector<std::string>& args) {
  std::vector<std::string> paths;
  double tolerance_mm = 0.0;
  for (std::size_t k = 0; k < args.size(); ++k) {
    if (args[k] == "--tolerance") {
      if (k + 1 >= args.size()) return usage();
      char* end = nullptr;
      tolerance_mm = std::strtod(args[k + 1].c_str(), &end);
      if (end == args[k + 1].c_str() || *end != '\0' || !std::isfinite(tolerance_mm) ||
          tolerance_mm <= 0.0) {
        std::fprintf(stderr, "argil convert: --tolerance needs a positive number [mm], got '%s'\n",
                     args[k + 1].c_str());
        return kExitUsage;
      }
      ++k;
    } else {
      paths.push_back(args[k]);
    }
  }
  if (paths.size() != 2) return usage();
  const Result<io::Model> read = io::read_model(paths[0]);
  if (!read.ok()) {
    std::fprintf(stderr, "argil convert: %s\n", read.status().message.c_str());
    return kExitFailure;
  }
  io::WriteOptions options;
  options.tessellation.chord_tolerance_mm =
      tolerance_mm > 0.0 ? tolerance_mm
                         : kDefaultRelativeChordTolerance * io::model_box(read.value()).diagonal();
  const Status written = io::write_model(read.value(), paths[1], options);
  if (!written.ok()) {
    std::fprintf(stderr, "argil convert: %s\n", written.message.c_str());
    return kExitFailure;
  }
  std::printf("converted %s -> %s (%zu faces)\n", paths[0].c_str(), paths[1].c_str(),
              read.value().faces.size());
  return kExitOk;
}

}  // namespace argil::cli
