#include "argil/io/cad/detail/occt_face_builder.hpp"

#include <BRepBuilderAPI_MakeEdge.hxx>
#include <BRepBuilderAPI_MakeFace.hxx>
#include <BRepCheck_Analyzer.hxx>
#include <BRepLib.hxx>
#include <BRepLib_CheckCurveOnSurface.hxx>
#include <BRep_Builder.hxx>
#include <BRep_Tool.hxx>
#include <Geom2d_BSplineCurve.hxx>
#include <Geom_BSplineSurface.hxx>
#include <ShapeFix_Face.hxx>
#include <TColStd_Array1OfInteger.hxx>
#include <TColStd_Array1OfReal.hxx>
#include <TColStd_Array2OfReal.hxx>
#include <TColgp_Array1OfPnt2d.hxx>
#include <TColgp_Array2OfPnt.hxx>
#include <TopExp_Explorer.hxx>
#include <TopLoc_Location.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Vertex.hxx>
#include <TopoDS_Wire.hxx>

#include <algorithm>
#include <cmath>
#include <string>

#include "argil/core/base/number_text.hpp"
#include "argil/io/cad/detail/occt_geometry.hpp"

namespace argil::io::detail {
namespace {

// ShapeFix may raise a tolerance up to this many export tolerances (closing a
// loop whose corner gaps it has to bridge); beyond that a defect is reported.
constexpr double kMaxFixTolerances = 1e3;

// A trim curve or domain side whose 3D image lies within this of a point is a
// degenerated edge. Fixed, not the export tolerance: the STEP writer drops
// degenerated edges and readers rebuild them where a wire's 3D gap is below
// their precision, Precision::Confusion() unless the file says otherwise; a
// longer collapsed side is kept as a (short) real edge, which every reader keeps.
constexpr double kDegenerateLength = 1e-7;  // [mm], Precision::Confusion()

gp_Pnt surface_point(const Handle(Geom_BSplineSurface) & s, const gp_Pnt2d& uv) {
  return s->Value(uv.X(), uv.Y());
}

// The largest distance of the curve's 3D image from its start, sampled densely
// enough to see every span of curve and surface: a curve within the tolerance of
// one point (a pole, a collapsed side) is a degenerated edge in OCCT.
double spread_from_start(const Handle(Geom2d_BSplineCurve) & curve,
                         const Handle(Geom_BSplineSurface) & surface) {
  const gp_Pnt start = surface_point(surface, curve->StartPoint());
  const int samples = 4 * (curve->NbPoles() + surface->NbUPoles() + surface->NbVPoles());
  const double t0 = curve->FirstParameter(), t1 = curve->LastParameter();
  double spread = 0.0;
  for (int k = 1; k <= samples; ++k) {
    const double t = t0 + (t1 - t0) * k / samples;
    spread = std::max(spread, start.Distance(surface_point(surface, curve->Value(t))));
  }
  return spread;
}

std::string curve_label(std::size_t loop, std::size_t curve) {
  return "loop " + std::to_string(loop) + " curve " + std::to_string(curve);
}

std::string edge_error_name(BRepBuilderAPI_EdgeError error) {
  switch (error) {
    case BRepBuilderAPI_EdgeDone:
      return "done";
    case BRepBuilderAPI_PointProjectionFailed:
      return "point projection failed";
    case BRepBuilderAPI_ParameterOutOfRange:
      return "parameter out of range";
    case BRepBuilderAPI_DifferentPointsOnClosedCurve:
      return "different points on a closed curve";
    case BRepBuilderAPI_PointWithInfiniteParameter:
      return "point with infinite parameter";
    case BRepBuilderAPI_DifferentsPointAndParameter:
      return "vertex and parameter disagree";
    case BRepBuilderAPI_LineThroughIdenticPoints:
      return "line through identical points";
  }
  return "error " + std::to_string(static_cast<int>(error));
}

std::string face_error_name(BRepBuilderAPI_FaceError error) {
  switch (error) {
    case BRepBuilderAPI_FaceDone:
      return "done";
    case BRepBuilderAPI_NoFace:
      return "no face";
    case BRepBuilderAPI_NotPlanar:
      return "not planar";
    case BRepBuilderAPI_CurveProjectionFailed:
      return "curve projection failed";
    case BRepBuilderAPI_ParametersOutOfRange:
      return "parameters out of range";
  }
  return "error " + std::to_string(static_cast<int>(error));
}

// A wire through the loop's pcurves (no 3D curves yet). Consecutive curves share
// one vertex at the middle of their 3D ends, with a tolerance covering the gap.
Result<TopoDS_Wire> make_wire(const TrimLoop& loop, std::size_t loop_index,
                              const Handle(Geom_BSplineSurface) & surface, double tolerance,
                              std::vector<EdgeOrigin>& origins) {
  BRep_Builder builder;
  std::vector<Handle(Geom2d_BSplineCurve)> curves;
  for (const TrimCurve& c : loop.curves) curves.push_back(to_occt(c));
  const std::size_t n = curves.size();
  std::vector<gp_Pnt> positions(n);
  std::vector<double> vertex_tolerances(n);
  for (std::size_t k = 0; k < n; ++k) {
    const gp_Pnt start = surface_point(surface, curves[k]->StartPoint());
    const gp_Pnt previous_end = surface_point(surface, curves[(k + n - 1) % n]->EndPoint());
    positions[k] = gp_Pnt((start.XYZ() + previous_end.XYZ()) * 0.5);
    vertex_tolerances[k] = std::max(tolerance, 0.6 * start.Distance(previous_end));
  }
  std::vector<bool> degenerate(n);
  for (std::size_t k = 0; k < n; ++k) {
    const double spread = spread_from_start(curves[k], surface);
    degenerate[k] = spread <= kDegenerateLength;
    if (degenerate[k]) {
      // Both vertices of a degenerated edge must cover the whole collapsed image.
      vertex_tolerances[k] = std::max(vertex_tolerances[k], spread);
      vertex_tolerances[(k + 1) % n] = std::max(vertex_tolerances[(k + 1) % n], spread);
    }
  }
  // Loop corners at one 3D point are one vertex: the ends of a curve closed in 3D
  // (a full circle, a collapsed side) and the two ends of a seam.
  std::vector<TopoDS_Vertex> vertices(n);
  std::vector<std::size_t> owner(n);
  for (std::size_t k = 0; k < n; ++k) {
    owner[k] = k;
    for (std::size_t j = 0; j < k; ++j) {
      if (owner[j] != j) continue;
      const double reach = std::max(vertex_tolerances[k], vertex_tolerances[j]);
      if (positions[k].Distance(positions[j]) <= reach) {
        owner[k] = j;
        vertex_tolerances[j] = std::max(vertex_tolerances[j],
                                        positions[k].Distance(positions[j]) + vertex_tolerances[k]);
        break;
      }
    }
  }
  for (std::size_t k = 0; k < n; ++k) {
    if (owner[k] == k) builder.MakeVertex(vertices[k], positions[k], vertex_tolerances[k]);
  }
  for (std::size_t k = 0; k < n; ++k) vertices[k] = vertices[owner[k]];

  // The STEP writer drops degenerated edges: a loop of nothing else would be empty.
  if (std::all_of(degenerate.begin(), degenerate.end(), [](bool d) { return d; })) {
    return Status::error(StatusCode::invalid_surface,
                         "loop " + std::to_string(loop_index) +
                             " collapses to a point: every trim curve maps within " +
                             number_text(kDegenerateLength) + " mm of one point");
  }
  TopoDS_Wire wire;
  builder.MakeWire(wire);
  for (std::size_t k = 0; k < n; ++k) {
    const TopoDS_Vertex& first = vertices[k];
    const TopoDS_Vertex& last = vertices[(k + 1) % n];
    TopoDS_Edge edge;
    if (degenerate[k]) {
      builder.MakeEdge(edge);
      builder.UpdateEdge(edge, curves[k], surface, TopLoc_Location(), tolerance);
      builder.Degenerated(edge, true);
      builder.Add(edge, first.Oriented(TopAbs_FORWARD));
      builder.Add(edge, last.Oriented(TopAbs_REVERSED));
      builder.Range(edge, curves[k]->FirstParameter(), curves[k]->LastParameter());
    } else {
      BRepBuilderAPI_MakeEdge make(curves[k], surface, first, last, curves[k]->FirstParameter(),
                                   curves[k]->LastParameter());
      if (!make.IsDone()) {
        return Status::error(
            StatusCode::invalid_surface,
            curve_label(loop_index, k) + " gives no edge (" + edge_error_name(make.Error()) + ")");
      }
      edge = make.Edge();
      builder.UpdateEdge(edge, tolerance);
    }
    origins.push_back({edge, loop_index, k});
    builder.Add(wire, edge);
  }
  wire.Closed(true);
  return wire;
}

bool has_real_edge(const TopoDS_Face& face) {
  for (TopExp_Explorer e(face, TopAbs_EDGE); e.More(); e.Next()) {
    if (!BRep_Tool::Degenerated(TopoDS::Edge(e.Current()))) return true;
  }
  return false;
}

// The trimmed face with 3D edge curves and measured tolerances; ShapeFix_Face
// on top when `fix`.
Result<BuiltFace> trimmed_face(const FaceRecord& record,
                               const Handle(Geom_BSplineSurface) & surface, double tolerance,
                               bool fix) {
  BuiltFace built;
  std::vector<TopoDS_Wire> wires;
  for (std::size_t l = 0; l < record.loops.size(); ++l) {
    Result<TopoDS_Wire> wire = make_wire(record.loops[l], l, surface, tolerance, built.origins);
    if (!wire.ok()) return wire.status();
    wires.push_back(wire.value());
  }
  BRepBuilderAPI_MakeFace make(surface, wires.front(), true);
  for (std::size_t w = 1; w < wires.size() && make.IsDone(); ++w) make.Add(wires[w]);
  if (!make.IsDone()) {
    return Status::error(StatusCode::invalid_surface,
                         "the trim loops give no face (" + face_error_name(make.Error()) + ")");
  }
  built.face = make.Face();
  // A failed approximation leaves its edge without a 3D curve: BRepCheck_Analyzer
  // then reports it (No3DCurve) by the edge's trim curve.
  BRepLib::BuildCurves3d(built.face, tolerance);
  if (fix) {
    ShapeFix_Face fixer(built.face);
    fixer.SetPrecision(tolerance);
    fixer.SetMinTolerance(tolerance);
    fixer.SetMaxTolerance(tolerance * kMaxFixTolerances);
    fixer.Perform();
    built.face = fixer.Face();
  }
  update_tolerances(built.face, tolerance);
  return built;
}

}  // namespace

// Edges: tolerance at least the export tolerance and the largest distance
// between the 3D curve and the pcurve on the surface (an approximated 3D curve
// is only as close as the approximation got; an exact one rounds at the size of
// the coordinates). Vertices: cover the edge ends they join.
void update_tolerances(const TopoDS_Face& face, double tolerance) {
  BRep_Builder builder;
  for (TopExp_Explorer e(face, TopAbs_EDGE); e.More(); e.Next()) {
    const TopoDS_Edge& edge = TopoDS::Edge(e.Current());
    builder.UpdateEdge(edge, std::max(tolerance, BRep_Tool::Tolerance(edge)));
    if (BRep_Tool::Degenerated(edge)) continue;
    BRepLib_CheckCurveOnSurface check(edge, face);
    check.Perform();
    if (!check.IsDone()) continue;  // BRepCheck_Analyzer then reports the edge
    // Margin for the rounding of the checker's own evaluation.
    const double deviation = check.MaxDistance() * (1.0 + 1e-6);
    if (deviation > BRep_Tool::Tolerance(edge)) builder.UpdateEdge(edge, deviation);
  }
  BRepLib::UpdateTolerances(face);
}

Result<BuiltFace> build_occt_face(const FaceRecord& record, double tolerance_mm) {
  const Handle(Geom_BSplineSurface) surface = to_occt(record.surface);
  Result<BuiltFace> built = BuiltFace{};
  if (!record.trimmed()) {
    // Iso-parametric 3D curves along the domain's sides: exact, no approximation.
    BRepBuilderAPI_MakeFace make(surface, kDegenerateLength);
    if (!make.IsDone()) {
      return Status::error(StatusCode::invalid_surface,
                           "the surface gives no face (" + face_error_name(make.Error()) + ")");
    }
    built.value().face = make.Face();
    if (!has_real_edge(built.value().face)) {
      return Status::error(
          StatusCode::invalid_surface,
          "the surface collapses to a point: every side of its domain maps within " +
              number_text(kDegenerateLength) + " mm of one point");
    }
    update_tolerances(built.value().face, tolerance_mm);
  } else {
    // One edge per trim curve as built keeps the trims as they are; ShapeFix_Face
    // (seams, small edges, gaps) runs only on a face that fails BRepCheck that
    // way, and its result is kept only when it passes: on a face with a
    // near-collapsed side it can open a closed wire.
    built = trimmed_face(record, surface, tolerance_mm, false);
    if (built.ok() && !BRepCheck_Analyzer(built.value().face).IsValid()) {
      Result<BuiltFace> fixed = trimmed_face(record, surface, tolerance_mm, true);
      if (fixed.ok() && BRepCheck_Analyzer(fixed.value().face).IsValid()) built = std::move(fixed);
    }
    if (!built.ok()) return built;
  }
  if (record.reversed) built.value().face.Reverse();
  return built;
}

Result<TopoDS_Face> build_occt_mesh_face(const FaceRecord& record, double tolerance_mm) {
  const Handle(Geom_BSplineSurface) surface = to_occt(record.surface);
  std::vector<EdgeOrigin> origins;
  std::vector<TopoDS_Wire> wires;
  for (std::size_t l = 0; l < record.loops.size(); ++l) {
    Result<TopoDS_Wire> wire = make_wire(record.loops[l], l, surface, tolerance_mm, origins);
    if (!wire.ok()) return wire.status();
    wires.push_back(wire.value());
  }
  if (wires.empty())
    return Status::error(StatusCode::invalid_argument, "the face has no trim loop");
  BRepBuilderAPI_MakeFace make(surface, wires.front(), true);
  for (std::size_t w = 1; w < wires.size() && make.IsDone(); ++w) make.Add(wires[w]);
  if (!make.IsDone()) {
    return Status::error(StatusCode::invalid_surface,
                         "the trim loops give no face (" + face_error_name(make.Error()) + ")");
  }
  TopoDS_Face face = make.Face();
  BRepLib::BuildCurves3d(face, tolerance_mm);
  return face;
}

}  // namespace argil::io::detail
