// Pictures: what cairo draws shows the surface (not blank, not uniform), a
// local change of the surface changes the picture only around it, and the
// force plot carries its curves. PNGs are decoded back with cairo.
#include <cairo.h>

#include <unistd.h>
#include <algorithm>
#include <array>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "argil/io/mesh/tessellate.hpp"
#include "argil/sculpt/output/pictures.hpp"
#include "argil/sculpt/output/session_pictures.hpp"

namespace argil::sculpt {
namespace {

struct Image {
  int width = 0, height = 0;
  std::vector<std::uint32_t> pixels;  // 0xRRGGBB
  std::uint32_t at(int x, int y) const { return pixels[static_cast<std::size_t>(y * width + x)]; }
};

struct Reader {
  const std::string* bytes;
  std::size_t offset = 0;
};

cairo_status_t read_bytes(void* closure, unsigned char* data, unsigned int length) {
  auto* r = static_cast<Reader*>(closure);
  if (r->offset + length > r->bytes->size()) return CAIRO_STATUS_READ_ERROR;
  std::memcpy(data, r->bytes->data() + r->offset, length);
  r->offset += length;
  return CAIRO_STATUS_SUCCESS;
}

Image decode(const std::string& png) {
  Reader reader{&png};
  cairo_surface_t* s = cairo_image_surface_create_from_png_stream(read_bytes, &reader);
  REQUIRE(cairo_surface_status(s) == CAIRO_STATUS_SUCCESS);
  Image image;
  image.width = cairo_image_surface_get_width(s);
  image.height = cairo_image_surface_get_height(s);
  const int stride = cairo_image_surface_get_stride(s);
  const unsigned char* data = cairo_image_surface_get_data(s);
  for (int y = 0; y < image.height; ++y) {
    const auto* row = reinterpret_cast<const std::uint32_t*>(data + y * stride);
    for (int x = 0; x < image.width; ++x) image.pixels.push_back(row[x] & 0xffffffu);
  }
  cairo_surface_destroy(s);
  return image;
}

/// A bicubic 8 x 8 sheet over [0, 100]^2 at z = 0, optionally with pole (3, 4) raised.
io::Model sheet(double bump) {
  BSplineSurface s;
  s.degree = {3, 3};
  Eigen::VectorXd knots(12);
  knots << 0, 0, 0, 0, 1, 2, 3, 4, 5, 5, 5, 5;
  s.knots = {knots, knots};
  const Eigen::VectorXd g = greville_abscissae(3, knots);
  s.control_points.resize(64, 3);
  for (int i = 0; i < 8; ++i) {
    for (int j = 0; j < 8; ++j) s.control_points.row(i * 8 + j) << 20 * g[i], 20 * g[j], 0.0;
  }
  s.control_points(3 * 8 + 4, 2) = bump;
  io::Model m;
  m.faces.push_back({s, {}, false, "", "sheet"});
  return m;
}

io::TriangleMesh mesh_of(const io::Model& m) {
  io::TessellationOptions options;
  options.chord_tolerance_mm = 0.05;
  const Result<io::TriangleMesh> mesh = io::tessellate(m, options);
  REQUIRE(mesh.ok());
  return mesh.value();
}

TEST_CASE("a surface picture shows the shaded surface and a local change only locally",
          "[pictures]") {
  const io::Model flat = sheet(0.0), bumped = sheet(15.0);
  const Box3 box{Eigen::Vector3d(0, 0, -1), Eigen::Vector3d(100, 100, 16)};
  const Camera camera = fit_camera(box, 400, 300);
  const Image before = decode(render_surface_png(mesh_of(flat), {}, camera).value());
  const Image after = decode(render_surface_png(mesh_of(bumped), {}, camera).value());
  REQUIRE(before.width == 400);
  REQUIRE(before.height == 300);
  long covered = 0;
  std::vector<std::uint32_t> colours;
  for (const std::uint32_t p : before.pixels) {
    covered += p != 0xffffffu;
    colours.push_back(p);
  }
  std::sort(colours.begin(), colours.end());
  const auto distinct = std::unique(colours.begin(), colours.end()) - colours.begin();
  // The sheet fills a good part of the fitted view, and it is not one flat colour
  // (antialiased edges and text alone give a few dozen).
  CHECK(covered > 400 * 300 / 5);
  CHECK(distinct > 3);

  // The raised pole moves the surface over its support, spans 1..5 in u and
  // 2..6 in v at most, that is x in [0, 100] x y in [20, 100] at worst: pixels
  // outside the projection of that region (plus the 15 mm bump height) match.
  int changed = 0, changed_far = 0;
  const Eigen::Vector3d support_min(0, 20, 0), support_max(100, 100, 15);
  Eigen::Vector2d lo(1e9, 1e9), hi(-1e9, -1e9);
  for (int corner = 0; corner < 8; ++corner) {
    const Eigen::Vector3d p((corner & 1) ? support_max.x() : support_min.x(),
                            (corner & 2) ? support_max.y() : support_min.y(),
                            (corner & 4) ? support_max.z() : support_min.z());
    lo = lo.cwiseMin(camera.project(p));
    hi = hi.cwiseMax(camera.project(p));
  }
  for (int y = 0; y < before.height; ++y) {
    for (int x = 0; x < before.width; ++x) {
      if (before.at(x, y) == after.at(x, y)) continue;
      ++changed;
      // Two pixels of slack for antialiasing at the region's edge.
      const bool inside = x >= lo.x() - 2 && x <= hi.x() + 2 && y >= lo.y() - 2 && y <= hi.y() + 2;
      changed_far += inside ? 0 : 1;
    }
  }
  CHECK(changed > 500);
  CHECK(changed_far == 0);

  // Where the pole was raised (projected), the two pictures differ.
  const Eigen::Vector2d at = camera.project(Eigen::Vector3d(20 * 2.0, 20 * 2.5, 6.0));
  int near = 0;
  for (int dy = -10; dy <= 10; ++dy) {
    for (int dx = -10; dx <= 10; ++dx) {
      const int x = static_cast<int>(at.x()) + dx, y = static_cast<int>(at.y()) + dy;
      near += before.at(x, y) != after.at(x, y);
    }
  }
  CHECK(near > 0);
}

TEST_CASE("the force plot draws axes and curves", "[pictures]") {
  std::vector<double> t;
  std::vector<Eigen::Vector3d> f;
  for (int k = 0; k <= 1000; ++k) {
    t.push_back(k * 1e-3);
    f.emplace_back(0.5 * std::sin(k * 0.01), 0.0, 3.0 * std::min(1.0, k * 0.002));
  }
  const Image plot =
      decode(plot_force_png(t, f, {.title = "test", .width = 640, .height = 360}).value());
  CHECK(plot.width == 640);
  long dark = 0;
  for (const std::uint32_t p : plot.pixels) {
    const int r = (p >> 16) & 0xff, g = (p >> 8) & 0xff, b = p & 0xff;
    dark += r + g + b < 150;
  }
  CHECK(dark > 1000);  // axes, labels and the |f| curve are dark
  CHECK_FALSE(plot_force_png({0.0}, {}, {.title = "mismatch"}).ok());
}

TEST_CASE("axis ticks are round numbers covering the range", "[pictures]") {
  const std::vector<double> ticks = nice_ticks(0.0, 2.3, 6);
  REQUIRE(ticks.size() >= 3);
  CHECK(ticks.front() <= 0.0);
  CHECK(ticks.back() >= 2.3);
  const double step = ticks[1] - ticks[0];
  CHECK(step == Approx(0.5));                 // 2.3 / 6 = 0.38 rounds up to 0.5
  CHECK(nice_ticks(-1.0, -1.0).size() >= 2);  // a flat range is widened
}

}  // namespace
}  // namespace argil::sculpt

namespace argil::sculpt {

TEST_CASE("the after picture colours the signed displacement, and says when nothing moved",
          "[pictures]") {
  const io::Model flat = sheet(0.0);
  // Pushed in: pole (3, 4) lowered 5 mm moves points along -z, against the
  // sheet's normal (+z, S_u x S_v), and nowhere out.
  const io::TriangleMesh pushed = mesh_of(sheet(-5.0));
  const SurfacePictureOptions in = after_picture_options(flat, pushed, 1e-3, "sheet");
  REQUIRE(in.vertex_displacement.size() == static_cast<std::size_t>(pushed.positions.rows()));
  CHECK(in.note.empty());
  const auto [lo, hi] =
      std::minmax_element(in.vertex_displacement.begin(), in.vertex_displacement.end());
  CHECK(*lo < -1.0);
  CHECK(*hi <= 1e-12);
  CHECK(in.displacement_scale == -*lo);
  // Raised: the same magnitudes, out.
  const SurfacePictureOptions out = after_picture_options(flat, mesh_of(sheet(5.0)), 1e-3, "sheet");
  CHECK(*std::max_element(out.vertex_displacement.begin(), out.vertex_displacement.end()) ==
        Approx(-*lo).epsilon(1e-12));
  // Not moved, or by less than eps: no colour, and a note that says so.
  for (const double bump : {0.0, 1e-9}) {
    const SurfacePictureOptions still =
        after_picture_options(flat, mesh_of(sheet(bump)), 1e-3, "sheet");
    CHECK(still.vertex_displacement.empty());
    CHECK_THAT(still.note, Catch::StartsWith("no change: no point moved more than"));
    // The picture draws it: clay shading and the note, no colour bar.
    const Box3 box{Eigen::Vector3d(0, 0, -1), Eigen::Vector3d(100, 100, 1)};
    CHECK(render_surface_png(mesh_of(sheet(bump)), {}, fit_camera(box, 400, 300), still).ok());
  }
}

}  // namespace argil::sculpt

namespace argil::sculpt {

TEST_CASE("the tool is drawn where given, and a zoom inset shows the region again", "[pictures]") {
  const io::TriangleMesh mesh = mesh_of(sheet(-5.0));
  const Box3 box{Eigen::Vector3d(0, 0, -6), Eigen::Vector3d(100, 100, 1)};
  const Camera camera = fit_camera(box, 400, 300);
  const Image plain = decode(render_surface_png(mesh, {}, camera).value());
  SurfacePictureOptions options;
  options.tool_position = Eigen::Vector3d(60, 60, 10);
  options.tool_radius_mm = 8.0;
  const Image with_tool = decode(render_surface_png(mesh, {}, camera, options).value());
  // Pixels change on the tool's outline (radius 8 mm around its projection) and
  // nowhere far from it.
  const Eigen::Vector2d at = camera.project(*options.tool_position);
  const double r = 8.0 * camera.pixels_per_mm;
  int on_outline = 0, far = 0;
  for (int y = 0; y < plain.height; ++y)
    for (int x = 0; x < plain.width; ++x) {
      if (plain.at(x, y) == with_tool.at(x, y)) continue;
      const double d = (Eigen::Vector2d(x, y) - at).norm();
      on_outline += d > r - 3 && d < r + 3;
      far += d > r + 3;
    }
  CHECK(on_outline > 20);
  CHECK(far == 0);
  // The inset (top right, 3/8 of each side) holds the zoomed surface.
  options.tool_position.reset();
  options.zoom = Box3{Eigen::Vector3d(30, 40, -6), Eigen::Vector3d(50, 60, 1)};
  const Image zoomed = decode(render_surface_png(mesh, {}, camera, options).value());
  const int w = 400 * 3 / 8, h = 300 * 3 / 8, x0 = 400 - w - 10, y0 = 10;
  int surface = 0;
  for (int y = y0 + 2; y < y0 + h - 20; ++y)
    for (int x = x0 + 2; x < x0 + w - 2; ++x) surface += zoomed.at(x, y) != 0xffffffu;
  // The inset shows the part of the sheet inside the box, cut away from the
  // rest: a 20 x 20 mm square seen from 35 degrees up, drawn to fit the box
  // (7 mm tall) in the inset. It covers a fair part of the inset, not all of it.
  CHECK(surface > (w - 4) * (h - 22) / 4);
  CHECK(surface < (w - 4) * (h - 22) * 9 / 10);
}

namespace {

/// Meshes appended: vertices and triangles of `b` after those of `a`.
io::TriangleMesh joined(const io::TriangleMesh& a, const io::TriangleMesh& b) {
  io::TriangleMesh m;
  const Eigen::Index na = a.positions.rows(), nb = b.positions.rows();
  m.positions.resize(na + nb, 3);
  m.positions << a.positions, b.positions;
  m.normals.resize(na + nb, 3);
  m.normals << a.normals, b.normals;
  m.uv.resize(na + nb, 2);
  m.uv << a.uv, b.uv;
  m.triangles.resize(a.triangles.rows() + b.triangles.rows(), 3);
  m.triangles << a.triangles, (b.triangles.array() + static_cast<int>(na)).matrix();
  return m;
}

/// One triangle per row of `corners` (three rows each), with the given normal.
io::TriangleMesh triangles(const Eigen::MatrixX3d& corners, const Eigen::Vector3d& normal) {
  io::TriangleMesh m;
  m.positions = corners;
  m.normals = normal.transpose().replicate(corners.rows(), 1);
  m.uv = Eigen::MatrixX2d::Zero(corners.rows(), 2);
  m.triangles.resize(corners.rows() / 3, 3);
  for (Eigen::Index t = 0; t < m.triangles.rows(); ++t)
    m.triangles.row(t) << static_cast<int>(3 * t), static_cast<int>(3 * t + 1),
        static_cast<int>(3 * t + 2);
  return m;
}

bool blue(std::uint32_t rgb) {
  const int r = static_cast<int>(rgb >> 16 & 0xff), b = static_cast<int>(rgb & 0xff);
  return b > r + 60;
}

}  // namespace

TEST_CASE("each pixel shows the nearest surface, whatever the triangles' sizes", "[pictures]") {
  // Seen from straight above. A long thin triangle rises from z = 0 at x = 0
  // to z = 20 at x = 100; a small one lies at z = 15 under its high end (at x
  // 80..90 the long one is at z = 16..18). Sorted by their mean depth (6.7
  // and 15) back to front, the small one was painted over the long one.
  Eigen::MatrixX3d corners(6, 3);
  corners << 0, -5, 0, 0, 5, 0, 100, 0, 20,  // long, rising
      80, -2, 15, 90, -2, 15, 85, 2, 15;     // small, under it
  const io::TriangleMesh mesh = triangles(corners, Eigen::Vector3d::UnitZ());
  const Camera camera = fit_camera(Box3{Eigen::Vector3d(0, -5, 0), Eigen::Vector3d(100, 5, 20)},
                                   400, 300, Eigen::Vector3d::UnitZ());
  SurfacePictureOptions options;
  options.vertex_displacement = {0, 0, 0, -1, -1, -1};  // the small one blue
  options.displacement_scale = 1.0;
  const Image image = decode(render_surface_png(mesh, {}, camera, options).value());
  const Eigen::Vector2d under = camera.project(Eigen::Vector3d(85, -0.5, 15));
  CHECK(image.at(static_cast<int>(under.x()), static_cast<int>(under.y())) != 0xffffffu);
  CHECK_FALSE(blue(image.at(static_cast<int>(under.x()), static_cast<int>(under.y()))));
  // Where the long one is narrower than the small one, the small one shows.
  int small_shows = 0;
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) small_shows += blue(image.at(x, y));
  CHECK(small_shows > 20);
}

TEST_CASE("the zoom inset shows its region when another surface is in front of it", "[pictures]") {
  // The sheet dented (blue) at z = -5 and a plain sheet 20 mm above it: from
  // 35 degrees up the plain one hides the dent in the whole view, and the
  // inset, which draws only what lies inside its box, shows it.
  const io::TriangleMesh dented = mesh_of(sheet(-5.0));
  io::TriangleMesh above = mesh_of(sheet(0.0));
  above.positions.col(2).array() += 20.0;
  const io::TriangleMesh mesh = joined(dented, above);
  SurfacePictureOptions options;
  options.vertex_displacement.assign(static_cast<std::size_t>(mesh.positions.rows()), 0.0);
  for (Eigen::Index v = 0; v < dented.positions.rows(); ++v)
    options.vertex_displacement[static_cast<std::size_t>(v)] = -1.0;
  options.displacement_scale = 1.0;
  options.zoom = Box3{Eigen::Vector3d(30, 40, -6), Eigen::Vector3d(50, 60, 1)};
  const Box3 box{Eigen::Vector3d(0, 0, -6), Eigen::Vector3d(100, 100, 21)};
  const Camera camera = fit_camera(box, 400, 300, view_direction(-60.0, 35.0));
  options.zoom_eye = Eigen::Vector3d::UnitZ();  // straight down: the upper sheet in front
  const Image image = decode(render_surface_png(mesh, {}, camera, options).value());
  const int w = 400 * 3 / 8, h = 300 * 3 / 8, x0 = 400 - w - 10, y0 = 10;
  int inset_blue = 0, inset = 0;
  for (int y = y0 + 2; y < y0 + h - 20; ++y)
    for (int x = x0 + 2; x < x0 + w - 2; ++x) {
      ++inset;
      inset_blue += blue(image.at(x, y));
    }
  CHECK(inset_blue > inset / 2);
}

}  // namespace argil::sculpt

namespace argil::sculpt {
namespace {

/// before.png of a run over the flat sheet whose device pressed hardest at
/// (60, 50, 2) turned by `turn` about z, holding `tools`.
Image pictured_press(const std::vector<PictureTool>& tools, const Eigen::Quaterniond& turn) {
  SessionPicturesRequest request;
  request.before = sheet(0.0);
  request.after = sheet(0.0);
  request.path.positions = {Eigen::Vector3d(20, 20, 20), Eigen::Vector3d(60, 50, 2),
                            Eigen::Vector3d(70, 50, 2)};
  request.path.engaged = {false, true, true};
  request.times = {0.0, 0.001, 0.002};
  request.forces = {Eigen::Vector3d::Zero(), Eigen::Vector3d(0, 0, 3), Eigen::Vector3d(0, 0, 1)};
  request.rotations = {Eigen::Quaterniond::Identity(), turn, Eigen::Quaterniond::Identity()};
  request.title = "pad";
  request.tolerance_mm = 0.01;
  request.tools = tools;
  const std::filesystem::path folder = std::filesystem::temp_directory_path() /
                                       ("argil-pictures-test-" + std::to_string(::getpid()));
  std::filesystem::create_directories(folder);
  REQUIRE(write_session_pictures(request, folder).ok());
  std::ifstream in(folder / kBeforePicture, std::ios::binary);
  const std::string png((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  std::filesystem::remove_all(folder);
  return decode(png);
}

}  // namespace

TEST_CASE("a B-spline tool is drawn posed by the device where it pressed hardest", "[pictures]") {
  // A flat 20 x 8 mm pad in its tool frame, centred on the frame's origin.
  BSplineSurface pad;
  pad.degree = {1, 1};
  Eigen::VectorXd knots(4);
  knots << 0, 0, 1, 1;
  pad.knots = {knots, knots};
  pad.control_points.resize(4, 3);
  pad.control_points << -10, -4, 0, -10, 4, 0, 10, -4, 0, 10, 4, 0;
  const Eigen::Quaterniond quarter_turn(Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitZ()));
  const Image plain = pictured_press({}, quarter_turn);
  // write_session_pictures' camera: fitted to the sheet and the engaged path,
  // looking from the sheet's normal tilted towards a three-quarter view.
  const Eigen::Vector3d eye = (Eigen::Vector3d::UnitZ() + 0.8 * view_direction(-60.0, 35.0));
  const Camera camera = fit_camera(Box3{Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(100, 100, 2)},
                                   960, 720, eye.normalized());
  for (const bool turned : {false, true}) {
    CAPTURE(turned);
    const Image drawn = pictured_press({PictureTool{0.0, pad}},
                                       turned ? quarter_turn : Eigen::Quaterniond::Identity());
    // The pad posed: 20 mm along x (8 along y), or along y when turned.
    const Eigen::Vector2d half = turned ? Eigen::Vector2d(4, 10) : Eigen::Vector2d(10, 4);
    std::vector<Eigen::Vector2d> corners;
    for (const double sx : {-1.0, 1.0})
      for (const double sy : {-1.0, 1.0})
        corners.push_back(
            camera.project(Eigen::Vector3d(60 + sx * half.x(), 50 + sy * half.y(), 2)));
    Eigen::Vector2d lo = corners[0], hi = corners[0];
    for (const Eigen::Vector2d& c : corners) {
      lo = lo.cwiseMin(c);
      hi = hi.cwiseMax(c);
    }
    int changed = 0, outside = 0;
    std::array<int, 4> near_corner{};
    for (int y = 0; y < plain.height; ++y)
      for (int x = 0; x < plain.width; ++x) {
        if (plain.at(x, y) == drawn.at(x, y)) continue;
        ++changed;
        const Eigen::Vector2d at(x, y);
        outside += (at.array() < lo.array() - 3).any() || (at.array() > hi.array() + 3).any();
        for (std::size_t c = 0; c < 4; ++c) near_corner[c] += (at - corners[c]).norm() < 3;
      }
    CHECK(changed > 200);
    CHECK(outside == 0);
    for (const int n : near_corner) CHECK(n > 0);
  }
}

}  // namespace argil::sculpt

namespace argil::sculpt {

TEST_CASE("a large change the whole view would see edge-on is looked at", "[pictures]") {
  // A floor (the sheet, 100 x 100 mm at z = 0) and a wall standing on its
  // edge x = 0 (the yz plane, 100 x 40 mm); the wall's middle is pushed 5 mm
  // in along x over most of it, too large a change for the zoom inset. The
  // view the floor decides sees the wall at a glancing angle (its normal about
  // 80 degrees from the eye): the change must still cover a good part of
  // after.png.
  io::Model before = sheet(0.0);
  io::Model wall_model = sheet(0.0);
  BSplineSurface& wall = wall_model.faces[0].surface;
  for (Eigen::Index k = 0; k < wall.control_points.rows(); ++k) {
    const Eigen::Vector3d p = wall.control_points.row(k).transpose();
    wall.control_points.row(k) << 0.0, p.x(), 0.4 * p.y();
  }
  before.faces.push_back(wall_model.faces[0]);
  io::Model after = before;
  BSplineSurface& pushed = after.faces[1].surface;
  for (int i = 1; i < 7; ++i)
    for (int j = 1; j < 7; ++j) pushed.control_points(i * 8 + j, 0) -= 5.0;
  SessionPicturesRequest request;
  request.before = before;
  request.after = after;
  request.path.positions = {Eigen::Vector3d(-20, 50, 20), Eigen::Vector3d(-10, 50, 20)};
  request.path.engaged = {false, false};
  request.times = {0.0, 0.001};
  request.forces = {Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()};
  request.title = "wall";
  request.tolerance_mm = 0.01;
  const std::filesystem::path folder = std::filesystem::temp_directory_path() /
                                       ("argil-pictures-wall-" + std::to_string(::getpid()));
  std::filesystem::create_directories(folder);
  REQUIRE(write_session_pictures(request, folder).ok());
  std::ifstream in(folder / kAfterPicture, std::ios::binary);
  const std::string png((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  std::filesystem::remove_all(folder);
  const Image image = decode(png);
  int changed = 0;
  for (const std::uint32_t p : image.pixels) {
    const int r = static_cast<int>(p >> 16 & 0xff), b = static_cast<int>(p & 0xff);
    changed += std::abs(b - r) > 60;  // blue (in) or red (out)
  }
  CHECK(changed > image.width * image.height / 10);
}

}  // namespace argil::sculpt
