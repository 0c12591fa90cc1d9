// Trim curves follow the rules surfaces follow: one knot validation serves
// both, so the trim path rejects what the surface path rejects, with the same
// message naming the field.
#include <catch2/catch.hpp>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "argil/io.hpp"

namespace argil::io {
namespace {

struct KnotCase {
  const char* what;
  int degree;
  std::vector<double> knots;
  const char* defect;  // what the message says is wrong
};

std::vector<KnotCase> bad_knot_cases() {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  return {
      {"an interior knot repeated beyond the degree",
       2,
       {0, 0, 0, 0.5, 0.5, 0.5, 1, 1, 1},
       "repeats 3 times"},
      {"a NaN knot", 2, {0, 0, 0, nan, 1, 1, 1}, "[3] is nan"},
      {"a knot beyond the supported magnitude",
       2,
       {0, 0, 0, 0.5, 1, 1, 2e12 + 1},
       "beyond the supported magnitude"},
      {"a non-empty span a few ulps wide",
       2,
       {0, 0, 0, 0.5, 0.5 + 1e-14, 1, 1, 1},
       "is shorter than"},
      {"an empty domain", 2, {1, 1, 1, 1, 1, 1}, "spans an empty domain"},
      {"decreasing knots", 2, {0, 0, 0, 0.7, 0.3, 1, 1, 1}, "[4] = 0.3 is below"},
      {"unclamped ends", 2, {0, 0, 0.1, 0.5, 1, 1, 1}, "is not clamped"},
  };
}

Eigen::VectorXd to_vector(const std::vector<double>& values) {
  return Eigen::Map<const Eigen::VectorXd>(values.data(), static_cast<Eigen::Index>(values.size()));
}

/// A curve with the case's knots and enough finite points for them.
TrimCurve curve_with(const KnotCase& c) {
  TrimCurve curve;
  curve.degree = c.degree;
  curve.knots = to_vector(c.knots);
  curve.points = TrimCurve::Points::Constant(std::max(curve.count(), 0), 2, 0.25);
  return curve;
}

/// A surface with the case's knots in u, linear in v, enough finite poles.
BSplineSurface surface_with(const KnotCase& c) {
  BSplineSurface s;
  s.degree = {c.degree, 1};
  s.knots = {to_vector(c.knots), Eigen::Vector4d(0, 0, 1, 1)};
  const int rows = std::max(s.count(Direction::u), 0) * s.count(Direction::v);
  s.control_points = ControlNet::Constant(rows, 3, 1.0);
  return s;
}

/// A valid unit-square face whose single loop holds `curve`.
FaceRecord face_with(const TrimCurve& curve) {
  FaceRecord face;
  face.surface.degree = {1, 1};
  face.surface.knots = {Eigen::Vector4d(0, 0, 1, 1), Eigen::Vector4d(0, 0, 1, 1)};
  face.surface.control_points.resize(4, 3);
  face.surface.control_points << 0, 0, 0, 0, 1, 0, 1, 0, 0, 1, 1, 0;
  face.loops.push_back(TrimLoop{true, {curve}});
  return face;
}

std::string replace_all(std::string text, const std::string& from, const std::string& to) {
  for (auto at = text.find(from); at != std::string::npos; at = text.find(from, at + to.size()))
    text.replace(at, from.size(), to);
  return text;
}

}  // namespace

TEST_CASE("trim curves reject every knot vector surfaces reject, with the same defect",
          "[io][trim]") {
  for (const KnotCase& c : bad_knot_cases()) {
    INFO(c.what);
    const Status on_surface = validate(surface_with(c));
    const Status on_curve = validate(curve_with(c));
    INFO("surface: " << on_surface.message);
    INFO("curve: " << on_curve.message);
    CHECK(on_surface.code == StatusCode::invalid_surface);
    CHECK(on_curve.code == StatusCode::invalid_surface);
    CHECK_THAT(on_curve.message, Catch::Contains(c.defect));
    // Same rule, same text: only the field name differs ("knots_u" vs "knots").
    CHECK(replace_all(on_surface.message, "knots_u", "knots") == on_curve.message);
  }
}

TEST_CASE("a bad trim curve's message names the face, loop, curve and knot field", "[io][trim]") {
  for (const KnotCase& c : bad_knot_cases()) {
    INFO(c.what);
    const Status direct = validate_trim_curve(curve_with(c));
    REQUIRE_FALSE(direct.ok());
    CHECK(direct.code == StatusCode::invalid_surface);
    CHECK_THAT(direct.message, Catch::StartsWith("trim curve: knots"));
    const Status in_face = validate_face(face_with(curve_with(c)), 3);
    REQUIRE_FALSE(in_face.ok());
    CHECK_THAT(in_face.message, Catch::StartsWith("face 3 loop 0 curve 0: trim curve: knots"));
  }
}

TEST_CASE("validate_face without an index gives the same message without the face prefix",
          "[io][trim]") {
  FaceRecord no_curves = face_with(curve_with(bad_knot_cases().front()));
  no_curves.loops.front().curves.clear();
  FaceRecord bad_surface = no_curves;
  bad_surface.surface.degree = {5, 1};  // more than the knots allow
  for (const FaceRecord& face :
       {face_with(curve_with(bad_knot_cases().front())), no_curves, bad_surface}) {
    const Status bare = validate_face(face);
    const Status named = validate_face(face, 12);
    REQUIRE_FALSE(bare.ok());
    CHECK(bare.code == named.code);
    CHECK(named.message == "face 12 " + bare.message);
    CHECK_THAT(bare.message, !Catch::StartsWith("face"));
  }
}

TEST_CASE("trim curve points and weights are checked by field and index", "[io][trim]") {
  TrimCurve line;
  line.degree = 1;
  line.knots = Eigen::Vector4d(0, 0, 1, 1);
  line.points.resize(2, 2);
  line.points << 0, 0, 1, 1;
  REQUIRE(validate_trim_curve(line).ok());

  TrimCurve bad_point = line;
  bad_point.points(1, 0) = std::numeric_limits<double>::infinity();
  CHECK_THAT(validate_trim_curve(bad_point).message, Catch::Contains("points[1]"));

  TrimCurve bad_weight = line;
  bad_weight.weights = Eigen::Vector2d(1.0, -2.0);
  CHECK_THAT(validate_trim_curve(bad_weight).message, Catch::Contains("weights[1] is -2"));

  TrimCurve three_columns = line;
  three_columns.points = TrimCurve::Points::Zero(2, 3);
  CHECK_THAT(validate_trim_curve(three_columns).message, Catch::Contains("expected 2 (u, v)"));
}

}  // namespace argil::io
