#pragma once
// The argil program's sub-commands. Each declares its command line once (a
// CommandDeclaration), takes the arguments after its name, prints results to stdout
// and errors to stderr, and returns the exit status.

#include <string>
#include <vector>

#include "options.hpp"

namespace argil::cli {

/// argil info FILE
const CommandDeclaration& info_command();
int run_info(const std::vector<std::string>& args);

/// argil convert IN OUT [--tolerance T]
const CommandDeclaration& convert_command();
int run_convert(const std::vector<std::string>& args);

/// argil collide A B [--face-a I] [--face-b J] [--tolerance E] [--refine] [--json]
const CommandDeclaration& collide_command();
int run_collide(const std::vector<std::string>& args);

/// argil sculpt SCENE [--script S] [--out DIR] [--tolerance E] [--fresh] [--realtime]
const CommandDeclaration& sculpt_command();
int run_sculpt(const std::vector<std::string>& args);

/// argil script SCENE OUT --face N --uv "U,V ..." [--model M] [--tool T] [--depth D] ...
const CommandDeclaration& script_command();
int run_script(const std::vector<std::string>& args);

/// argil view INPUT [--out FILE] [--scene SCENE] [--every N] [--scale S] [--chord C]
const CommandDeclaration& view_command();
int run_view(const std::vector<std::string>& args);

/// argil materials
const CommandDeclaration& materials_command();
int run_materials(const std::vector<std::string>& args);

/// argil help [COMMAND]
const CommandDeclaration& help_command();
int run_help(const std::vector<std::string>& args);

/// A command the program dispatches to.
struct Command {
  const CommandDeclaration& (*spec)();
  int (*run)(const std::vector<std::string>& args);
};

/// Every command, in the order the program's usage lists them.
const std::vector<Command>& all_commands();

/// The command called `name`, or nullptr.
const Command* find_command(const std::string& name);

/// The program's usage: synopsis and each command with its one-line summary.
std::string program_usage();

/// Exit statuses shared by the commands.
inline constexpr int kExitOk = 0;
inline constexpr int kExitFailure = 1;
inline constexpr int kExitUsage = 2;

}  // namespace argil::cli
