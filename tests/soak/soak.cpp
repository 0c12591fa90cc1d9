// Soak (docs/robustness.md): a long run of scripted random strokes through the full
// haptic tick. Fails on any NaN or Inf, on energy that keeps growing, or on
// memory that keeps growing; prints the peak RSS.
//
//   argil_soak [ticks] [poles] [sphere|bspline] [seed] [node budget]
#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <string>
#include <vector>

#include "argil/core.hpp"

namespace {

constexpr double kDt = 1e-3;  // [s]

// AddressSanitizer quarantines freed memory, so resident size grows without a
// leak: the memory check only means something in a plain build.
#if defined(__SANITIZE_ADDRESS__)
constexpr bool kSanitizedMemory = true;
#else
constexpr bool kSanitizedMemory = false;
#endif

/// Resident set size now [kB], from /proc/self/statm.
long resident_kb() {
  long pages = 0, resident = 0;
  if (FILE* f = std::fopen("/proc/self/statm", "r")) {
    if (std::fscanf(f, "%ld %ld", &pages, &resident) != 2) resident = 0;
    std::fclose(f);
  }
  return resident * (sysconf(_SC_PAGESIZE) / 1024);
}

long peak_rss_kb() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return usage.ru_maxrss;
}

argil::BSplineSurface panel(int n) {
  argil::BSplineSurface s;
  s.degree = {3, 3};
  for (auto& k : s.knots) {
    k.resize(n + 4);
    for (int i = 0; i < n + 4; ++i) k[i] = std::clamp((i - 3.0) / (n - 3.0), 0.0, 1.0);
  }
  s.control_points.resize(n * n, 3);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      s.control_points.row(s.pole_index(i, j)) << 10.0 * i, 10.0 * j,
          10.0 * std::sin(0.3 * i) * std::cos(0.2 * j);
  return s;
}

argil::BSplineSurface cap_tool() {
  argil::BSplineSurface tool = panel(4);
  for (int k = 0; k < 16; ++k) {
    const double x = tool.control_points(k, 0) / 10.0 * 4.0 - 6.0;
    const double y = tool.control_points(k, 1) / 10.0 * 4.0 - 6.0;
    tool.control_points.row(k) << x, y, 0.05 * (x * x + y * y);
  }
  return tool;
}

/// Random strokes: approach from above, press, drag along a random direction
/// at a random speed, lift and release; a pause between strokes.
class StrokeScript {
 public:
  StrokeScript(const argil::BSplineSurface& rest, std::uint64_t seed, double tool_offset)
      : rest_(rest), rng_(seed), offset_(tool_offset) {
    next_stroke();
  }

  argil::DeviceSample sample() {
    argil::DeviceSample pose;
    const int t = tick_++;
    if (t >= end_) {
      next_stroke();
      return sample();
    }
    const double s = std::min(1.0, static_cast<double>(t - start_) / (end_ - start_ - 1));
    const Eigen::Vector2d uv = (from_ + s * (to_ - from_)).cwiseMax(0.0).cwiseMin(1.0);
    const auto d = argil::evaluate_derivatives(rest_, uv[0], uv[1], 1);
    // Press profile: down over the first tenth, up over the last tenth.
    const double ramp = std::min({1.0, 10.0 * s, 10.0 * (1.0 - s)});
    pose.X_WD = argil::Pose::at(d.point +
                                Eigen::Vector3d::UnitZ() * (offset_ + 5.0 - (5.0 + press_) * ramp));
    pose.engaged = s > 0.02 && s < 0.98;
    return pose;
  }

 private:
  void next_stroke() {
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    start_ = tick_;
    from_ = {0.1 + 0.8 * unit(rng_), 0.1 + 0.8 * unit(rng_)};
    const double angle = 2.0 * M_PI * unit(rng_);
    const double length = 0.05 + 0.3 * unit(rng_);  // in parameters
    to_ = from_ + length * Eigen::Vector2d(std::cos(angle), std::sin(angle));
    press_ = 3.0 * unit(rng_);
    end_ = start_ + 200 + static_cast<int>(1800 * unit(rng_));  // 0.2 to 2 s
  }

  const argil::BSplineSurface& rest_;
  std::mt19937_64 rng_;
  double offset_;
  int tick_ = 0, start_ = 0, end_ = 0;
  Eigen::Vector2d from_, to_;
  double press_ = 0.0;
};

}  // namespace

int main(int argc, char** argv) {
  const long ticks = argc > 1 ? std::atol(argv[1]) : 1000000;
  const int poles = argc > 2 ? std::atoi(argv[2]) : 16;
  const bool sphere = argc > 3 ? std::string(argv[3]) != "bspline" : true;
  const std::uint64_t seed = argc > 4 ? std::strtoull(argv[4], nullptr, 10) : 1;
  const long budget = argc > 5 ? std::atol(argv[5]) : 0;  // 0: the hierarchy's default
  if (ticks < 10 || poles < 4) {
    std::fprintf(stderr, "usage: argil_soak [ticks >= 10] [poles >= 4] [sphere|bspline] [seed]\n");
    return 2;
  }

  const argil::BSplineSurface rest = panel(poles);
  argil::WorldOptions options;
  options.tolerance = 0.05;
  options.coupling = {.stiffness = 1.0, .damping = 0.002, .max_force = 8.0};
  auto world =
      argil::HapticWorld::create(sphere ? argil::ToolShape{argil::SphereToolShape{5.0}}
                                        : argil::ToolShape{argil::SurfaceToolShape{cap_tool()}},
                                 options);
  const argil::Material clay = *argil::material_preset("clay");
  if (!world.ok() || !world.value().add_deformable(rest, clay, {}, /*friction=*/0.3).ok()) {
    std::fprintf(stderr, "soak: could not build the world\n");
    return 2;
  }
  argil::HapticWorld& w = world.value();
  if (budget > 0) w.set_node_budget(0, static_cast<std::size_t>(budget));
  StrokeScript script(rest, seed, sphere ? 5.0 : 0.0);

  constexpr int kDeciles = 10;
  std::vector<double> energy_max(kDeciles, 0.0);
  std::vector<long> rss(kDeciles, 0);
  std::vector<std::size_t> nodes(kDeciles, 0);
  const long per_decile = ticks / kDeciles;
  for (long t = 0; t < ticks; ++t) {
    const argil::TickResult r = w.step(script.sample(), kDt);
    if (!r.status.ok() || !r.force.allFinite() || !r.proxy.X_WT.p.allFinite()) {
      std::fprintf(stderr, "soak: tick %ld: bad step (%s)\n", t, r.status.message.c_str());
      return 1;
    }
    const argil::DeformableBody* body = w.deformable(0);
    const double energy = body->kinetic_energy() + body->potential_energy();
    if (!std::isfinite(energy)) {
      std::fprintf(stderr, "soak: tick %ld: energy %g\n", t, energy);
      return 1;
    }
    const int decile = static_cast<int>(std::min<long>(kDeciles - 1, t / per_decile));
    energy_max[static_cast<std::size_t>(decile)] =
        std::max(energy_max[static_cast<std::size_t>(decile)], energy);
    if (t % 1000 == 999 && !w.surface(0).control_points.allFinite()) {
      std::fprintf(stderr, "soak: tick %ld: control points not finite\n", t);
      return 1;
    }
    if ((t + 1) % per_decile == 0) {
      rss[static_cast<std::size_t>(decile)] = resident_kb();
      nodes[static_cast<std::size_t>(decile)] = w.hierarchy(0).node_count();
    }
  }

  std::printf("soak: %ld ticks, %dx%d, %s tool, seed %llu\n", ticks, poles, poles,
              sphere ? "sphere" : "bspline", static_cast<unsigned long long>(seed));
  for (int d = 0; d < kDeciles; ++d)
    std::printf("  decile %d: max energy %.4g mJ, RSS %ld kB, hierarchy nodes %zu\n", d,
                energy_max[static_cast<std::size_t>(d)], rss[static_cast<std::size_t>(d)],
                nodes[static_cast<std::size_t>(d)]);
  std::printf("  peak RSS %ld kB\n", peak_rss_kb());
  // Strokes are drawn from one distribution, so energy is stationary: a last
  // decile far above every earlier one means growth. Memory must stay flat
  // after warm-up (nodes are created lazily where the tool first goes).
  const double before = *std::max_element(energy_max.begin(), energy_max.end() - 1);
  if (energy_max.back() > 4.0 * before + 1e-9) {
    std::fprintf(stderr, "soak: energy grows: %g mJ at the end against at most %g mJ before\n",
                 energy_max.back(), before);
    return 1;
  }
  // Flat memory: the hierarchy's node budget caps the lazily grown nodes, so
  // after the first half (which holds the warm-up to the budget) the resident
  // size must not climb above what it reached there.
  const long first_half = *std::max_element(rss.begin(), rss.begin() + kDeciles / 2);
  const long second_half = *std::max_element(rss.begin() + kDeciles / 2, rss.end());
  if (!kSanitizedMemory && second_half > first_half + 4096) {
    std::fprintf(stderr, "soak: memory grows: %ld kB late against %ld kB in the first half\n",
                 second_half, first_half);
    return 1;
  }
  return 0;
}
