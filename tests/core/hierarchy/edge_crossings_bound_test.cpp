// chord_lean() and edge_rise() against chords sampled from the B-spline's own
// evaluation (which shares nothing with the bounds' net differences), and
// crosses_at_most_once() against counted crossings of an edge with a patch.
#include <catch2/catch.hpp>
#include <cmath>
#include <random>
#include <vector>

#include "argil/core/geometry/evaluate.hpp"
#include "argil/core/hierarchy/edge_crossings_bound.hpp"
#include "argil/core/hierarchy/normal_cone.hpp"
#include "argil/core/hierarchy/surface_hierarchy.hpp"
#include "core/hierarchy/grown_nodes.hpp"
#include "support/random_surface.hpp"

namespace argil {
namespace {

constexpr int kDepth = 3;  // levels grown below each root

/// The node's point at local (s, t) in [0, 1]^2, through the B-spline.
Eigen::Vector3d at(const BSplineSurface& s, const ParamRect& r, double a, double b) {
  return evaluate(s, r.u0 + a * r.width(), r.v0 + b * r.height());
}

/// Local (s, t) of edge `e` at position `x` along it (ring order).
Eigen::Vector2d on_edge(PatchEdge e, double x) {
  switch (e) {
    case PatchEdge::t0:
      return {x, 0.0};
    case PatchEdge::s1:
      return {1.0, x};
    case PatchEdge::t1:
      return {x, 1.0};
    case PatchEdge::s0:
      break;
  }
  return {0.0, x};
}

TEST_CASE("chord lean and edge rise bound every sampled chord", "[edge_crossings_bound]") {
  std::mt19937_64 rng(777);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  OperatorCache cache;
  int bounded = 0, risen = 0;
  for (int k = 0; k < 12; ++k) {
    test::RandomSurfaceOptions options;
    options.max_degree = 4;
    options.max_extra_poles = 3;
    const BSplineSurface s = test::random_surface(rng, options);
    Result<SurfaceHierarchy> built = SurfaceHierarchy::build(s, cache);
    REQUIRE(built.ok());
    const SurfaceHierarchy& h = built.value();
    for (const int id : test::grown_nodes(h, kDepth)) {
      const HierarchyNode n = h.node(id);
      const std::optional<NormalCone> cone = normal_cone(n.patch);
      if (!cone) continue;
      INFO("surface " << k << " node " << id << " level " << n.level);
      const double lean = chord_lean(n.patch, cone->axis);
      if (lean < 1.0) {
        ++bounded;
        for (int m = 0; m < 200; ++m) {
          const Eigen::Vector3d w =
              at(s, n.rect, unit(rng), unit(rng)) - at(s, n.rect, unit(rng), unit(rng));
          if (w.norm() < 1e-9) continue;
          CHECK(std::abs(cone->axis.dot(w)) / w.norm() <= lean + 1e-9);
        }
      }
      for (const PatchEdge e : {PatchEdge::t0, PatchEdge::s1, PatchEdge::t1, PatchEdge::s0}) {
        const double rise = edge_rise(n.patch, e, cone->axis);
        if (rise == 0.0) continue;
        ++risen;
        for (int m = 0; m < 50; ++m) {
          const Eigen::Vector2d p = on_edge(e, unit(rng)), q = on_edge(e, unit(rng));
          const Eigen::Vector3d w = at(s, n.rect, p[0], p[1]) - at(s, n.rect, q[0], q[1]);
          if (w.norm() < 1e-9) continue;
          CHECK(std::abs(cone->axis.dot(w)) / w.norm() >= rise - 1e-9);
        }
      }
    }
  }
  // Three levels down most nodes are nearly flat: bounds must exist there.
  CHECK(bounded > 100);
  CHECK(risen > 100);
}

/// A bilinear patch with corners c00, c10, c01, c11.
BezierPatch bilinear(const Eigen::Vector3d& c00, const Eigen::Vector3d& c10,
                     const Eigen::Vector3d& c01, const Eigen::Vector3d& c11) {
  BezierPatch p{1, 1, PatchNet(4, 4)};
  p.points << c00.transpose(), 1, c01.transpose(), 1, c10.transpose(), 1, c11.transpose(), 1;
  return p;
}

TEST_CASE("an edge certified to cross once never crosses twice", "[edge_crossings_bound]") {
  // A plane z = 0 gently bent into a quadratic bump, and quadratic edge
  // curves through it: where one crosses twice the certificate must fail;
  // where it rises steeply, it must hold.
  BezierPatch sheet{2, 2, PatchNet(9, 4)};
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b)
      sheet.points.row(a * 3 + b) << a, b, (a == 1 && b == 1) ? 0.1 : 0.0, 1;
  const std::optional<NormalCone> cone = normal_cone(sheet);
  REQUIRE(cone);
  const double lean = chord_lean(sheet, cone->axis);
  REQUIRE(lean < 1.0);
  // Quadratic edge curves from (0.2, 1, z0) through a middle pole at z1 to
  // (1.8, 1, z2): rising ones (one crossing, or none), valleys and ridges
  // (two crossings, or none).
  const std::vector<double> heights{-0.6, -0.2, -0.04, 0.04, 0.2, 0.6};
  int twice = 0, certified = 0;
  for (const double z0 : heights) {
    for (const double z1 : heights) {
      for (const double z2 : heights) {
        BezierPatch edge{2, 1, PatchNet(6, 4)};
        const double z[3] = {z0, z1, z2};
        for (int a = 0; a < 3; ++a) {
          const double x = 0.2 + 0.8 * a;
          edge.points.row(a * 2) << x, 1.0, z[a], 1;
          edge.points.row(a * 2 + 1) << x, 1.5, z[a], 1;
        }
        const double rise = edge_rise(edge, PatchEdge::t0, cone->axis);
        // Crossings of the curve with the sheet, counted by sign changes of
        // height minus the sheet's height on a dense sampling.
        int crossings = 0;
        double last = 0.0;
        for (int m = 0; m <= 20000; ++m) {
          const double t = m / 20000.0;
          const Eigen::Vector3d c = evaluate(edge, t, 0.0);
          const Eigen::Vector3d on = evaluate(sheet, c.x() / 2.0, c.y() / 2.0);
          const double d = c.z() - on.z();
          if (m > 0 && (d > 0.0) != (last > 0.0)) ++crossings;
          last = d;
        }
        INFO("z " << z0 << " " << z1 << " " << z2 << " rise " << rise << " lean " << lean);
        if (crossings >= 2) ++twice;
        if (crosses_at_most_once(rise, lean)) {
          ++certified;
          CHECK(crossings <= 1);
        }
        // Steep and straight: the bound must hold.
        if (z0 == -0.6 && z1 == 0.04 && z2 == 0.6) CHECK(crosses_at_most_once(rise, lean));
      }
    }
  }
  // Both kinds occur, so the check above is exercised both ways.
  CHECK(twice > 10);
  CHECK(certified > 10);
  // A collapsed edge is one point; a flat patch's chords lie in its plane.
  const BezierPatch flat = bilinear({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0});
  CHECK(chord_lean(flat, Eigen::Vector3d::UnitZ()) == 0.0);
  BezierPatch point_edge = flat;
  point_edge.points.row(2) = point_edge.points.row(0);  // c10 onto c00
  CHECK(edge_rise(point_edge, PatchEdge::t0, Eigen::Vector3d::UnitZ()) == 1.0);
  CHECK(edge_rise(flat, PatchEdge::t0, Eigen::Vector3d::UnitZ()) == 0.0);
}

}  // namespace
}  // namespace argil
