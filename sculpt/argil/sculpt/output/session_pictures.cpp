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

}  // namespace

Status write_session_pictures(const io::Model& before, const io::Model& after, const ToolPath& path,
                              const std::vector<double>& times,
                              const std::vector<Eigen::Vector3d>& forces, const std::string& title,
                              const std::filesystem::path& folder) {
  Box3 box = merge(io::model_box(before), io::model_box(after));
  io::TessellationOptions options;
  options.chord_tolerance_mm = std::max(box.diagonal() * kPictureChordRelative, 1e-9);
  Result<io::TriangleMesh> before_mesh = io::tessellate(before, options);
  if (!before_mesh.ok()) return before_mesh.status();
  Result<io::TriangleMesh> after_mesh = io::tessellate(after, options);
  if (!after_mesh.ok()) return after_mesh.status();
  // The engaged part of the path is where the tool worked: frame it too.
  for (std::size_t k = 0; k < path.positions.size(); ++k) {
    if (k < path.engaged.size() && path.engaged[k]) {
      box.min = box.min.cwiseMin(path.positions[k]);
      box.max = box.max.cwiseMax(path.positions[k]);
    }
  }
  // Look at the surfaces from the side their mean normal points to, tilted
  // towards a three-quarter view so curvature shows; a closed or twisted set
  // of faces (mean normal near zero) gets the three-quarter view alone.
  Eigen::Vector3d mean_normal = Eigen::Vector3d::Zero();
  const io::TriangleMesh& original = before_mesh.value();
  for (Eigen::Index t = 0; t < original.triangles.rows(); ++t) {
    const Eigen::Vector3d a = original.positions.row(original.triangles(t, 0)).transpose();
    const Eigen::Vector3d b = original.positions.row(original.triangles(t, 1)).transpose();
    const Eigen::Vector3d c = original.positions.row(original.triangles(t, 2)).transpose();
    mean_normal += (b - a).cross(c - a);  // area weighted
  }
  const Eigen::Vector3d three_quarter = view_direction(-60.0, 35.0);
  Eigen::Vector3d eye = three_quarter;
  if (mean_normal.norm() > 0.0) {
    mean_normal.normalize();
    if (mean_normal.dot(three_quarter) < 0) mean_normal = -mean_normal;
    eye = (mean_normal + 0.8 * three_quarter).normalized();
  }
  const Camera camera = fit_camera(box, 960, 720, eye);

  // How far each point of the sculpted surface moved: the same (face, u, v) on both.
  const io::TriangleMesh& mesh = after_mesh.value();
  SurfacePictureOptions after_options;
  after_options.title = title + ": after";
  after_options.vertex_displacement.resize(static_cast<std::size_t>(mesh.positions.rows()));
  double largest = 0.0;
  for (Eigen::Index k = 0; k < mesh.positions.rows(); ++k) {
    const auto face = static_cast<std::size_t>(mesh.vertex_face[static_cast<std::size_t>(k)]);
    const Eigen::Vector3d was = evaluate(before.faces[face].surface, mesh.uv(k, 0), mesh.uv(k, 1));
    const double moved = (mesh.positions.row(k).transpose() - was).norm();
    after_options.vertex_displacement[static_cast<std::size_t>(k)] = moved;
    largest = std::max(largest, moved);
  }
  if (largest > 0.0) {
    after_options.displacement_scale = largest;
  } else {
    after_options.vertex_displacement.clear();
  }
  SurfacePictureOptions before_options;
  before_options.title = title + ": before";

  const struct {
    const char* name;
    Result<std::string> png;
  } pictures[] = {
      {kBeforePicture, render_surface_png(before_mesh.value(), path, camera, before_options)},
      {kAfterPicture, render_surface_png(mesh, path, camera, after_options)},
      {kForcePicture, plot_force_png(times, forces, title + ": force on the device")},
  };
  for (const auto& picture : pictures) {
    if (!picture.png.ok()) return picture.png.status();
    const Status written = io::write_bytes_atomically(folder / picture.name, picture.png.value());
    if (!written.ok()) return written;
  }
  return Status::success();
}

}  // namespace argil::sculpt
