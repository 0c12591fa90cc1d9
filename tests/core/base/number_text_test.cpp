// number_text: the shortest text that reads back to the same double.
#include <catch2/catch.hpp>

#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <random>
#include <string>

#include "argil/core.hpp"

namespace {

using argil::number_text;
using Limits = std::numeric_limits<double>;

/// Reads `text` back as strtod does: the oracle the messages are meant for.
double read_back(const std::string& text) { return std::strtod(text.c_str(), nullptr); }

bool round_trips(double x) {
  const double y = read_back(number_text(x));
  return std::bit_cast<std::uint64_t>(y) == std::bit_cast<std::uint64_t>(x);
}

/// Significant digits of a decimal text ("-1.25e-05" has 3).
int significant_digits(const std::string& text) {
  const std::string mantissa = text.substr(0, text.find('e'));
  std::string digits;
  for (const char c : mantissa)
    if (c >= '0' && c <= '9') digits += c;
  const auto first = digits.find_first_not_of('0');
  if (first == std::string::npos) return 1;
  digits = digits.substr(first);
  if (mantissa.find('.') != std::string::npos || text.find('e') != std::string::npos)
    return static_cast<int>(digits.size());
  return static_cast<int>(digits.find_last_not_of('0') + 1);  // "120" has 2
}

/// True when some text with `digits` significant digits reads back to `x`
/// (the correctly rounded one; an independent check through printf).
bool has_text_with_digits(double x, int digits) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.*e", digits - 1, x);
  return std::strtod(buffer, nullptr) == x;
}

}  // namespace

TEST_CASE("number_text reads back to the same double for random bit patterns", "[number_text]") {
  std::mt19937_64 random(20261122);
  int checked = 0;
  for (int k = 0; k < 200000; ++k) {
    const double x = std::bit_cast<double>(random());
    if (std::isnan(x)) continue;
    INFO("bits " << std::bit_cast<std::uint64_t>(x) << " text " << number_text(x));
    REQUIRE(round_trips(x));
    ++checked;
  }
  CHECK(checked > 199000);
}

TEST_CASE("number_text reads back to the same double for values of everyday magnitude",
          "[number_text]") {
  std::mt19937_64 random(7);
  std::uniform_real_distribution<double> exponent(-12.0, 12.0), mantissa(-1.0, 1.0);
  for (int k = 0; k < 100000; ++k) {
    const double x = mantissa(random) * std::pow(10.0, exponent(random));
    INFO("x " << number_text(x));
    REQUIRE(round_trips(x));
  }
}

TEST_CASE("number_text is the shortest text that reads back", "[number_text]") {
  // printf's correctly rounded text with one digit fewer must not read back.
  std::mt19937_64 random(11);
  std::uniform_real_distribution<double> exponent(-300.0, 300.0), mantissa(1.0, 10.0);
  for (int k = 0; k < 20000; ++k) {
    const double x = mantissa(random) * std::pow(10.0, exponent(random));
    const std::string text = number_text(x);
    const int digits = significant_digits(text);
    INFO("x " << text << " digits " << digits);
    REQUIRE(digits <= 17);
    if (digits > 1) REQUIRE_FALSE(has_text_with_digits(x, digits - 1));
  }
}

TEST_CASE("number_text prints the extremes exactly", "[number_text]") {
  const std::array<double, 12> extremes = {Limits::max(),
                                           -Limits::max(),
                                           Limits::min(),
                                           -Limits::min(),
                                           Limits::denorm_min(),
                                           -Limits::denorm_min(),
                                           Limits::epsilon(),
                                           0.1,
                                           1e-5,
                                           1e-12,
                                           std::nextafter(1.0, 2.0),
                                           9.9999999999999995e-21};
  for (const double x : extremes) {
    INFO("x " << number_text(x));
    CHECK(round_trips(x));
  }
  CHECK(number_text(0.1) == "0.1");
  CHECK(number_text(1e-5) == "1e-05");
  CHECK(number_text(1e-20) == "1e-20");
  CHECK(number_text(120.0) == "120");
  CHECK(number_text(-3.0) == "-3");
  CHECK(number_text(Limits::denorm_min()) == "5e-324");
  CHECK(number_text(Limits::max()) == "1.7976931348623157e+308");
  CHECK(number_text(0.1 + 0.2) == "0.30000000000000004");
}

TEST_CASE("number_text names zeros, infinities and NaN", "[number_text]") {
  CHECK(number_text(0.0) == "0");
  CHECK(number_text(-0.0) == "-0");
  CHECK(round_trips(-0.0));
  CHECK(number_text(Limits::infinity()) == "inf");
  CHECK(number_text(-Limits::infinity()) == "-inf");
  CHECK(number_text(Limits::quiet_NaN()) == "nan");
  CHECK(std::isinf(read_back(number_text(Limits::infinity()))));
}

TEST_CASE("vector_text prints each coordinate as number_text", "[number_text]") {
  CHECK(argil::vector_text(Eigen::Vector3d(0.1, -2.0, 1e-5)) == "(0.1, -2, 1e-05)");
  CHECK(argil::vector_text(Eigen::Vector2d(0.5, 120.0)) == "(0.5, 120)");
}

TEST_CASE("interval_text marks open and closed ends and carries the unit", "[number_text]") {
  using argil::Interval;
  using argil::IntervalEnds;
  CHECK(argil::interval_text({0.0, 1e6}, "N/mm") == "[0, 1e+06] N/mm");
  CHECK(argil::interval_text({0.0, 0.01, IntervalEnds::open_low}, "s") == "(0, 0.01] s");
  CHECK(argil::interval_text({0.0, 1.0, IntervalEnds::open}, "") == "(0, 1)");
  CHECK(argil::out_of_interval_text(-3.0, {0.0, 1e6}, "N/mm") ==
        "must be in [0, 1e+06] N/mm, got -3 N/mm");
}

TEST_CASE("Interval::contains honours each kind of end and rejects NaN", "[number_text]") {
  using argil::Interval;
  using argil::IntervalEnds;
  const Interval closed{0.0, 1.0};
  CHECK(closed.contains(0.0));
  CHECK(closed.contains(1.0));
  CHECK_FALSE(closed.contains(std::nextafter(1.0, 2.0)));
  const Interval open_low{0.0, 1.0, IntervalEnds::open_low};
  CHECK_FALSE(open_low.contains(0.0));
  CHECK(open_low.contains(Limits::denorm_min()));
  CHECK(open_low.contains(1.0));
  const Interval open_high{0.0, 1.0, IntervalEnds::open_high};
  CHECK(open_high.contains(0.0));
  CHECK_FALSE(open_high.contains(1.0));
  const Interval open{0.0, 1.0, IntervalEnds::open};
  CHECK_FALSE(open.contains(0.0));
  CHECK_FALSE(open.contains(1.0));
  CHECK(open.contains(0.5));
  CHECK_FALSE(closed.contains(Limits::quiet_NaN()));
}

TEST_CASE("number_text does not spell large integers out beyond their shortest digits",
          "[number_text]") {
  CHECK(number_text(2867114766066001641472.0) == "2.8671147660660016e+21");
  CHECK(number_text(123456789012345678.0) == "123456789012345680");
  CHECK(number_text(-1e21) == "-1e+21");
  CHECK(number_text(1e15) == "1e+15");
  CHECK(number_text(1234.0) == "1234");
}

TEST_CASE("limit_text prints a bound that is itself allowed, in at most 3 significant digits",
          "[number_text]") {
  using argil::LimitSide;
  std::mt19937_64 random(3);
  std::uniform_real_distribution<double> exponent(-300.0, 300.0), mantissa(-10.0, 10.0);
  for (int k = 0; k < 50000; ++k) {
    const double x = mantissa(random) * std::pow(10.0, exponent(random));
    const std::string lower = argil::limit_text(x, LimitSide::lower);
    const std::string upper = argil::limit_text(x, LimitSide::upper);
    INFO("x " << number_text(x) << " lower " << lower << " upper " << upper);
    REQUIRE(significant_digits(lower) <= 3);
    REQUIRE(significant_digits(upper) <= 3);
    REQUIRE(read_back(lower) >= x);
    REQUIRE(read_back(upper) <= x);
    // Within one unit of the third digit: 1% of the magnitude at most.
    const double unit = std::abs(x) * 1e-2;
    REQUIRE(read_back(lower) - x <= unit);
    REQUIRE(x - read_back(upper) <= unit);
  }
}

TEST_CASE("limit_text rounds a lower bound up and an upper bound down", "[number_text]") {
  using argil::LimitSide;
  CHECK(argil::limit_text(1.6248076809271923e-11, LimitSide::lower) == "1.63e-11");
  CHECK(argil::limit_text(1.6248076809271923e-11, LimitSide::upper) == "1.62e-11");
  CHECK(argil::limit_text(0.00020050441990140765, LimitSide::lower) == "0.000201");
  CHECK(argil::limit_text(2005.0441990140766, LimitSide::upper) == "2000");
  CHECK(argil::limit_text(-2005.0441990140766, LimitSide::lower) == "-2000");
  CHECK(argil::limit_text(9.9951, LimitSide::lower) == "10");
  CHECK(argil::limit_text(0.1, LimitSide::lower) == "0.1");
  CHECK(argil::limit_text(0.1, LimitSide::upper) == "0.1");
  CHECK(argil::limit_text(0.0, LimitSide::lower) == "0");
  CHECK(argil::limit_text(Limits::infinity(), LimitSide::upper) == "inf");
  CHECK(argil::limit_text(Limits::max(), LimitSide::lower) == "1.7976931348623157e+308");
  CHECK(argil::limit_text(Limits::max(), LimitSide::upper) == "1.79e+308");
}

TEST_CASE("approx_text rounds to the nearest 3 significant digits", "[number_text]") {
  CHECK(argil::approx_text(16.24807680927192) == "16.2");
  CHECK(argil::approx_text(2005.0441990140766) == "2010");
  CHECK(argil::approx_text(-0.0012349) == "-0.00123");
  CHECK(argil::approx_text(120.0) == "120");
  CHECK(argil::approx_text(Limits::quiet_NaN()) == "nan");
  std::mt19937_64 random(5);
  std::uniform_real_distribution<double> exponent(-300.0, 300.0), mantissa(1.0, 10.0);
  for (int k = 0; k < 20000; ++k) {
    const double x = mantissa(random) * std::pow(10.0, exponent(random));
    const std::string text = argil::approx_text(x);
    INFO("x " << number_text(x) << " text " << text);
    REQUIRE(significant_digits(text) <= 3);
    REQUIRE(std::abs(read_back(text) - x) <= x * 5e-3 * (1.0 + 1e-12));
  }
}
