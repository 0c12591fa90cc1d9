// One-off cost of a deformable body (docs/benchmarks.md, "Creating a body"):
// the shell matrices by Gauss quadrature, DeformableBody::create (which
// integrates them again, builds the hierarchy, checks the conditioning and
// factorises the step matrix at the haptic step), and the first step.
#include <cstdio>

#include "bench_timing.hpp"
#include "haptic_loop_sections.hpp"

namespace argil::bench {

namespace {

constexpr int kCreationsPerRun = 5;

struct CreationTimes {
  double shell_us = 0.0, create_us = 0.0, first_step_us = 0.0, next_step_us = 0.0;
};

/// Median times of kCreationsPerRun creations with a cold operator cache
/// (what adding a face to a world costs the first time its knots are seen).
Result<CreationTimes> time_creation(const BSplineSurface& surface, const Material& material) {
  std::vector<double> shell, create, first, next;
  for (int k = 0; k < kCreationsPerRun; ++k) {
    double start = thread_cpu_us();
    const ShellMatrices matrices = shell_matrices(surface);
    shell.push_back(thread_cpu_us() - start);
    if (matrices.total_area <= 0.0) return Status::error(StatusCode::invalid_argument, "no area");

    OperatorCache cache;
    start = thread_cpu_us();
    Result<DeformableBody> body = DeformableBody::create(surface, material, {}, cache);
    create.push_back(thread_cpu_us() - start);
    if (!body.ok()) return body.status();

    start = thread_cpu_us();
    if (Status s = body.value().step(kHapticStep); !s.ok()) return s;
    first.push_back(thread_cpu_us() - start);
    start = thread_cpu_us();
    if (Status s = body.value().step(kHapticStep); !s.ok()) return s;
    next.push_back(thread_cpu_us() - start);
  }
  return CreationTimes{median(shell), median(create), median(first), median(next)};
}

}  // namespace

void creation_section(const std::vector<BenchFace>& faces, int repeats) {
  const Material clay = *material_preset("clay");
  std::printf(
      "\nCreating a deformable body (clay, thread CPU time; median over %d runs of the "
      "median of %d creations):\n\n",
      repeats, kCreationsPerRun);
  std::printf(
      "| Face | Net | Poles | Shell matrices | create (factorises) | First step | "
      "Later step |\n|---|---|---:|---:|---:|---:|---:|\n");
  for (const BenchFace& f : faces) {
    std::vector<double> shell, create, first, next;
    Status failure = Status::success();
    for (int run = 0; run < repeats && failure.ok(); ++run) {
      const Result<CreationTimes> t = time_creation(f.surface, clay);
      if (!t.ok()) {
        failure = t.status();
        break;
      }
      shell.push_back(t.value().shell_us);
      create.push_back(t.value().create_us);
      first.push_back(t.value().first_step_us);
      next.push_back(t.value().next_step_us);
    }
    const int poles = f.surface.count(Direction::u) * f.surface.count(Direction::v);
    if (!failure.ok()) {
      std::printf("| %s | %s | %d | not created: %s |\n", f.name.c_str(),
                  net_text(f.surface).c_str(), poles, failure.message.c_str());
      continue;
    }
    std::printf("| %s | %s | %d | %s | %s | %s | %s |\n", f.name.c_str(),
                net_text(f.surface).c_str(), poles, time_text(median(shell)).c_str(),
                time_text(median(create)).c_str(), time_text(median(first)).c_str(),
                time_text(median(next)).c_str());
    std::fflush(stdout);
  }
}

}  // namespace argil::bench
