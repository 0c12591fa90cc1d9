#pragma once
// Internal to argil_io: one FaceRecord as an OpenCASCADE face for export. The
// face keeps the record's (u, v) trims whatever its control points did, so
// everything 3D (edge curves, vertices, tolerances) is derived here from the
// surface as it is now.

#include <TopoDS_Edge.hxx>
#include <TopoDS_Face.hxx>

#include <cstddef>
#include <vector>

#include "argil/core/base/status.hpp"
#include "argil/io/model/model.hpp"

namespace argil::io::detail {

/// Which trim curve an edge of a built face came from, for messages.
struct EdgeOrigin {
  TopoDS_Edge edge;
  std::size_t loop = 0;
  std::size_t curve = 0;
};

/// A face for the STEP and IGES writers, not yet checked by BRepCheck_Analyzer.
struct BuiltFace {
  TopoDS_Face face;
  std::vector<EdgeOrigin> origins;  // trimmed records: one per trim curve
};

/// Builds the face of `record` (which validate_face() accepts) at `tolerance_mm`
/// (export_tolerance()):
/// - untrimmed: the surface bounded by its domain, exact iso-parametric edges;
/// - trimmed: one edge per trim curve from its pcurve, a vertex per loop corner
///   (corners at one 3D point within the vertices' tolerances share it), 3D
///   curves by BRepLib::BuildCurves3d at the tolerance; only when that face
///   fails BRepCheck_Analyzer, the same passed through ShapeFix_Face, kept if it
///   passes;
/// - sides and trim curves whose 3D image lies within 1e-7 mm of a point
///   (OpenCASCADE's Precision::Confusion()) are degenerated edges;
/// - every edge's tolerance raised to the largest distance between its 3D curve
///   and its pcurve on the surface (BRepLib_CheckCurveOnSurface), every vertex's
///   to cover the edge ends it joins (BRepLib::UpdateTolerances).
/// The face is not checked here (face_defects() does). Errors: a trim curve
/// OpenCASCADE makes no edge of, loops that make no face, a loop or surface that
/// collapses to a point; the message names the loop and curve, not the face.
Result<BuiltFace> build_occt_face(const FaceRecord& record, double tolerance_mm);

/// The trimmed face of `record` for OpenCASCADE's mesher, which discretizes
/// edges along their pcurves on the surface: one edge per trim curve and a
/// vertex per loop corner as build_occt_face() makes them, but no 3D curves,
/// tolerance updates, checks or fixing (a tenth of the time). Errors as
/// build_occt_face() gives them for trimmed records.
Result<TopoDS_Face> build_occt_mesh_face(const FaceRecord& record, double tolerance_mm);

/// Raises every edge tolerance of `face` to at least `tolerance_mm` and to the
/// largest distance between its 3D curve and its pcurve on the face's surface
/// (BRepLib_CheckCurveOnSurface), then every vertex's to cover the edge ends
/// it joins (BRepLib::UpdateTolerances).
void update_tolerances(const TopoDS_Face& face, double tolerance_mm);

}  // namespace argil::io::detail
