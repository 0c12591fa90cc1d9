// Per-tick contact on a deforming 32x32 bicubic panel whose control points all
// move every tick: argil's sphere tool on the lazy hierarchy against the FCL
// route (re-tessellate to the same chord error, refit the AABB tree, collide).
// The same for a B-spline tool (a rigid bicubic dome pressed and dragged across
// the panel) against FCL mesh-mesh. Closest-point queries against
// OpenCASCADE's local and global projection. A scene of 64 panels with the
// broad phase against the narrow phase on every pair.
#include <fcl/geometry/bvh/BVH_model.h>
#include <fcl/geometry/shape/sphere.h>
#include <fcl/narrowphase/collision.h>
#include <fcl/narrowphase/collision_object.h>
#include <Extrema_GenLocateExtPS.hxx>
#include <GeomAPI_ProjectPointOnSurf.hxx>
#include <GeomAdaptor_Surface.hxx>

#include <cmath>
#include <memory>
#include <vector>

#include "bench_surfaces.hpp"
#include "median_ratio_reporter.hpp"

namespace {

constexpr int kPoles = 32;
constexpr double kToolRadius = 10.0;  // [mm]
constexpr double kPress = 1.0;        // sphere depth into the undeformed panel [mm]
constexpr int kPathSteps = 1000;      // one second of ticks at 1 kHz

/// Chord tolerance of the run [mm] from the benchmark argument [um]:
/// 50 um is about 1e-4 of the panel diagonal, 500 um about 1e-3.
double chord_tolerance(const benchmark::State& state) {
  return 1e-3 * static_cast<double>(state.range(0));
}

/// Every control point moves every tick: a travelling wave of 0.5 mm. The
/// frames are computed before timing (they stand for the deformation solver's
/// output), so a tick measures taking new control points and colliding.
std::vector<argil::ControlNet> deformation_frames(const argil::ControlNet& rest) {
  std::vector<argil::ControlNet> frames(kPathSteps, rest);
  for (int tick = 0; tick < kPathSteps; ++tick) {
    const double phase = 0.02 * tick;
    argil::ControlNet& out = frames[static_cast<std::size_t>(tick)];
    for (Eigen::Index k = 0; k < out.rows(); ++k) {
      out(k, 2) += 0.5 * std::sin(phase + 0.05 * rest(k, 0) + 0.03 * rest(k, 1));
    }
  }
  return frames;
}

/// Tool centres along a diagonal stroke, pressing kPress into the rest surface.
std::vector<Eigen::Vector3d> tool_path(const argil::BSplineSurface& s) {
  std::vector<Eigen::Vector3d> path;
  for (int k = 0; k < kPathSteps; ++k) {
    const double t = 0.2 + 0.6 * k / (kPathSteps - 1);
    const auto d = argil::evaluate_derivatives(s, t, 0.3 + 0.4 * t, 1);
    path.push_back(d.point + argil::unit_normal(d) * (kToolRadius - kPress));
  }
  return path;
}

/// Uniform grid fine enough that triangles are within `chord` of the surface:
/// (du^2 |S_uu| + 2 du dv |S_uv| + dv^2 |S_vv|) / 8 <= chord (second derivatives
/// sampled densely, with a 20% margin for the wave).
int grid_for_chord(const argil::BSplineSurface& s, double chord) {
  double suu = 0, suv = 0, svv = 0;
  for (int a = 0; a <= 200; ++a)
    for (int b = 0; b <= 200; ++b) {
      const auto d = argil::evaluate_derivatives(s, a / 200.0, b / 200.0, 2);
      suu = std::max(suu, d.duu.norm());
      suv = std::max(suv, d.duv.norm());
      svv = std::max(svv, d.dvv.norm());
    }
  const double second = 1.2 * (suu + 2 * suv + svv);
  return static_cast<int>(std::ceil(1.0 / std::sqrt(8.0 * chord / second))) + 1;
}

void argil_sphere_tick(benchmark::State& state) {
  const argil::BSplineSurface rest = argil::bench::bicubic_panel(kPoles);
  argil::OperatorCache cache;
  argil::SurfaceHierarchy h = argil::SurfaceHierarchy::build(rest, cache).value();
  const std::vector<Eigen::Vector3d> path = tool_path(rest);
  const std::vector<argil::ControlNet> frames = deformation_frames(rest.control_points);
  const argil::CollisionRequest request{.tolerance = chord_tolerance(state)};
  int tick = 0;
  long contacts = 0, leaves = 0, refreshed = 0, visited = 0;
  for (auto _ : state) {
    h.set_control_points(frames[static_cast<std::size_t>(tick % kPathSteps)]);
    const auto tool =
        argil::make_sphere(path[static_cast<std::size_t>(tick % kPathSteps)], kToolRadius);
    const argil::CollisionResult r = argil::collide(h, *tool, request);
    contacts += static_cast<long>(r.contacts.size());
    leaves += r.counters.leaf_pairs;
    refreshed += r.counters.nodes_refreshed;
    visited += r.counters.nodes_visited;
    ++tick;
  }
  state.counters["contacts_per_tick"] = static_cast<double>(contacts) / tick;
  state.counters["leaves_per_tick"] = static_cast<double>(leaves) / tick;
  state.counters["refreshed_per_tick"] = static_cast<double>(refreshed) / tick;
  state.counters["visited_per_tick"] = static_cast<double>(visited) / tick;
}

void fcl_sphere_tick(benchmark::State& state) {
  const argil::BSplineSurface rest = argil::bench::bicubic_panel(kPoles);
  argil::OperatorCache cache;
  const argil::SurfaceOperators ops = argil::surface_operators(rest, cache).value();
  const int n = grid_for_chord(rest, chord_tolerance(state));
  const Eigen::VectorXd t = Eigen::VectorXd::LinSpaced(n, 0.0, 1.0);
  const argil::SamplingRows rows = ops.u->sampling_rows(t);  // generous to FCL: our fast grid path
  argil::SurfaceGrid grid;
  argil::evaluate_grid(rest, rows, rows, 0, grid);
  std::vector<fcl::Vector3d> vertices(static_cast<std::size_t>(n) * n);
  std::vector<fcl::Triangle> triangles;
  for (int a = 0; a + 1 < n; ++a)
    for (int b = 0; b + 1 < n; ++b) {
      const auto id = [n](int i, int j) { return static_cast<std::size_t>(i * n + j); };
      triangles.emplace_back(id(a, b), id(a + 1, b), id(a + 1, b + 1));
      triangles.emplace_back(id(a, b), id(a + 1, b + 1), id(a, b + 1));
    }
  for (std::size_t k = 0; k < vertices.size(); ++k)
    vertices[k] = grid.points.row(static_cast<Eigen::Index>(k)).transpose();
  auto mesh = std::make_shared<fcl::BVHModel<fcl::AABBd>>();
  mesh->beginModel(static_cast<int>(triangles.size()), static_cast<int>(vertices.size()));
  mesh->addSubModel(vertices, triangles);
  mesh->endModel();
  fcl::CollisionObjectd mesh_object(mesh);
  const std::vector<Eigen::Vector3d> path = tool_path(rest);
  auto sphere = std::make_shared<fcl::Sphered>(kToolRadius);
  argil::BSplineSurface moved = rest;
  const std::vector<argil::ControlNet> frames = deformation_frames(rest.control_points);
  int tick = 0;
  long contacts = 0;
  for (auto _ : state) {
    moved.control_points = frames[static_cast<std::size_t>(tick % kPathSteps)];
    argil::evaluate_grid(moved, rows, rows, 0, grid);  // re-tessellate
    for (std::size_t k = 0; k < vertices.size(); ++k)
      vertices[k] = grid.points.row(static_cast<Eigen::Index>(k)).transpose();
    mesh->beginUpdateModel();
    mesh->updateSubModel(vertices);
    mesh->endUpdateModel(true, true);  // refit the AABB tree
    mesh_object.computeAABB();
    fcl::CollisionObjectd tool(
        sphere,
        fcl::Transform3d(Eigen::Translation3d(path[static_cast<std::size_t>(tick % kPathSteps)])));
    fcl::CollisionRequestd request(256, true);
    fcl::CollisionResultd result;
    fcl::collide(&tool, &mesh_object, request, result);
    contacts += static_cast<long>(result.numContacts());
    ++tick;
  }
  state.counters["contacts_per_tick"] = static_cast<double>(contacts) / tick;
  state.counters["triangles"] = static_cast<double>(triangles.size());
}

/// A rigid bicubic "thumb": an 8x8 dome 30 mm wide whose lowest point is its
/// origin, opening upwards (it presses with its underside).
argil::BSplineSurface thumb_tool() {
  constexpr int n = 8;
  argil::BSplineSurface s;
  s.degree = {3, 3};
  s.knots = {argil::bench::uniform_knots(3, n), argil::bench::uniform_knots(3, n)};
  s.control_points.resize(n * n, 3);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const double x = 30.0 * (i / (n - 1.0) - 0.5), y = 30.0 * (j / (n - 1.0) - 0.5);
      s.control_points.row(s.pole_index(i, j)) << x, y, 0.02 * (x * x + y * y);
    }
  return s;
}

/// Where the thumb's origin goes each tick: kPress below the rest panel.
std::vector<Eigen::Vector3d> thumb_path(const argil::BSplineSurface& panel) {
  std::vector<Eigen::Vector3d> path;
  for (int k = 0; k < kPathSteps; ++k) {
    const double t = 0.2 + 0.6 * k / (kPathSteps - 1);
    path.push_back(argil::evaluate(panel, t, 0.3 + 0.4 * t) - Eigen::Vector3d(0, 0, kPress));
  }
  return path;
}

void argil_thumb_tick(benchmark::State& state) {
  const argil::BSplineSurface rest = argil::bench::bicubic_panel(kPoles);
  const argil::BSplineSurface thumb = thumb_tool();
  argil::OperatorCache cache;
  argil::SurfaceHierarchy panel = argil::SurfaceHierarchy::build(rest, cache).value();
  argil::SurfaceHierarchy tool = argil::SurfaceHierarchy::build(thumb, cache).value();
  const std::vector<Eigen::Vector3d> path = thumb_path(rest);
  const std::vector<argil::ControlNet> frames = deformation_frames(rest.control_points);
  const argil::CollisionRequest request{.tolerance = chord_tolerance(state), .refine = false};
  argil::ControlNet posed = thumb.control_points;
  int tick = 0;
  long contacts = 0, curve_points = 0, leaves = 0;
  for (auto _ : state) {
    const std::size_t k = static_cast<std::size_t>(tick % kPathSteps);
    panel.set_control_points(frames[k]);
    posed = thumb.control_points.rowwise() + path[k].transpose();  // the rigid tool's pose
    tool.set_control_points(posed);
    const argil::CollisionResult r = argil::collide(panel, tool, request);
    contacts += static_cast<long>(r.contacts.size());
    for (const auto& c : r.curves) curve_points += static_cast<long>(c.points.size());
    leaves += r.counters.leaf_pairs;
    ++tick;
  }
  state.counters["contacts_per_tick"] = static_cast<double>(contacts) / tick;
  state.counters["curve_points_per_tick"] = static_cast<double>(curve_points) / tick;
  state.counters["leaf_pairs_per_tick"] = static_cast<double>(leaves) / tick;
}

/// An FCL mesh of `s` on an n x n parameter grid, re-evaluated by update().
struct FclGridMesh {
  FclGridMesh(const argil::BSplineSurface& surface, argil::OperatorCache& cache, int n)
      : s(surface), count(n) {
    const argil::SurfaceOperators ops = argil::surface_operators(s, cache).value();
    const Eigen::VectorXd t = Eigen::VectorXd::LinSpaced(n, 0.0, 1.0);
    rows = ops.u->sampling_rows(t);
    for (int a = 0; a + 1 < n; ++a)
      for (int b = 0; b + 1 < n; ++b) {
        const auto id = [n](int i, int j) { return static_cast<std::size_t>(i * n + j); };
        triangles.emplace_back(id(a, b), id(a + 1, b), id(a + 1, b + 1));
        triangles.emplace_back(id(a, b), id(a + 1, b + 1), id(a, b + 1));
      }
    fill_vertices();
    model = std::make_shared<fcl::BVHModel<fcl::AABBd>>();
    model->beginModel(static_cast<int>(triangles.size()), static_cast<int>(vertices.size()));
    model->addSubModel(vertices, triangles);
    model->endModel();
  }
  void fill_vertices() {
    argil::evaluate_grid(s, rows, rows, 0, grid);
    vertices.resize(static_cast<std::size_t>(count) * count);
    for (std::size_t k = 0; k < vertices.size(); ++k)
      vertices[k] = grid.points.row(static_cast<Eigen::Index>(k)).transpose();
  }
  /// Re-tessellate with new control points and refit the AABB tree.
  void update(const argil::ControlNet& points) {
    s.control_points = points;
    fill_vertices();
    model->beginUpdateModel();
    model->updateSubModel(vertices);
    model->endUpdateModel(true, true);
  }

  argil::BSplineSurface s;
  int count;
  argil::SamplingRows rows;
  argil::SurfaceGrid grid;
  std::vector<fcl::Vector3d> vertices;
  std::vector<fcl::Triangle> triangles;
  std::shared_ptr<fcl::BVHModel<fcl::AABBd>> model;
};

void fcl_thumb_tick(benchmark::State& state) {
  const argil::BSplineSurface rest = argil::bench::bicubic_panel(kPoles);
  const argil::BSplineSurface thumb = thumb_tool();
  argil::OperatorCache cache;
  const double chord = chord_tolerance(state);
  FclGridMesh panel(rest, cache, grid_for_chord(rest, chord));
  // The tool is rigid: FCL keeps its tree and only moves it (no refit).
  const FclGridMesh tool(thumb, cache, grid_for_chord(thumb, chord));
  fcl::CollisionObjectd panel_object(panel.model);
  const std::vector<Eigen::Vector3d> path = thumb_path(rest);
  const std::vector<argil::ControlNet> frames = deformation_frames(rest.control_points);
  int tick = 0;
  long contacts = 0;
  for (auto _ : state) {
    const std::size_t k = static_cast<std::size_t>(tick % kPathSteps);
    panel.update(frames[k]);
    panel_object.computeAABB();
    fcl::CollisionObjectd tool_object(tool.model, fcl::Transform3d(Eigen::Translation3d(path[k])));
    fcl::CollisionRequestd request(256, true);
    fcl::CollisionResultd result;
    fcl::collide(&tool_object, &panel_object, request, result);
    contacts += static_cast<long>(result.numContacts());
    ++tick;
  }
  state.counters["contacts_per_tick"] = static_cast<double>(contacts) / tick;
  state.counters["triangles"] = static_cast<double>(panel.triangles.size() + tool.triangles.size());
}

/// A scene of 8 x 8 small deformable panels (8x8 poles each, 80 mm apart, so
/// any two may meet) and a sphere tool sweeping across them: the broad phase
/// against the narrow phase on every body pair (2016 surface pairs, 64 tool pairs).
struct PanelScene {
  PanelScene() {
    for (int i = 0; i < 8; ++i)
      for (int j = 0; j < 8; ++j) {
        argil::BSplineSurface s = argil::bench::bicubic_panel(8);
        s.control_points.rowwise() += Eigen::RowVector3d(80.0 * i, 80.0 * j, 0.0);
        surfaces.push_back(argil::SurfaceHierarchy::build(s, cache).value());
      }
    for (int k = 0; k < kPathSteps; ++k) {
      const double t = static_cast<double>(k) / (kPathSteps - 1);
      const Eigen::Vector3d on = argil::evaluate(surfaces[0].surface(), 0.5, 0.5);
      path.push_back(on + Eigen::Vector3d(600.0 * t, 400.0 * t, kToolRadius - kPress));
    }
  }
  argil::OperatorCache cache;
  std::vector<argil::SurfaceHierarchy> surfaces;
  std::vector<Eigen::Vector3d> path;
};

void argil_scene_broad_phase(benchmark::State& state) {
  PanelScene scene;
  const argil::CollisionRequest request{.tolerance = 0.05};
  int tick = 0;
  long candidates = 0;
  for (auto _ : state) {
    const auto tool =
        argil::make_sphere(scene.path[static_cast<std::size_t>(tick % kPathSteps)], kToolRadius);
    std::vector<argil::SceneBody> bodies;
    for (auto& s : scene.surfaces) bodies.push_back({&s, nullptr, false});
    bodies.push_back({nullptr, tool.get(), false});
    const auto result = argil::collide_scene(bodies, request);
    candidates += result.value().candidate_pairs;
    ++tick;
  }
  state.counters["candidate_pairs_per_tick"] = static_cast<double>(candidates) / tick;
}

void argil_scene_all_pairs(benchmark::State& state) {
  PanelScene scene;
  const argil::CollisionRequest request{.tolerance = 0.05};
  int tick = 0;
  long in_contact = 0;
  for (auto _ : state) {
    const auto tool =
        argil::make_sphere(scene.path[static_cast<std::size_t>(tick % kPathSteps)], kToolRadius);
    for (std::size_t a = 0; a < scene.surfaces.size(); ++a) {
      in_contact += argil::collide(scene.surfaces[a], *tool, request).contacts.empty() ? 0 : 1;
      for (std::size_t b = a + 1; b < scene.surfaces.size(); ++b) {
        const auto r = argil::collide(scene.surfaces[a], scene.surfaces[b], request);
        in_contact += r.contacts.empty() ? 0 : 1;
      }
    }
    ++tick;
  }
  state.counters["pairs_in_contact_per_tick"] = static_cast<double>(in_contact) / tick;
}

/// Query points around the panel, 5 to 40 mm off the surface.
std::vector<Eigen::Vector3d> query_points(const argil::BSplineSurface& s) {
  std::vector<Eigen::Vector3d> q;
  for (int k = 0; k < 256; ++k) {
    const double u = 0.05 + 0.9 * std::fmod(0.618034 * k, 1.0);
    const double v = 0.05 + 0.9 * std::fmod(0.414214 * k, 1.0);
    const auto d = argil::evaluate_derivatives(s, u, v, 1);
    q.push_back(d.point + argil::unit_normal(d) * (5.0 + 35.0 * std::fmod(0.2718 * k, 1.0)) +
                Eigen::Vector3d(3.0, -2.0, 0.0));
  }
  return q;
}

void argil_closest_point(benchmark::State& state) {
  const argil::BSplineSurface s = argil::bench::bicubic_panel(kPoles);
  argil::OperatorCache cache;
  argil::SurfaceHierarchy h = argil::SurfaceHierarchy::build(s, cache).value();
  const auto q = query_points(s);
  std::size_t k = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(
        argil::closest_point(h, q[k++ % q.size()], {.tolerance = 1e-6}).distance);
  }
}

void occt_local_closest_point(benchmark::State& state) {
  const argil::BSplineSurface s = argil::bench::bicubic_panel(kPoles);
  GeomAdaptor_Surface adaptor(argil::bench::to_occt(s));
  const auto q = query_points(s);
  Extrema_GenLocateExtPS locate(adaptor, 1e-9, 1e-9);
  std::size_t k = 0;
  for (auto _ : state) {
    const Eigen::Vector3d& p = q[k++ % q.size()];
    locate.Perform(gp_Pnt(p.x(), p.y(), p.z()), 0.5, 0.5);  // local: from the domain centre
    benchmark::DoNotOptimize(locate.IsDone());
  }
}

void occt_global_closest_point(benchmark::State& state) {
  const argil::BSplineSurface s = argil::bench::bicubic_panel(kPoles);
  const Handle(Geom_BSplineSurface) oc = argil::bench::to_occt(s);
  const auto q = query_points(s);
  GeomAPI_ProjectPointOnSurf projection;
  projection.Init(oc, 0.0, 1.0, 0.0, 1.0);
  std::size_t k = 0;
  for (auto _ : state) {
    const Eigen::Vector3d& p = q[k++ % q.size()];
    projection.Perform(gp_Pnt(p.x(), p.y(), p.z()));
    benchmark::DoNotOptimize(projection.NbPoints());
  }
}

BENCHMARK(argil_sphere_tick)
    ->Name("tick32_sphere/argil")
    ->Arg(50)
    ->Arg(500)
    ->Repetitions(7)
    ->ReportAggregatesOnly(true)
    ->Unit(benchmark::kMicrosecond);
BENCHMARK(fcl_sphere_tick)
    ->Name("tick32_sphere/fcl_retessellate_refit")
    ->Arg(50)
    ->Arg(500)
    ->Repetitions(7)
    ->ReportAggregatesOnly(true)
    ->Unit(benchmark::kMicrosecond);
BENCHMARK(argil_thumb_tick)
    ->Name("tick32_thumb/argil")
    ->Arg(50)
    ->Arg(500)
    ->Repetitions(7)
    ->ReportAggregatesOnly(true)
    ->Unit(benchmark::kMicrosecond);
BENCHMARK(fcl_thumb_tick)
    ->Name("tick32_thumb/fcl_retessellate_refit")
    ->Arg(50)
    ->Arg(500)
    ->Repetitions(7)
    ->ReportAggregatesOnly(true)
    ->Unit(benchmark::kMicrosecond);
BENCHMARK(argil_scene_broad_phase)
    ->Name("scene64_sphere/broad_phase")
    ->Repetitions(7)
    ->ReportAggregatesOnly(true)
    ->Unit(benchmark::kMicrosecond);
BENCHMARK(argil_scene_all_pairs)
    ->Name("scene64_sphere/every_pair")
    ->Repetitions(7)
    ->ReportAggregatesOnly(true)
    ->Unit(benchmark::kMicrosecond);
BENCHMARK(argil_closest_point)
    ->Name("closest_point/argil_global_eps1e-6")
    ->Repetitions(7)
    ->ReportAggregatesOnly(true)
    ->Unit(benchmark::kMicrosecond);
BENCHMARK(occt_local_closest_point)
    ->Name("closest_point/occt_local")
    ->Repetitions(7)
    ->ReportAggregatesOnly(true)
    ->Unit(benchmark::kMicrosecond);
BENCHMARK(occt_global_closest_point)
    ->Name("closest_point/occt_global")
    ->Repetitions(7)
    ->ReportAggregatesOnly(true)
    ->Unit(benchmark::kMicrosecond);

}  // namespace

int main(int argc, char** argv) {
  return argil::bench::run_with_ratios(
      argc, argv,
      {{"tick32_sphere/fcl_retessellate_refit/50", "tick32_sphere/argil/50"},
       {"tick32_sphere/fcl_retessellate_refit/500", "tick32_sphere/argil/500"},
       {"tick32_thumb/fcl_retessellate_refit/50", "tick32_thumb/argil/50"},
       {"tick32_thumb/fcl_retessellate_refit/500", "tick32_thumb/argil/500"},
       {"scene64_sphere/every_pair", "scene64_sphere/broad_phase"},
       {"closest_point/occt_local", "closest_point/argil_global_eps1e-6"},
       {"closest_point/occt_global", "closest_point/argil_global_eps1e-6"}});
}
