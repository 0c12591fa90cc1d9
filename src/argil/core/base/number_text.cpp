#include "argil/core/base/number_text.hpp"

#include <array>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
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

/// x as m * 10^k with |m| in [100, 999]: the 3-digit decimal nearest to x.
struct ThreeDigits {
  long long m = 0;
  int k = 0;

  double value() const {
    const std::string text = std::to_string(m) + "e" + std::to_string(k);
    return std::strtod(text.c_str(), nullptr);
  }
};

ThreeDigits nearest_three_digits(double x) {
  // %.2e rounds correctly to 3 significant digits: "1.62e-11".
  std::array<char, 40> text{};
  std::snprintf(text.data(), text.size(), "%.2e", x);
  const std::string s(text.data());
  const std::size_t e = s.find('e');
  std::string digits;
  for (std::size_t i = 0; i < e; ++i)
    if (s[i] == '-' || (s[i] >= '0' && s[i] <= '9')) digits += s[i];
  return {std::stoll(digits), std::stoi(s.substr(e + 1)) - 2};
}

bool is_special(double x) { return x == 0.0 || !std::isfinite(x); }

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

std::string limit_text(double bound, LimitSide side) {
  if (is_special(bound)) return number_text(bound);
  ThreeDigits t = nearest_three_digits(bound);
  // One step of the last digit moves the decimal past the bound when the
  // nearest one fell on the forbidden side; |m| stays within 3 digits or
  // becomes 1000 / 99, both at most 3 significant digits.
  if (side == LimitSide::lower && t.value() < bound) ++t.m;
  if (side == LimitSide::upper && t.value() > bound) --t.m;
  const double printed = t.value();
  return std::isfinite(printed) ? number_text(printed) : number_text(bound);
}

std::string approx_text(double x) {
  if (is_special(x)) return number_text(x);
  const double printed = nearest_three_digits(x).value();
  return std::isfinite(printed) ? number_text(printed) : number_text(x);
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
