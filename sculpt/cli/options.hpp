#pragma once
// The command line of every argil command, declared once per command: its
// operands, options (with argument, range, unit and default) and usage text.
// One parser checks them all, so -h/--help, unknown options and bad values
// behave the same in every command.

#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "argil/core/base/number_text.hpp"

namespace argil::cli {

/// The range of a length or count that must be positive and finite: (0, inf).
inline constexpr Interval kPositiveFinite{0.0, std::numeric_limits<double>::infinity(),
                                          IntervalEnds::open};

/// What follows an option on the command line.
enum class ValueKind {
  none,    // a flag
  text,    // any non-empty word (a path)
  index,   // an integer >= 0
  number,  // a number inside OptionDeclaration::range, in OptionDeclaration::unit
};

struct OptionDeclaration {
  std::string name{};      // "--tolerance"
  std::string argument{};  // "E"; empty for a flag
  ValueKind kind = ValueKind::none;
  std::string description{};   // what it does, one line
  Interval range{};            // ValueKind::number only
  std::string unit{};          // of range and value ("mm"); empty for pure numbers
  std::string default_text{};  // "1e-4 of the faces' size"; empty when none
};

struct CommandDeclaration {
  std::string name;                   // "collide"
  std::vector<std::string> operands;  // {"A", "B"}
  bool last_operand_optional = false;
  std::string summary;      // one line, for the program's usage
  std::string description;  // a few lines for the command's usage, '\n'-separated
  std::vector<OptionDeclaration> options;
};

/// Arguments that passed every check of their CommandDeclaration.
struct Arguments {
  std::vector<std::string> operands;
  std::vector<std::pair<std::string, std::string>> values;  // (option, value); "" for flags

  bool flag(std::string_view name) const;
  /// The value given to option `name` (the last one when repeated), if any.
  std::optional<std::string> text(std::string_view name) const;
  std::optional<double> number(std::string_view name) const;
  std::optional<long> index(std::string_view name) const;
};

/// The arguments of one run, or the exit status when the command must not run:
/// kExitOk after printing its usage for -h/--help, kExitUsage after printing
/// what is wrong and the usage to stderr.
struct ParseResult {
  std::optional<Arguments> arguments;
  int exit_status = 0;
};

/// Checks `args` (the words after the command's name) against `spec`.
ParseResult parse_arguments(const CommandDeclaration& spec, const std::vector<std::string>& args);

/// The command's usage: synopsis, description, and one line per option naming
/// its argument, range with unit, and default.
std::string usage_text(const CommandDeclaration& spec);

/// Prints "argil NAME: message", then the usage, to stderr; returns kExitUsage.
int usage_error(const CommandDeclaration& spec, const std::string& message);

}  // namespace argil::cli
