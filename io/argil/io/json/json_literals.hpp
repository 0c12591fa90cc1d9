#pragma once
// Non-standard JSON number literals (NaN, Infinity, -Infinity, written by Python's
// json module) and numbers that overflow a double (1e999) would stop a strict JSON
// parser with a byte offset only. Quoting them as marked strings lets a reader
// report them with their field path instead.

#include <optional>
#include <string>
#include <string_view>

namespace argil::io {

/// Prefix of the string a non-finite literal becomes, followed by the literal.
inline constexpr std::string_view kNonFiniteMarker = "argil:non-finite:";

/// `text` with every non-finite literal outside strings replaced by the string
/// "argil:non-finite:<literal>"; everything else is copied unchanged.
std::string quote_non_finite_literals(std::string_view text);

/// The original literal when `text` (a string value) is such a marker; nullopt otherwise.
std::optional<std::string> non_finite_marker_literal(std::string_view text);

}  // namespace argil::io
