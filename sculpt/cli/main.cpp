// The argil program: dispatches sub-commands. Exit status 0 on success,
// 1 when a command fails, 2 for a malformed command line; errors on stderr.
#include <cstdio>
#include <string>
#include <vector>

#include "commands.hpp"

#ifndef ARGIL_VERSION
#error "ARGIL_VERSION must be defined by the build (project(argil VERSION ...))"
#endif

int main(int argc, char** argv) {
  using namespace argil::cli;
  if (argc < 2) {
    std::fputs(program_usage().c_str(), stderr);
    return kExitUsage;
  }
  const std::string first = argv[1];
  const std::vector<std::string> args(argv + 2, argv + argc);
  if (first == "--help" || first == "-h") return run_help({});
  if (first == "--version") {
    std::printf("argil %s\n", ARGIL_VERSION);
    return kExitOk;
  }
  if (const Command* command = find_command(first)) return command->run(args);
  const char* kind = first.size() > 1 && first[0] == '-' ? "option" : "command";
  std::fprintf(stderr, "argil: unknown %s '%s'\n\n%s", kind, first.c_str(),
               program_usage().c_str());
  return kExitUsage;
}
