// A face that validate_face() accepts but that no valid OpenCASCADE face can
// carry (a trim loop crossing itself, a net collapsed to a point) makes the STEP
// or IGES export fail with an error naming the file, the face (index, source
// entity, name) and the defect, and writes nothing: an existing file stays as
// it was. Faces of real files are the carriers, so nothing else is wrong.
#include <catch2/catch.hpp>

#include "argil/io.hpp"
#include "generated_models.hpp"
#include "test_files.hpp"

namespace argil::io {
namespace {

/// `face` trimmed by a bow tie in the middle of its domain: four lines from
/// corner to corner that cross at the centre.
FaceRecord with_crossing_loop(FaceRecord face) {
  const BSplineSurface& s = face.surface;
  const Eigen::Vector2d lo(s.domain_start(Direction::u), s.domain_start(Direction::v));
  const Eigen::Vector2d hi(s.domain_end(Direction::u), s.domain_end(Direction::v));
  const Eigen::Vector2d a = lo + 0.25 * (hi - lo), c = lo + 0.75 * (hi - lo);
  const Eigen::Vector2d b(c.x(), a.y()), d(a.x(), c.y());
  TrimLoop bow_tie;
  bow_tie.curves = {test::line(a, b), test::line(b, d), test::line(d, c), test::line(c, a)};
  face.loops = {bow_tie};
  face.name = "bow tie";
  return face;
}

/// `face` with every control point moved onto its first: a valid net whose
/// surface is a single point.
FaceRecord collapsed_to_a_point(FaceRecord face) {
  ControlNet& net = face.surface.control_points;
  for (Eigen::Index k = 1; k < net.rows(); ++k) net.row(k) = net.row(0);
  return face;
}

// The screw's faces without their B-rep: these tests are about one face at a
// time, as the face-by-face export builds and names it (a face whose trims no
// longer match its edges cannot be written with shared edges at all).
Model screw() {
  Result<Model> model = read_model(test::shared_data("screw.step"));
  REQUIRE(model.ok());
  model.value().topology = {};
  return std::move(model).value();
}

}  // namespace

TEST_CASE("a face whose trim loop crosses itself fails the export by name, nothing is written",
          "[io][cad][export]") {
  Model model = screw();
  const std::size_t bad = 3;  // a rational face of the screw
  REQUIRE(model.faces[bad].surface.is_rational());
  model.faces[bad] = with_crossing_loop(model.faces[bad]);
  REQUIRE(validate_face(model.faces[bad]).ok());
  test::TempDir dir;
  for (const char* name : {"screw.step", "screw.iges"}) {
    INFO(name);
    const std::filesystem::path path = dir / name;
    test::write_bytes(path, "previous content");
    const Status written = write_model(model, path);
    CHECK(written.code == StatusCode::invalid_surface);
    CHECK_THAT(written.message, Catch::StartsWith(path.string() + ": 1 of 10 faces"));
    CHECK_THAT(written.message, Catch::Contains("face 3 (" + model.faces[bad].source_id +
                                                " \"bow tie\") fails BRepCheck_Analyzer"));
    CHECK_THAT(written.message, Catch::Contains("loop 0 (wire): BRepCheck_SelfIntersectingWire"));
    // Only the bad face is named.
    CHECK_THAT(written.message, !Catch::Contains("face 2"));
    CHECK(test::read_bytes(path) == "previous content");
  }
  // The face as read exports: the defect was the loop.
  model.faces[bad] = screw().faces[bad];
  CHECK(write_model(model, dir / "screw.step").message == "");
}

TEST_CASE("a net collapsed to a point fails the export by name, trimmed or not",
          "[io][cad][export]") {
  Model model = screw();
  model.faces.push_back(test::trimmed_face());
  model.faces[0] = collapsed_to_a_point(model.faces[0]);  // trimmed, from the screw
  model.faces.back() = collapsed_to_a_point(model.faces.back());
  model.faces.back().loops.clear();  // untrimmed
  REQUIRE(validate_face(model.faces[0]).ok());
  REQUIRE(validate_face(model.faces.back()).ok());
  test::TempDir dir;
  const Status written = write_model(model, dir / "collapsed.step");
  CHECK(written.code == StatusCode::invalid_surface);
  CHECK_THAT(written.message, Catch::Contains("2 of 11 faces"));
  CHECK_THAT(written.message, Catch::Contains("face 0 (" + model.faces[0].source_id +
                                              "): loop 0 collapses to a point"));
  CHECK_THAT(
      written.message,
      Catch::Contains("face 10 (test \"asymmetric, trimmed\"): the surface collapses to a point"));
  CHECK_FALSE(std::filesystem::exists(dir / "collapsed.step"));
}

TEST_CASE("the export tolerance is eps, capped by 1e-7 of the model size, at least 1e-7 mm",
          "[io][cad][export]") {
  const Model model = screw();
  const double size = model_box(model).diagonal();
  REQUIRE(size > 10.0);  // so that 1e-7 of it is above OpenCASCADE's 1e-7 mm
  CHECK(export_tolerance(model, 0.0) == kExportRelativeTolerance * size);
  CHECK(export_tolerance(model, 1.0) == kExportRelativeTolerance * size);
  CHECK(export_tolerance(model, 2e-7) == 2e-7);
  CHECK(export_tolerance(model, 1e-12) == kMinExportTolerance);
}

}  // namespace argil::io
