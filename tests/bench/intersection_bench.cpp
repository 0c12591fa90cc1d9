// Surface-surface intersection, same surfaces for every peer: a wavy bicubic
// panel crossed by a smaller one stood up at 70 degrees (16x16 vs 8x8 poles,
// and 32x32 vs 16x16). argil::collide with refinement against OpenCASCADE
// GeomAPI_IntSS and SISL (s1859 topology alone, and s1859 plus s1310 marching,
// which is what yields curves). Then argil's time against achieved error as
// eps goes from 1e-1 to 1e-8 of the model size, the error measured with
// OpenCASCADE (its curves' samples against our set, our points against its
// surfaces). SISL is AGPL: it is linked into this benchmark only.
#include <sisl.h>
#include <GeomAPI_IntSS.hxx>
#include <GeomAPI_ProjectPointOnSurf.hxx>
#include <GeomInt_IntSS.hxx>
#include <Geom_Curve.hxx>
#include <Precision.hxx>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <string>
#include <vector>

#include "bench_surfaces.hpp"
#include "median_ratio_reporter.hpp"

namespace {

struct Scene {
  argil::BSplineSurface a, b;
  double size = 0.0;  // diagonal of both control-point boxes together [mm]
};

/// Panel n_a crossed by panel n_b turned 70 degrees about a horizontal axis at
/// 30 degrees heading, centred on the middle of panel a.
Scene crossing_scene(int n_a, int n_b) {
  Scene s;
  s.a = argil::bench::bicubic_panel(n_a);
  s.b = argil::bench::bicubic_panel(n_b);
  constexpr double kPi = 3.14159265358979323846;
  const Eigen::Vector3d axis(std::cos(kPi / 6), std::sin(kPi / 6), 0.0);
  const Eigen::Matrix3d r = Eigen::AngleAxisd(70.0 * kPi / 180.0, axis).toRotationMatrix();
  const Eigen::Vector3d centre_a = argil::evaluate(s.a, 0.5, 0.5);
  const Eigen::Vector3d centre_b = argil::evaluate(s.b, 0.5, 0.5);
  const Eigen::Vector3d t = centre_a - r * centre_b;
  s.b.control_points = ((s.b.control_points * r.transpose()).rowwise() + t.transpose()).eval();
  argil::Box3 box = argil::control_point_box(s.a);
  const argil::Box3 box_b = argil::control_point_box(s.b);
  box.min = box.min.cwiseMin(box_b.min);
  box.max = box.max.cwiseMax(box_b.max);
  s.size = box.diagonal();
  return s;
}

const Scene& scene_16_8() {
  static const Scene s = crossing_scene(16, 8);
  return s;
}
const Scene& scene_32_16() {
  static const Scene s = crossing_scene(32, 16);
  return s;
}

/// A polynomial surface as SISL wants it: order = degree + 1, vertices with
/// the first parameter running fastest, copied (icopy = 1).
SISLSurf* to_sisl(const argil::BSplineSurface& s) {
  const int nu = s.count(argil::Direction::u), nv = s.count(argil::Direction::v);
  std::vector<double> ku(s.knots[0].data(), s.knots[0].data() + s.knots[0].size());
  std::vector<double> kv(s.knots[1].data(), s.knots[1].data() + s.knots[1].size());
  std::vector<double> coef(static_cast<std::size_t>(nu) * static_cast<std::size_t>(nv) * 3);
  for (int j = 0; j < nv; ++j)
    for (int i = 0; i < nu; ++i)
      for (int d = 0; d < 3; ++d)
        coef[(static_cast<std::size_t>(j) * static_cast<std::size_t>(nu) +
              static_cast<std::size_t>(i)) *
                 3 +
             static_cast<std::size_t>(d)] = s.control_points(s.pole_index(i, j), d);
  return newSurf(nu, nv, s.degree[0] + 1, s.degree[1] + 1, ku.data(), kv.data(), coef.data(), 1, 3,
                 1);
}

constexpr double kRelativeEps = 1e-6;
// SISL's computational resolution: relative rounding of doubles.
constexpr double kSislResolution = 1e-15;

/// argil: hierarchies built once; every iteration sets new control points
/// (the pair and the pair moved together by a thousandth of its size, in
/// turn: the same intersection, every pole changed), so every node's Bezier
/// net and bounds are recomputed when reached (node topology is reused, as it
/// is between haptic ticks; unchanged points would refresh nothing).
void run_argil(benchmark::State& state, const Scene& s, double relative_eps) {
  argil::OperatorCache cache;
  argil::SurfaceHierarchy ha = argil::SurfaceHierarchy::build(s.a, cache).value();
  argil::SurfaceHierarchy hb = argil::SurfaceHierarchy::build(s.b, cache).value();
  const argil::CollisionRequest request{.tolerance = relative_eps * s.size, .refine = true};
  argil::CollisionResult r;
  const Eigen::RowVector3d shift(1e-3 * s.size, 0.0, 0.0);
  const argil::ControlNet a[2] = {s.a.control_points, s.a.control_points.rowwise() + shift};
  const argil::ControlNet b[2] = {s.b.control_points, s.b.control_points.rowwise() + shift};
  int turn = 0;
  for (auto _ : state) {
    turn = 1 - turn;
    ha.set_control_points(a[turn]);
    hb.set_control_points(b[turn]);
    r = argil::collide(ha, hb, request);
    benchmark::DoNotOptimize(r.curves.data());
  }
  std::size_t points = 0;
  for (const auto& c : r.curves) points += c.points.size();
  state.counters["curves"] = static_cast<double>(r.curves.size());
  state.counters["points"] = static_cast<double>(points);
  state.counters["leaf_pairs"] = static_cast<double>(r.counters.leaf_pairs);
}

void run_occt(benchmark::State& state, const Scene& s) {
  const Handle(Geom_BSplineSurface) a = argil::bench::to_occt(s.a);
  const Handle(Geom_BSplineSurface) b = argil::bench::to_occt(s.b);
  int lines = 0;
  for (auto _ : state) {
    GeomAPI_IntSS x(a, b, kRelativeEps * s.size);
    lines = x.IsDone() ? x.NbLines() : -1;
    benchmark::DoNotOptimize(lines);
  }
  state.counters["curves"] = lines;
}

void run_sisl(benchmark::State& state, const Scene& s, bool march) {
  SISLSurf* a = to_sisl(s.a);
  SISLSurf* b = to_sisl(s.b);
  int curves = 0, status = 0, march_status = 0;
  for (auto _ : state) {
    int jpt = 0, jcrv = 0;
    double *gpar1 = nullptr, *gpar2 = nullptr;
    SISLIntcurve** wcurve = nullptr;
    s1859(a, b, kSislResolution, kRelativeEps * s.size, &jpt, &gpar1, &gpar2, &jcrv, &wcurve,
          &status);
    if (march) {
      // icur = 1: make the 3D curve; amax = 0: no extra step limit; igraph = 0.
      for (int k = 0; k < jcrv; ++k)
        s1310(a, b, wcurve[k], kRelativeEps * s.size, 0.0, 1, 0, &march_status);
    }
    curves = jcrv;
    std::free(gpar1);
    std::free(gpar2);
    if (wcurve) freeIntcrvlist(wcurve, jcrv);
  }
  freeSurf(a);
  freeSurf(b);
  state.counters["curves"] = curves;
  state.counters["status"] = status;
  if (march) state.counters["march_status"] = march_status;
}

void argil_16_8(benchmark::State& st) { run_argil(st, scene_16_8(), kRelativeEps); }
void occt_16_8(benchmark::State& st) { run_occt(st, scene_16_8()); }
void sisl_16_8(benchmark::State& st) { run_sisl(st, scene_16_8(), false); }
void sisl_march_16_8(benchmark::State& st) { run_sisl(st, scene_16_8(), true); }
void argil_32_16(benchmark::State& st) { run_argil(st, scene_32_16(), kRelativeEps); }
void occt_32_16(benchmark::State& st) { run_occt(st, scene_32_16()); }
void sisl_32_16(benchmark::State& st) { run_sisl(st, scene_32_16(), false); }
void sisl_march_32_16(benchmark::State& st) { run_sisl(st, scene_32_16(), true); }

double sweep_eps(int exponent) { return std::pow(10.0, -exponent); }
// One name per eps: the reporter keys medians by name without arguments.
std::string sweep_name(int exponent) {
  return "ssi16x8_sweep/argil_eps1e-" + std::to_string(exponent);
}

#define ARGIL_SSI_BENCH(fn, name)                                              \
  BENCHMARK(fn)->Name(name)->Repetitions(7)->ReportAggregatesOnly(true)->Unit( \
      benchmark::kMillisecond)
ARGIL_SSI_BENCH(argil_16_8, "ssi16x8/argil_refined_eps1e-6");
ARGIL_SSI_BENCH(occt_16_8, "ssi16x8/occt_intss");
ARGIL_SSI_BENCH(sisl_16_8, "ssi16x8/sisl_s1859");
ARGIL_SSI_BENCH(sisl_march_16_8, "ssi16x8/sisl_s1859_s1310");
ARGIL_SSI_BENCH(argil_32_16, "ssi32x16/argil_refined_eps1e-6");
ARGIL_SSI_BENCH(occt_32_16, "ssi32x16/occt_intss");
ARGIL_SSI_BENCH(sisl_32_16, "ssi32x16/sisl_s1859");
ARGIL_SSI_BENCH(sisl_march_32_16, "ssi32x16/sisl_s1859_s1310");

/// Distance from p to our curve polylines and contact points.
double distance_to_result(const Eigen::Vector3d& p, const argil::CollisionResult& r) {
  double best = std::numeric_limits<double>::infinity();
  for (const auto& c : r.curves)
    for (std::size_t k = 0; k < c.points.size(); ++k) {
      best = std::min(best, (c.points[k] - p).norm());
      if (k + 1 == c.points.size()) continue;
      const Eigen::Vector3d d = c.points[k + 1] - c.points[k];
      if (d.squaredNorm() == 0.0) continue;
      const double t = std::clamp((p - c.points[k]).dot(d) / d.squaredNorm(), 0.0, 1.0);
      best = std::min(best, (c.points[k] + t * d - p).norm());
    }
  for (const auto& c : r.contacts) best = std::min(best, (c.point - p).norm());
  return best;
}

/// The eps sweep table: time from the run, error from one query per eps
/// measured against OpenCASCADE (its curves at 1e-9 of the size, 200 samples each).
void print_sweep(const argil::bench::MedianRatioReporter& reporter) {
  const Scene& s = scene_16_8();
  const Handle(Geom_BSplineSurface) oa = argil::bench::to_occt(s.a);
  const Handle(Geom_BSplineSurface) ob = argil::bench::to_occt(s.b);
  GeomInt_IntSS occt(oa, ob, 1e-9 * s.size);
  std::vector<Eigen::Vector3d> samples;
  for (int i = 1; occt.IsDone() && i <= occt.NbLines(); ++i) {
    const Handle(Geom_Curve)& line = occt.Line(i);
    const double t0 = line->FirstParameter(), t1 = line->LastParameter();
    if (Precision::IsInfinite(t0) || Precision::IsInfinite(t1)) continue;
    for (int k = 0; k <= 200; ++k) {
      const gp_Pnt p = line->Value(t0 + (t1 - t0) * k / 200.0);
      samples.emplace_back(p.X(), p.Y(), p.Z());
    }
  }
  GeomAPI_ProjectPointOnSurf pa, pb;
  pa.Init(oa, 0.0, 1.0, 0.0, 1.0, Precision::Confusion());
  pb.Init(ob, 0.0, 1.0, 0.0, 1.0, Precision::Confusion());
  std::printf(
      "\nTime against achieved error, 16x16 vs 8x8, model size %.4g mm; OCCT reference: %d curves, "
      "%zu samples, TolReached3d %.3g of size\n",
      s.size, occt.IsDone() ? occt.NbLines() : -1, samples.size(), occt.TolReached3d() / s.size);
  std::printf("%9s  %12s  %10s  %8s  %16s  %16s\n", "eps/size", "median [ms]", "leaf pairs",
              "points", "OCCT->ours/size", "ours->surf/size");
  argil::OperatorCache cache;
  for (int e = 1; e <= 8; ++e) {
    argil::SurfaceHierarchy ha = argil::SurfaceHierarchy::build(s.a, cache).value();
    argil::SurfaceHierarchy hb = argil::SurfaceHierarchy::build(s.b, cache).value();
    const argil::CollisionResult r =
        argil::collide(ha, hb, {.tolerance = sweep_eps(e) * s.size, .refine = true});
    double occt_to_ours = 0.0, ours_to_surfaces = 0.0;
    for (const Eigen::Vector3d& p : samples)
      occt_to_ours = std::max(occt_to_ours, distance_to_result(p, r));
    std::size_t points = 0;
    for (const auto& c : r.curves)
      for (const Eigen::Vector3d& p : c.points) {
        ++points;
        pa.Perform(gp_Pnt(p.x(), p.y(), p.z()));
        pb.Perform(gp_Pnt(p.x(), p.y(), p.z()));
        const double da =
            pa.NbPoints() > 0 ? pa.LowerDistance() : std::numeric_limits<double>::infinity();
        const double db =
            pb.NbPoints() > 0 ? pb.LowerDistance() : std::numeric_limits<double>::infinity();
        ours_to_surfaces = std::max({ours_to_surfaces, da, db});
      }
    std::printf("%9.0e  %12.4g  %10ld  %8zu  %16.3g  %16.3g\n", sweep_eps(e),
                reporter.median(sweep_name(e)), r.counters.leaf_pairs, points,
                occt_to_ours / s.size, ours_to_surfaces / s.size);
  }
}

}  // namespace

int main(int argc, char** argv) {
  for (int e = 1; e <= 8; ++e) {
    benchmark::RegisterBenchmark(
        sweep_name(e).c_str(),
        [e](benchmark::State& st) { run_argil(st, scene_16_8(), sweep_eps(e)); })
        ->Repetitions(5)
        ->ReportAggregatesOnly(true)
        ->Unit(benchmark::kMillisecond);
  }
  return argil::bench::run_with_ratios(
      argc, argv,
      {{"ssi16x8/occt_intss", "ssi16x8/argil_refined_eps1e-6"},
       {"ssi16x8/sisl_s1859", "ssi16x8/argil_refined_eps1e-6"},
       {"ssi16x8/sisl_s1859_s1310", "ssi16x8/argil_refined_eps1e-6"},
       {"ssi32x16/occt_intss", "ssi32x16/argil_refined_eps1e-6"},
       {"ssi32x16/sisl_s1859", "ssi32x16/argil_refined_eps1e-6"},
       {"ssi32x16/sisl_s1859_s1310", "ssi32x16/argil_refined_eps1e-6"}},
      print_sweep);
}
