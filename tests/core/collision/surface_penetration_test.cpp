// Penetration depth between surfaces: exact for a paraboloid pressed into a
// plane, and against brute force on a dense sampling for curved surfaces.
#include <Eigen/Geometry>
#include <catch2/catch.hpp>
#include <cmath>
#include <random>

#include "argil/core.hpp"
#include "surface_pairs.hpp"

using namespace argil;
using argil::test::graph_surface;
using argil::test::hierarchy_for;
using argil::test::moved;

namespace {

/// The exact paraboloid z = c (x^2 + y^2) over [-half, half]^2 as one
/// biquadratic Bezier patch: (2u - 1)^2 has Bernstein coefficients 1, -1, 1.
BSplineSurface paraboloid(double half, double c) {
  BSplineSurface s;
  s.degree = {2, 2};
  for (auto& k : s.knots) {
    k.resize(6);
    k << 0, 0, 0, 1, 1, 1;
  }
  const double b[3] = {1.0, -1.0, 1.0};
  s.control_points.resize(9, 3);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      s.control_points.row(s.pole_index(i, j)) << half * (i - 1), half * (j - 1),
          c * half * half * (b[i] + b[j]);
  return s;
}

/// The plane z = 0 over [-size, size]^2, normal +z (behind it: z < 0).
BSplineSurface plane(double size) {
  BSplineSurface s;
  s.degree = {1, 1};
  for (auto& k : s.knots) {
    k.resize(4);
    k << 0, 0, 1, 1;
  }
  s.control_points.resize(4, 3);
  s.control_points << -size, -size, 0, -size, size, 0, size, -size, 0, size, size, 0;
  return s;
}

double deepest(const CollisionResult& r) {
  double d = -std::numeric_limits<double>::infinity();
  for (const Contact& c : r.contacts) d = std::max(d, c.depth);
  return d;
}

}  // namespace

TEST_CASE("a paraboloid pressed into a plane has the exact penetration depth") {
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  for (int trial = 0; trial < 40; ++trial) {
    const double press = std::pow(10.0, -3.0 + 3.0 * (unit(rng) + 1.0) / 2.0);  // 1e-3..1 mm
    const Eigen::Vector3d at(20 * unit(rng), 20 * unit(rng), -press);
    const Eigen::Matrix3d R =
        Eigen::Quaterniond(Eigen::Vector4d(unit(rng), unit(rng), unit(rng), unit(rng)).normalized())
            .toRotationMatrix();
    const Eigen::Vector3d t(100 * unit(rng), 100 * unit(rng), 100 * unit(rng));
    // The whole scene moved rigidly: the depth must not change.
    SurfaceHierarchy a = hierarchy_for(moved(plane(60.0), R, t));
    SurfaceHierarchy b =
        hierarchy_for(moved(moved(paraboloid(15.0, 0.03), Eigen::Matrix3d::Identity(), at), R, t));
    CollisionRequest request;
    request.tolerance = 1e-3 * press;
    const CollisionResult r = collide(a, b, request);
    INFO("trial " << trial << " press " << press);
    REQUIRE(r.region_count == 1);
    REQUIRE(r.contacts.front().depth > 0.0);
    CHECK(std::abs(r.contacts.front().depth - press) <= 1e-9 * (1.0 + press));
    // The deepest point is the paraboloid's apex, its foot right above.
    const Eigen::Vector3d apex = R * at + t;
    CHECK((evaluate(b.surface(), r.contacts.front().uv_b[0], r.contacts.front().uv_b[1]) - apex)
              .norm() <= 1e-6);
    CHECK((r.contacts.front().point - (apex + press * (R * Eigen::Vector3d::UnitZ()))).norm() <=
          1e-6);
    CHECK(r.contacts.front().normal.dot(R * Eigen::Vector3d::UnitZ()) > 1.0 - 1e-12);
  }
}

TEST_CASE("no penetration is reported for surfaces only touching, apart, or without depth") {
  SurfaceHierarchy a = hierarchy_for(plane(60.0));
  CollisionRequest request;
  request.tolerance = 1e-3;
  // Apex 0.5 eps above the plane: a near touch, no depth.
  SurfaceHierarchy above = hierarchy_for(
      moved(paraboloid(15.0, 0.03), Eigen::Matrix3d::Identity(), Eigen::Vector3d(0, 0, 5e-4)));
  const CollisionResult touch = collide(a, above, request);
  REQUIRE_FALSE(touch.contacts.empty());
  CHECK(deepest(touch) <= 0.0);
  // Pressed in, but depth not requested: crossings only (depth 0).
  SurfaceHierarchy pressed = hierarchy_for(
      moved(paraboloid(15.0, 0.03), Eigen::Matrix3d::Identity(), Eigen::Vector3d(0, 0, -0.5)));
  request.compute_depth = false;
  CHECK(deepest(collide(a, pressed, request)) == 0.0);
  request.compute_depth = true;
  CHECK(std::abs(deepest(collide(a, pressed, request)) - 0.5) <= 1e-9);
}

TEST_CASE("penetration depth of a paraboloid into a curved graph matches brute force") {
  std::mt19937_64 rng(17);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  constexpr double kSize = 100.0;
  int checked = 0;
  for (int trial = 0; trial < 12; ++trial) {
    const BSplineSurface a = graph_surface(rng, kSize, 2.0, 0.0, 3, 3);
    const double press = 0.2 + 0.8 * (unit(rng) + 1.0) / 2.0;
    const Eigen::Vector2d where(50 + 15 * unit(rng), 50 + 15 * unit(rng));
    const double ground = evaluate(a, where[0] / kSize, where[1] / kSize).z();
    const BSplineSurface b = moved(paraboloid(12.0, 0.05), Eigen::Matrix3d::Identity(),
                                   Eigen::Vector3d(where[0], where[1], ground - press));
    SurfaceHierarchy ha = hierarchy_for(a);
    SurfaceHierarchy hb = hierarchy_for(b);
    CollisionRequest request;
    request.tolerance = 1e-4;
    const CollisionResult r = collide(ha, hb, request);
    if (r.region_count != 1) continue;  // a wavy graph can cut the paraboloid twice

    // Brute force: b points below the graph (z < z_a(x, y), exact as x, y are
    // linear in u, v); each one's distance to a, sampled densely in the window
    // of half width z_a - z around it, which holds its nearest point on a.
    constexpr int kB = 80, kWindow = 41;
    double truth = 0.0;
    for (int i = 0; i < kB; ++i)
      for (int j = 0; j < kB; ++j) {
        const Eigen::Vector3d x = evaluate(b, i / (kB - 1.0), j / (kB - 1.0));
        const double below = evaluate(a, x.x() / kSize, x.y() / kSize).z() - x.z();
        if (below <= truth) continue;  // cannot beat the best: its distance is <= below
        double nearest = below;
        for (int p = 0; p < kWindow; ++p)
          for (int q = 0; q < kWindow; ++q) {
            const double sx = x.x() + below * (2.0 * p / (kWindow - 1) - 1.0);
            const double sy = x.y() + below * (2.0 * q / (kWindow - 1) - 1.0);
            nearest = std::min(nearest, (evaluate(a, sx / kSize, sy / kSize) - x).norm());
          }
        truth = std::max(truth, nearest);
      }
    INFO("trial " << trial << " press " << press << " truth " << truth);
    // The window pitch (below / 20) overestimates a distance by at most
    // pitch^2 / (4 distance) ~ 1e-3 of it; b's 0.3 mm pitch misses the deepest
    // point by less than curvature * pitch^2 ~ 5e-3 mm here.
    const double ours = deepest(r);
    CHECK(ours >= truth - 2e-3 * truth);
    CHECK(ours <= truth + 5e-3);
    ++checked;
  }
  CHECK(checked >= 8);
}
