// Checks the outputs of `argil sculpt` on an example, for CTest:
//  1. the exported surfaces (STEP, IGES, JSON) re-import through argil::io,
//     each the input face or its exact refinement (a deformable face the tool
//     works on may be refined before the run), with control points identical
//     to the JSON export's (bit for bit);
//  2. rigid models did not move at all;
//  3. each deformable model changed: some point moved more than --changed-min
//     (default 2 eps: clearly above the tolerance), and it lies within reach of the engaged tool
//     path;
//  4. it changed nowhere else: every sampled point farther than the reach from
//     the engaged path moved less than --quiet-max (default 1% of the largest
//     move, at least eps);
//  5. the pictures decode (cairo) and show something: before.png and after.png
//     are at least 5% covered by the surface and hold many colours, force.png
//     holds the curves, and after.png differs from before.png.
// The reach is the tool's radius plus the B-spline support of a control point:
// (degree + 1) times the longest control-polygon leg. Samples: a 41 x 41 grid
// in each face's parameter domain, compared at equal (u, v) before and after.
//
// usage: example_check SCENE OUTDIR [--changed-min MM] [--quiet-max MM]
#include <cairo.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "argil/core/geometry/evaluate.hpp"
#include "argil/io/files/model_files.hpp"
#include "argil/sculpt/scene/scene.hpp"
#include "argil/sculpt/script/script.hpp"

namespace {

using argil::BSplineSurface;
using argil::Direction;

int failures = 0;

void check(bool ok, const std::string& what) {
  std::printf("%s: %s\n", ok ? "ok  " : "FAIL", what.c_str());
  if (!ok) ++failures;
}

bool same_bits(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
  return a.rows() == b.rows() && a.cols() == b.cols() &&
         std::memcmp(a.data(), b.data(), sizeof(double) * static_cast<std::size_t>(a.size())) == 0;
}

bool same_structure(const BSplineSurface& a, const BSplineSurface& b) {
  return a.degree == b.degree && a.knots[0] == b.knots[0] && a.knots[1] == b.knots[1] &&
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
  // The tool acts between samples too: use the proxy-free device path, engaged part.
  std::vector<std::vector<Eigen::Vector3d>> strokes;
  bool was = false;
  {
    argil::sculpt::ScriptSampler sampler(recorded.value(), scene.haptic_rate);
    for (long long k = 0; k < sampler.tick_count(); ++k) {
      const argil::DeviceSample s = sampler.sample(k);
      if (s.engaged && !was) strokes.emplace_back();
      if (s.engaged) strokes.back().push_back(s.X_WD.p);
      was = s.engaged;
    }
  }
  check(!strokes.empty(), "the run had at least one stroke");

  for (const argil::sculpt::ModelOptions& spec : scene.models) {
    const auto input = argil::io::read_model(spec.file);
    check(input.ok(), spec.name + ": input model reads");
    if (!input.ok()) return 1;
    std::vector<argil::io::FaceRecord> before;
    if (spec.faces.empty()) before = input.value().faces;
    for (const int f : spec.faces)
      before.push_back(input.value().faces[static_cast<std::size_t>(f)]);

    const auto json = argil::io::read_model(out / (spec.name + ".json"));
    check(json.ok(),
          spec.name + ".json re-imports" + (json.ok() ? "" : ": " + json.status().message));
    if (!json.ok()) return 1;
    const std::vector<argil::io::FaceRecord>& after = json.value().faces;
    check(after.size() == before.size(), spec.name + ".json has the scene's faces");
    if (after.size() != before.size()) return 1;
    for (const char* ext : {".step", ".iges"}) {
      const bool wanted = std::string(ext) == ".step" ? scene.outputs.step : scene.outputs.iges;
      if (!wanted) continue;
      const auto cad = argil::io::read_model(out / (spec.name + ext));
      check(cad.ok(),
            spec.name + ext + " re-imports" + (cad.ok() ? "" : ": " + cad.status().message));
      if (!cad.ok()) continue;
      bool same = cad.value().faces.size() == after.size();
      for (std::size_t f = 0; same && f < after.size(); ++f) {
        same =
            same_structure(cad.value().faces[f].surface, after[f].surface) &&
            same_bits(cad.value().faces[f].surface.control_points, after[f].surface.control_points);
      }
      check(same, spec.name + ext + " holds the JSON's control points bit for bit");
    }

    double largest = 0.0, largest_distance = 0.0, reach = 0.0;
    std::vector<std::pair<double, double>> samples;  // (moved, distance to the path)
    for (std::size_t f = 0; f < before.size(); ++f) {
      const BSplineSurface& b = before[f].surface;
      const BSplineSurface& a = after[f].surface;
      check(spec.deformable ? refines(a, b) : same_structure(a, b),
            spec.name + " face " + std::to_string(f) +
                (spec.deformable ? " is the input face or its exact refinement"
                                 : " keeps degrees and knots"));
      if (!spec.deformable) {
        check(same_bits(a.control_points, b.control_points),
              spec.name + " (rigid) face " + std::to_string(f) + " did not move");
        continue;
      }
      reach =
          std::max(reach, tool_radius + (std::max(b.degree[0], b.degree[1]) + 1) * longest_leg(b));
      const int n = 41;
      for (int i = 0; i < n; ++i) {
        for (int j = 0; j < n; ++j) {
          const double u =
              b.domain_start(Direction::u) +
              (b.domain_end(Direction::u) - b.domain_start(Direction::u)) * i / (n - 1);
          const double v =
              b.domain_start(Direction::v) +
              (b.domain_end(Direction::v) - b.domain_start(Direction::v)) * j / (n - 1);
          const Eigen::Vector3d pb = argil::evaluate(b, u, v);
          const double moved = (argil::evaluate(a, u, v) - pb).norm();
          double d = INFINITY;
          for (const auto& stroke : strokes) d = std::min(d, distance_to_path(pb, stroke));
          samples.emplace_back(moved, d);
          if (moved > largest) {
            largest = moved;
            largest_distance = d;
          }
        }
      }
    }
    if (!spec.deformable) continue;
    const double quiet = quiet_max >= 0 ? quiet_max : std::max(eps, 0.01 * largest);
    double loudest_far = 0.0;
    int far_samples = 0;
    for (const auto& [moved, d] : samples) {
      if (d > reach) {
        loudest_far = std::max(loudest_far, moved);
        ++far_samples;
      }
    }
    char line[256];
    std::snprintf(line, sizeof line, "%s changed: largest move %.4g mm (needs > %.4g)",
                  spec.name.c_str(), largest, changed_min);
    check(largest > changed_min, line);
    std::snprintf(line, sizeof line,
                  "%s changed where the tool went: the largest move is %.4g mm from the path "
                  "(reach %.4g mm)",
                  spec.name.c_str(), largest_distance, reach);
    check(largest_distance <= reach, line);
    std::snprintf(line, sizeof line,
                  "%s changed nowhere else: %d samples beyond the reach moved at most %.4g mm "
                  "(allowed %.4g)",
                  spec.name.c_str(), far_samples, loudest_far, quiet);
    check(loudest_far <= quiet, line);
    check(far_samples > 0,
          spec.name + ": some samples lie beyond the reach (the check is not empty)");
  }
  if (scene.outputs.pictures) check_pictures(out);
  std::printf("%s\n", failures == 0 ? "all checks passed" : "CHECKS FAILED");
  return failures == 0 ? 0 : 1;
}
