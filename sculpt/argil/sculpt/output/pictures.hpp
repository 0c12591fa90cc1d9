#pragma once
// Pictures of a session (PNG through cairo): shaded surfaces seen by an
// orthographic camera with the tool path drawn over them, and a plot of the
// device force over time. The surfaces go through a depth buffer
// (detail/depth_raster.hpp); cairo draws the rest and writes the PNG.

#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

#include "argil/core/base/status.hpp"
#include "argil/core/geometry/bspline_surface.hpp"
#include "argil/io/mesh/tessellate.hpp"

namespace argil::sculpt {

/// An orthographic view: the camera looks along -eye_direction (unit, from the
/// scene towards the viewer), z up unless looking straight down it.
struct Camera {
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();  // [mm]
  Eigen::Vector3d eye_direction = Eigen::Vector3d(0, 0, 1);
  Eigen::Vector3d right = Eigen::Vector3d::UnitX();
  Eigen::Vector3d up = Eigen::Vector3d::UnitY();
  double pixels_per_mm = 1.0;
  int width = 960, height = 720;  // [pixels]

  /// Pixel coordinates (x right, y down) of a point.
  Eigen::Vector2d project(const Eigen::Vector3d& p_W) const;
  /// Distance towards the viewer [mm]: larger is nearer.
  double depth(const Eigen::Vector3d& p_W) const { return (p_W - centre).dot(eye_direction); }
};

/// Unit direction towards the viewer from azimuth and elevation [deg]
/// (azimuth about z from +x, elevation above the xy plane).
Eigen::Vector3d view_direction(double azimuth_deg, double elevation_deg);

/// A camera seeing `box` whole with a margin, looking along -eye_direction.
Camera fit_camera(const Box3& box, int width, int height,
                  const Eigen::Vector3d& eye_direction = view_direction(-60.0, 35.0));

/// A device path: positions [mm] and whether the tool was engaged there.
struct ToolPath {
  std::vector<Eigen::Vector3d> positions;
  std::vector<bool> engaged;
};

/// What a surface picture shows beyond the shaded mesh.
struct SurfacePictureOptions {
  std::string title;
  /// Per-vertex signed displacement along the surface's outward normal [mm]
  /// (negative: pushed in) to colour by, interpolated across each triangle
  /// (empty: plain clay colour).
  std::vector<double> vertex_displacement;
  /// The ends of the colour scale, -scale (blue, in) .. +scale (red, out) [mm]
  /// (> 0 when colouring); 0 is neutral.
  double displacement_scale = 0.0;
  /// Shown where the scale would be, when there is nothing to colour (a
  /// model that did not move says so); empty: nothing.
  std::string note;
  /// The tool drawn where it pressed hardest: a sphere's outline (radius > 0)
  /// or a point's cross (radius 0); none when unset.
  std::optional<Eigen::Vector3d> tool_position;
  double tool_radius_mm = 0.0;
  /// A B-spline tool's surface posed there [mm], drawn in place of the sphere:
  /// a faint fill with its border (the mesh's open edges) outlined.
  io::TriangleMesh tool_mesh;
  /// A region drawn again, zoomed, in an inset at the top right (its frame
  /// marked on the whole view); none when unset.
  std::optional<Box3> zoom;
  /// The inset's eye direction (towards the viewer); none: the whole view's.
  std::optional<Eigen::Vector3d> zoom_eye;
};

/// The mesh shaded smoothly (a head light and a raking key light at each
/// vertex from its normal, two-sided, interpolated per pixel; each pixel shows
/// the nearest surface (a depth buffer), drawn at twice the size and scaled
/// down so edges are antialiased) with the tool path on top (engaged segments
/// red, free moves grey), as PNG bytes. The zoom inset shows only the surface
/// inside its region.
Result<std::string> render_surface_png(const io::TriangleMesh& mesh, const ToolPath& path,
                                       const Camera& camera,
                                       const SurfacePictureOptions& options = {});

/// Force on the device over time: |f| and the x, y, z components [N] against
/// time [s], with axes, ticks, labels and a legend, as PNG bytes.
/// `times` and `forces` have the same length.
struct ForcePlotOptions {
  std::string title;
  int width = 960;  // [px]
  int height = 540;
};
Result<std::string> plot_force_png(const std::vector<double>& times,
                                   const std::vector<Eigen::Vector3d>& forces,
                                   const ForcePlotOptions& options = {});

/// Axis ticks for [lo, hi]: round numbers 1, 2 or 5 times a power of ten, about
/// `target` of them, covering the range.
std::vector<double> nice_ticks(double lo, double hi, int target = 6);

}  // namespace argil::sculpt
