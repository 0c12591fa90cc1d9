// Points and normals on a 64x64 grid of a 32x32 bicubic surface: through the
// precomputed operators, through direct evaluation, and through OpenCASCADE's
// Geom_BSplineSurface::D1, in the same run.
#include <Geom_BSplineSurface.hxx>
#include <TColStd_Array1OfInteger.hxx>
#include <TColStd_Array1OfReal.hxx>
#include <TColgp_Array2OfPnt.hxx>
#include <gp_Pnt.hxx>
#include <gp_Vec.hxx>

#include <cmath>

#include "argil/core.hpp"
#include "median_ratio_reporter.hpp"

namespace {

constexpr int kPoles = 32;
constexpr int kDegree = 3;
constexpr int kGrid = 64;

Eigen::VectorXd uniform_knots() {
  Eigen::VectorXd k(kPoles + kDegree + 1);
  for (Eigen::Index i = 0; i < k.size(); ++i) {
    k[i] = std::clamp(static_cast<double>(i - kDegree) / (kPoles - kDegree), 0.0, 1.0);
  }
  return k;
}

argil::BSplineSurface bicubic() {
  argil::BSplineSurface s;
  s.degree = {kDegree, kDegree};
  s.knots = {uniform_knots(), uniform_knots()};
  s.control_points.resize(kPoles * kPoles, 3);
  for (int i = 0; i < kPoles; ++i)
    for (int j = 0; j < kPoles; ++j)
      s.control_points.row(s.pole_index(i, j)) << 10.0 * i, 10.0 * j,
          20.0 * std::sin(0.3 * i) * std::cos(0.2 * j);
  return s;
}

Handle(Geom_BSplineSurface) to_occt(const argil::BSplineSurface& s) {
  TColgp_Array2OfPnt poles(1, kPoles, 1, kPoles);
  for (int i = 0; i < kPoles; ++i)
    for (int j = 0; j < kPoles; ++j) {
      const auto p = s.control_points.row(s.pole_index(i, j));
      poles.SetValue(i + 1, j + 1, gp_Pnt(p[0], p[1], p[2]));
    }
  const int distinct = kPoles - kDegree + 1;
  TColStd_Array1OfReal knots(1, distinct);
  TColStd_Array1OfInteger mults(1, distinct);
  for (int k = 0; k < distinct; ++k) {
    knots.SetValue(k + 1, static_cast<double>(k) / (distinct - 1));
    mults.SetValue(k + 1, k == 0 || k == distinct - 1 ? kDegree + 1 : 1);
  }
  return new Geom_BSplineSurface(poles, knots, knots, mults, mults, kDegree, kDegree);
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

BENCHMARK(operators)->Name("grid64_points_normals/argil_operators")->Repetitions(9)->ReportAggregatesOnly(true)->Unit(benchmark::kMicrosecond);
BENCHMARK(direct)->Name("grid64_points_normals/argil_direct")->Repetitions(9)->ReportAggregatesOnly(true)->Unit(benchmark::kMicrosecond);
BENCHMARK(occt_d1)->Name("grid64_points_normals/occt_D1")->Repetitions(9)->ReportAggregatesOnly(true)->Unit(benchmark::kMicrosecond);

}  // namespace

int main(int argc, char** argv) {
  return argil::bench::run_with_ratios(
      argc, argv,
      {{"grid64_points_normals/argil_direct", "grid64_points_normals/argil_operators"},
       {"grid64_points_normals/occt_D1", "grid64_points_normals/argil_operators"},
       {"grid64_points_normals/occt_D1", "grid64_points_normals/argil_direct"}});
}
