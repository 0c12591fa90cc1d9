#include "argil/core/base/number_text.hpp"

#include <array>
#include <charconv>
#include <cmath>
#include <optional>

namespace argil {

namespace {

// The longest shortest-round-trip text of a double is 24 characters
// ("-2.2250738585072014e-308"); 32 leaves room.
using Buffer = std::array<char, 32>;

std::string to_text(double x, std::optional<std::chars_format> format) {
  Buffer buffer{};
  const std::to_chars_result r =
      format ? std::to_chars(buffer.data(), buffer.data() + buffer.size(), x, *format)
             : std::to_chars(buffer.data(), buffer.data() + buffer.size(), x);
  return std::string(buffer.data(), r.ptr);
}

}  // namespace

std::string number_text(double x) {
  if (std::isnan(x)) return "nan";
  if (std::isinf(x)) return x > 0.0 ? "inf" : "-inf";
  // Plain to_chars picks the shorter of fixed and scientific notation, but
  // fixed notation spells large integers out exactly ("2867114766066001641472"):
  // digits beyond the shortest round trip are noise, so those go scientific.
  const std::string plain = to_text(x, std::nullopt);
  if (plain.find_first_of(".e") != std::string::npos) return plain;
  const std::string scientific = to_text(x, std::chars_format::scientific);
  const std::size_t mantissa_end = scientific.find('e');
  const std::size_t sign = x < 0.0 ? 1 : 0;
  const std::size_t digits = mantissa_end - sign - (scientific.find('.') < mantissa_end ? 1 : 0);
  const bool padded_with_zeros = plain.find_first_not_of('0', sign + digits) == std::string::npos;
  return padded_with_zeros ? plain : scientific;
}

bool Interval::contains(double x) const {
  const bool low_ok =
      ends == IntervalEnds::closed || ends == IntervalEnds::open_high ? x >= low : x > low;
  const bool high_ok =
      ends == IntervalEnds::closed || ends == IntervalEnds::open_low ? x <= high : x < high;
  return low_ok && high_ok;  // false for NaN
}

std::string interval_text(const Interval& range, std::string_view unit) {
  const bool low_open = range.ends == IntervalEnds::open || range.ends == IntervalEnds::open_low;
  const bool high_open = range.ends == IntervalEnds::open || range.ends == IntervalEnds::open_high;
  std::string out = low_open ? "(" : "[";
  out += number_text(range.low) + ", " + number_text(range.high);
  out += high_open ? ")" : "]";
  if (!unit.empty()) out += " " + std::string(unit);
  return out;
}

std::string out_of_interval_text(double value, const Interval& range, std::string_view unit) {
  std::string out = "must be in " + interval_text(range, unit) + ", got " + number_text(value);
  if (!unit.empty()) out += " " + std::string(unit);
  return out;
}

}  // namespace argil
