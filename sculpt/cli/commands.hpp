#pragma once
// The argil program's sub-commands. Each takes the arguments after its name,
// prints results to stdout and errors to stderr, and returns the exit status.

#include <string>
#include <vector>

namespace argil::cli {

/// argil info FILE
int run_info(const std::vector<std::string>& args);

/// argil convert IN OUT [--tolerance T]
int run_convert(const std::vector<std::string>& args);

/// argil collide A B [--face-a I] [--face-b J] [--tolerance E] [--refine] [--json]
int run_collide(const std::vector<std::string>& args);

/// argil sculpt SCENE [--script S] [--out DIR] [--tolerance E] [--fresh] [--realtime]
int run_sculpt(const std::vector<std::string>& args);

/// Exit statuses shared by the commands.
inline constexpr int kExitOk = 0;
inline constexpr int kExitFailure = 1;
inline constexpr int kExitUsage = 2;

}  // namespace argil::cli
