// Points and normals on a 64x64 grid of a 32x32 bicubic surface: through the
// precomputed operators, through direct evaluation, and through OpenCASCADE's
// Geom_BSplineSurface::D1, in the same run.
#include <gp_Vec.hxx>

#include "bench_surfaces.hpp"
#include "median_ratio_reporter.hpp"

namespace {

constexpr int kPoles = 32;
constexpr int kGrid = 64;

argil::BSplineSurface bicubic() { return argil::bench::bicubic_panel(kPoles); }
Handle(Geom_BSplineSurface) to_occt(const argil::BSplineSurface& s) {
  return argil::bench::to_occt(s);
}

Eigen::VectorXd grid_parameters() { return Eigen::VectorXd::LinSpaced(kGrid, 0.0, 1.0); }

void operators(benchmark::State& state) {
  const argil::BSplineSurface s = bicubic();
  argil::OperatorCache cache;
  const argil::SurfaceOperators ops = argil::surface_operators(s, cache).value();
  // Rows are structure: built once, outside the timed loop, like the cache does.
  const argil::SamplingRows ru = ops.u->sampling_rows(grid_parameters());
  const argil::SamplingRows rv = ops.v->sampling_rows(grid_parameters());
  argil::SurfaceGrid grid;
  for (auto _ : state) {
    argil::evaluate_grid(s, ru, rv, 1, grid);
    benchmark::DoNotOptimize(grid.normals.data());
  }
  state.SetItemsProcessed(state.iterations() * kGrid * kGrid);
}

void direct(benchmark::State& state) {
  const argil::BSplineSurface s = bicubic();
  const Eigen::VectorXd t = grid_parameters();
  argil::ControlNet points(kGrid * kGrid, 3), normals(kGrid * kGrid, 3);
  for (auto _ : state) {
    for (int a = 0; a < kGrid; ++a)
      for (int b = 0; b < kGrid; ++b) {
        const argil::SurfaceDerivatives d = argil::evaluate_derivatives(s, t[a], t[b], 1);
        points.row(a * kGrid + b) = d.point;
        normals.row(a * kGrid + b) = argil::unit_normal(d);
      }
    benchmark::DoNotOptimize(normals.data());
  }
  state.SetItemsProcessed(state.iterations() * kGrid * kGrid);
}

void occt_d1(benchmark::State& state) {
  const Handle(Geom_BSplineSurface) oc = to_occt(bicubic());
  const Eigen::VectorXd t = grid_parameters();
  argil::ControlNet points(kGrid * kGrid, 3), normals(kGrid * kGrid, 3);
  for (auto _ : state) {
    for (int a = 0; a < kGrid; ++a)
      for (int b = 0; b < kGrid; ++b) {
        gp_Pnt p;
        gp_Vec du, dv;
        oc->D1(t[a], t[b], p, du, dv);
        gp_Vec n = du.Crossed(dv);
        const double length = n.Magnitude();
        if (length > 0.0) n.Divide(length);
        points.row(a * kGrid + b) << p.X(), p.Y(), p.Z();
        normals.row(a * kGrid + b) << n.X(), n.Y(), n.Z();
      }
    benchmark::DoNotOptimize(normals.data());
  }
  state.SetItemsProcessed(state.iterations() * kGrid * kGrid);
}

BENCHMARK(operators)
    ->Name("grid64_points_normals/argil_operators")
    ->Repetitions(9)
    ->ReportAggregatesOnly(true)
    ->Unit(benchmark::kMicrosecond);
BENCHMARK(direct)
    ->Name("grid64_points_normals/argil_direct")
    ->Repetitions(9)
    ->ReportAggregatesOnly(true)
    ->Unit(benchmark::kMicrosecond);
BENCHMARK(occt_d1)
    ->Name("grid64_points_normals/occt_D1")
    ->Repetitions(9)
    ->ReportAggregatesOnly(true)
    ->Unit(benchmark::kMicrosecond);

}  // namespace

int main(int argc, char** argv) {
  return argil::bench::run_with_ratios(
      argc, argv,
      {{"grid64_points_normals/argil_direct", "grid64_points_normals/argil_operators"},
       {"grid64_points_normals/occt_D1", "grid64_points_normals/argil_operators"},
       {"grid64_points_normals/occt_D1", "grid64_points_normals/argil_direct"}});
}
