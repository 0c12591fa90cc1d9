#pragma once
// The IO data model: a CAD model as a list of sculptable faces. Each face is a
// B-spline surface plus its trim loops in that surface's parameter space, so the
// trims stay valid while the control points move.

#include <Eigen/Core>
#include <map>
#include <string>
#include <vector>

#include "argil/core/geometry/bspline_curve.hpp"
#include "argil/core/geometry/bspline_surface.hpp"
#include "argil/core/geometry/trim_region.hpp"
#include "argil/io/model/topology.hpp"

namespace argil::io {

/// A planar B-spline or NURBS curve in a surface's (u, v) parameter space:
/// a BSplineCurve whose points have two columns, (u, v).
using TrimCurve = BSplineCurve;

/// A closed chain of trim curves, each starting where the previous one ends
/// (within kMaxTrimGapRatio of the loop). The outer loop runs counter-clockwise
/// in (u, v), inner loops (holes) clockwise, so the kept region is on the left
/// of every curve. The core's type: argil::TrimRegion is built from these.
using TrimLoop = argil::TrimLoop;

/// One face of a CAD model, ready to sculpt.
struct FaceRecord {
  BSplineSurface surface;       // control points in [mm]
  std::vector<TrimLoop> loops;  // empty: the whole surface domain is the face
  bool reversed = false;        // the face normal is -S_u x S_v
  std::string source_id;        // entity in the source file: "#123" (STEP), "D45" (IGES)
  std::string name;             // entity name or label from the source, may be empty

  bool trimmed() const { return !loops.empty(); }
};

/// The unit a file declared. Argil always holds lengths in millimetres; this
/// records where they came from: source value * to_mm = stored value [mm].
struct SourceUnit {
  std::string name = "mm";
  double to_mm = 1.0;
};

/// A set of faces with units, the B-rep that joins them (empty for loose
/// faces), free-form metadata (key -> text) and what the reader recovered
/// from (a file's quirks that did not stop it: one line each).
struct Model {
  SourceUnit source_unit;
  std::vector<FaceRecord> faces;
  Topology topology;
  std::map<std::string, std::string> metadata;
  std::vector<std::string> warnings;
};

/// Axis-aligned box of all control points of all faces [mm]; encloses the
/// model (convex hull property). An empty model gives a zero box at the origin.
Box3 model_box(const Model& model);

}  // namespace argil::io
