// The argil program: dispatches sub-commands. Exit status 0 on success,
// non-zero with the error on stderr otherwise.
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "commands.hpp"

namespace {

void print_usage(std::FILE* out) {
  std::fprintf(
      out,
      "usage: argil <command> [args]\n"
      "commands:\n"
      "  info FILE                         faces, degrees, control nets, trims,\n"
      "                                    units and bounding box of a model\n"
      "  convert IN OUT [--tolerance T]    convert between STEP (.step .stp),\n"
      "                                    IGES (.iges .igs), JSON (.json) and meshes\n"
      "                                    (.stl .obj .ply .glb); T is the mesh chord\n"
      "                                    tolerance [mm], default 1e-3 of the model size\n"
      "  collide A B [--face-a I] [--face-b J] [--tolerance E] [--refine] [--json]\n"
      "                                    intersection curves and contact regions of\n"
      "                                    face I of A and face J of B (default 0, 0);\n"
      "                                    E is eps [mm], default 1e-4 of the faces' size\n"
      "  sculpt SCENE [--script S] [--out DIR] [--tolerance E] [--fresh] [--realtime]\n"
      "                                    runs a sculpting session: the scene's tool\n"
      "                                    driven by script S (default the scene's);\n"
      "                                    writes the sculpted surfaces (STEP, IGES,\n"
      "                                    JSON), forces.csv, contacts.csv, timing.json,\n"
      "                                    recorded.csv and pictures to DIR (default\n"
      "                                    out/<scene>); resumes an interrupted run from\n"
      "                                    DIR/session.journal unless --fresh\n"
      "  --help                            this text\n");
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2 || std::strcmp(argv[1], "--help") == 0) {
    print_usage(argc < 2 ? stderr : stdout);
    return argc < 2 ? argil::cli::kExitUsage : argil::cli::kExitOk;
  }
  const std::string command = argv[1];
  const std::vector<std::string> args(argv + 2, argv + argc);
  if (command == "info") return argil::cli::run_info(args);
  if (command == "convert") return argil::cli::run_convert(args);
  if (command == "collide") return argil::cli::run_collide(args);
  if (command == "sculpt") return argil::cli::run_sculpt(args);
  std::fprintf(stderr, "argil: unknown command '%s'\n", argv[1]);
  print_usage(stderr);
  return argil::cli::kExitUsage;
}
