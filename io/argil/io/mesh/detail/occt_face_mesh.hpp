#pragma once
// Internal to argil_io: a trimmed face triangulated by OpenCASCADE's BRepMesh,
// conforming to its trim curves (the boundary vertices lie on them).

#include <Eigen/Core>
#include <array>
#include <vector>

#include "argil/core/base/status.hpp"
#include "argil/io/model/model.hpp"

namespace argil::io::detail {

/// Triangles over (u, v) nodes of one face.
struct FaceTriangles {
  std::vector<Eigen::Vector2d> uv;
  std::vector<std::array<int, 3>> triangles;  // counter-clockwise in (u, v)
};

/// Meshes `face` (trimmed; validate_face() and validate_trim_loops() accept it)
/// with BRepMesh_IncrementalMesh at a linear deflection of `deflection_mm` and
/// an angular deflection of 0.5 rad, on the face build_occt_face() makes for
/// export. Errors: OpenCASCADE builds no face, or BRepMesh leaves it without
/// triangles.
Result<FaceTriangles> occt_face_triangles(const FaceRecord& face, double deflection_mm);

}  // namespace argil::io::detail
