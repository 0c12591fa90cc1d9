// The one-off cost of refining real faces for a tool (docs/benchmarks.md):
// every face of a file refined over its whole domain, as a session does
// before its first tick for the faces its script comes near.
#include <chrono>
#include <cstdio>

#include "bench_timing.hpp"
#include "haptic_loop_sections.hpp"

namespace argil::bench {

void tool_refinement_section(const std::vector<std::string>& files, double size_fraction) {
  std::printf(
      "\nRefinement for a tool of radius %g of the part's size, every face (whole "
      "domain), CPU time:\n\n",
      size_fraction);
  std::printf(
      "| File | faces | refined | poles before | poles after | largest net after | "
      "region p50 | refine p50 | refine max | total |\n");
  std::printf("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n");
  for (const std::string& file : files) {
    const Result<io::Model> model =
        read_bench_model(std::string(ARGIL_BENCH_DATA_DIR) + "/" + file);
    if (!model.ok()) continue;
    const double resolution = size_fraction * io::model_box(model.value()).diagonal();
    RefinementGoal goal;
    goal.resolution = resolution;
    std::vector<double> refine_us, region_us;
    long before = 0, after = 0;
    int refined = 0, largest_u = 0, largest_v = 0;
    for (const io::FaceRecord& face : model.value().faces) {
      const BSplineSurface& s = face.surface;
      const ParamRect all{s.domain_start(Direction::u), s.domain_end(Direction::u),
                          s.domain_start(Direction::v), s.domain_end(Direction::v)};
      // The region query a session runs: a path through the face's middle.
      const Eigen::Vector3d middle = evaluate(s, all.centre().x(), all.centre().y());
      double t0 = thread_cpu_us();
      const std::optional<ParamRect> near = region_near_path(s, {middle}, 3.0 * resolution);
      region_us.push_back(thread_cpu_us() - t0);
      if (!near) continue;
      t0 = thread_cpu_us();
      const Result<Refinement> r = refine_region(s, all, goal);
      refine_us.push_back(thread_cpu_us() - t0);
      if (!r.ok()) {
        std::printf("%s: %s\n", file.c_str(), r.status().message.c_str());
        continue;
      }
      const BSplineSurface& f = r.value().surface;
      before += static_cast<long>(s.control_points.rows());
      after += static_cast<long>(f.control_points.rows());
      refined += r.value().report.changed() ? 1 : 0;
      if (f.control_points.rows() > static_cast<Eigen::Index>(largest_u) * largest_v) {
        largest_u = f.count(Direction::u);
        largest_v = f.count(Direction::v);
      }
    }
    double total = 0.0;
    for (const double t : refine_us) total += t;
    const Percentiles refine = percentiles(refine_us);
    std::printf("| %s | %zu | %d | %ld | %ld | %d x %d | %.0f us | %.0f us | %.1f ms | %.1f ms |\n",
                file.c_str(), model.value().faces.size(), refined, before, after, largest_u,
                largest_v, percentiles(region_us).p50, refine.p50, 1e-3 * refine.max, 1e-3 * total);
  }
}

}  // namespace argil::bench
