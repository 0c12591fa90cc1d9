// Checks the outputs of `argil sculpt` on an example, for CTest:
//  1. the exported models (STEP, IGES, JSON) re-import through argil::io with
//     every face of the input file: a face the scene does not name is the
//     input's, every field bit for bit (JSON); a named face is the input face
//     or its exact refinement (a deformable face the tool works on may be
//     refined before the run); every face has control points identical
//     to the JSON export's (bit for bit; IGES has no face orientation, so a
//     reversed face comes back on the mirrored surface: its net is then the
//     JSON's in reverse order along one direction, bit for bit);
//  2. rigid models did not move at all;
//  3. each deformable model changed: some point moved more than --changed-min
//     (default 2 eps: clearly above the tolerance), and it lies within reach of
//     the tool's path;
//  4. it changed nowhere else, face by face:
//     - a face the tool never came near (every sample farther from the path
//       than the tool's radius, eps and the sampling grid's chord) did not
//       move: bit for bit when it was not refined, else it is the input's
//       exact refinement rebuilt here (degree elevation, knot insertion) to
//       rounding. A deformable model's faces are joined along their shared
//       edges, so such a face may be carried by its joints, by at most the
//       largest move, when a chain of shared edges joins it to a face the tool
//       came near;
//     - the faces stayed joined: along every edge two named faces (or a
//       closed face's seam) share, the gap between them grew by at most eps
//       at each of 33 points
//       and the angle between their normals changed by at most
//       kTangentJoinAngle (1 degree)
//       (33 points along one use, each against the other use's nearest of 513);
//     - on the other faces every control point that moved (against that
//       rebuilt refinement) more than --quiet-max lies within reach of the
//       path: the tool's radius plus the size of the control points around it
//       that bound its support (a control point moves only when its support
//       meets a contact);
//     - every sample farther than the face's reach from the path moved less
//       than --quiet-max (default 1% of the largest move, at least eps);
//  5. the pictures decode (cairo) and show something: before.png and after.png
//     are at least 5% covered by the surface and hold many colours, force.png
//     holds the curves, and after.png differs from before.png.
// The path is where the device went while engaged (recorded.csv) and where
// the tool itself went then (the proxy in forces.csv). A face's reach is the
// tool's radius plus the B-spline support of a control point, (degree + 1)
// times the longest control-polygon leg of the sculpted net. Samples: a
// 41 x 41 grid in each face's parameter domain, compared at equal (u, v).
//
// usage: example_check SCENE OUTDIR [--changed-min MM] [--quiet-max MM]
#include <cairo.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

#include "argil/core/deform/edge_joint.hpp"
#include "argil/core/geometry/bspline_curve.hpp"
#include "argil/core/geometry/degree_elevation.hpp"
#include "argil/core/geometry/evaluate.hpp"
#include "argil/core/geometry/knot_insertion.hpp"
#include "argil/io/files/model_files.hpp"
#include "argil/sculpt/scene/scene.hpp"
#include "argil/sculpt/script/script.hpp"

namespace {

using argil::BSplineSurface;
using argil::Direction;

int failures = 0;

Eigen::Vector2d uv_at(const BSplineSurface& s, const argil::BSplineCurve& pcurve, double t) {
  const Eigen::VectorXd uv = argil::evaluate(pcurve, t);
  return {std::clamp(uv[0], s.domain_start(Direction::u), s.domain_end(Direction::u)),
          std::clamp(uv[1], s.domain_start(Direction::v), s.domain_end(Direction::v))};
}

Eigen::Vector3d point_at(const BSplineSurface& s, const argil::BSplineCurve& pcurve, double t) {
  const Eigen::Vector2d uv = uv_at(s, pcurve, t);
  return argil::evaluate(s, uv.x(), uv.y());
}

Eigen::Vector3d normal_at(const BSplineSurface& s, const argil::BSplineCurve& pcurve, double t) {
  const Eigen::Vector2d uv = uv_at(s, pcurve, t);
  return argil::unit_normal(s, uv.x(), uv.y());
}

/// Two faces along an edge they share, at 33 points along one use, each
/// against the nearest point of the other use (the nearest of 513, refined):
/// how far apart they are [mm] and the angle between their normals as lines
/// [rad] (a face's orientation in the file does not matter).
struct EdgeSamples {
  std::vector<double> gap, angle;
};

EdgeSamples edge_samples(const BSplineSurface& a, const argil::BSplineCurve& on_a,
                         const BSplineSurface& b, const argil::BSplineCurve& on_b) {
  constexpr int kDense = 512, kSparse = 32;
  std::vector<Eigen::Vector3d> dense;
  std::vector<double> dense_t;
  const double b0 = on_b.domain_start(), b1 = on_b.domain_end();
  for (int k = 0; k <= kDense; ++k) {
    dense_t.push_back(b0 + (b1 - b0) * k / kDense);
    dense.push_back(point_at(b, on_b, dense_t.back()));
  }
  const double a0 = on_a.domain_start(), a1 = on_a.domain_end();
  EdgeSamples out;
  for (int k = 0; k <= kSparse; ++k) {
    const double t = a0 + (a1 - a0) * k / kSparse;
    const Eigen::Vector3d p = point_at(a, on_a, t);
    std::size_t nearest = 0;
    for (std::size_t q = 1; q < dense.size(); ++q)
      if ((p - dense[q]).norm() < (p - dense[nearest]).norm()) nearest = q;
    // Refined between the dense points either side (golden section): the two
    // curves may run at different paces, and a dense point can be far off.
    double lo = dense_t[nearest > 0 ? nearest - 1 : 0];
    double hi = dense_t[std::min(nearest + 1, dense_t.size() - 1)];
    const auto distance = [&](double s) { return (point_at(b, on_b, s) - p).norm(); };
    const double g = 0.5 * (std::sqrt(5.0) - 1.0);
    for (int it = 0; it < 60; ++it) {
      const double x1 = hi - g * (hi - lo), x2 = lo + g * (hi - lo);
      if (distance(x1) < distance(x2)) {
        hi = x2;
      } else {
        lo = x1;
      }
    }
    const double tb = 0.5 * (lo + hi);
    out.gap.push_back(distance(tb));
    const Eigen::Vector3d na = normal_at(a, on_a, t), nb = normal_at(b, on_b, tb);
    out.angle.push_back(std::atan2(na.cross(nb).norm(), std::abs(na.dot(nb))));
  }
  return out;
}

void check(bool ok, const std::string& what) {
  std::printf("%s: %s\n", ok ? "ok  " : "FAIL", what.c_str());
  if (!ok) ++failures;
}

bool same_bits(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
  if (a.rows() != b.rows() || a.cols() != b.cols()) return false;
  // An empty matrix may hold no storage at all; memcmp must not see null.
  return a.size() == 0 ||
         std::memcmp(a.data(), b.data(), sizeof(double) * static_cast<std::size_t>(a.size())) == 0;
}

bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

bool same_bits(const BSplineSurface& a, const BSplineSurface& b) {
  return a.degree == b.degree && same_bits(a.knots[0], b.knots[0]) &&
         same_bits(a.knots[1], b.knots[1]) && same_bits(a.control_points, b.control_points) &&
         same_bits(a.weights, b.weights);
}

/// Every field of a face, bit for bit: its surface, trims, orientation and
/// source entity (JSON keeps them all exactly).
bool same_face(const argil::io::FaceRecord& a, const argil::io::FaceRecord& b) {
  if (!same_bits(a.surface, b.surface) || a.reversed != b.reversed || a.source_id != b.source_id ||
      a.name != b.name || a.loops.size() != b.loops.size())
    return false;
  for (std::size_t l = 0; l < a.loops.size(); ++l) {
    const argil::io::TrimLoop &la = a.loops[l], &lb = b.loops[l];
    if (la.outer != lb.outer || la.curves.size() != lb.curves.size()) return false;
    for (std::size_t k = 0; k < la.curves.size(); ++k) {
      const argil::BSplineCurve &ca = la.curves[k], &cb = lb.curves[k];
      if (ca.degree != cb.degree || !same_bits(ca.knots, cb.knots) ||
          !same_bits(ca.points, cb.points) || !same_bits(ca.weights, cb.weights))
        return false;
    }
  }
  return true;
}

bool same_structure(const BSplineSurface& a, const BSplineSurface& b) {
  // Eigen compares vectors of equal size only: a refined face has more knots.
  auto same_knots = [&](int d) {
    return a.knots[d].size() == b.knots[d].size() && a.knots[d] == b.knots[d];
  };
  return a.degree == b.degree && same_knots(0) && same_knots(1) &&
         a.weights.size() == b.weights.size() && a.control_points.rows() == b.control_points.rows();
}

/// `a` is `b` refined exactly (degree elevation, knot insertion; the run
/// refines deformable faces where the tool works): the same domain, no lower
/// degree, and every knot of `b` in `a` at least as often as the elevation
/// requires, so `a` can represent `b` at equal (u, v).
bool refines(const BSplineSurface& a, const BSplineSurface& b) {
  for (int d = 0; d < 2; ++d) {
    const Eigen::VectorXd &ka = a.knots[static_cast<std::size_t>(d)],
                          &kb = b.knots[static_cast<std::size_t>(d)];
    const int raise = a.degree[static_cast<std::size_t>(d)] - b.degree[static_cast<std::size_t>(d)];
    if (raise < 0 || ka[0] != kb[0] || ka[ka.size() - 1] != kb[kb.size() - 1]) return false;
    for (Eigen::Index k = 0; k < kb.size(); ++k)
      if (std::count(ka.begin(), ka.end(), kb[k]) < std::count(kb.begin(), kb.end(), kb[k]) + raise)
        return false;
  }
  return a.weights.size() == 0 || b.weights.size() > 0;
}

/// Longest distance between neighbouring control points [mm].
double longest_leg(const BSplineSurface& s) {
  double leg = 0.0;
  const int nu = s.count(Direction::u), nv = s.count(Direction::v);
  for (int i = 0; i < nu; ++i) {
    for (int j = 0; j < nv; ++j) {
      const Eigen::Vector3d p = s.control_points.row(s.pole_index(i, j)).transpose();
      if (i + 1 < nu)
        leg = std::max(leg, (s.control_points.row(s.pole_index(i + 1, j)).transpose() - p).norm());
      if (j + 1 < nv)
        leg = std::max(leg, (s.control_points.row(s.pole_index(i, j + 1)).transpose() - p).norm());
    }
  }
  return leg;
}

/// `cad` is `json` on the parameter-mirrored surface along one direction, as
/// IGES gives back a reversed face: the same degrees, the other direction's
/// knots bit for bit, this direction's knots mirrored (a + b - k, to the
/// rounding of that sum: 4 ulps of the knot range's magnitude), and the
/// control points and weights in reverse order along it, bit for bit.
bool mirrored_copy(const BSplineSurface& cad, const BSplineSurface& json) {
  if (cad.degree != json.degree || cad.knots[0].size() != json.knots[0].size() ||
      cad.knots[1].size() != json.knots[1].size() || cad.weights.size() != json.weights.size() ||
      cad.control_points.rows() != json.control_points.rows())
    return false;
  const int nu = json.count(Direction::u), nv = json.count(Direction::v);
  for (int d = 0; d < 2; ++d) {
    const auto sd = static_cast<std::size_t>(d);
    const Eigen::VectorXd &kc = cad.knots[sd], &kj = json.knots[sd];
    if (cad.knots[1 - sd] != json.knots[1 - sd]) continue;
    const double a = kj[0], b = kj[kj.size() - 1];
    const double ulps =
        4.0 * std::numeric_limits<double>::epsilon() * std::max(std::abs(a), std::abs(b));
    bool same = true;
    for (Eigen::Index k = 0; same && k < kj.size(); ++k)
      same = std::abs(kc[k] - (a + b - kj[kj.size() - 1 - k])) <= ulps;
    for (int i = 0; same && i < nu; ++i) {
      for (int j = 0; same && j < nv; ++j) {
        const Eigen::Index mine = json.pole_index(d == 0 ? nu - 1 - i : i, d == 1 ? nv - 1 - j : j);
        const Eigen::Index theirs = cad.pole_index(i, j);
        for (int c = 0; same && c < 3; ++c)
          same = same_bits(cad.control_points(theirs, c), json.control_points(mine, c));
        if (same && json.weights.size() > 0)
          same = same_bits(cad.weights[theirs], json.weights[mine]);
      }
    }
    if (same) return true;
  }
  return false;
}

/// The input face `b` rebuilt on the net of its refinement `a` (precondition:
/// refines(a, b)): degree elevation, then every knot `a` has more often than
/// `b`. Exact in the shape; the control points agree with the session's
/// refinement to rounding (the steps run in another order).
argil::Result<BSplineSurface> rebuilt_refinement(const BSplineSurface& b, const BSplineSurface& a) {
  BSplineSurface s = b;
  for (int d = 0; d < 2; ++d) {
    const auto sd = static_cast<std::size_t>(d);
    const auto dir = d == 0 ? Direction::u : Direction::v;
    if (a.degree[sd] > s.degree[sd]) {
      argil::Result<BSplineSurface> up = argil::elevate_degree(s, dir, a.degree[sd] - s.degree[sd]);
      if (!up.ok()) return up.status();
      s = std::move(up).value();
    }
    const Eigen::VectorXd& ka = a.knots[sd];
    for (Eigen::Index k = a.degree[sd] + 1; k < a.count(dir); ++k) {
      if (k > 0 && ka[k] == ka[k - 1]) continue;
      const Eigen::VectorXd& ks = s.knots[sd];
      const auto more =
          std::count(ka.begin(), ka.end(), ka[k]) - std::count(ks.begin(), ks.end(), ka[k]);
      if (more <= 0) continue;
      argil::Result<BSplineSurface> finer =
          argil::insert_knot(s, dir, ka[k], static_cast<int>(more));
      if (!finer.ok()) return finer.status();
      s = std::move(finer).value();
    }
  }
  return s;
}

/// Largest distance from control point (i, j) to the control points of the
/// (2p + 1) x (2q + 1) window about it: its support lies in their convex hull
/// (each span lies in the hull of its own (p + 1) x (q + 1) poles), so every
/// point of the support is within this distance of the control point.
double support_size(const BSplineSurface& s, int i, int j) {
  const int nu = s.count(Direction::u), nv = s.count(Direction::v);
  const Eigen::Vector3d p = s.control_points.row(s.pole_index(i, j)).transpose();
  double size = 0.0;
  for (int k = std::max(0, i - s.degree[0]); k <= std::min(nu - 1, i + s.degree[0]); ++k)
    for (int l = std::max(0, j - s.degree[1]); l <= std::min(nv - 1, j + s.degree[1]); ++l)
      size = std::max(size, (s.control_points.row(s.pole_index(k, l)).transpose() - p).norm());
  return size;
}

double distance_to_path(const Eigen::Vector3d& p, const std::vector<Eigen::Vector3d>& path) {
  double best = INFINITY;
  for (std::size_t k = 0; k < path.size(); ++k) {
    if (k + 1 < path.size()) {
      const Eigen::Vector3d a = path[k], b = path[k + 1];
      const Eigen::Vector3d ab = b - a;
      const double len2 = ab.squaredNorm();
      const double t = len2 > 0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
      best = std::min(best, (a + t * ab - p).norm());
    } else {
      best = std::min(best, (path[k] - p).norm());
    }
  }
  return best;
}

/// Decoded RGB pixels of a PNG (0xRRGGBB); empty when it does not decode.
std::vector<std::uint32_t> read_png(const std::filesystem::path& path, int& width, int& height) {
  cairo_surface_t* image = cairo_image_surface_create_from_png(path.c_str());
  std::vector<std::uint32_t> pixels;
  if (cairo_surface_status(image) == CAIRO_STATUS_SUCCESS) {
    width = cairo_image_surface_get_width(image);
    height = cairo_image_surface_get_height(image);
    const int stride = cairo_image_surface_get_stride(image);
    const unsigned char* data = cairo_image_surface_get_data(image);
    for (int y = 0; y < height; ++y) {
      const auto* row = reinterpret_cast<const std::uint32_t*>(data + y * stride);
      for (int x = 0; x < width; ++x) pixels.push_back(row[x] & 0xffffffu);
    }
  }
  cairo_surface_destroy(image);
  return pixels;
}

void check_pictures(const std::filesystem::path& out) {
  std::vector<std::uint32_t> surfaces[2];
  const char* names[] = {"before.png", "after.png", "force.png"};
  for (int k = 0; k < 3; ++k) {
    int width = 0, height = 0;
    const std::vector<std::uint32_t> pixels = read_png(out / names[k], width, height);
    check(!pixels.empty(), std::string(names[k]) + " decodes");
    if (pixels.empty()) continue;
    std::vector<std::uint32_t> colours = pixels;
    std::sort(colours.begin(), colours.end());
    const auto distinct = std::unique(colours.begin(), colours.end()) - colours.begin();
    const auto white = std::count(pixels.begin(), pixels.end(), 0xffffffu);
    const double covered = 1.0 - static_cast<double>(white) / static_cast<double>(pixels.size());
    char line[160];
    std::snprintf(line, sizeof line, "%s shows something: %.1f%% not background, %ld colours",
                  names[k], 100.0 * covered, static_cast<long>(distinct));
    // Surfaces fill a good part of the frame; the plot is mostly white but has
    // axes, labels and curves.
    check(k < 2 ? covered > 0.05 && distinct > 100 : covered > 0.01 && distinct > 20, line);
    if (k < 2) surfaces[k] = pixels;
  }
  if (!surfaces[0].empty() && surfaces[0].size() == surfaces[1].size()) {
    long differ = 0;
    for (std::size_t i = 0; i < surfaces[0].size(); ++i) differ += surfaces[0][i] != surfaces[1][i];
    check(differ > 0, "after.png differs from before.png (" + std::to_string(differ) + " pixels)");
  }
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 3) {
    std::fprintf(stderr, "usage: example_check SCENE OUTDIR [--changed-min MM] [--quiet-max MM]\n");
    return 2;
  }
  const std::filesystem::path scene_path = argv[1], out = argv[2];
  double changed_min = -1.0, quiet_max = -1.0;
  for (int k = 3; k + 1 < argc; k += 2) {
    if (std::strcmp(argv[k], "--changed-min") == 0) changed_min = std::atof(argv[k + 1]);
    if (std::strcmp(argv[k], "--quiet-max") == 0) quiet_max = std::atof(argv[k + 1]);
  }
  const argil::Result<argil::sculpt::Scene> scene_read = argil::sculpt::read_scene(scene_path);
  if (!scene_read.ok()) {
    std::fprintf(stderr, "%s\n", scene_read.status().message.c_str());
    return 1;
  }
  const argil::sculpt::Scene& scene = scene_read.value();
  const double eps = scene.tolerance;
  if (changed_min < 0) changed_min = 2.0 * eps;  // clearly above the certified tolerance

  // The engaged tool path and the tool's radius about its frame origin.
  const argil::Result<argil::sculpt::Script> recorded =
      argil::sculpt::read_script(out / "recorded.csv");
  if (!recorded.ok()) {
    std::fprintf(stderr, "%s\n", recorded.status().message.c_str());
    return 1;
  }
  const int tool_index = scene.tool_index(recorded.value().tool);
  check(tool_index >= 0, "recorded.csv names a scene tool");
  if (tool_index < 0) return 1;
  const argil::sculpt::ToolOptions& tool = scene.tools[static_cast<std::size_t>(tool_index)];
  double tool_radius = tool.radius;
  if (tool.type == argil::sculpt::ToolType::bspline) {
    const auto tool_model = argil::io::read_model(tool.file);
    check(tool_model.ok(), "the B-spline tool reads");
    if (!tool_model.ok()) return 1;
    const auto& net =
        tool_model.value().faces[static_cast<std::size_t>(tool.face)].surface.control_points;
    tool_radius = net.rowwise().norm().maxCoeff();  // convex hull: encloses the tool
  }
  // The tool acts between samples too: the device path while engaged,
  // polylines through every tick, and the tool's own path then (the proxy,
  // held outside the surface while the device goes in).
  std::vector<std::vector<Eigen::Vector3d>> strokes;
  std::vector<bool> engaged;
  {
    argil::sculpt::ScriptSampler sampler(recorded.value(), scene.haptic_rate);
    bool was = false;
    for (long long k = 0; k < sampler.tick_count(); ++k) {
      const argil::DeviceSample s = sampler.sample(k);
      if (s.engaged && !was) strokes.emplace_back();
      if (s.engaged) strokes.back().push_back(s.X_WD.p);
      engaged.push_back(s.engaged);
      was = s.engaged;
    }
  }
  check(!strokes.empty(), "the run had at least one stroke");
  {
    std::ifstream forces(out / "forces.csv");
    std::string line;
    std::getline(forces, line);  // header
    bool was = false;
    long long rows = 0;
    while (std::getline(forces, line)) {
      long long tick = 0;
      double t = 0, f[4], clamped = 0;
      Eigen::Vector3d proxy;
      const bool read =
          std::sscanf(line.c_str(), "%lld,%lf,%lf,%lf,%lf,%lf,%lf,%lf,%lf,%lf", &tick, &t, &f[0],
                      &f[1], &f[2], &f[3], &clamped, &proxy.x(), &proxy.y(), &proxy.z()) == 10;
      if (!read || tick < 0 || tick >= static_cast<long long>(engaged.size())) break;
      ++rows;
      const bool on = engaged[static_cast<std::size_t>(tick)];
      if (on && !was) strokes.emplace_back();
      if (on) strokes.back().push_back(proxy);
      was = on;
    }
    check(rows == static_cast<long long>(engaged.size()),
          "forces.csv holds the tool's position at every tick");
  }
  const auto path_distance = [&strokes](const Eigen::Vector3d& p) {
    double d = INFINITY;
    for (const auto& stroke : strokes) d = std::min(d, distance_to_path(p, stroke));
    return d;
  };

  for (const argil::sculpt::ModelOptions& spec : scene.models) {
    const auto input = argil::io::read_model(spec.file);
    check(input.ok(), spec.name + ": input model reads");
    if (!input.ok()) return 1;
    const std::vector<argil::io::FaceRecord>& file_faces = input.value().faces;
    std::vector<int> file_face;  // face index in the model's file of each named face
    if (spec.faces.empty()) {    // "all"
      for (std::size_t f = 0; f < file_faces.size(); ++f) file_face.push_back(static_cast<int>(f));
    } else {
      file_face = spec.faces;
    }
    std::vector<bool> named(file_faces.size(), false);
    std::vector<argil::io::FaceRecord> before;  // the named faces, as read
    for (const int f : file_face) {
      named[static_cast<std::size_t>(f)] = true;
      before.push_back(file_faces[static_cast<std::size_t>(f)]);
    }

    // The exports hold the whole file, every face in its place.
    const auto json = argil::io::read_model(out / (spec.name + ".json"));
    check(json.ok(),
          spec.name + ".json re-imports" + (json.ok() ? "" : ": " + json.status().message));
    if (!json.ok()) return 1;
    const std::vector<argil::io::FaceRecord>& exported = json.value().faces;
    check(exported.size() == file_faces.size(), spec.name + ".json holds every face of the file (" +
                                                    std::to_string(exported.size()) + " of " +
                                                    std::to_string(file_faces.size()) + ")");
    if (exported.size() != file_faces.size()) return 1;
    int unnamed = 0, unnamed_changed = 0;
    for (std::size_t f = 0; f < file_faces.size(); ++f) {
      if (named[f]) continue;
      ++unnamed;
      if (!same_face(exported[f], file_faces[f])) ++unnamed_changed;
    }
    if (unnamed > 0) {
      check(unnamed_changed == 0,
            spec.name + ".json: the " + std::to_string(unnamed) +
                " faces the scene does not name are the input's, bit for bit (" +
                std::to_string(unnamed_changed) + " differ)");
    }
    std::vector<argil::io::FaceRecord> after;  // the named faces, as exported
    for (const int f : file_face) after.push_back(exported[static_cast<std::size_t>(f)]);
    for (const char* ext : {".step", ".iges"}) {
      const bool wanted = std::string(ext) == ".step" ? scene.outputs.step : scene.outputs.iges;
      if (!wanted) continue;
      const auto cad = argil::io::read_model(out / (spec.name + ext));
      check(cad.ok(),
            spec.name + ext + " re-imports" + (cad.ok() ? "" : ": " + cad.status().message));
      if (!cad.ok()) continue;
      bool same = cad.value().faces.size() == exported.size();
      int mirrored = 0;
      for (std::size_t f = 0; same && f < exported.size(); ++f) {
        const BSplineSurface& c = cad.value().faces[f].surface;
        const BSplineSurface& j = exported[f].surface;
        same = same_structure(c, j) && same_bits(c.control_points, j.control_points);
        // IGES 144 has no orientation flag (docs/io.md): a reversed face
        // comes back forward on the mirrored surface.
        if (!same && std::string(ext) == ".iges" && exported[f].reversed &&
            !cad.value().faces[f].reversed && mirrored_copy(c, j)) {
          same = true;
          ++mirrored;
        }
      }
      check(same, spec.name + ext + " holds the JSON's " + std::to_string(exported.size()) +
                      " faces, control points bit for bit" +
                      (mirrored > 0 ? " (" + std::to_string(mirrored) +
                                          " reversed faces mirrored, as IGES stores them)"
                                    : ""));
    }

    // The model's size, for the rounding of a rebuilt refinement.
    double size = 0.0;
    {
      Eigen::Vector3d lo = Eigen::Vector3d::Constant(INFINITY), hi = -lo;
      for (const auto& face : before) {
        lo = lo.cwiseMin(face.surface.control_points.colwise().minCoeff().transpose());
        hi = hi.cwiseMax(face.surface.control_points.colwise().maxCoeff().transpose());
      }
      size = (hi - lo).norm();
    }
    struct FaceSamples {
      std::vector<std::pair<double, double>> moved_and_distance;
      double reach = 0.0;    // tool radius + one support of the sculpted net [mm]
      double nearest = 0.0;  // nearest sample to the path [mm]
      double chord = 0.0;    // longest distance between neighbouring samples [mm]
    };
    std::vector<FaceSamples> faces(before.size());
    double largest = 0.0, largest_distance = 0.0, largest_reach = 0.0;
    for (std::size_t f = 0; f < before.size(); ++f) {
      const BSplineSurface& b = before[f].surface;
      const BSplineSurface& a = after[f].surface;
      const std::string name = spec.name + " face " + std::to_string(file_face[f]);
      check(spec.deformable ? refines(a, b) : same_structure(a, b),
            name + (spec.deformable ? " is the input face or its exact refinement"
                                    : " keeps degrees and knots"));
      if (!spec.deformable) {
        check(same_bits(a.control_points, b.control_points), name + " (rigid) did not move");
        continue;
      }
      FaceSamples& fs = faces[f];
      fs.reach = tool_radius + (std::max(a.degree[0], a.degree[1]) + 1) * longest_leg(a);
      fs.nearest = INFINITY;
      const int n = 41;
      std::vector<Eigen::Vector3d> row(n), previous_row;
      for (int i = 0; i < n; ++i) {
        for (int j = 0; j < n; ++j) {
          const double u =
              b.domain_start(Direction::u) +
              (b.domain_end(Direction::u) - b.domain_start(Direction::u)) * i / (n - 1);
          const double v =
              b.domain_start(Direction::v) +
              (b.domain_end(Direction::v) - b.domain_start(Direction::v)) * j / (n - 1);
          const Eigen::Vector3d pb = argil::evaluate(b, u, v);
          row[static_cast<std::size_t>(j)] = pb;
          if (j > 0)
            fs.chord = std::max(fs.chord, (pb - row[static_cast<std::size_t>(j - 1)]).norm());
          if (i > 0)
            fs.chord = std::max(fs.chord, (pb - previous_row[static_cast<std::size_t>(j)]).norm());
          const double moved = (argil::evaluate(a, u, v) - pb).norm();
          const double d = path_distance(pb);
          fs.nearest = std::min(fs.nearest, d);
          fs.moved_and_distance.emplace_back(moved, d);
          if (moved > largest) {
            largest = moved;
            largest_distance = d;
            largest_reach = fs.reach;
          }
        }
        previous_row = row;
      }
    }
    if (!spec.deformable) continue;
    const double quiet = quiet_max >= 0 ? quiet_max : std::max(eps, 0.01 * largest);
    char line[320];
    std::snprintf(line, sizeof line, "%s changed: largest move %.4g mm (needs > %.4g)",
                  spec.name.c_str(), largest, changed_min);
    check(largest > changed_min, line);
    std::snprintf(line, sizeof line,
                  "%s changed where the tool went: the largest move is %.4g mm from the path "
                  "(reach %.4g mm)",
                  spec.name.c_str(), largest_distance, largest_reach);
    check(largest_distance <= largest_reach, line);

    // Faces (named, by index in `before`) joined to a face the tool came near.
    const argil::io::Topology& topology = input.value().topology;
    std::vector<int> named_index(file_faces.size(), -1);
    for (std::size_t f = 0; f < file_face.size(); ++f)
      named_index[static_cast<std::size_t>(file_face[f])] = static_cast<int>(f);
    const auto came_near = [&](int f) {
      return faces[static_cast<std::size_t>(f)].nearest <=
             tool_radius + eps + faces[static_cast<std::size_t>(f)].chord;
    };
    // Joined to one through a chain of shared edges: the joints carry it, by
    // no more than the largest move (they do not amplify it).
    std::vector<char> joined_to_near(before.size(), 0);
    for (std::size_t f = 0; f < before.size(); ++f)
      joined_to_near[f] = came_near(static_cast<int>(f));
    for (bool grew = true; grew;) {
      grew = false;
      for (const argil::io::Edge& edge : topology.edges) {
        if (edge.degenerate || edge.uses.size() != 2) continue;  // as sessions join
        for (const argil::io::EdgeUse& x : edge.uses)
          for (const argil::io::EdgeUse& y : edge.uses) {
            const int fx = named_index[x.face], fy = named_index[y.face];
            if (fx < 0 || fy < 0 || joined_to_near[static_cast<std::size_t>(fx)] ||
                !joined_to_near[static_cast<std::size_t>(fy)])
              continue;
            joined_to_near[static_cast<std::size_t>(fx)] = 1;
            grew = true;
          }
      }
    }

    // Nowhere else, face by face.
    int far_samples = 0, far_poles = 0;
    for (std::size_t f = 0; f < before.size(); ++f) {
      const BSplineSurface& b = before[f].surface;
      const BSplineSurface& a = after[f].surface;
      const FaceSamples& fs = faces[f];
      const std::string name = spec.name + " face " + std::to_string(file_face[f]);
      if (!refines(a, b)) continue;  // reported above
      double loudest_far = 0.0;
      int far_here = 0;
      for (const auto& [moved, d] : fs.moved_and_distance) {
        if (d > fs.reach) {
          loudest_far = std::max(loudest_far, moved);
          ++far_here;
        }
      }
      far_samples += far_here;
      if (far_here > 0) {
        std::snprintf(line, sizeof line,
                      "%s changed nowhere else: %d samples beyond its reach (%.4g mm) moved at "
                      "most %.4g mm (allowed %.4g)",
                      name.c_str(), far_here, fs.reach, loudest_far, quiet);
        check(loudest_far <= quiet, line);
      }
      // The tool cannot touch a face none of whose points came within its
      // radius (and eps) of the path; the samples are one chord apart.
      const bool near = fs.nearest <= tool_radius + eps + fs.chord;
      const bool refined = !same_structure(a, b);
      // How far a face the tool never came near may be carried by its joints:
      // not at all when no chain of joints reaches a face it came near.
      const bool carried_by_joints = spec.deformable && joined_to_near[f];
      const double carried = carried_by_joints ? largest : 0.0;
      if (!near && !refined) {
        if (!carried_by_joints) {
          std::snprintf(line, sizeof line,
                        "%s, %.4g mm from the path, never near the tool, did not move (bit for "
                        "bit)",
                        name.c_str(), fs.nearest);
          check(same_bits(a.control_points, b.control_points) && same_bits(a.weights, b.weights),
                line);
        } else {
          const double moved = (a.control_points - b.control_points).rowwise().norm().maxCoeff();
          std::snprintf(line, sizeof line,
                        "%s, %.4g mm from the path, never near the tool, carried by its joints "
                        "%.3g mm (allowed %.3g: joined to a face the tool came near)",
                        name.c_str(), fs.nearest, moved, carried);
          check(same_bits(a.weights, b.weights) && moved <= carried, line);
        }
        far_poles += static_cast<int>(a.control_points.rows());
        continue;
      }
      if (!refined && same_bits(a.control_points, b.control_points)) continue;  // untouched
      const argil::Result<BSplineSurface> rebuilt = rebuilt_refinement(b, a);
      check(rebuilt.ok() && same_structure(rebuilt.value(), a),
            name + ": the input face refined here has the sculpted net's knots");
      if (!rebuilt.ok() || !same_structure(rebuilt.value(), a)) continue;
      const BSplineSurface& rest = rebuilt.value();
      if (!near) {
        // Refined for the tool's reach, but never touched: only rounding, or
        // carried by its joints.
        const double rounding = 1e-12 * size;  // elevation by collocation: to rounding
        const double allowed = std::max(rounding, carried);
        const double moved = (a.control_points - rest.control_points).rowwise().norm().maxCoeff();
        std::snprintf(
            line, sizeof line,
            "%s, %.4g mm from the path, never near the tool: refined exactly, its "
            "control points within %.3g mm of the input's refinement (allowed %.3g%s)",
            name.c_str(), fs.nearest, moved, allowed,
            carried_by_joints ? ", carried by its joints to a face the tool came near" : "");
        check(moved <= allowed, line);
        far_poles += static_cast<int>(a.control_points.rows());
        continue;
      }
      int moved_poles = 0, astray = 0, beyond = 0;
      double worst = 0.0;  // most a moved pole lies beyond its reach [mm]
      for (int i = 0; i < a.count(Direction::u); ++i) {
        for (int j = 0; j < a.count(Direction::v); ++j) {
          const Eigen::Index k = a.pole_index(i, j);
          const Eigen::Vector3d p = rest.control_points.row(k).transpose();
          const double pole_reach = tool_radius + eps + support_size(rest, i, j);
          const double d = path_distance(p);
          if (d > pole_reach) ++beyond;
          if ((a.control_points.row(k) - rest.control_points.row(k)).norm() <= quiet) continue;
          ++moved_poles;
          if (d > pole_reach) {
            ++astray;
            worst = std::max(worst, d - pole_reach);
          }
        }
      }
      far_poles += beyond;
      std::snprintf(line, sizeof line,
                    "%s: the %d control points that moved more than %.4g mm all have supports "
                    "within the tool's reach of the path (%d do not, by up to %.4g mm; %d "
                    "control points lie beyond)",
                    name.c_str(), moved_poles, quiet, astray, worst, beyond);
      check(astray == 0, line);
    }
    check(far_samples > 0 || far_poles > 0,
          spec.name +
              ": some samples or control points lie beyond the reach (the check is not "
              "empty)");

    // The faces stayed joined: no shared edge opened by more than eps, and
    // none turned about itself by more than kTangentJoinAngle (a G1 edge stays
    // G1, a crease keeps its angle).
    if (spec.deformable) {
      int shared = 0, opened = 0, turned = 0;
      double widest = 0.0, widest_before = 0.0, most_turned = 0.0;
      std::size_t widest_edge = 0, turned_edge = 0;
      for (std::size_t e = 0; e < topology.edges.size(); ++e) {
        const argil::io::Edge& edge = topology.edges[e];
        if (edge.degenerate || edge.uses.size() != 2) continue;
        const argil::io::EdgeUse& x = edge.uses[0];
        const argil::io::EdgeUse& y = edge.uses[1];
        // A face the scene does not name is not in the session: nothing joins it.
        if (!named[x.face] || !named[y.face]) continue;
        ++shared;
        const EdgeSamples was = edge_samples(file_faces[x.face].surface, x.pcurve,
                                             file_faces[y.face].surface, y.pcurve);
        const EdgeSamples is =
            edge_samples(exported[x.face].surface, x.pcurve, exported[y.face].surface, y.pcurve);
        // Sample by sample: a gap the input had elsewhere hides no opening.
        std::size_t k_most = 0;
        for (std::size_t k = 1; k < was.gap.size(); ++k)
          if (is.gap[k] - was.gap[k] > is.gap[k_most] - was.gap[k_most]) k_most = k;
        const double gap_before = was.gap[k_most], gap_after = is.gap[k_most];
        if (gap_after - gap_before > widest - widest_before) {
          widest = gap_after;
          widest_before = gap_before;
          widest_edge = e;
        }
        if (gap_after > gap_before + eps) ++opened;
        double turn = 0.0;
        for (std::size_t k = 0; k < was.angle.size(); ++k)
          turn = std::max(turn, std::abs(is.angle[k] - was.angle[k]));
        if (turn > most_turned) most_turned = turn, turned_edge = e;
        if (turn > argil::kTangentJoinAngle) ++turned;
      }
      if (shared > 0) {
        std::snprintf(line, sizeof line,
                      "%s stayed joined: %d of the %d edges its named faces share opened by more "
                      "than eps; the most widened, edge %zu, %.3g mm apart (%.3g mm in the input)",
                      spec.name.c_str(), opened, shared, widest_edge, widest, widest_before);
        check(opened == 0, line);
        std::snprintf(line, sizeof line,
                      "%s kept its edges' angles: %d of %d turned by more than %.3g rad; the "
                      "most, edge %zu, by %.3g rad",
                      spec.name.c_str(), turned, shared, argil::kTangentJoinAngle, turned_edge,
                      most_turned);
        check(turned == 0, line);
      }
    }
  }
  if (scene.outputs.pictures) check_pictures(out);
  std::printf("%s\n", failures == 0 ? "all checks passed" : "CHECKS FAILED");
  return failures == 0 ? 0 : 1;
}
