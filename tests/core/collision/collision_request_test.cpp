// check_request's messages: a rejected tolerance names the allowed bound in mm
// and prints every number as its shortest round-trip text.
#include <catch2/catch.hpp>

#include <regex>
#include <string>

#include "argil/core.hpp"
#include "support/random_surface.hpp"

namespace argil {
namespace {

using test::asymmetric_surface;

/// Runs of 6 equal digits are what 17-digit printing of a short decimal looks
/// like ("9.9999999999999995e-21", "1.0000000000000001e-05").
bool has_digit_noise(const std::string& text) {
  return std::regex_search(text, std::regex("(\\d)\\1{5}"));
}

}  // namespace

TEST_CASE("a tolerance below the surface's bound names the bound in mm, in shortest numbers",
          "[collision][request]") {
  OperatorCache cache;
  const BSplineSurface s = asymmetric_surface();
  Result<SurfaceHierarchy> h = SurfaceHierarchy::build(s, cache);
  REQUIRE(h.ok());
  const double size = h.value().block(0).bound.box.diagonal();
  const Status status = check_request({.tolerance = 1e-20}, h.value());
  REQUIRE(status.code == StatusCode::invalid_argument);
  INFO(status.message);
  CHECK_THAT(status.message,
             Catch::Contains("tolerance 1e-20 mm is below the smallest this surface allows, " +
                             limit_text(kMinRelativeTolerance * size, LimitSide::lower) +
                             " mm (1e-12 of its " + approx_text(size) + " mm size)"));
  CHECK_FALSE(has_digit_noise(status.message));
}

TEST_CASE("the printed tolerance bounds are themselves accepted", "[collision][request]") {
  OperatorCache cache;
  Result<SurfaceHierarchy> h = SurfaceHierarchy::build(asymmetric_surface(), cache);
  REQUIRE(h.ok());
  const double size = h.value().block(0).bound.box.diagonal();
  const std::string lowest = limit_text(kMinRelativeTolerance * size, LimitSide::lower);
  const std::string highest = limit_text(size, LimitSide::upper);
  INFO(lowest << " " << highest);
  CHECK(check_request({.tolerance = std::stod(lowest)}, h.value()).ok());
  CHECK(check_request({.tolerance = std::stod(highest)}, h.value()).ok());
}

TEST_CASE("a tolerance above the surface's size names the size in mm", "[collision][request]") {
  OperatorCache cache;
  Result<SurfaceHierarchy> h = SurfaceHierarchy::build(asymmetric_surface(), cache);
  REQUIRE(h.ok());
  const double size = h.value().block(0).bound.box.diagonal();
  const Status status = check_request({.tolerance = 1e5}, h.value());
  REQUIRE(status.code == StatusCode::invalid_argument);
  CHECK_THAT(status.message,
             Catch::Contains("tolerance 1e+05 mm is above the largest this surface allows, its "
                             "size " +
                             limit_text(size, LimitSide::upper) + " mm"));
}

TEST_CASE("a non-positive or NaN tolerance is rejected with its value in mm",
          "[collision][request]") {
  OperatorCache cache;
  Result<SurfaceHierarchy> h = SurfaceHierarchy::build(asymmetric_surface(), cache);
  REQUIRE(h.ok());
  CHECK_THAT(check_request({.tolerance = -1e-5}, h.value()).message,
             Catch::Contains("tolerance -1e-05 mm must be positive and finite"));
  CHECK_THAT(check_request({.tolerance = std::nan("")}, h.value()).message,
             Catch::Contains("tolerance nan mm"));
}

}  // namespace argil
