#pragma once
// Internal to argil_io: a model and its topology as one OpenCASCADE B-rep, the
// way the file it came from held it: one edge per topology edge, shared by the
// faces that use it; one vertex per topology vertex; each face's wires from its
// uses in loop order; shells, solids and products as recorded.

#include <TopoDS_Edge.hxx>
#include <TopoDS_Face.hxx>
#include <TopoDS_Shape.hxx>

#include <vector>

#include "argil/core/base/status.hpp"
#include "argil/io/model/model.hpp"

namespace argil::io::detail {

struct BuiltBrep {
  std::vector<TopoDS_Face> faces;  // per model face, oriented as the model says
  std::vector<TopoDS_Edge> edges;  // per topology edge
  /// Per product: a compound of the solids, shells and faces it holds
  /// directly, in the world frame; null when it holds none.
  std::vector<TopoDS_Shape> products;
  /// Solids, shells and faces no product holds, in one compound; null: none.
  TopoDS_Shape unheld;
};

/// Builds the B-rep of `model` (validate_topology(model) holds and
/// uses_placed(model.topology)) at `tolerance_mm` (export_tolerance()):
/// - surfaces exactly as the faces hold them;
/// - an edge's 3D curve is approximated (BRepLib::BuildCurve3d) from its first
///   use; the other uses' pcurves are mapped affinely onto its range and,
///   where they run at another pace (farther than the tolerance from the 3D
///   curve at one parameter), re-parametrised to it by nearest points and
///   interpolation;
/// - a vertex sits at the mean of the points the uses' ends reach, its
///   tolerance covering all of them (and a degenerated edge's whole image);
/// - tolerances are raised to what BRepLib_CheckCurveOnSurface measures, so a
///   face that moved away from its neighbour across a shared edge gets an edge
///   as wide as the gap (the caller reports it).
/// Errors name the edge or face OpenCASCADE could not build.
Result<BuiltBrep> build_occt_brep(const Model& model, double tolerance_mm);

}  // namespace argil::io::detail
