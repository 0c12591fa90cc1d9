#include "argil/io/json/json_literals.hpp"

#include <cmath>
#include <cstdlib>

namespace argil::io {

std::string quote_non_finite_literals(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  bool in_string = false;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (in_string) {
      out += c;
      if (c == '\\' && i + 1 < text.size()) {
        out += text[++i];
      } else if (c == '"') {
        in_string = false;
      }
      continue;
    }
    if (c == '"') in_string = true;
    bool replaced = false;
    for (std::string_view literal : {"-Infinity", "Infinity", "NaN"}) {
      if (text.substr(i, literal.size()) == literal) {
        out += '"';
        out += kNonFiniteMarker;
        out += literal;
        out += '"';
        i += literal.size() - 1;
        replaced = true;
        break;
      }
    }
    if (!replaced && (c == '-' || (c >= '0' && c <= '9'))) {
      // A number too large for a double (1e999) would stop the parser without
      // a field path; mark it like Infinity.
      const std::size_t end = text.find_first_not_of("+-.0123456789eE", i);
      const std::string token(text.substr(i, end - i));
      if (std::isinf(std::strtod(token.c_str(), nullptr))) {
        out += '"';
        out += kNonFiniteMarker;
        out += token;
        out += '"';
      } else {
        out += token;
      }
      i += token.size() - 1;
      replaced = true;
    }
    if (!replaced) out += c;
  }
  return out;
}

std::optional<std::string> non_finite_marker_literal(std::string_view text) {
  if (text.substr(0, kNonFiniteMarker.size()) != kNonFiniteMarker) return std::nullopt;
  return std::string(text.substr(kNonFiniteMarker.size()));
}

}  // namespace argil::io
