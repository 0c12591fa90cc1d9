// The one translation unit that uses cairo.
#include "argil/sculpt/output/pictures.hpp"

#include <cairo.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <memory>
#include <optional>

#include "argil/sculpt/output/detail/depth_raster.hpp"

namespace argil::sculpt {
namespace {

struct SurfaceDeleter {
  void operator()(cairo_surface_t* s) const { cairo_surface_destroy(s); }
};
struct ContextDeleter {
  void operator()(cairo_t* c) const { cairo_destroy(c); }
};
using SurfacePtr = std::unique_ptr<cairo_surface_t, SurfaceDeleter>;
using ContextPtr = std::unique_ptr<cairo_t, ContextDeleter>;

cairo_status_t append_png_bytes(void* closure, const unsigned char* data, unsigned int length) {
  static_cast<std::string*>(closure)->append(reinterpret_cast<const char*>(data), length);
  return CAIRO_STATUS_SUCCESS;
}

Result<std::string> encode_png(cairo_surface_t* surface) {
  cairo_surface_flush(surface);
  std::string bytes;
  const cairo_status_t status =
      cairo_surface_write_to_png_stream(surface, append_png_bytes, &bytes);
  if (status != CAIRO_STATUS_SUCCESS) {
    return Status::error(StatusCode::io_error,
                         std::string("PNG encoding failed: ") + cairo_status_to_string(status));
  }
  return bytes;
}

Result<std::pair<SurfacePtr, ContextPtr>> canvas(int width, int height) {
  if (width < 16 || height < 16 || width > 8192 || height > 8192) {
    return Status::error(StatusCode::invalid_argument, "picture size " + std::to_string(width) +
                                                           " x " + std::to_string(height) +
                                                           " is outside 16 .. 8192 pixels");
  }
  SurfacePtr surface(cairo_image_surface_create(CAIRO_FORMAT_RGB24, width, height));
  if (cairo_surface_status(surface.get()) != CAIRO_STATUS_SUCCESS) {
    return Status::error(StatusCode::io_error, "cannot create a cairo image surface");
  }
  ContextPtr context(cairo_create(surface.get()));
  cairo_set_source_rgb(context.get(), 1.0, 1.0, 1.0);
  cairo_paint(context.get());
  return std::make_pair(std::move(surface), std::move(context));
}

void draw_text(cairo_t* cr, double x, double y, const std::string& text, double size,
               bool centred = false, bool right_aligned = false) {
  cairo_select_font_face(cr, "sans-serif", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
  cairo_set_font_size(cr, size);
  cairo_text_extents_t extents;
  cairo_text_extents(cr, text.c_str(), &extents);
  double left = x;
  if (centred) left = x - extents.width / 2 - extents.x_bearing;
  if (right_aligned) left = x - extents.width - extents.x_bearing;
  cairo_move_to(cr, left, y);
  cairo_show_text(cr, text.c_str());
}

std::string tick_label(double value, double step) {
  // Enough decimals to tell neighbouring ticks apart.
  const int decimals = std::max(0, static_cast<int>(-std::floor(std::log10(step) + 1e-9)));
  char buffer[32];
  if (std::abs(value) < step * 1e-6) value = 0.0;
  if (decimals > 6 || (std::abs(value) >= 1e6)) {
    std::snprintf(buffer, sizeof buffer, "%.3g", value);
  } else {
    std::snprintf(buffer, sizeof buffer, "%.*f", decimals, value);
  }
  return buffer;
}

}  // namespace

Eigen::Vector2d Camera::project(const Eigen::Vector3d& p_W) const {
  const Eigen::Vector3d d = p_W - centre;
  return {0.5 * width + pixels_per_mm * d.dot(right), 0.5 * height - pixels_per_mm * d.dot(up)};
}

Eigen::Vector3d view_direction(double azimuth_deg, double elevation_deg) {
  const double az = azimuth_deg * M_PI / 180.0, el = elevation_deg * M_PI / 180.0;
  return {std::cos(el) * std::cos(az), std::cos(el) * std::sin(az), std::sin(el)};
}

Camera fit_camera(const Box3& box, int width, int height, const Eigen::Vector3d& eye_direction) {
  Camera c;
  c.width = width;
  c.height = height;
  c.centre = 0.5 * (box.min + box.max);
  c.eye_direction = eye_direction.normalized();
  const Eigen::Vector3d world_up =
      std::abs(c.eye_direction.z()) > 0.999 ? Eigen::Vector3d::UnitY() : Eigen::Vector3d::UnitZ();
  c.right = world_up.cross(c.eye_direction).normalized();
  c.up = c.eye_direction.cross(c.right);
  // The box's projected extent along right and up, with an 8% margin each side.
  double half_x = 0.0, half_y = 0.0;
  for (int corner = 0; corner < 8; ++corner) {
    const Eigen::Vector3d p((corner & 1) ? box.max.x() : box.min.x(),
                            (corner & 2) ? box.max.y() : box.min.y(),
                            (corner & 4) ? box.max.z() : box.min.z());
    half_x = std::max(half_x, std::abs((p - c.centre).dot(c.right)));
    half_y = std::max(half_y, std::abs((p - c.centre).dot(c.up)));
  }
  const double usable = 0.84;
  const double sx = half_x > 0 ? usable * 0.5 * width / half_x : 1.0;
  const double sy = half_y > 0 ? usable * 0.5 * height / half_y : 1.0;
  c.pixels_per_mm = std::min(sx, sy);
  if (!std::isfinite(c.pixels_per_mm) || c.pixels_per_mm <= 0) c.pixels_per_mm = 1.0;
  return c;
}

namespace {

/// Neutral (0) to blue (-1, pushed in) or red (+1, pushed out).
Eigen::Vector3d diverging(double t) {
  t = std::clamp(t, -1.0, 1.0);
  const Eigen::Vector3d neutral(0.86, 0.84, 0.80), in(0.12, 0.32, 0.85), out(0.86, 0.18, 0.12);
  return t < 0.0 ? ((1.0 + t) * neutral - t * in).eval() : ((1.0 - t) * neutral + t * out).eval();
}

// Supersampling of the shaded triangles in each direction: the depth buffer
// samples one point per pixel, so the triangles are drawn this much larger
// and scaled down (silhouettes and trims come out smooth).
constexpr int kSupersampling = 2;

/// The mesh into the depth buffer, shaded by a head light and a raking key
/// light from over the viewer's left shoulder (diffuse and a little specular,
/// so a dent on a nearly flat panel shows by its shading), clay or coloured by
/// the signed displacement, both per vertex and interpolated per pixel
/// (Gouraud). With `clip`, only the surface inside the box.
void shade(DepthRaster& raster, const io::TriangleMesh& mesh, const Camera& camera,
           const SurfacePictureOptions& options, const std::optional<Box3>& clip) {
  const bool coloured = !options.vertex_displacement.empty();
  const Eigen::Vector3d light =
      (0.45 * camera.eye_direction + 0.75 * camera.up - 0.5 * camera.right).normalized();
  const Eigen::Vector3d half_way = (light + camera.eye_direction).normalized();
  const Eigen::Vector3d clay(0.82, 0.64, 0.47);
  const auto vertex_colour = [&](int v, const Eigen::Vector3d& flat_normal) {
    Eigen::Vector3d n = mesh.normals.row(v).transpose();
    if (!(n.squaredNorm() > 0.5)) n = flat_normal;
    if (n.dot(camera.eye_direction) < 0.0) n = -n;  // the side seen
    // A head light keeps every face turned to the viewer lit; the raking key
    // light adds the relief.
    const double head = n.dot(camera.eye_direction);
    const double key = std::max(0.0, n.dot(light));
    const double specular = std::pow(std::max(0.0, n.dot(half_way)), 40.0);
    const Eigen::Vector3d base =
        coloured ? diverging(options.vertex_displacement[static_cast<std::size_t>(v)] /
                             options.displacement_scale)
                 : clay;
    const Eigen::Vector3d lit =
        base * (0.25 + 0.55 * head + 0.35 * key) + Eigen::Vector3d::Constant(0.15 * specular);
    return Eigen::Vector3d(lit.cwiseMin(1.0));
  };
  for (Eigen::Index t = 0; t < mesh.triangles.rows(); ++t) {
    const int v[3] = {mesh.triangles(t, 0), mesh.triangles(t, 1), mesh.triangles(t, 2)};
    RasterTriangle r;
    for (int k = 0; k < 3; ++k) r.point[k] = mesh.positions.row(v[k]).transpose();
    Eigen::Vector3d n = (r.point[1] - r.point[0]).cross(r.point[2] - r.point[0]);
    if (n.norm() == 0.0) continue;
    n.normalize();
    for (int k = 0; k < 3; ++k) {
      r.pixel[k] = camera.project(r.point[k]);
      r.depth[k] = camera.depth(r.point[k]);
      r.colour[k] = vertex_colour(v[k], n);
    }
    raster.draw(r, clip);
  }
}

/// The shaded mesh onto `cr`: drawn kSupersampling times larger into a depth
/// buffer, then scaled down with a box filter. Where nothing is drawn `cr`
/// shows through.
void draw_triangles(cairo_t* cr, const io::TriangleMesh& mesh, const Camera& camera,
                    const SurfacePictureOptions& options, const std::optional<Box3>& clip = {}) {
  Camera large = camera;
  large.width *= kSupersampling;
  large.height *= kSupersampling;
  large.pixels_per_mm *= kSupersampling;
  SurfacePtr layer(cairo_image_surface_create(CAIRO_FORMAT_ARGB32, large.width, large.height));
  int scale = kSupersampling;
  if (cairo_surface_status(layer.get()) != CAIRO_STATUS_SUCCESS) {
    // Out of memory for the large layer: draw without supersampling.
    large = camera;
    scale = 1;
    layer.reset(cairo_image_surface_create(CAIRO_FORMAT_ARGB32, large.width, large.height));
    if (cairo_surface_status(layer.get()) != CAIRO_STATUS_SUCCESS) return;
  }
  DepthRaster raster(large.width, large.height);
  shade(raster, mesh, large, options, clip);
  cairo_surface_flush(layer.get());
  unsigned char* data = cairo_image_surface_get_data(layer.get());
  const int stride = cairo_image_surface_get_stride(layer.get());
  for (int y = 0; y < large.height; ++y) {
    auto* row = reinterpret_cast<std::uint32_t*>(data + static_cast<std::ptrdiff_t>(y) * stride);
    for (int x = 0; x < large.width; ++x) row[x] = raster.argb(x, y);
  }
  cairo_surface_mark_dirty(layer.get());
  cairo_save(cr);
  cairo_scale(cr, 1.0 / scale, 1.0 / scale);
  cairo_set_source_surface(cr, layer.get(), 0.0, 0.0);
  cairo_pattern_set_filter(cairo_get_source(cr), CAIRO_FILTER_GOOD);
  cairo_paint(cr);
  cairo_restore(cr);
}

/// The tool path: red where engaged, grey where moving freely.
void draw_tool_path(cairo_t* cr, const ToolPath& path, const Camera& camera) {
  cairo_set_line_width(cr, 2.0);
  cairo_set_line_cap(cr, CAIRO_LINE_CAP_ROUND);
  for (std::size_t k = 1; k < path.positions.size(); ++k) {
    const bool on = k < path.engaged.size() && path.engaged[k] && path.engaged[k - 1];
    if (on)
      cairo_set_source_rgb(cr, 0.85, 0.05, 0.05);
    else
      cairo_set_source_rgba(cr, 0.25, 0.25, 0.25, 0.6);
    const Eigen::Vector2d p0 = camera.project(path.positions[k - 1]);
    const Eigen::Vector2d p1 = camera.project(path.positions[k]);
    cairo_move_to(cr, p0.x(), p0.y());
    cairo_line_to(cr, p1.x(), p1.y());
    cairo_stroke(cr);
  }
}

/// A B-spline tool's posed mesh: one faint fill (drawn as a group so that
/// overlapping triangles do not darken) and its border, the edges whose ends
/// lie on the same side of the (u, v) domain.
void draw_tool_mesh(cairo_t* cr, const Camera& camera, const io::TriangleMesh& mesh) {
  const auto corner = [&](int vertex) {
    return camera.project(mesh.positions.row(vertex).transpose());
  };
  cairo_push_group(cr);
  cairo_set_source_rgb(cr, 0.3, 0.3, 0.35);
  for (Eigen::Index t = 0; t < mesh.triangles.rows(); ++t) {
    const Eigen::Vector2d a = corner(mesh.triangles(t, 0)), b = corner(mesh.triangles(t, 1)),
                          c = corner(mesh.triangles(t, 2));
    cairo_move_to(cr, a.x(), a.y());
    cairo_line_to(cr, b.x(), b.y());
    cairo_line_to(cr, c.x(), c.y());
    cairo_close_path(cr);
  }
  cairo_fill(cr);
  cairo_pop_group_to_source(cr);
  cairo_paint_with_alpha(cr, 0.15);  // faint: the change under it shows
  const Eigen::Vector2d lo = mesh.uv.colwise().minCoeff().transpose();
  const Eigen::Vector2d hi = mesh.uv.colwise().maxCoeff().transpose();
  const auto on_side = [&](int a, int b) {
    for (int d = 0; d < 2; ++d) {
      for (const double side : {lo[d], hi[d]}) {
        if (mesh.uv(a, d) == side && mesh.uv(b, d) == side) return true;
      }
    }
    return false;
  };
  cairo_set_source_rgba(cr, 0.15, 0.15, 0.2, 0.9);
  cairo_set_line_width(cr, 1.5);
  for (Eigen::Index t = 0; t < mesh.triangles.rows(); ++t) {
    for (int e = 0; e < 3; ++e) {
      const int a = mesh.triangles(t, e), b = mesh.triangles(t, (e + 1) % 3);
      if (!on_side(a, b)) continue;
      const Eigen::Vector2d pa = corner(a), pb = corner(b);
      cairo_move_to(cr, pa.x(), pa.y());
      cairo_line_to(cr, pb.x(), pb.y());
    }
  }
  cairo_stroke(cr);
}

/// The tool where it pressed hardest: a translucent disc with its outline for
/// a sphere (its silhouette in an orthographic view), a cross for a point,
/// the posed surface for a B-spline tool.
void draw_tool(cairo_t* cr, const Camera& camera, const SurfacePictureOptions& options) {
  if (options.tool_mesh.triangles.rows() > 0) {
    draw_tool_mesh(cr, camera, options.tool_mesh);
    return;
  }
  if (!options.tool_position) return;
  const Eigen::Vector2d at = camera.project(*options.tool_position);
  const double r = options.tool_radius_mm * camera.pixels_per_mm;
  cairo_set_line_width(cr, 1.5);
  if (r >= 1.0) {
    cairo_new_path(cr);
    cairo_arc(cr, at.x(), at.y(), r, 0.0, 2.0 * M_PI);
    cairo_set_source_rgba(cr, 0.3, 0.3, 0.35, 0.08);  // faint: the change under it shows
    cairo_fill_preserve(cr);
    cairo_set_source_rgba(cr, 0.15, 0.15, 0.2, 0.9);
    cairo_stroke(cr);
  } else {
    cairo_set_source_rgba(cr, 0.15, 0.15, 0.2, 0.9);
    cairo_move_to(cr, at.x() - 6, at.y() - 6);
    cairo_line_to(cr, at.x() + 6, at.y() + 6);
    cairo_move_to(cr, at.x() - 6, at.y() + 6);
    cairo_line_to(cr, at.x() + 6, at.y() - 6);
    cairo_stroke(cr);
  }
}

/// The box's outline as the camera sees it: the projection's bounding rectangle.
std::pair<Eigen::Vector2d, Eigen::Vector2d> projected_rectangle(const Camera& camera,
                                                                const Box3& box) {
  Eigen::Vector2d lo(1e300, 1e300), hi(-1e300, -1e300);
  for (int corner = 0; corner < 8; ++corner) {
    const Eigen::Vector3d p((corner & 1) ? box.max.x() : box.min.x(),
                            (corner & 2) ? box.max.y() : box.min.y(),
                            (corner & 4) ? box.max.z() : box.min.z());
    lo = lo.cwiseMin(camera.project(p));
    hi = hi.cwiseMax(camera.project(p));
  }
  return {lo, hi};
}

/// Colour bar: displacement -scale .. +scale along the normal, bottom right.
void draw_colour_bar(cairo_t* cr, const Camera& camera, double displacement_scale) {
  const double x0 = camera.width - 260.0, y0 = camera.height - 30.0, w = 220.0, h = 12.0;
  for (int k = 0; k < 100; ++k) {
    const Eigen::Vector3d col = diverging(-1.0 + 2.0 * k / 99.0);
    cairo_set_source_rgb(cr, col.x(), col.y(), col.z());
    cairo_rectangle(cr, x0 + w * k / 100.0, y0, w / 100.0 + 0.5, h);
    cairo_fill(cr);
  }
  cairo_set_source_rgb(cr, 0.1, 0.1, 0.1);
  char low[64], high[64];
  std::snprintf(low, sizeof low, "-%.3g mm", displacement_scale);
  std::snprintf(high, sizeof high, "+%.3g mm", displacement_scale);
  draw_text(cr, x0, y0 - 4, low, 12);
  draw_text(cr, x0 + w / 2, y0 - 4, "0", 12, true);
  draw_text(cr, x0 + w, y0 - 4, high, 12, false, true);
  draw_text(cr, x0 + w / 2, y0 + h + 13, "in  <  displacement along the normal  >  out", 11, true);
}

/// Title, the path legend and the colour bar (or the note in its place).
void draw_surface_labels(cairo_t* cr, const Camera& camera, const SurfacePictureOptions& options) {
  cairo_set_source_rgb(cr, 0.1, 0.1, 0.1);
  draw_text(cr, 14, 26, options.title, 18);
  cairo_set_source_rgb(cr, 0.85, 0.05, 0.05);
  draw_text(cr, 14, camera.height - 14.0, "tool path (engaged)", 13);
  cairo_set_source_rgb(cr, 0.4, 0.4, 0.4);
  draw_text(cr, 160, camera.height - 14.0, "free move", 13);
  if (!options.vertex_displacement.empty()) {
    draw_colour_bar(cr, camera, options.displacement_scale);
  } else if (!options.note.empty()) {
    cairo_set_source_rgb(cr, 0.1, 0.1, 0.1);
    draw_text(cr, camera.width - 14.0, camera.height - 14.0, options.note, 13, false, true);
  }
}

}  // namespace

Result<std::string> render_surface_png(const io::TriangleMesh& mesh, const ToolPath& path,
                                       const Camera& camera, const SurfacePictureOptions& options) {
  Result<std::pair<SurfacePtr, ContextPtr>> made = canvas(camera.width, camera.height);
  if (!made.ok()) return made.status();
  cairo_t* cr = made.value().second.get();
  if (!options.vertex_displacement.empty() &&
      (options.vertex_displacement.size() != static_cast<std::size_t>(mesh.positions.rows()) ||
       !(options.displacement_scale > 0.0))) {
    return Status::error(StatusCode::invalid_argument,
                         "vertex_displacement needs one value per vertex and a positive scale");
  }
  draw_triangles(cr, mesh, camera, options);
  draw_tool_path(cr, path, camera);  // on top
  draw_tool(cr, camera, options);
  if (options.zoom) {
    // The region marked on the whole view, then drawn again in the inset.
    const auto [lo, hi] = projected_rectangle(camera, *options.zoom);
    cairo_set_source_rgba(cr, 0.1, 0.1, 0.1, 0.8);
    cairo_set_line_width(cr, 1.0);
    cairo_rectangle(cr, lo.x(), lo.y(), hi.x() - lo.x(), hi.y() - lo.y());
    cairo_stroke(cr);
    const int w = camera.width * 3 / 8, h = camera.height * 3 / 8;
    const double x0 = camera.width - w - 10.0, y0 = 10.0;
    const Camera inset =
        fit_camera(*options.zoom, w, h, options.zoom_eye.value_or(camera.eye_direction));
    cairo_save(cr);
    cairo_rectangle(cr, x0, y0, w, h);
    cairo_clip(cr);
    cairo_set_source_rgb(cr, 1.0, 1.0, 1.0);
    cairo_paint(cr);
    cairo_translate(cr, x0, y0);
    // Only the surface inside the region: faces in front of it (a tube
    // before the one dented) would hide the change.
    draw_triangles(cr, mesh, inset, options, options.zoom);
    draw_tool_path(cr, path, inset);
    draw_tool(cr, inset, options);
    cairo_restore(cr);
    cairo_set_source_rgb(cr, 0.1, 0.1, 0.1);
    cairo_rectangle(cr, x0, y0, w, h);
    cairo_stroke(cr);
    draw_text(cr, x0 + 6, y0 + h - 8, "zoom: where the surface moved", 12);
  }
  draw_surface_labels(cr, camera, options);
  return encode_png(made.value().first.get());
}

std::vector<double> nice_ticks(double lo, double hi, int target) {
  if (!(hi > lo)) {
    const double pad = lo == 0.0 ? 1.0 : std::abs(lo) * 0.5;
    lo -= pad;
    hi += pad;
  }
  const double raw = (hi - lo) / std::max(1, target);
  const double magnitude = std::pow(10.0, std::floor(std::log10(raw)));
  double step = magnitude;
  for (const double m : {1.0, 2.0, 5.0, 10.0}) {
    step = m * magnitude;
    if (step >= raw) break;
  }
  std::vector<double> ticks;
  const double first = std::floor(lo / step) * step;
  for (double t = first; ticks.size() < 100; t += step) {
    ticks.push_back(t);
    if (t >= hi) break;
  }
  return ticks;
}

namespace {

/// The plot area [pixels] and the data ranges it shows.
struct PlotFrame {
  double left, right, top, bottom;
  double t_lo, t_hi, f_lo, f_hi;
  double x(double t) const { return left + (t - t_lo) / (t_hi - t_lo) * (right - left); }
  double y(double f) const { return bottom - (f - f_lo) / (f_hi - f_lo) * (bottom - top); }
};

/// Vertical grid lines with ticks and labels at the time ticks.
void draw_time_axis(cairo_t* cr, const PlotFrame& frame, const std::vector<double>& ticks) {
  for (const double t : ticks) {
    cairo_set_source_rgb(cr, 0.9, 0.9, 0.9);
    cairo_move_to(cr, frame.x(t), frame.top);
    cairo_line_to(cr, frame.x(t), frame.bottom);
    cairo_stroke(cr);
    cairo_set_source_rgb(cr, 0.15, 0.15, 0.15);
    cairo_move_to(cr, frame.x(t), frame.bottom);
    cairo_line_to(cr, frame.x(t), frame.bottom + 5);
    cairo_stroke(cr);
    draw_text(cr, frame.x(t), frame.bottom + 20,
              tick_label(t, ticks.size() > 1 ? ticks[1] - ticks[0] : 1.0), 12, true);
  }
}

/// Horizontal grid lines with ticks and labels at the force ticks.
void draw_force_axis(cairo_t* cr, const PlotFrame& frame, const std::vector<double>& ticks) {
  for (const double f : ticks) {
    cairo_set_source_rgb(cr, 0.9, 0.9, 0.9);
    cairo_move_to(cr, frame.left, frame.y(f));
    cairo_line_to(cr, frame.right, frame.y(f));
    cairo_stroke(cr);
    cairo_set_source_rgb(cr, 0.15, 0.15, 0.15);
    cairo_move_to(cr, frame.left - 5, frame.y(f));
    cairo_line_to(cr, frame.left, frame.y(f));
    cairo_stroke(cr);
    draw_text(cr, frame.left - 8, frame.y(f) + 4,
              tick_label(f, ticks.size() > 1 ? ticks[1] - ticks[0] : 1.0), 12, false, true);
  }
}

/// The frame's border, the axis titles and the plot title.
void draw_plot_labels(cairo_t* cr, const PlotFrame& frame, const std::string& title, int height) {
  cairo_set_source_rgb(cr, 0.15, 0.15, 0.15);
  cairo_rectangle(cr, frame.left, frame.top, frame.right - frame.left, frame.bottom - frame.top);
  cairo_stroke(cr);
  draw_text(cr, 0.5 * (frame.left + frame.right), height - 18.0, "time [s]", 14, true);
  cairo_save(cr);
  cairo_translate(cr, 22, 0.5 * (frame.top + frame.bottom));
  cairo_rotate(cr, -M_PI / 2);
  draw_text(cr, 0, 0, "force on the device [N]", 14, true);
  cairo_restore(cr);
  draw_text(cr, frame.left, 30, title, 18);
}

struct ForceCurve {
  int component;  // 3 = magnitude
  double r, g, b, width;
  const char* name;
};
// Components thin, magnitude thick.
constexpr ForceCurve kForceCurves[] = {{0, 0.85, 0.25, 0.2, 1.2, "fx"},
                                       {1, 0.2, 0.6, 0.25, 1.2, "fy"},
                                       {2, 0.2, 0.35, 0.85, 1.2, "fz"},
                                       {3, 0.05, 0.05, 0.05, 2.0, "|f|"}};

/// The force curves, clipped to the frame, and their legend above it.
void draw_force_curves(cairo_t* cr, const PlotFrame& frame, const std::vector<double>& times,
                       const std::vector<Eigen::Vector3d>& forces) {
  cairo_rectangle(cr, frame.left, frame.top, frame.right - frame.left, frame.bottom - frame.top);
  cairo_clip(cr);
  for (const ForceCurve& c : kForceCurves) {
    cairo_set_source_rgb(cr, c.r, c.g, c.b);
    cairo_set_line_width(cr, c.width);
    for (std::size_t k = 0; k < times.size(); ++k) {
      const double value = c.component == 3 ? forces[k].norm() : forces[k][c.component];
      if (k == 0)
        cairo_move_to(cr, frame.x(times[k]), frame.y(value));
      else
        cairo_line_to(cr, frame.x(times[k]), frame.y(value));
    }
    cairo_stroke(cr);
  }
  cairo_reset_clip(cr);
  double legend_x = frame.right - 260;
  for (const ForceCurve& c : kForceCurves) {
    cairo_set_source_rgb(cr, c.r, c.g, c.b);
    cairo_set_line_width(cr, c.width + 1);
    cairo_move_to(cr, legend_x, 32);
    cairo_line_to(cr, legend_x + 22, 32);
    cairo_stroke(cr);
    draw_text(cr, legend_x + 27, 37, c.name, 13);
    legend_x += 65;
  }
}

}  // namespace

Result<std::string> plot_force_png(const std::vector<double>& times,
                                   const std::vector<Eigen::Vector3d>& forces,
                                   const ForcePlotOptions& options) {
  const std::string& title = options.title;
  const int width = options.width;
  const int height = options.height;
  if (times.size() != forces.size()) {
    return Status::error(StatusCode::invalid_argument,
                         "force plot: times and forces differ in length");
  }
  Result<std::pair<SurfacePtr, ContextPtr>> made = canvas(width, height);
  if (!made.ok()) return made.status();
  cairo_t* cr = made.value().second.get();
  double f_lo = 0.0, f_hi = 0.0;
  for (const Eigen::Vector3d& f : forces) {
    f_lo = std::min({f_lo, f.minCoeff()});
    f_hi = std::max({f_hi, f.maxCoeff(), f.norm()});
  }
  const std::vector<double> xt =
      nice_ticks(times.empty() ? 0.0 : times.front(), times.empty() ? 1.0 : times.back(), 8);
  const std::vector<double> yt = nice_ticks(f_lo, f_hi, 6);
  const PlotFrame frame{80,         width - 30.0, 50,         height - 60.0,
                        xt.front(), xt.back(),    yt.front(), yt.back()};
  cairo_set_line_width(cr, 1.0);
  draw_time_axis(cr, frame, xt);
  draw_force_axis(cr, frame, yt);
  draw_plot_labels(cr, frame, title, height);
  draw_force_curves(cr, frame, times, forces);
  return encode_png(made.value().first.get());
}

}  // namespace argil::sculpt
