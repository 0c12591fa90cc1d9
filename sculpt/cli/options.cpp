#include "options.hpp"

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstdlib>

#include "commands.hpp"

namespace argil::cli {
namespace {

bool is_help(const std::string& word) { return word == "-h" || word == "--help"; }

/// A word that names an option rather than an operand ("-" alone is an operand,
/// the usual name of stdin/stdout).
bool looks_like_option(const std::string& word) { return word.size() > 1 && word[0] == '-'; }

const OptionDeclaration* find_option(const CommandDeclaration& spec, const std::string& name) {
  for (const OptionDeclaration& o : spec.options)
    if (o.name == name) return &o;
  return nullptr;
}

/// A number as typed on the command line, and whether a double can hold it:
/// "1e-400" reads as 0 and "1e400" as inf, so messages echo the text instead.
struct TypedNumber {
  double value = 0.0;
  bool beyond_double = false;
};

std::optional<TypedNumber> read_double(const std::string& text) {
  if (text.empty()) return std::nullopt;
  char* end = nullptr;
  errno = 0;
  const double x = std::strtod(text.c_str(), &end);
  if (*end != '\0') return std::nullopt;
  return TypedNumber{x, errno == ERANGE};
}

std::optional<long> read_long(const std::string& text) {
  if (text.empty()) return std::nullopt;
  char* end = nullptr;
  errno = 0;
  const long x = std::strtol(text.c_str(), &end, 10);
  if (*end != '\0' || errno == ERANGE) return std::nullopt;
  return x;
}

/// What is wrong with `value` for `option` ("" when nothing), ranges and
/// values in the option's unit.
std::string value_problem(const OptionDeclaration& option, const std::string& value) {
  const std::string name = option.name + " " + option.argument;
  switch (option.kind) {
    case ValueKind::none:
      return "";
    case ValueKind::text:
      return value.empty() ? name + " must not be empty" : "";
    case ValueKind::index: {
      const std::optional<long> i = read_long(value);
      return i && *i >= 0 ? "" : name + " must be an integer >= 0, got '" + value + "'";
    }
    case ValueKind::number: {
      const std::optional<TypedNumber> x = read_double(value);
      if (!x) return name + " needs a number, got '" + value + "'";
      if (option.range.contains(x->value)) return "";
      if (!x->beyond_double)
        return name + " " + out_of_interval_text(x->value, option.range, option.unit);
      const std::string unit = option.unit.empty() ? "" : " " + std::string(option.unit);
      return name + " must be in " + interval_text(option.range, option.unit) + ", got " + value +
             unit;
    }
  }
  return "";
}

std::string operand_list(const CommandDeclaration& spec) {
  std::string out;
  for (std::size_t k = 0; k < spec.operands.size(); ++k) {
    const bool optional = spec.last_operand_optional && k + 1 == spec.operands.size();
    out += (k > 0 ? " " : "") + (optional ? "[" + spec.operands[k] + "]" : spec.operands[k]);
  }
  return out;
}

std::string count_problem(const CommandDeclaration& spec, std::size_t got) {
  const std::size_t most = spec.operands.size();
  const std::size_t least = spec.last_operand_optional ? most - 1 : most;
  if (got >= least && got <= most) return "";
  if (most == 0) return "expected no arguments, got " + std::to_string(got);
  const std::string expected =
      least == most ? std::to_string(most) : std::to_string(least) + " or " + std::to_string(most);
  return "expected " + expected + (most == 1 ? " argument" : " arguments") + " (" +
         operand_list(spec) + "), got " + std::to_string(got);
}

/// `text` wrapped at spaces to lines of at most kWidth columns, the first starting at
/// column `indent` (after what precedes it), the rest indented to it.
std::string wrapped(const std::string& text, std::size_t indent) {
  constexpr std::size_t kWidth = 79;
  std::string out;
  std::size_t column = indent;
  std::size_t start = 0;
  while (start < text.size()) {
    // Breaks at spaces, but not after a comma: intervals like "(0, inf)" stay whole.
    std::size_t end = text.find(' ', start);
    while (end != std::string::npos && end > 0 && text[end - 1] == ',')
      end = text.find(' ', end + 1);
    if (end == std::string::npos) end = text.size();
    const std::size_t length = end - start;
    if (column > indent && column + 1 + length > kWidth) {
      out += "\n" + std::string(indent, ' ');
      column = indent;
    } else if (column > indent) {
      out += ' ';
      ++column;
    }
    out.append(text, start, length);
    column += length;
    start = end + 1;
  }
  return out;
}

}  // namespace

bool Arguments::flag(std::string_view name) const {
  return std::any_of(values.begin(), values.end(), [&](const auto& v) { return v.first == name; });
}

std::optional<std::string> Arguments::text(std::string_view name) const {
  for (auto v = values.rbegin(); v != values.rend(); ++v)
    if (v->first == name) return v->second;
  return std::nullopt;
}

std::optional<double> Arguments::number(std::string_view name) const {
  const std::optional<std::string> t = text(name);
  if (!t) return std::nullopt;
  const std::optional<TypedNumber> x = read_double(*t);
  return x ? std::optional<double>(x->value) : std::nullopt;
}

std::optional<long> Arguments::index(std::string_view name) const {
  const std::optional<std::string> t = text(name);
  return t ? read_long(*t) : std::nullopt;
}

ParseResult parse_arguments(const CommandDeclaration& spec, const std::vector<std::string>& args) {
  Arguments out;
  for (std::size_t k = 0; k < args.size(); ++k) {
    const std::string& word = args[k];
    if (is_help(word)) {
      std::fputs(usage_text(spec).c_str(), stdout);
      return {std::nullopt, kExitOk};
    }
    if (!looks_like_option(word)) {
      out.operands.push_back(word);
      continue;
    }
    const OptionDeclaration* option = find_option(spec, word);
    if (option == nullptr)
      return {std::nullopt, usage_error(spec, "unknown option '" + word + "'")};
    if (option->kind == ValueKind::none) {
      out.values.emplace_back(word, "");
      continue;
    }
    if (k + 1 >= args.size()) {
      return {std::nullopt, usage_error(spec, word + " needs a value (" + option->argument + ")")};
    }
    const std::string& value = args[++k];
    if (const std::string problem = value_problem(*option, value); !problem.empty())
      return {std::nullopt, usage_error(spec, problem)};
    out.values.emplace_back(word, value);
  }
  if (const std::string problem = count_problem(spec, out.operands.size()); !problem.empty())
    return {std::nullopt, usage_error(spec, problem)};
  return {std::move(out), kExitOk};
}

std::string usage_text(const CommandDeclaration& spec) {
  std::string out = "usage: argil " + spec.name;
  if (!spec.operands.empty()) out += " " + operand_list(spec);
  if (!spec.options.empty()) out += " [options]";
  out += "\n" + spec.summary + "\n";
  if (!spec.description.empty()) out += "\n" + spec.description + "\n";
  std::vector<std::pair<std::string, std::string>> rows;
  for (const OptionDeclaration& o : spec.options) {
    std::string text = o.description;
    if (o.kind == ValueKind::number)
      text += "; " + o.argument + " in " + interval_text(o.range, o.unit);
    if (o.kind == ValueKind::index) text += "; " + o.argument + " >= 0";
    if (!o.default_text.empty()) text += " (default " + o.default_text + ")";
    rows.emplace_back(o.argument.empty() ? o.name : o.name + " " + o.argument, text);
  }
  rows.emplace_back("-h, --help", "print this usage and exit");
  std::size_t width = 0;
  for (const auto& row : rows) width = std::max(width, row.first.size());
  out += "\noptions:\n";
  for (const auto& [left, right] : rows)
    out +=
        "  " + left + std::string(width + 2 - left.size(), ' ') + wrapped(right, width + 4) + "\n";
  return out;
}

int usage_error(const CommandDeclaration& spec, const std::string& message) {
  std::fprintf(stderr, "argil %s: %s\n\n%s", spec.name.c_str(), message.c_str(),
               usage_text(spec).c_str());
  return kExitUsage;
}

}  // namespace argil::cli
