// normal_cone() against dense samples of the B-spline's own normals (an
// evaluation path that shares nothing with the cone's Bernstein products), and
// least_crossing_angle() on cones whose answer is known.
#include <catch2/catch.hpp>
#include <cmath>
#include <random>
#include <vector>

#include "argil/core/geometry/evaluate.hpp"
#include "argil/core/hierarchy/normal_cone.hpp"
#include "argil/core/hierarchy/surface_hierarchy.hpp"
#include "core/hierarchy/grown_nodes.hpp"
#include "support/random_surface.hpp"

namespace argil {
namespace {

constexpr int kSamples = 11;     // per side of a node's rectangle
constexpr int kDepth = 3;        // levels grown below each root
constexpr double kInset = 1e-9;  // of a node's sides, at its edges

TEST_CASE("normal cones hold every sampled normal of polynomial patches", "[normal_cone]") {
  std::mt19937_64 rng(4242);
  OperatorCache cache;
  int nodes = 0, with_cone = 0;
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
      ++nodes;
      const std::optional<NormalCone> cone = normal_cone(n.patch);
      if (!cone) continue;
      ++with_cone;
      INFO("surface " << k << " node " << id << " level " << n.level);
      REQUIRE(cone->half_angle < 0.5 * M_PI);
      double worst = -1.0;  // sampled angle beyond the half angle [rad]
      for (int i = 0; i < kSamples; ++i) {
        for (int j = 0; j < kSamples; ++j) {
          // Just inside the rectangle: at a C0 knot line the derivatives
          // evaluated on the edge may be the neighbouring element's.
          const double a = kInset + (1.0 - 2.0 * kInset) * i / (kSamples - 1);
          const double b = kInset + (1.0 - 2.0 * kInset) * j / (kSamples - 1);
          const double u = n.rect.u0 + a * n.rect.width();
          const double v = n.rect.v0 + b * n.rect.height();
          const SurfaceDerivatives d = evaluate_derivatives(s, u, v, 1);
          const Eigen::Vector3d normal = d.du.cross(d.dv);
          REQUIRE(normal.norm() > 0.0);
          const double angle = std::atan2(normal.cross(cone->axis).norm(), normal.dot(cone->axis));
          worst = std::max(worst, angle - cone->half_angle);
        }
      }
      CHECK(worst <= 1e-9);
    }
  }
  // Random nets fold at the roots, but most nodes three levels down are
  // nearly flat: the cones must exist where they can.
  CHECK(with_cone > nodes / 2);
}

TEST_CASE("normal cones: none for rational, degenerate or folded patches", "[normal_cone]") {
  BezierPatch plane{1, 1, PatchNet(4, 4)};
  plane.points << 0, 0, 0, 1, 0, 1, 0, 1, 1, 0, 0, 1, 1, 1, 0, 1;  // rows a * 2 + b
  const std::optional<NormalCone> flat = normal_cone(plane);
  REQUIRE(flat);
  CHECK(std::abs(std::abs(flat->axis.z()) - 1.0) < 1e-15);
  CHECK(flat->half_angle < 1e-8);

  BezierPatch weighted = plane;
  weighted.points.row(3) *= 2.0;  // one weight 2: rational
  CHECK_FALSE(normal_cone(weighted));

  BezierPatch collapsed = plane;
  collapsed.points.row(1) = collapsed.points.row(0);  // corner edge of zero length
  CHECK_FALSE(normal_cone(collapsed));

  // A fold: a quadratic in u whose tangent turns right back, so its
  // normals point both ways.
  BezierPatch folded{2, 1, PatchNet(6, 4)};
  folded.points << 0, 0, 0, 1, 0, 1, 0, 1, 2, 0, 0, 1, 2, 1, 0, 1, 0, 0, 0, 1, 0, 1, 0, 1;
  CHECK_FALSE(normal_cone(folded));
  // Turned back short of that, its normals still lie on one side: a wide
  // cone, which holds them.
  folded.points(4, 2) = folded.points(5, 2) = 0.1;
  const std::optional<NormalCone> wide = normal_cone(folded);
  REQUIRE(wide);
  CHECK(wide->half_angle > 0.49 * M_PI);
}

TEST_CASE("least crossing angle of two cones", "[normal_cone]") {
  const auto turned = [](double degrees) {
    const double r = degrees * M_PI / 180.0;
    return Eigen::Vector3d(std::sin(r), 0.0, std::cos(r));
  };
  const NormalCone a{turned(0), 0.1};
  CHECK(least_crossing_angle(a, {turned(60), 0.2}) == Approx(M_PI / 3 - 0.3).epsilon(1e-12));
  // Lines, not directions: 170 degrees apart is 10 degrees from parallel.
  CHECK(least_crossing_angle(a, {turned(170), 0.05}) == Approx(M_PI / 18 - 0.15).epsilon(1e-12));
  CHECK(least_crossing_angle(a, {turned(170), 0.2}) == 0.0);
  CHECK(least_crossing_angle(a, {turned(5), 0.0}) == 0.0);
}

}  // namespace
}  // namespace argil
