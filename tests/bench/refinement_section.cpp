// Dent depth and peak force against exact refinement of the face
// (docs/benchmarks.md, "Refinement"): the material is a property of the face,
// not of its control net, so the same press should give the same dent and
// force on every level.
#include <cmath>
#include <cstdio>

#include "haptic_loop_sections.hpp"

namespace argil::bench {

namespace {

constexpr int kGrid = 129;  // dent samples per direction over the domain

/// Points and outward unit normals of the rest face on the dent grid.
struct RestGrid {
  std::vector<Eigen::Vector3d> points, normals;
};

double grid_parameter(const BSplineSurface& s, Direction d, int k) {
  return s.domain_start(d) + (s.domain_end(d) - s.domain_start(d)) * k / (kGrid - 1);
}

RestGrid rest_grid(const BenchFace& face) {
  RestGrid g;
  const BSplineSurface& s = face.surface;
  for (int a = 0; a < kGrid; ++a) {
    for (int b = 0; b < kGrid; ++b) {
      const double u = grid_parameter(s, Direction::u, a), v = grid_parameter(s, Direction::v, b);
      g.points.push_back(evaluate_derivatives(s, u, v, 0).point);
      g.normals.push_back((face.reversed ? -1.0 : 1.0) * unit_normal(s, u, v));
    }
  }
  return g;
}

/// Deepest inward displacement of `current` from the rest face over the grid
/// [mm]. Exact refinement keeps the parametrisation, so the grid compares the
/// same material points on every level.
double dent_depth(const BSplineSurface& current, const RestGrid& rest) {
  double deepest = 0.0;
  std::size_t k = 0;
  for (int a = 0; a < kGrid; ++a) {
    for (int b = 0; b < kGrid; ++b, ++k) {
      const double u = grid_parameter(current, Direction::u, a);
      const double v = grid_parameter(current, Direction::v, b);
      const Eigen::Vector3d d = evaluate_derivatives(current, u, v, 0).point - rest.points[k];
      deepest = std::max(deepest, -d.dot(rest.normals[k]));
    }
  }
  return deepest;
}

struct LevelResult {
  std::string net;
  double loaded = 0.0, residual = 0.0, peak_force = 0.0;
  int failed = 0;
};

std::string change_text(double value, double previous) {
  if (previous <= 0.0) return "";
  char text[32];
  std::snprintf(text, sizeof text, " (%+.2g%%)", 100.0 * (value - previous) / previous);
  return text;
}

}  // namespace

void refinement_section(const std::vector<RefinementCase>& cases) {
  std::printf(
      "\nDent and peak force against refinement (the same press on every level: sphere "
      "0.05, press 0.01 of the face size; hold %d ticks, then rise and relax %d ticks; "
      "dent = deepest inward displacement over a %dx%d grid):\n\n",
      kHoldTicks, kRelaxTicks, kGrid, kGrid);
  std::printf(
      "| Face | Material | Level | Net | Dent under the tool | Dent after release | "
      "Peak force |\n|---|---|---:|---|---:|---:|---:|\n");
  for (const RefinementCase& c : cases) {
    const StrokeOptions stroke = scaled_stroke(c.face.surface);
    const RestGrid rest = rest_grid(c.face);
    for (const char* material_name : {"foam", "clay"}) {
      const Material material = *material_preset(material_name);
      LevelResult previous;
      for (int level = 0; level <= 2; ++level) {
        const BSplineSurface fine = refine_midpoints(c.face.surface, level);
        const BenchFace body{c.face.name, fine, c.face.reversed, ""};
        Result<HapticWorld> world = make_world(body, material, stroke);
        if (!world.ok()) {
          std::printf("| %s | %s | %d | not run: %s |\n", c.name.c_str(), material_name, level,
                      world.status().message.c_str());
          break;
        }
        LevelResult r{.net = net_text(fine)};
        const TickLog log = run_ticks(
            world.value(),
            [&](int t) { return press_device(c.face, stroke, c.u_fraction, c.v_fraction, t); },
            kPressTicks,
            [&](int t) {
              if (t == kHoldEndTick - 1) r.loaded = dent_depth(world.value().surface(0), rest);
            });
        r.residual = dent_depth(world.value().surface(0), rest);
        r.peak_force = log.peak_force;
        r.failed = log.failed;
        std::printf("| %s | %s | %d | %s | %.4g mm%s | %.4g mm%s | %.4g N%s |%s\n", c.name.c_str(),
                    material_name, level, r.net.c_str(), r.loaded,
                    level > 0 ? change_text(r.loaded, previous.loaded).c_str() : "", r.residual,
                    level > 0 && r.residual > 1e-3 * r.loaded
                        ? change_text(r.residual, previous.residual).c_str()
                        : "",
                    r.peak_force,
                    level > 0 ? change_text(r.peak_force, previous.peak_force).c_str() : "",
                    r.failed > 0 ? (" failed ticks: " + log.first_error).c_str() : "");
        std::fflush(stdout);
        previous = r;
      }
    }
  }
}

}  // namespace argil::bench
