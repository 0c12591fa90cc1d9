// What the tick costs against what the scene holds (docs/benchmarks.md, "The
// tick against the scene's size"): a sphere presses one spot of one face and
// circles there while the scene holds 1 to 1000 faces, a whole CAD part, or
// one face of up to 1024 x 1024 poles. Each row runs in a child process so
// its peak memory is its own and a row that cannot finish is reported, not
// waited on.
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <string>

#include "bench_faces.hpp"
#include "bench_timing.hpp"
#include "haptic_loop_sections.hpp"

namespace argil::bench {

namespace {

/// Where and how the sphere works: it descends along `normal` onto `point`
/// to `press` under the rest surface in 50 ticks, then circles there with a
/// radius of half the sphere's, once a second, in the tangent plane.
struct Spot {
  Eigen::Vector3d point = Eigen::Vector3d::Zero(), normal = Eigen::Vector3d::UnitZ(),
                  tangent = Eigen::Vector3d::UnitX();
  double radius = 2.0;      // sphere [mm]
  double press = 0.3;       // [mm]
  double tolerance = 0.01;  // eps [mm]
};

Eigen::Vector3d spot_device(const Spot& s, int tick) {
  const double descend = std::min(1.0, tick / 50.0);
  const double height = s.radius + 1.0 - descend * (1.0 + s.press);
  const double a = 2.0 * M_PI * kTickSeconds * std::max(0, tick - 50);
  const Eigen::Vector3d bitangent = s.normal.cross(s.tangent);
  return s.point + height * s.normal +
         0.5 * s.radius * descend * (std::cos(a) * s.tangent + std::sin(a) * bitangent);
}

/// The spot at the middle of a face's domain: a 2 mm sphere, or one sized for
/// the face (the benchmark's scaled stroke: sphere 0.05 of its size, press 0.01).
Spot face_spot(const BenchFace& face, bool scaled) {
  const BSplineSurface& s = face.surface;
  const double u = 0.5 * (s.domain_start(Direction::u) + s.domain_end(Direction::u));
  const double v = 0.5 * (s.domain_start(Direction::v) + s.domain_end(Direction::v));
  const SurfaceDerivatives d = evaluate_derivatives(s, u, v, 1);
  const StrokeOptions stroke = scaled_stroke(s);
  Spot spot;
  spot.point = d.point;
  spot.normal = (face.reversed ? -1.0 : 1.0) * unit_normal(s, u, v);
  spot.tangent = d.du.normalized();
  if (!scaled) return spot;
  spot.radius = stroke.radius;
  spot.press = stroke.press;
  spot.tolerance = stroke.tolerance;
  return spot;
}

/// Peak resident memory of this process [MiB].
double peak_memory_mib() {
  std::ifstream status("/proc/self/status");
  for (std::string line; std::getline(status, line);) {
    if (line.rfind("VmHWM:", 0) == 0) return std::atof(line.c_str() + 6) / 1024.0;
  }
  return 0.0;
}

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

/// Runs one row in this (child) process and prints it.
void run_row(const ScaleCase& c, int ticks, int repeats) {
  const Material clay = *material_preset("clay");
  int pressed = -1;
  std::vector<BenchFace> faces = c.faces(pressed);
  if (pressed < 0 || pressed >= static_cast<int>(faces.size())) {
    std::printf("| %s | not run: no face to press |\n", c.name.c_str());
    return;
  }
  const Spot spot = face_spot(faces[static_cast<std::size_t>(pressed)], c.scaled);
  std::vector<Percentiles> runs;
  double create_s = 0.0, worst = 0.0;
  int bodies = 0, refused = 0;
  long poles = 0;
  for (int run = 0; run < repeats; ++run) {
    WorldOptions o;
    o.tolerance = spot.tolerance;
    o.coupling = {.stiffness = 1.0, .damping = 0.002, .max_force = 8.0};
    Result<HapticWorld> world = HapticWorld::create(SphereToolShape{spot.radius}, o);
    if (!world.ok()) {
      std::printf("| %s | not run: %s |\n", c.name.c_str(), world.status().message.c_str());
      return;
    }
    const auto create_start = std::chrono::steady_clock::now();
    bodies = refused = 0;
    poles = 0;
    for (const BenchFace& f : faces) {
      if (world.value().add_deformable(f.surface, clay, {}, 0.3).ok()) {
        ++bodies;
        poles += f.surface.control_points.rows();
      } else {
        ++refused;
      }
    }
    create_s = seconds_since(create_start);
    const TickLog log = run_ticks(
        world.value(), [&](int t) { return spot_device(spot, t); }, ticks);
    if (log.failed > 0 || log.contacts == 0) {
      std::printf("| %s | not run: %d failed ticks (%s), %ld contacts |\n", c.name.c_str(),
                  log.failed, log.first_error.c_str(), log.contacts);
      return;
    }
    runs.push_back(percentiles(log.cpu_us));
    worst = std::max(worst, runs.back().max);
  }
  const Percentiles p = median_of(runs);
  std::printf("| %s | %d (%d refused) | %ld | %.3g s | %s | %s | %s | %s | %.0f MiB |\n",
              c.name.c_str(), bodies, refused, poles, create_s, time_text(p.p50).c_str(),
              time_text(p.p99).c_str(), time_text(p.p999).c_str(), time_text(worst).c_str(),
              peak_memory_mib());
  std::printf("scale-csv,%s,%ld,%.6g,%.6g,%.6g,%.6g\n", c.name.c_str(), poles, p.p50, p.p99, p.p999,
              worst);
}

}  // namespace

void scale_section(const std::vector<ScaleCase>& cases, int ticks, int repeats, int row_seconds) {
  std::printf(
      "\nThe tick against the scene's size: a sphere presses one spot (clay) and circles "
      "there; per-tick thread CPU time, median of %d runs of %d ticks; each row in its own "
      "process (peak resident memory), at most %d s a row:\n\n",
      repeats, ticks, row_seconds);
  std::printf(
      "| Scene | deformable faces | poles | create | p50 | p99 | p99.9 | worst tick | peak "
      "memory |\n");
  std::printf("|---|---:|---:|---:|---:|---:|---:|---:|---:|\n");
  std::fflush(stdout);
  for (const ScaleCase& c : cases) {
    const pid_t child = fork();
    if (child == 0) {
      alarm(static_cast<unsigned>(row_seconds));  // a row that cannot finish is killed
      run_row(c, ticks, repeats);
      std::fflush(stdout);
      _exit(0);
    }
    int status = 0;
    if (child < 0 || waitpid(child, &status, 0) != child) {
      std::printf("| %s | not run: could not start its process |\n", c.name.c_str());
    } else if (WIFSIGNALED(status)) {
      std::printf("| %s | not run: %s after at most %d s |\n", c.name.c_str(),
                  WTERMSIG(status) == SIGALRM ? "stopped" : strsignal(WTERMSIG(status)),
                  row_seconds);
    }
    std::fflush(stdout);
  }
}

}  // namespace argil::bench
