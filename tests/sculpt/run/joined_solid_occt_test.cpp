// A press across an edge of a closed solid, exported, checked by OpenCASCADE:
// the screw_dent example's sphere pressed into the screw's flat end (a disc
// joined to the chamfer along its rim, which the sphere reaches) keeps the
// solid one valid closed shell, and the volume OpenCASCADE measures drops by
// the dent's volume integrated here over the moved faces.
#include <BRepCheck_Analyzer.hxx>
#include <BRepGProp.hxx>
#include <GProp_GProps.hxx>
#include <IFSelect_ReturnStatus.hxx>
#include <STEPControl_Reader.hxx>
#include <ShapeAnalysis_Shell.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS_Shape.hxx>
#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <string>

#include "argil/core/geometry/evaluate.hpp"
#include "argil/core/geometry/trim_region.hpp"
#include "argil/io/files/model_files.hpp"
#include "argil/sculpt/run/session_runner.hpp"

namespace argil::sculpt {
namespace {

namespace fs = std::filesystem;

const fs::path kWork = fs::path(ARGIL_BINARY_DIR) / "joined-solid-test";
const fs::path kScrew = fs::path(ARGIL_SOURCE_DIR) / "tests/data/screw.step";
const fs::path kScene = fs::path(ARGIL_SOURCE_DIR) / "examples/screw_dent/scene.json";

TopoDS_Shape read_step(const fs::path& file) {
  STEPControl_Reader reader;
  REQUIRE(reader.ReadFile(file.c_str()) == IFSelect_RetDone);
  REQUIRE(reader.TransferRoots() > 0);
  return reader.OneShape();
}

int count(const TopoDS_Shape& shape, TopAbs_ShapeEnum kind) {
  int n = 0;
  for (TopExp_Explorer e(shape, kind); e.More(); e.Next()) ++n;
  return n;
}

/// Adaptive integration to 1e-9: the default rule read the screw written by
/// argil 29 mm^3 (0.8%) larger than the same screw as read, more than the dent.
double volume(const TopoDS_Shape& shape) {
  GProp_GProps props;
  BRepGProp::VolumeProperties(shape, props, 1e-9);
  return props.Mass();
}

/// How much the volume bounded by the faces grows when each face moves from
/// `before` to `after`: the integral of the displacement along the face's
/// normal (outward on a closed solid: the surface's normal, reversed for a
/// reversed face) over the trimmed face, a midpoint rule on an n x n grid of
/// its domain. First order in the displacement.
double volume_growth(const io::FaceRecord& before, const io::FaceRecord& after, int n) {
  const BSplineSurface& s0 = before.surface;
  const BSplineSurface& s1 = after.surface;
  const Result<TrimRegion> trim = TrimRegion::create(before.loops);
  REQUIRE(trim.ok());
  const double u0 = s0.domain_start(Direction::u), u1 = s0.domain_end(Direction::u);
  const double v0 = s0.domain_start(Direction::v), v1 = s0.domain_end(Direction::v);
  const double du = (u1 - u0) / n, dv = (v1 - v0) / n;
  double sum = 0.0;
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      const double u = u0 + (i + 0.5) * du, v = v0 + (j + 0.5) * dv;
      if (!trim.value().contains({u, v})) continue;
      const SurfaceDerivatives d = evaluate_derivatives(s0, u, v, 1);
      Eigen::Vector3d area = d.du.cross(d.dv);  // normal times the area element
      if (before.reversed) area = -area;
      sum += (evaluate(s1, u, v) - d.point).dot(area) * du * dv;
    }
  }
  return sum;
}

}  // namespace

TEST_CASE("a press across the screw's rim keeps one valid closed solid, less the dent's volume",
          "[run][joint][occt]") {
  const fs::path out = kWork / "out";
  RunOptions options{.scene = kScene, .out = out, .fresh = true};
  options.outputs = OutputOptions{.step = true,
                                  .iges = false,
                                  .json = true,
                                  .forces = false,
                                  .contacts = false,
                                  .timing = false,
                                  .pictures = false};
  const Result<RunReport> run = run_session(options);
  INFO(run.status().message);
  REQUIRE(run.ok());
  REQUIRE(run.value().failed_outputs.empty());

  const TopoDS_Shape input = read_step(kScrew);
  const TopoDS_Shape sculpted = read_step(out / "screw.step");
  CHECK(count(sculpted, TopAbs_SOLID) == 1);
  CHECK(count(sculpted, TopAbs_SHELL) == 1);
  CHECK(count(sculpted, TopAbs_FACE) == count(input, TopAbs_FACE));
  CHECK(BRepCheck_Analyzer(sculpted).IsValid());
  ShapeAnalysis_Shell shells;
  shells.LoadShells(sculpted);
  shells.CheckOrientedShells(sculpted, true);
  CHECK_FALSE(shells.HasFreeEdges());
  CHECK_FALSE(shells.HasBadEdges());

  // The dent's volume: every face's displacement along its outward normal,
  // integrated over the trimmed face (the faces the joints carried included).
  const Result<io::Model> before = io::read_model(kScrew);
  const Result<io::Model> after = io::read_model(out / "screw.json");
  REQUIRE(before.ok());
  REQUIRE(after.ok());
  REQUIRE(after.value().faces.size() == before.value().faces.size());
  double growth = 0.0;
  for (std::size_t f = 0; f < before.value().faces.size(); ++f)
    growth += volume_growth(before.value().faces[f], after.value().faces[f], 400);
  const double dropped = volume(input) - volume(sculpted);
  CAPTURE(volume(input), dropped, growth);
  // A dent: the volume drops (4.80 mm^3 measured; 4.79 integrated here, the
  // disc 4.32 of it, the chamfer and shank the joints carried 0.48).
  REQUIRE(dropped > 1.0);
  // The integral is first order in the displacement (0.13 mm on a 4 mm disc)
  // and samples trimmed faces on a grid: within 1% of the dent's volume.
  CHECK(std::abs(dropped + growth) <= 0.01 * dropped);
}

}  // namespace argil::sculpt
