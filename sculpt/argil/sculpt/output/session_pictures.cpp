#include "argil/sculpt/output/session_pictures.hpp"

#include <Eigen/Geometry>
#include <algorithm>

#include "argil/core/geometry/evaluate.hpp"
#include "argil/io/base/atomic_write.hpp"

namespace argil::sculpt {
namespace {

Box3 merge(const Box3& a, const Box3& b) { return {a.min.cwiseMin(b.min), a.max.cwiseMax(b.max)}; }

// Chord tolerance of the picture meshes relative to the model size: finer than
// a pixel of a 960-pixel-wide view.
constexpr double kPictureChordRelative = 5e-4;

/// The box grown to hold the engaged part of the path, where the tool worked.
Box3 with_engaged_path(Box3 box, const ToolPath& path) {
  for (std::size_t k = 0; k < path.positions.size(); ++k) {
    if (k < path.engaged.size() && path.engaged[k]) {
      box.min = box.min.cwiseMin(path.positions[k]);
      box.max = box.max.cwiseMax(path.positions[k]);
    }
  }
  return box;
}

/// Looks at the surfaces from the side their mean normal points to, tilted
/// towards a three-quarter view so curvature shows; a closed or twisted set
/// of faces (mean normal near zero) gets the three-quarter view alone.
Eigen::Vector3d eye_direction_for(const io::TriangleMesh& mesh) {
  Eigen::Vector3d mean_normal = Eigen::Vector3d::Zero();
  for (Eigen::Index t = 0; t < mesh.triangles.rows(); ++t) {
    const Eigen::Vector3d a = mesh.positions.row(mesh.triangles(t, 0)).transpose();
    const Eigen::Vector3d b = mesh.positions.row(mesh.triangles(t, 1)).transpose();
    const Eigen::Vector3d c = mesh.positions.row(mesh.triangles(t, 2)).transpose();
    mean_normal += (b - a).cross(c - a);  // area weighted
  }
  const Eigen::Vector3d three_quarter = view_direction(-60.0, 35.0);
  if (!(mean_normal.norm() > 0.0)) return three_quarter;
  mean_normal.normalize();
  if (mean_normal.dot(three_quarter) < 0) mean_normal = -mean_normal;
  return (mean_normal + 0.8 * three_quarter).normalized();
}

/// The "after" picture coloured by how far each point of the sculpted surface
/// moved: the same (face, u, v) on both models. Plain when nothing moved.
SurfacePictureOptions after_options_for(const io::Model& before, const io::TriangleMesh& mesh,
                                        const std::string& title) {
  SurfacePictureOptions options;
  options.title = title + ": after";
  options.vertex_displacement.resize(static_cast<std::size_t>(mesh.positions.rows()));
  double largest = 0.0;
  for (Eigen::Index k = 0; k < mesh.positions.rows(); ++k) {
    const auto face = static_cast<std::size_t>(mesh.vertex_face[static_cast<std::size_t>(k)]);
    const Eigen::Vector3d was = evaluate(before.faces[face].surface, mesh.uv(k, 0), mesh.uv(k, 1));
    const double moved = (mesh.positions.row(k).transpose() - was).norm();
    options.vertex_displacement[static_cast<std::size_t>(k)] = moved;
    largest = std::max(largest, moved);
  }
  if (largest > 0.0) {
    options.displacement_scale = largest;
  } else {
    options.vertex_displacement.clear();
  }
  return options;
}

}  // namespace

Status write_session_pictures(const SessionPicturesRequest& request,
                              const std::filesystem::path& folder) {
  const io::Model& before = request.before;
  const io::Model& after = request.after;
  const ToolPath& path = request.path;
  const std::string& title = request.title;
  const Box3 models = merge(io::model_box(before), io::model_box(after));
  io::TessellationOptions options;
  options.chord_tolerance_mm = std::max(models.diagonal() * kPictureChordRelative, 1e-9);
  Result<io::TriangleMesh> before_mesh = io::tessellate(before, options);
  if (!before_mesh.ok()) return before_mesh.status();
  Result<io::TriangleMesh> after_mesh = io::tessellate(after, options);
  if (!after_mesh.ok()) return after_mesh.status();
  const Camera camera =
      fit_camera(with_engaged_path(models, path), 960, 720, eye_direction_for(before_mesh.value()));
  SurfacePictureOptions before_options;
  before_options.title = title + ": before";
  const struct {
    const char* name;
    Result<std::string> png;
  } pictures[] = {
      {kBeforePicture, render_surface_png(before_mesh.value(), path, camera, before_options)},
      {kAfterPicture, render_surface_png(after_mesh.value(), path, camera,
                                         after_options_for(before, after_mesh.value(), title))},
      {kForcePicture,
       plot_force_png(request.times, request.forces, {.title = title + ": force on the device"})},
  };
  for (const auto& picture : pictures) {
    if (!picture.png.ok()) return picture.png.status();
    const Status written = io::write_bytes_atomically(folder / picture.name, picture.png.value());
    if (!written.ok()) return written;
  }
  return Status::success();
}

}  // namespace argil::sculpt
