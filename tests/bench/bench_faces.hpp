#pragma once
// Faces the haptic-loop benchmark deforms: synthetic panels and plates, real
// faces read from STEP/IGES through argil::io, and their exact refinement.

#include <filesystem>
#include <string>
#include <vector>

#include "argil/core.hpp"
#include "argil/io.hpp"

namespace argil::bench {

/// A face to deform, with what the tables say about it.
struct BenchFace {
  std::string name;  // "bearing.iges face 65", "C0 plate"
  BSplineSurface surface;
  bool reversed = false;  // the outward normal is -S_u x S_v
  std::string origin;     // "index 161, source D4185, degree 5x3, 6x4 poles, trimmed ..."
};

/// A flat bicubic panel, n x n poles on a `pitch` grid in z = 0.
BSplineSurface flat_panel(int n, double pitch);

/// The high-degree C0 plate, 20 x 20 mm: degree 1 x 10, knots_v = [0 x11,
/// 0.5 x10, 1 x11] (a C0 knot line at v = 0.5), poles (20 i, j, 0) for
/// i = 0..1, j = 0..20 (the deformation tests' plate, tests/support).
BSplineSurface c0_plate();

/// `surface` with every non-empty knot span halved `levels` times by exact
/// knot insertion, in u and in v: the same surface and parametrisation on a
/// finer net (the deformation tests' refinement, tests/support).
BSplineSurface refine_midpoints(const BSplineSurface& surface, int levels);

/// "d_u x d_v, n_u x n_v poles, rational" for the tables.
std::string net_text(const BSplineSurface& surface);

/// The size tolerances and strokes scale with: the control-point box diagonal [mm].
double face_size(const BSplineSurface& surface);

/// Indices of the faces with interior control points (at least 3 poles each
/// way), polynomial or rational as asked, largest control net first; ties go
/// to the lowest index.
std::vector<int> faces_by_net_size(const io::Model& model, bool rational);

/// The face at `index` of `model`, named after `file`.
BenchFace model_face(const io::Model& model, int index, const std::string& file);

/// Reads a CAD file of the benchmark data; prints and returns the error when
/// it does not import.
Result<io::Model> read_bench_model(const std::filesystem::path& path);

}  // namespace argil::bench
