// argil help [COMMAND]: the program's usage, or one command's; and the table
// of commands the program dispatches to.
#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

#include "commands.hpp"

namespace argil::cli {

const CommandDeclaration& help_command() {
  static const CommandDeclaration spec{
      .name = "help",
      .operands = {"COMMAND"},
      .last_operand_optional = true,
      .summary = "print the usage of COMMAND, or of the program without one",
      .description = "",
      .options = {},
  };
  return spec;
}

const std::vector<Command>& all_commands() {
  static const std::vector<Command> commands = {
      {info_command, run_info},           {convert_command, run_convert},
      {collide_command, run_collide},     {sculpt_command, run_sculpt},
      {script_command, run_script},       {view_command, run_view},
      {materials_command, run_materials}, {help_command, run_help},
  };
  return commands;
}

const Command* find_command(const std::string& name) {
  for (const Command& c : all_commands())
    if (c.spec().name == name) return &c;
  return nullptr;
}

std::string program_usage() {
  std::string out =
      "usage: argil COMMAND [ARGS]\n"
      "       argil help COMMAND, or argil COMMAND --help, for a command's options\n"
      "\ncommands:\n";
  std::size_t width = 0;
  for (const Command& c : all_commands()) width = std::max(width, c.spec().name.size());
  for (const Command& c : all_commands()) {
    const CommandDeclaration& spec = c.spec();
    out += "  " + spec.name + std::string(width + 2 - spec.name.size(), ' ') + spec.summary + "\n";
  }
  out +=
      "\noptions:\n"
      "  -h, --help  print this usage and exit\n"
      "  --version   print the version and exit\n";
  return out;
}

int run_help(const std::vector<std::string>& args) {
  const ParseResult parsed = parse_arguments(help_command(), args);
  if (!parsed.arguments) return parsed.exit_status;
  const std::vector<std::string>& operands = parsed.arguments->operands;
  if (operands.empty()) {
    std::fputs(program_usage().c_str(), stdout);
    return kExitOk;
  }
  const Command* command = find_command(operands[0]);
  if (command == nullptr) {
    std::fprintf(stderr, "argil help: unknown command '%s'\n\n%s", operands[0].c_str(),
                 program_usage().c_str());
    return kExitUsage;
  }
  std::fputs(usage_text(command->spec()).c_str(), stdout);
  return kExitOk;
}

}  // namespace argil::cli
