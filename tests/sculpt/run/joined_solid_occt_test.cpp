// A press across an edge of a closed solid, exported, checked by OpenCASCADE:
// the screw_dent example's sphere pressed into the screw's flat end (a disc
// joined to the chamfer along its rim, which the sphere reaches) keeps the
// solid one valid closed shell, and the volume OpenCASCADE measures drops by
// the dent's volume integrated here over the moved faces.
#include <BRepAdaptor_Surface.hxx>
#include <BRepBuilderAPI_NurbsConvert.hxx>
#include <BRepCheck_Analyzer.hxx>
#include <BRepGProp.hxx>
#include <BRepLProp_SLProps.hxx>
#include <BRepPrimAPI_MakeBox.hxx>
#include <BRep_Tool.hxx>
#include <GProp_GProps.hxx>
#include <Geom2d_Curve.hxx>
#include <IFSelect_ReturnStatus.hxx>
#include <STEPControl_Reader.hxx>
#include <STEPControl_Writer.hxx>
#include <ShapeAnalysis_Shell.hxx>
#include <TopExp.hxx>
#include <TopExp_Explorer.hxx>
#include <TopTools_IndexedDataMapOfShapeListOfShape.hxx>
#include <TopTools_ListOfShape.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Edge.hxx>
#include <TopoDS_Face.hxx>
#include <TopoDS_Shape.hxx>
#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <string>

#include "argil/core/deform/edge_joint.hpp"
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

/// Runs `scene` into `out`, writing only STEP and JSON; every output written.
void run_to_step_and_json(const fs::path& scene, const fs::path& out) {
  RunOptions options{.scene = scene, .out = out, .fresh = true};
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
}

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

/// The widest edge tolerance of `shape` [mm]: the exporter grows an edge's
/// tolerance to cover the gap between its faces (BRepLib_CheckCurveOnSurface).
double widest_edge_tolerance(const TopoDS_Shape& shape) {
  double widest = 0.0;
  for (TopExp_Explorer e(shape, TopAbs_EDGE); e.More(); e.Next())
    widest = std::max(widest, BRep_Tool::Tolerance(TopoDS::Edge(e.Current())));
  return widest;
}

/// The angle between the normals of the two faces along each edge they share
/// (as lines), at 17 points of the edge's pcurves: per edge, in the order of
/// the shape's edge map, each sample's angle [rad].
std::vector<std::vector<double>> edge_angles(const TopoDS_Shape& shape) {
  TopTools_IndexedDataMapOfShapeListOfShape faces_of;
  TopExp::MapShapesAndUniqueAncestors(shape, TopAbs_EDGE, TopAbs_FACE, faces_of);
  std::vector<std::vector<double>> out;
  for (int k = 1; k <= faces_of.Extent(); ++k) {
    const TopoDS_Edge& edge = TopoDS::Edge(faces_of.FindKey(k));
    const TopTools_ListOfShape& faces = faces_of.FindFromIndex(k);
    if (faces.Extent() != 2) continue;
    const TopoDS_Face& a = TopoDS::Face(faces.First());
    const TopoDS_Face& b = TopoDS::Face(faces.Last());
    double first = 0.0, last = 0.0;
    const Handle(Geom2d_Curve) on_a = BRep_Tool::CurveOnSurface(edge, a, first, last);
    double first_b = 0.0, last_b = 0.0;
    const Handle(Geom2d_Curve) on_b = BRep_Tool::CurveOnSurface(edge, b, first_b, last_b);
    REQUIRE(!on_a.IsNull());
    REQUIRE(!on_b.IsNull());
    std::vector<double> angles;
    for (int i = 0; i <= 16; ++i) {
      const double t = first + (last - first) * i / 16.0;
      const gp_Pnt2d pa = on_a->Value(t), pb = on_b->Value(t);
      BRepLProp_SLProps la(BRepAdaptor_Surface(a), pa.X(), pa.Y(), 1, 1e-9);
      BRepLProp_SLProps lb(BRepAdaptor_Surface(b), pb.X(), pb.Y(), 1, 1e-9);
      REQUIRE(la.IsNormalDefined());
      REQUIRE(lb.IsNormalDefined());
      const gp_Vec na(la.Normal()), nb(lb.Normal());
      angles.push_back(std::atan2(na.Crossed(nb).Magnitude(), std::abs(na.Dot(nb))));
    }
    out.push_back(angles);
  }
  return out;
}

/// A 20 mm box made by OpenCASCADE, its planes converted to B-splines, as a STEP file.
void write_box(const fs::path& file) {
  const TopoDS_Shape box = BRepPrimAPI_MakeBox(20.0, 20.0, 20.0).Shape();
  BRepBuilderAPI_NurbsConvert convert(box);
  STEPControl_Writer writer;
  REQUIRE(writer.Transfer(convert.Shape(), STEPControl_AsIs) == IFSelect_RetDone);
  REQUIRE(writer.Write(file.c_str()) == IFSelect_RetDone);
}

/// A scene pressing a sphere (r = 3 mm) 0.8 mm into the box's edge along
/// x = y = 0, from outside along the diagonal between its two faces.
void write_box_scene(const fs::path& dir) {
  std::ofstream scene(dir / "scene.json");
  scene << R"({ "format": "argil.scene", "version": 2, "tolerance": 0.005,
    "coupling": { "stiffness": 1.0, "damping": 0.0, "max_force": 5.0 },
    "models": [ { "name": "box", "file": "box.step", "faces": "all", "kind": "deformable",
                  "material": "clay" } ],
    "tools": [ { "name": "ball", "type": "sphere", "radius": 3 } ],
    "script": "press.json" })";
  const double out = std::numbers::sqrt2 / 2.0;  // along the diagonal, per mm
  const auto at = [&](double distance) {
    return "[" + std::to_string(-out * distance) + ", " + std::to_string(-out * distance) +
           ", 10.0]";
  };
  std::ofstream script(dir / "press.json");
  script << R"({ "format": "argil.script", "version": 1, "tool": "ball", "keyframes": [
    { "t": 0.0, "position": )"
         << at(8.0) << R"( },
    { "t": 0.2, "position": )"
         << at(3.5) << R"(, "event": "engage" },
    { "t": 0.8, "position": )"
         << at(2.2) << R"( },
    { "t": 1.1, "position": )"
         << at(2.2) << R"( },
    { "t": 1.3, "position": )"
         << at(4.0) << R"(, "event": "release" },
    { "t": 1.5, "position": )"
         << at(8.0) << R"( } ] })";
}

}  // namespace

TEST_CASE(
    "a press across the edge of a box keeps one valid closed solid, its crease, less the "
    "dent's volume",
    "[run][joint][occt]") {
  const fs::path dir = kWork / "box";
  fs::create_directories(dir);
  write_box(dir / "box.step");
  write_box_scene(dir);
  run_to_step_and_json(dir / "scene.json", dir / "out");

  const TopoDS_Shape input = read_step(dir / "box.step");
  const TopoDS_Shape sculpted = read_step(dir / "out" / "box.step");
  CHECK(count(sculpted, TopAbs_SOLID) == 1);
  CHECK(count(sculpted, TopAbs_FACE) == 6);
  CHECK(BRepCheck_Analyzer(sculpted).IsValid());
  ShapeAnalysis_Shell shells;
  shells.LoadShells(sculpted);
  shells.CheckOrientedShells(sculpted, true);
  CHECK_FALSE(shells.HasFreeEdges());
  // The faces stayed within eps of each other along every edge.
  CHECK(widest_edge_tolerance(sculpted) <= 0.005);
  // Every edge stays a right-angled crease, within kTangentJoinAngle.
  const std::vector<std::vector<double>> angles = edge_angles(sculpted);
  REQUIRE(angles.size() == 12);
  double worst = 0.0;
  for (const std::vector<double>& edge : angles)
    for (const double a : edge) worst = std::max(worst, std::abs(a - std::numbers::pi / 2));
  CAPTURE(worst);
  CHECK(worst <= kTangentJoinAngle);

  const Result<io::Model> before = io::read_model(dir / "box.step");
  const Result<io::Model> after = io::read_model(dir / "out" / "box.json");
  REQUIRE(before.ok());
  REQUIRE(after.ok());
  REQUIRE(after.value().faces.size() == before.value().faces.size());
  double growth = 0.0;
  int moved = 0;
  for (std::size_t f = 0; f < before.value().faces.size(); ++f) {
    const double g = volume_growth(before.value().faces[f], after.value().faces[f], 400);
    growth += g;
    if (std::abs(g) > 1e-3) ++moved;
  }
  const double dropped = volume(input) - volume(sculpted);
  CAPTURE(volume(input), dropped, growth, moved);
  // Both faces either side of the edge took the dent.
  CHECK(moved >= 2);
  REQUIRE(dropped > 0.1);
  CHECK(std::abs(dropped + growth) <= 0.02 * dropped);
}

TEST_CASE("a press across the screw's rim keeps one valid closed solid, less the dent's volume",
          "[run][joint][occt]") {
  const fs::path out = kWork / "out";
  run_to_step_and_json(kScene, out);

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
  CHECK(widest_edge_tolerance(sculpted) <= 0.005);

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
