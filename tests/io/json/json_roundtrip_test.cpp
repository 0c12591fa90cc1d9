// parse_json / to_json round trips: every double bit for bit, and whole models
// (generated surfaces, trims, flags, units, metadata) unchanged.
#include <bit>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <vector>

#include "argil/io.hpp"
#include "bit_difference.hpp"
#include "generated_models.hpp"

namespace argil::io {

TEST_CASE("JSON keeps every double bit for bit, subnormals and extremes included", "[io][json]") {
  std::mt19937_64 rng(7);
  std::vector<double> values{0.0,
                             -0.0,
                             std::numeric_limits<double>::min(),
                             std::numeric_limits<double>::denorm_min(),
                             -std::numeric_limits<double>::denorm_min(),
                             std::numeric_limits<double>::max(),
                             std::numeric_limits<double>::lowest(),
                             std::numeric_limits<double>::epsilon(),
                             0.1,
                             1.0 / 3.0,
                             5e-324 * 3,
                             1e308,
                             123456789012345678.0};
  while (values.size() < 30000) {
    const double x = std::bit_cast<double>(rng());
    if (std::isfinite(x)) values.push_back(x);
  }
  // Doubles ride in trim-curve poles, the one place whose values have no range
  // beyond being finite (surface coordinates are limited, docs/range.md); the
  // positions need not be sane. The surface takes the values that fit its range.
  Model model;
  for (std::size_t start = 0; start < values.size(); start += 3000) {
    FaceRecord face;
    face.surface.degree = {1, 1};
    face.surface.knots = {Eigen::Vector4d(0, 0, 1, 1), Eigen::VectorXd(1002)};
    face.surface.knots[1] << 0.0, Eigen::VectorXd::LinSpaced(1000, 0.0, 1.0), 1.0;
    face.surface.control_points.resize(2000, 3);
    for (Eigen::Index k = 0; k < 6000; ++k) {
      const double x = values[(start + static_cast<std::size_t>(k)) % values.size()];
      face.surface.control_points.data()[k] = std::abs(x) <= kMaxCoordinate ? x : 0.0;
    }
    TrimCurve curve;
    curve.degree = 1;
    curve.points.resize(1500, 2);
    curve.knots.resize(1502);
    curve.knots << 0.0, Eigen::VectorXd::LinSpaced(1500, 0.0, 1.0), 1.0;
    for (Eigen::Index k = 0; k < 3000; ++k) {
      curve.points.data()[k] = values[(start + static_cast<std::size_t>(k)) % values.size()];
    }
    face.loops.push_back({true, {curve}});
    model.faces.push_back(face);
  }
  const Result<std::string> text = to_json(model);
  REQUIRE(text.ok());
  const Result<Model> back = parse_json(text.value());
  REQUIRE(back.ok());
  test::require_same_surfaces(model, back.value());
  for (std::size_t f = 0; f < model.faces.size(); ++f) {
    const TrimCurve& a = model.faces[f].loops[0].curves[0];
    const TrimCurve& b = back.value().faces[f].loops[0].curves[0];
    REQUIRE(b.points.size() == a.points.size());
    // Bit for bit, signed zeros included.
    CHECK(std::memcmp(a.points.data(), b.points.data(), sizeof(double) * 3000) == 0);
  }
}

TEST_CASE("JSON round trip is bit-exact for surfaces, trims, flags, units and metadata",
          "[io][json]") {
  Model model = test::generated_model();
  model.faces.push_back(test::trimmed_face());
  model.faces.back().reversed = true;
  model.source_unit = {"inch", 25.4};
  model.metadata["author"] = "argil tests";
  const Result<std::string> text = to_json(model);
  REQUIRE(text.ok());
  const Result<Model> back = parse_json(text.value(), "roundtrip.json");
  REQUIRE(back.ok());
  test::require_same_surfaces(model, back.value());
  const FaceRecord& a = model.faces.back();
  const FaceRecord& b = back.value().faces.back();
  CHECK(b.reversed);
  CHECK(b.name == a.name);
  CHECK(b.source_id == a.source_id);
  REQUIRE(b.loops.size() == a.loops.size());
  for (std::size_t l = 0; l < a.loops.size(); ++l) {
    CHECK(b.loops[l].outer == a.loops[l].outer);
    REQUIRE(b.loops[l].curves.size() == a.loops[l].curves.size());
    for (std::size_t c = 0; c < a.loops[l].curves.size(); ++c) {
      CHECK(test::curve_difference(a.loops[l].curves[c], b.loops[l].curves[c]) == "");
    }
  }
  CHECK(back.value().source_unit.name == "inch");
  CHECK(back.value().source_unit.to_mm == 25.4);
  CHECK(back.value().metadata == model.metadata);
  // Writing what was read gives the same text: the format is a fixed point.
  CHECK(to_json(back.value()).value() == text.value());
}

}  // namespace argil::io
