// The B-rep argil writes, against what OpenCASCADE's own readers find in the
// input and in the output (tests/support/occt_topology.hpp): a real file
// converted to STEP (and IGES, where it holds solids) keeps its products,
// solids, closed shells and shared edges, reads back valid with no free edge
// on a closed shell, and every surface comes back bit for bit.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstring>
#include <string>

#include "argil/io.hpp"
#include "support/occt_topology.hpp"
#include "test_files.hpp"

namespace argil::io {
namespace {

bool same_bits(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
  return a.rows() == b.rows() && a.cols() == b.cols() &&
         (a.size() == 0 || std::memcmp(a.data(), b.data(),
                                       sizeof(double) * static_cast<std::size_t>(a.size())) == 0);
}

bool same_surface(const BSplineSurface& a, const BSplineSurface& b) {
  return a.degree == b.degree && same_bits(a.knots[0], b.knots[0]) &&
         same_bits(a.knots[1], b.knots[1]) && same_bits(a.control_points, b.control_points) &&
         same_bits(a.weights, b.weights);
}

// Converts `name` to `extension` and compares the output with the input,
// both as OpenCASCADE reads them.
void check_round_trip(const char* name, const char* extension) {
  INFO(name << " -> " << extension);
  test::TempDir dir;
  const std::filesystem::path input = test::shared_data(name);
  const std::filesystem::path output = dir / (std::string("out") + extension);
  const Result<Model> read = read_model(input);
  REQUIRE(read.ok());
  std::vector<std::string> warnings;
  WriteOptions options;
  options.cad.warnings = &warnings;
  const Status written = write_model(read.value(), output, options);
  INFO(written.message);
  REQUIRE(written.ok());
  // Written whole, not as the loose faces of the fallback.
  CHECK(warnings.empty());

  const test::OcctTopology in = test::occt_topology(input);
  const test::OcctTopology out = test::occt_topology(output);
  CHECK(out.valid);
  CHECK(out.faces == in.faces);
  CHECK(out.solids == in.solids);
  CHECK(out.closed_shells == in.closed_shells);
  CHECK(out.shared_edges == in.shared_edges);
  CHECK(out.seam_edges == in.seam_edges);
  CHECK(out.free_edges == in.free_edges);  // none on a closed shell, where the input had none
  // Within the adaptive integration's own accuracy (1e-7 asked, 7e-6 seen on
  // STEP). Through IGES, Ventilator's volume comes back 1.3e-5 off with the
  // same surfaces bit for bit: the faces' boundaries as read from IGES differ.
  const double volume_error = std::string(extension) == ".step" ? 1e-5 : 1e-4;
  if (in.solids > 0) CHECK(out.volume == Approx(in.volume).epsilon(volume_error));

  // argil's own reading of the output: the same B-rep, the same surfaces.
  const Result<Model> back = read_model(output);
  REQUIRE(back.ok());
  const TopologyCounts a = count_topology(read.value().topology);
  const TopologyCounts b = count_topology(back.value().topology);
  CHECK(b.solids == a.solids);
  CHECK(b.closed_shells == a.closed_shells);
  CHECK(b.shared_edges == a.shared_edges);
  CHECK(b.seam_edges == a.seam_edges);
  if (std::string(extension) == ".step") {
    CHECK(b.products == a.products);
    for (std::size_t p = 0; p < std::min(a.products, b.products); ++p) {
      CHECK(back.value().topology.products[p].name == read.value().topology.products[p].name);
    }
  }
  REQUIRE(back.value().faces.size() == read.value().faces.size());
  // Assemblies place their parts: geometry moved into a part's frame and back
  // is equal within rounding, not bit for bit.
  const bool placed = a.products > 1;
  std::size_t same = 0;
  for (std::size_t f = 0; f < read.value().faces.size(); ++f) {
    same += same_surface(back.value().faces[f].surface, read.value().faces[f].surface) ? 1u : 0u;
  }
  if (!placed) CHECK(same == read.value().faces.size());
  // Placed parts: moved into their frames and back, the same poles within rounding.
  const double size = model_box(read.value()).diagonal();
  double worst = 0.0;
  for (std::size_t f = 0; f < read.value().faces.size(); ++f) {
    const ControlNet& before = read.value().faces[f].surface.control_points;
    const ControlNet& after = back.value().faces[f].surface.control_points;
    REQUIRE(before.rows() == after.rows());
    worst = std::max(worst, (before - after).cwiseAbs().maxCoeff());
  }
  CHECK(worst <= 1e-12 * size);
}

TEST_CASE("real solids converted to STEP keep products, solids, closed shells and shared edges",
          "[io][occt][brep]") {
  for (const char* name : {"screw.step", "Ventilator.stp", "as1-oc-214.stp",
                           "face_recognition_sample_part.stp", "sliced_cylinder.step"}) {
    check_round_trip(name, ".step");
  }
}

TEST_CASE("real solids converted to IGES are BRep solids (186) with their shells and edges",
          "[io][occt][brep]") {
  for (const char* name :
       {"screw.step", "sliced_cylinder.step", "face_recognition_sample_part.stp"}) {
    check_round_trip(name, ".igs");
  }
}

#ifndef ARGIL_SANITIZED_BUILD
TEST_CASE("a larger solid and an assembly converted to IGES keep their solids and edges",
          "[io][occt][brep]") {
  for (const char* name : {"Ventilator.stp", "as1-oc-214.stp"}) check_round_trip(name, ".igs");
}
#endif

TEST_CASE("loose IGES faces convert to STEP and IGES as loose faces", "[io][occt][brep]") {
  for (const char* name : {"bearing.iges", "surf114.igs"}) {
    check_round_trip(name, ".step");
    check_round_trip(name, ".igs");
  }
}

// Writes `model` to `file` with eps 0.005 mm; returns the warnings it gave.
std::vector<std::string> write_at_5um(const Model& model, const std::filesystem::path& file) {
  std::vector<std::string> warnings;
  WriteOptions options;
  options.cad.tolerance_mm = 0.005;
  options.cad.warnings = &warnings;
  const Status written = write_model(model, file, options);
  INFO(written.message);
  REQUIRE(written.ok());
  return warnings;
}

TEST_CASE("a face moved off its neighbours exports as a solid whose open edges are reported",
          "[io][occt][brep]") {
  const Result<Model> read = read_model(test::shared_data("screw.step"));
  REQUIRE(read.ok());
  Model model = read.value();
  // The bottom disc lowered by 0.05 mm, ten times eps: its edge opens.
  model.faces[9].surface.control_points.col(2).array() -= 0.05;
  test::TempDir dir;
  const std::vector<std::string> warnings = write_at_5um(model, dir / "opened.step");
  REQUIRE(warnings.size() == 1);
  CHECK_THAT(warnings[0], Catch::Contains("shared edges are open wider than eps (0.005 mm)"));
  CHECK_THAT(warnings[0], Catch::Contains("face 9"));
  const test::OcctTopology out = test::occt_topology(dir / "opened.step");
  CHECK(out.valid);
  CHECK(out.solids == 1);
  CHECK(out.faces == 10);
  // As read, nothing is open at the same eps.
  CHECK(write_at_5um(read.value(), dir / "closed.step").empty());
}

TEST_CASE("a placement that is not a rotation and a translation is refused by name",
          "[io][topology][bad]") {
  const Result<Model> read = read_model(test::shared_data("as1-oc-214.stp"));
  REQUIRE(read.ok());
  Model model = read.value();
  REQUIRE(model.topology.products.size() > 1);
  model.topology.products[1].placement.col(0) *= -1.0;  // a mirror
  const Status status = validate_topology(model);
  CHECK_FALSE(status.ok());
  CHECK_THAT(status.message,
             Catch::Contains("products[1].placement: not a rotation and a translation"));
}

TEST_CASE("11752.stp (1018 faces) converts to one product with one valid closed solid",
          "[io][occt][brep][slow]") {
  check_round_trip("11752.stp", ".step");
}

TEST_CASE("11752.stp's faces on closed surfaces, moved 2 um, export as one valid solid",
          "[io][occt][brep][slow]") {
  const Result<Model> read = read_model(test::shared_data("11752.stp"));
  REQUIRE(read.ok());
  Model model = read.value();
  // A smooth field of the position, as a sculpt moves them: the poles a seam
  // shares move alike, and every face on a cylinder or torus moves, among them
  // the 13 whose seams OpenCASCADE's conversion puts inside the domain.
  const double size = model_box(model).diagonal();
  std::size_t moved = 0;
  for (FaceRecord& face : model.faces) {
    BSplineSurface& s = face.surface;
    const auto coincide = [&](Eigen::Index a, Eigen::Index b) {
      return (s.control_points.row(a) - s.control_points.row(b)).norm() <= 1e-9 * size;
    };
    const int nu = s.count(Direction::u), nv = s.count(Direction::v);
    const bool closed = coincide(s.pole_index(0, 0), s.pole_index(nu - 1, 0)) ||
                        coincide(s.pole_index(0, 0), s.pole_index(0, nv - 1));
    if (!closed) continue;
    ++moved;
    for (Eigen::Index row = 0; row < s.control_points.rows(); ++row) {
      const Eigen::Vector3d p = s.control_points.row(row);
      s.control_points.row(row) +=
          2e-3 * Eigen::RowVector3d(std::sin(p.y() / 3), std::cos(p.z() / 5), std::sin(p.x() / 7));
    }
  }
  CHECK(moved >= 13);
  test::TempDir dir;
  std::vector<std::string> warnings;
  WriteOptions options;
  options.cad.tolerance_mm = 0.02;
  options.cad.warnings = &warnings;
  const Status written = write_model(model, dir / "moved.step", options);
  INFO(written.message);
  REQUIRE(written.ok());
  // Written whole: before, face 913 read back with its wire open, and the
  // export fell back to loose faces.
  std::string heard;
  for (const std::string& w : warnings) heard += w + "\n";
  INFO(heard);
  CHECK(warnings.empty());
  const test::OcctTopology out = test::occt_topology(dir / "moved.step");
  CHECK(out.valid);
  CHECK(out.solids == 1);
  CHECK(out.faces == 1018);
}

TEST_CASE("a B-rep torn apart is written face by face, and the warning says which write failed",
          "[io][occt][brep]") {
  const Result<Model> read = read_model(test::shared_data("screw.step"));
  REQUIRE(read.ok());
  Model model = read.value();
  // The shank moved 20 mm and stretched: its neighbour's wire no longer
  // closes, so the solid fails its read-back and the faces go alone.
  model.faces[5].surface.control_points.col(2).array() -= 20.0;
  model.faces[5].surface.control_points.col(0).array() *= 1.5;
  test::TempDir dir;
  const std::vector<std::string> warnings = write_at_5um(model, dir / "torn.step");
  REQUIRE(warnings.size() == 1);
  INFO(warnings[0]);
  CHECK_THAT(warnings[0], Catch::Contains("the B-rep could not be written whole (1 of 10 faces "
                                          "do not read back valid: face 6"));
  CHECK_THAT(warnings[0], Catch::EndsWith("its faces were written one by one instead (no shared "
                                          "edges, shells or solids), and every one of them reads "
                                          "back valid"));
  const test::OcctTopology out = test::occt_topology(dir / "torn.step");
  CHECK(out.solids == 0);
  CHECK(out.faces == 10);
}

}  // namespace
}  // namespace argil::io
