#pragma once
// How argil prints numbers in messages, failure reports and its own text files
// (scripts, CSV logs, CLI JSON): the shortest text that reads back to the same
// double, so a value pastes into a regression test exactly and reads without
// 17-digit noise ("1e-05", not "1.0000000000000001e-05"). STEP and IGES go
// through OpenCASCADE's writers with their own exact format.

#include <string>
#include <string_view>

namespace argil {

/// The shortest decimal text that std::strtod reads back to exactly `x`
/// (std::to_chars, shortest round trip): "0.1", "1e-05", "-0", "120".
/// NaN prints as "nan", infinities as "inf" and "-inf".
std::string number_text(double x);

/// Which side of a limit the allowed values lie on: a lower bound allows
/// values at or above it, an upper bound values at or below it.
enum class LimitSide { lower, upper };

/// A derived limit (a bound computed from a model's size, say) in 3
/// significant digits, rounded towards the allowed side so that the printed
/// text, read back, is itself allowed: a lower bound rounds up ("1.63e-11" for
/// 1.6248e-11), an upper bound rounds down. Zero, infinities and NaN print as
/// number_text; a bound whose rounding would overflow also prints exactly.
std::string limit_text(double bound, LimitSide side);

/// A derived quantity (a model's size) in 3 significant digits, rounded to
/// nearest: "16.2" for 16.248. For reading, not for pasting back.
std::string approx_text(double x);

/// "(x, y, z)" for any vector with size() and operator[] (Eigen vectors,
/// std::array), each coordinate as number_text.
template <class Vector>
std::string vector_text(const Vector& v) {
  std::string out = "(";
  for (decltype(v.size()) k = 0; k < v.size(); ++k) {
    if (k > 0) out += ", ";
    out += number_text(static_cast<double>(v[k]));
  }
  return out + ")";
}

/// Which ends of an Interval belong to it.
enum class IntervalEnds { closed, open_low, open_high, open };

/// A range of allowed values, for messages that reject a value.
struct Interval {
  double low = 0.0;
  double high = 0.0;
  IntervalEnds ends = IntervalEnds::closed;

  bool contains(double x) const;
};

/// "[0, 1e+06] N/mm", "(0, 0.01] s": the interval in mathematical notation
/// followed by `unit` (omitted when empty).
std::string interval_text(const Interval& range, std::string_view unit);

/// "must be in [0, 1e+06] N/mm, got -3 N/mm": the rejection of `value`,
/// range and value both in `unit`.
std::string out_of_interval_text(double value, const Interval& range, std::string_view unit);

}  // namespace argil
