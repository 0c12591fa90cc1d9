#include "argil/sculpt/output/session_pictures.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cstdio>
#include <optional>
#include <utility>
#include <vector>

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

/// Where the tool pressed hardest: the engaged sample of the largest force.
std::optional<std::size_t> hardest_press(const SessionPicturesRequest& request) {
  std::optional<std::size_t> at;
  double largest = -1.0;
  const std::size_t n = std::min(request.path.positions.size(), request.forces.size());
  for (std::size_t k = 0; k < n; ++k) {
    if (k >= request.path.engaged.size() || !request.path.engaged[k]) continue;
    const double f = request.forces[k].norm();
    if (f > largest) {
      largest = f;
      at = k;
    }
  }
  return at;
}

/// The tool held at tick k (none when the request names no tools).
const PictureTool* tool_at(const SessionPicturesRequest& request, std::size_t k) {
  if (request.tools.empty()) return nullptr;
  const int index = k < request.tool_index.size() ? request.tool_index[k] : 0;
  if (index < 0 || index >= static_cast<int>(request.tools.size())) return nullptr;
  return &request.tools[static_cast<std::size_t>(index)];
}

/// A B-spline tool's surface posed by the device at tick k, tessellated.
Result<io::TriangleMesh> posed_tool_mesh(const SessionPicturesRequest& request, std::size_t k,
                                         const BSplineSurface& tool,
                                         const io::TessellationOptions& options) {
  const Eigen::Quaterniond R =
      k < request.rotations.size() ? request.rotations[k] : Eigen::Quaterniond::Identity();
  io::Model posed;
  posed.faces.emplace_back().surface = tool;
  ControlNet& poles = posed.faces.front().surface.control_points;
  for (Eigen::Index i = 0; i < poles.rows(); ++i) {
    poles.row(i) = (R * poles.row(i).transpose() + request.path.positions[k]).transpose();
  }
  return io::tessellate(posed, options);
}

/// How far each vertex of `after_mesh` moved from the same (face, u, v) of
/// `before` [mm].
std::vector<Eigen::Vector3d> vertex_movements(const io::Model& before,
                                              const io::TriangleMesh& after_mesh) {
  std::vector<Eigen::Vector3d> moved(static_cast<std::size_t>(after_mesh.positions.rows()));
  for (Eigen::Index k = 0; k < after_mesh.positions.rows(); ++k) {
    const auto face = static_cast<std::size_t>(after_mesh.vertex_face[static_cast<std::size_t>(k)]);
    moved[static_cast<std::size_t>(k)] =
        after_mesh.positions.row(k).transpose() -
        evaluate(before.faces[face].surface, after_mesh.uv(k, 0), after_mesh.uv(k, 1));
  }
  return moved;
}

/// after_picture_options() from the vertices' movements.
SurfacePictureOptions signed_colouring(const io::Model& before, const io::TriangleMesh& after_mesh,
                                       const std::vector<Eigen::Vector3d>& moved,
                                       double tolerance_mm, const std::string& title) {
  SurfacePictureOptions options;
  options.title = title + ": after";
  options.vertex_displacement.resize(moved.size());
  double largest_signed = 0.0, largest_moved = 0.0;
  for (std::size_t k = 0; k < moved.size(); ++k) {
    const io::FaceRecord& was_face =
        before.faces[static_cast<std::size_t>(after_mesh.vertex_face[k])];
    const auto row = static_cast<Eigen::Index>(k);
    const Eigen::Vector3d normal =
        (was_face.reversed ? -1.0 : 1.0) *
        unit_normal(was_face.surface, after_mesh.uv(row, 0), after_mesh.uv(row, 1));
    const double along = moved[k].dot(normal);
    options.vertex_displacement[k] = along;
    largest_signed = std::max(largest_signed, std::abs(along));
    largest_moved = std::max(largest_moved, moved[k].norm());
  }
  if (largest_moved > tolerance_mm && largest_signed > 0.0) {
    options.displacement_scale = largest_signed;
  } else {
    options.vertex_displacement.clear();
    char note[160];
    std::snprintf(note, sizeof note, "no change: no point moved more than %.3g mm (eps %.3g mm)",
                  largest_moved, tolerance_mm);
    options.note = note;
  }
  return options;
}

/// The vertices that moved by more than a tenth of the largest movement (and
/// eps): the visible change; none when nothing moved by more than eps.
std::vector<Eigen::Index> visibly_moved(const std::vector<Eigen::Vector3d>& moved,
                                        double tolerance_mm) {
  double largest = 0.0;
  for (const Eigen::Vector3d& m : moved) largest = std::max(largest, m.norm());
  std::vector<Eigen::Index> out;
  if (!(largest > tolerance_mm)) return out;
  const double visible = std::max(tolerance_mm, 0.1 * largest);
  for (std::size_t k = 0; k < moved.size(); ++k)
    if (moved[k].norm() > visible) out.push_back(static_cast<Eigen::Index>(k));
  return out;
}

/// The box of the vertices in `visible`; none when there are none.
std::optional<Box3> region_box(const io::TriangleMesh& mesh,
                               const std::vector<Eigen::Index>& visible) {
  if (visible.empty()) return std::nullopt;
  Box3 box{Eigen::Vector3d::Constant(1e300), Eigen::Vector3d::Constant(-1e300)};
  for (const Eigen::Index k : visible) {
    const Eigen::Vector3d p = mesh.positions.row(k).transpose();
    box.min = box.min.cwiseMin(p);
    box.max = box.max.cwiseMax(p);
  }
  return box;
}

/// Whether a change spanning `change` is small enough for the zoom inset: a
/// third of the model at most (beyond, the whole view shows it).
bool fits_inset(const Box3& change, const Box3& models) {
  return !(change.diagonal() > models.diagonal() / 3.0);
}

/// The zoom inset's region round the visible change `change`: grown by half
/// its size and to at least three tool radii; none when the change does not
/// fit the inset.
std::optional<Box3> moved_region(const Box3& change, double tool_radius_mm, const Box3& models) {
  if (!fits_inset(change, models)) return std::nullopt;
  const Eigen::Vector3d centre = 0.5 * (change.min + change.max);
  const Eigen::Vector3d half =
      (0.75 * (change.max - change.min)).cwiseMax(Eigen::Vector3d::Constant(1.5 * tool_radius_mm));
  return Box3{centre - half, centre + half};
}

/// The mean unit normal of the vertices in `visible`; none when they cancel out.
std::optional<Eigen::Vector3d> mean_normal(const io::TriangleMesh& mesh,
                                           const std::vector<Eigen::Index>& visible) {
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();
  for (const Eigen::Index k : visible) normal += mesh.normals.row(k).transpose();
  if (!(normal.norm() > 1e-9)) return std::nullopt;
  return normal.normalized();
}

/// Where to look at a change from: its mean outward normal (mean_normal of
/// the vertices that moved visibly), tilted a third of the way towards the
/// whole view's eye so its relief shows.
Eigen::Vector3d change_eye(const Eigen::Vector3d& normal, const Eigen::Vector3d& view_eye) {
  const Eigen::Vector3d tangent = view_eye - view_eye.dot(normal) * normal;
  return (normal + 0.5 * tangent).normalized();
}

}  // namespace

SurfacePictureOptions after_picture_options(const io::Model& before,
                                            const io::TriangleMesh& after_mesh, double tolerance_mm,
                                            const std::string& title) {
  return signed_colouring(before, after_mesh, vertex_movements(before, after_mesh), tolerance_mm,
                          title);
}

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
  const std::vector<Eigen::Vector3d> moved = vertex_movements(before, after_mesh.value());
  const std::vector<Eigen::Index> visible = visibly_moved(moved, request.tolerance_mm);
  // A change too large for the zoom inset (below) that the whole view sees
  // at a glancing angle or from behind (its mean normal more than 60 degrees
  // from the eye) is looked at by the whole view: a groove along the side of
  // a screw was on its silhouette.
  const std::optional<Box3> change = region_box(after_mesh.value(), visible);
  const std::optional<Eigen::Vector3d> change_normal = mean_normal(after_mesh.value(), visible);
  Eigen::Vector3d eye = eye_direction_for(before_mesh.value());
  if (change && !fits_inset(*change, models) && change_normal && change_normal->dot(eye) < 0.5)
    eye = change_eye(*change_normal, eye);
  const Camera camera = fit_camera(with_engaged_path(models, path), 960, 720, eye);
  SurfacePictureOptions before_options;
  before_options.title = title + ": before";
  const std::optional<std::size_t> press = hardest_press(request);
  if (const PictureTool* tool = press ? tool_at(request, *press) : nullptr) {
    before_options.tool_position = path.positions[*press];
    before_options.tool_radius_mm = tool->radius_mm;
    if (tool->surface) {
      Result<io::TriangleMesh> posed = posed_tool_mesh(request, *press, *tool->surface, options);
      if (!posed.ok()) return posed.status();
      before_options.tool_mesh = std::move(posed).value();
      // The zoom on the change is at least the tool's size.
      before_options.tool_radius_mm = 0.5 * control_point_box(*tool->surface).diagonal();
    }
  }
  SurfacePictureOptions after_options =
      signed_colouring(before, after_mesh.value(), moved, request.tolerance_mm, title);
  after_options.tool_position = before_options.tool_position;
  after_options.tool_radius_mm = before_options.tool_radius_mm;
  after_options.tool_mesh = before_options.tool_mesh;
  if (change) after_options.zoom = moved_region(*change, after_options.tool_radius_mm, models);
  if (after_options.zoom && change_normal)
    after_options.zoom_eye = change_eye(*change_normal, camera.eye_direction);
  const struct {
    const char* name;
    Result<std::string> png;
  } pictures[] = {
      {kBeforePicture, render_surface_png(before_mesh.value(), path, camera, before_options)},
      {kAfterPicture, render_surface_png(after_mesh.value(), path, camera, after_options)},
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
