#pragma once
// Adaptive triangulation of trimmed B-spline faces within a chord tolerance, for
// mesh export and viewers. No third-party types: meshes are written elsewhere.

#include <Eigen/Core>
#include <string>
#include <vector>

#include "argil/core/base/status.hpp"
#include "argil/io/model/model.hpp"

namespace argil::io {

/// How finely tessellate() samples.
struct TessellationOptions {
  /// Largest allowed distance between the mesh and the surface [mm], checked at
  /// every triangle's centroid and edge midpoints.
  double chord_tolerance_mm = 0.05;
  /// Subdivision depth limit below each knot-span patch (a cell is at least
  /// 2^-max_depth of its span wide); reached only at singular points.
  int max_depth = 16;
  /// tessellate() fails once the faces done so far hold more triangles than
  /// this (0: no limit): a tolerance far too fine for the model stops early
  /// instead of filling memory and disk.
  std::size_t max_triangles = 0;
};

/// Triangles over all faces of a model. Every vertex keeps the face and (u, v)
/// it was evaluated at, so its exact surface point is known.
struct TriangleMesh {
  Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor> positions;  // [mm]
  Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor> normals;    // unit, face side
  Eigen::Matrix<double, Eigen::Dynamic, 2, Eigen::RowMajor> uv;         // surface parameters
  std::vector<int> vertex_face;                                         // face of each vertex
  /// A label per face of the model (tessellate() only): "face 3 #120 Fillet",
  /// the face's index, then its source entity and name when it has them.
  std::vector<std::string> face_names;
  /// Vertex indices, counter-clockwise seen from the side the normals point to.
  Eigen::Matrix<int, Eigen::Dynamic, 3, Eigen::RowMajor> triangles;
  /// One line per face whose trims could only be approximated ("face 12: trims
  /// approximated by whole triangles (...)").
  std::vector<std::string> warnings;
};

/// Tessellates one face (preconditions: validate_face(face).ok() and
/// validate_trim_loops(face.loops).ok()). `face_index`
/// fills TriangleMesh::vertex_face.
///
/// Untrimmed faces: each non-empty knot-span patch is split into four
/// recursively until the fan of triangles from a cell's centre to its boundary
/// vertices is within the chord tolerance at its edge midpoints and centroids
/// (measured as |S(u, v) - linear interpolation| at the interpolated (u, v), an
/// upper bound of the distance to the surface). Cells take their neighbours'
/// vertices on shared edges into their fan, so the mesh has no cracks.
///
/// Trimmed faces are meshed conforming to their trim curves (the border
/// vertices lie on them) by OpenCASCADE's BRepMesh at a deflection of the
/// chord tolerance, lowered (up to twice, by a factor of 2 to 4) until every
/// triangle passes the same chord bound. Where that fails, the face falls back
/// to the cells above, keeping the triangles whose (u, v) centroid lies inside
/// the trims (TrimRegion::contains), and TriangleMesh::warnings says so.
///
/// Every vertex is evaluated on argil's surface at its (u, v). Normals are
/// S_u x S_v / |S_u x S_v| from the surface derivatives, flipped on reversed
/// faces.
TriangleMesh tessellate_face(const FaceRecord& face, const TessellationOptions& options = {},
                             int face_index = 0);

/// Tessellates every face and concatenates the meshes, face after face.
/// Fails when a face or its trim loops do not validate (the message names the
/// face, loop and curve), the tolerance is not positive or below 1e-7 of the
/// model's control-point diagonal (mesh files hold float32 coordinates), or
/// the triangles pass options.max_triangles (invalid_argument; the message
/// gives the count reached and after how many faces).
Result<TriangleMesh> tessellate(const Model& model, const TessellationOptions& options = {});

/// About how many triangles tessellate(model, options) makes, at a small
/// fraction of its cost: two coarse tessellations (at 1e-2 and 2.5e-3 of the
/// model's size, or options' tolerance when coarser) fit N(t) = a + b / t,
/// the count of flat faces (a) plus that of curved ones, whose cells shrink
/// as sqrt(t) (b / t), and the fit is read at options.chord_tolerance_mm.
/// Fails as tessellate() does on faces that do not validate.
Result<std::size_t> estimate_triangle_count(const Model& model,
                                            const TessellationOptions& options = {});

}  // namespace argil::io
