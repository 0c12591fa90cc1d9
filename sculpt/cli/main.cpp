// The argil program: dispatches sub-commands. Exit status 0 on success,
// non-zero with the error on stderr otherwise.
#include <cstdio>
#include <cstring>
#include <string>

namespace {

void print_usage(std::FILE* out) {
  std::fprintf(out,
               "usage: argil <command> [args]\n"
               "commands:\n"
               "  --help       this text\n");
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2 || std::strcmp(argv[1], "--help") == 0) {
    print_usage(argc < 2 ? stderr : stdout);
    return argc < 2 ? 2 : 0;
  }
  std::fprintf(stderr, "argil: unknown command '%s'\n", argv[1]);
  print_usage(stderr);
  return 2;
}
