// The conservative hierarchy and the implicit/point tool queries, checked
// against analytic answers and brute force on a dense sampling.
#include <catch2/catch.hpp>
#include <cmath>
#include <random>

#include "argil/core.hpp"
#include "support/random_surface.hpp"
#include "surface_pairs.hpp"

using argil::BSplineSurface;
using argil::Direction;

namespace {

double model_size(const BSplineSurface& s) { return argil::control_point_box(s).diagonal(); }

/// The asymmetric surface flattened onto z = 0 (same knots, weights, layout).
BSplineSurface flat_surface() {
  BSplineSurface s = argil::test::asymmetric_surface(true);
  s.control_points.col(2).setZero();
  return s;
}

/// Minimum of the tool function over a dense sampling of the surface.
double brute_force_minimum(const BSplineSurface& s, const argil::ImplicitTool& tool, int n = 200) {
  double best = std::numeric_limits<double>::infinity();
  for (int a = 0; a <= n; ++a)
    for (int b = 0; b <= n; ++b) {
      const double u = s.domain_start(Direction::u) +
                       (s.domain_end(Direction::u) - s.domain_start(Direction::u)) * a / n;
      const double v = s.domain_start(Direction::v) +
                       (s.domain_end(Direction::v) - s.domain_start(Direction::v)) * b / n;
      best = std::min(best, tool.distance(argil::evaluate(s, u, v)).value);
    }
  return best;
}

}  // namespace

TEST_CASE(
    "node spheres enclose their sub-patch and flatness bounds the distance to its triangles") {
  std::mt19937_64 rng(31);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int trial = 0; trial < 30; ++trial) {
    argil::test::RandomSurfaceOptions options;
    options.rational = trial % 2 == 0;
    options.max_weight = trial % 4 == 0 ? 10.0 : 3.0;
    const BSplineSurface s = argil::test::random_surface(rng, options);
    argil::SurfaceHierarchy h = argil::test::hierarchy_for(s);
    std::vector<int> ids = h.roots();
    for (int level = 0; level < 3; ++level) {
      std::vector<int> next;
      for (int id : ids) {
        for (int k = 0; k < 4; ++k) next.push_back(h.child(id, k / 2, k % 2));
      }
      ids.insert(ids.end(), next.begin(), next.end());
      if (ids.size() > 400) break;
    }
    for (int id : ids) {
      const argil::HierarchyNode n = h.node(id);
      const auto& c = n.bound.corners;
      for (int k = 0; k < 12; ++k) {
        const double a = unit(rng), b = unit(rng);
        const Eigen::Vector3d p = argil::evaluate(s, n.rect.u0 + a * (n.rect.u1 - n.rect.u0),
                                                  n.rect.v0 + b * (n.rect.v1 - n.rect.v0));
        const Eigen::Vector3d t = a >= b
                                      ? Eigen::Vector3d((1 - a) * c[0] + (a - b) * c[1] + b * c[3])
                                      : Eigen::Vector3d((1 - b) * c[0] + (b - a) * c[2] + a * c[3]);
        const double slack = 1e-12 * model_size(s);  // rounding of the subdivided nets
        INFO("trial " << trial << " node level " << n.level);
        CHECK((p - n.bound.center).norm() <= n.bound.radius + slack);
        CHECK((p - t).norm() <= n.bound.flatness + slack);
        CHECK((p.array() >= n.bound.box.min.array() - slack).all());
        CHECK((p.array() <= n.bound.box.max.array() + slack).all());
      }
    }
  }
}

TEST_CASE("a sphere tool pressing into a plane gives the exact depth, point and normal") {
  const BSplineSurface s = flat_surface();
  argil::SurfaceHierarchy h = argil::test::hierarchy_for(s);
  const Eigen::Vector3d p = argil::evaluate(s, 0.41, 0.73);
  for (double depth : {0.0, 1e-6, 0.01, 0.5, 2.0}) {
    const double radius = 3.0;
    const auto tool = argil::make_sphere(p + Eigen::Vector3d(0, 0, radius - depth), radius);
    const argil::CollisionResult r = argil::collide(h, *tool, {.tolerance = 1e-5});
    INFO("depth " << depth);
    REQUIRE(r.region_count == 1);
    REQUIRE(!r.contacts.empty());
    const argil::Contact& c = r.contacts.front();
    CHECK(c.depth == Approx(depth).margin(1e-10));  // Newton converges to rounding
    CHECK((c.point - p).norm() < 1e-8);
    CHECK(std::abs(std::abs(c.normal.z()) - 1.0) < 1e-12);
    CHECK(c.region == 0);
  }
  // Just out of reach: farther than eps is no contact; within eps touches.
  const auto far = argil::make_sphere(p + Eigen::Vector3d(0, 0, 3.0 + 2e-5), 3.0);
  CHECK(argil::collide(h, *far, {.tolerance = 1e-5}).contacts.empty());
  const auto near = argil::make_sphere(p + Eigen::Vector3d(0, 0, 3.0 + 5e-6), 3.0);
  CHECK(argil::collide(h, *near, {.tolerance = 1e-5}).region_count == 1);
}

TEST_CASE("a plane tool against an exact cylinder patch gives the exact depth") {
  // Quarter cylinder of radius 10 around the x axis: rational quadratic arc in u.
  const BSplineSurface s = argil::test::cylinder_x(10.0, 0.0, 40.0);
  argil::SurfaceHierarchy h = argil::test::hierarchy_for(s);
  // The arc goes from (y, z) = (0, -10) to (10, 0); a plane with normal (0, 1, 1)/sqrt2
  // touches it at 45 degrees: the lowest value of n.x on the arc is -10.
  const Eigen::Vector3d n = Eigen::Vector3d(0, -1, 1).normalized();
  // n.x on the arc = (-y + z) / sqrt2, minimal at (10, 0)?  Check against brute force.
  for (double offset : {-8.0, -5.0, -1.0}) {
    const auto tool = argil::make_plane(n, offset);
    const double expected = -brute_force_minimum(s, *tool, 400);
    const argil::CollisionResult r = argil::collide(h, *tool, {.tolerance = 1e-5});
    REQUIRE(!r.contacts.empty());
    // Brute force sits on a grid: the exact optimum is at least as deep.
    CHECK(r.contacts.front().depth >= expected - 1e-12);
    CHECK(r.contacts.front().depth <= expected + 1e-3);
    // Every reported point really lies within eps of the tool's inside.
    for (const auto& c : r.contacts) CHECK(tool->distance(c.point).value <= 1e-5);
  }
  // A tangent plane along the cylinder: z <= -10 + tiny touches the bottom line.
  const auto tangent = argil::make_plane(Eigen::Vector3d(0, 0, 1), -10.0);
  const argil::CollisionResult r = argil::collide(h, *tangent, {.tolerance = 1e-5});
  REQUIRE(r.region_count == 1);
  CHECK(r.contacts.front().depth ==
        Approx(0.0).margin(1e-12));  // touching exactly: depth 0 up to rounding
}

TEST_CASE(
    "no penetration deeper than eps is missed and every contact is within eps, for every tool "
    "type") {
  std::mt19937_64 rng(77);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  int with_contact = 0, without = 0;
  for (int trial = 0; trial < 60; ++trial) {
    argil::test::RandomSurfaceOptions options;
    options.rational = trial % 2 == 1;
    options.max_degree = 4;
    options.max_extra_poles = 4;
    const BSplineSurface s = argil::test::random_surface(rng, options);
    argil::SurfaceHierarchy h = argil::test::hierarchy_for(s);
    const double size = model_size(s);
    const double eps = 1e-4 * size;
    // A tool centred near a random surface point, offset along z.
    const Eigen::Vector3d anchor = argil::evaluate(
        s,
        s.domain_start(Direction::u) +
            unit(rng) * (s.domain_end(Direction::u) - s.domain_start(Direction::u)),
        s.domain_start(Direction::v) +
            unit(rng) * (s.domain_end(Direction::v) - s.domain_start(Direction::v)));
    const double r = (0.05 + 0.1 * unit(rng)) * size;
    const Eigen::Vector3d c = anchor + Eigen::Vector3d(0, 0, r * (unit(rng) * 1.6 - 0.3));
    const Eigen::Matrix3d R =
        Eigen::AngleAxisd(6.28 * unit(rng), Eigen::Vector3d(unit(rng), unit(rng), 1).normalized())
            .toRotationMatrix();
    std::unique_ptr<argil::ImplicitTool> tool;
    switch (trial % 7) {
      case 0:
        tool = argil::make_sphere(c, r);
        break;
      case 1:
        tool = argil::make_plane(Eigen::Vector3d(0.1, -0.2, 1.0),
                                 Eigen::Vector3d(0.1, -0.2, 1.0).normalized().dot(c) - r);
        break;
      case 2:
        tool = argil::make_capsule(c - R.col(0) * r, c + R.col(0) * r, 0.5 * r);
        break;
      case 3:
        tool = argil::make_box(R, c, Eigen::Vector3d(r, 0.6 * r, 0.4 * r));
        break;
      case 4:
        tool = argil::make_ellipsoid(R, c, Eigen::Vector3d(r, 0.7 * r, 0.5 * r));
        break;
      case 5:
        tool = argil::make_torus(R, c, r, 0.3 * r);
        break;
      default: {
        const Eigen::Vector3d centre = c;
        const double radius = r;
        // A sphere given as a user SDF with a loose Lipschitz bound.
        tool = argil::make_user_sdf(
            [centre, radius](const Eigen::Vector3d& x) { return (x - centre).norm() - radius; },
            1.5);
      }
    }
    const argil::CollisionResult result = argil::collide(h, *tool, {.tolerance = eps});
    const double brute = brute_force_minimum(s, *tool, 150);
    INFO("trial " << trial << " tool " << trial % 7 << " brute-force minimum " << brute << " eps "
                  << eps);
    if (brute <= -eps) {
      ++with_contact;
      REQUIRE_FALSE(result.contacts.empty());
      // The deepest contact is at least as deep as the sampled minimum, up to eps.
      double deepest = -1e300;
      for (const auto& ct : result.contacts) deepest = std::max(deepest, ct.depth);
      CHECK(deepest >= -brute - eps);
    }
    if (brute > eps) {
      ++without;
    }
    for (const auto& ct : result.contacts) {
      CHECK(tool->distance(ct.point).value <= eps * (1 + 1e-9));
      CHECK((argil::evaluate(s, ct.uv_a[0], ct.uv_a[1]) - ct.point).norm() <= 1e-12 * size);
    }
  }
  CHECK(with_contact > 10);
  CHECK(without > 5);
}

TEST_CASE("after control points move, queries match a freshly built hierarchy (no stale bounds)") {
  std::mt19937_64 rng(5);
  std::normal_distribution<double> jitter(0.0, 1.0);
  BSplineSurface s = argil::test::asymmetric_surface(true);
  argil::SurfaceHierarchy persistent = argil::test::hierarchy_for(s);
  const auto tool =
      argil::make_sphere(argil::evaluate(s, 0.5, 0.5) + Eigen::Vector3d(0, 0, 4.0), 5.0);
  for (int move = 0; move < 15; ++move) {
    // Move a few control points by up to a few mm.
    for (int k = 0; k < 3; ++k) {
      const Eigen::Index row =
          static_cast<Eigen::Index>(rng() % static_cast<std::uint64_t>(s.control_points.rows()));
      s.control_points.row(row) += 2.0 * Eigen::RowVector3d(jitter(rng), jitter(rng), jitter(rng));
    }
    persistent.set_control_points(s.control_points, s.weights);
    argil::SurfaceHierarchy fresh = argil::test::hierarchy_for(s);
    const auto a = argil::collide(persistent, *tool, {.tolerance = 1e-4});
    const auto b = argil::collide(fresh, *tool, {.tolerance = 1e-4});
    INFO("move " << move);
    REQUIRE(a.contacts.size() == b.contacts.size());
    CHECK(a.region_count == b.region_count);
    for (std::size_t k = 0; k < a.contacts.size(); ++k) {
      CHECK(a.contacts[k].point == b.contacts[k].point);
      CHECK(a.contacts[k].depth == b.contacts[k].depth);
    }
    const Eigen::Vector3d q(20.0 * jitter(rng), 15.0 * jitter(rng), 5.0 * jitter(rng));
    CHECK(argil::closest_point(persistent, q).point == argil::closest_point(fresh, q).point);
  }
}

TEST_CASE("a node budget keeps memory bounded without changing any result") {
  std::mt19937_64 rng(8);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  BSplineSurface s = argil::test::asymmetric_surface(true);
  argil::SurfaceHierarchy bounded = argil::test::hierarchy_for(s);
  argil::SurfaceHierarchy grown = argil::test::hierarchy_for(s);
  bounded.set_node_budget(40);
  grown.set_node_budget(std::size_t{1} << 30);
  std::size_t largest = 0;
  for (int tick = 0; tick < 60; ++tick) {
    s.control_points.col(2).array() += 0.01 * std::sin(0.3 * tick);
    bounded.set_control_points(s.control_points, s.weights);
    grown.set_control_points(s.control_points, s.weights);
    // The tool wanders, so the grown hierarchy keeps reaching new places.
    const Eigen::Vector3d at = argil::evaluate(s, unit(rng), unit(rng));
    const auto tool = argil::make_sphere(at + Eigen::Vector3d(0, 0, 1.5), 2.0);
    const auto a = argil::collide(bounded, *tool, {.tolerance = 1e-3});
    const auto b = argil::collide(grown, *tool, {.tolerance = 1e-3});
    INFO("tick " << tick);
    REQUIRE(a.contacts.size() == b.contacts.size());
    for (std::size_t k = 0; k < a.contacts.size(); ++k) {
      CHECK(a.contacts[k].point == b.contacts[k].point);
      CHECK(a.contacts[k].depth == b.contacts[k].depth);
    }
    const auto pa = argil::closest_point(bounded, at), pb = argil::closest_point(grown, at);
    INFO("bounded " << pa.point.transpose() << " d " << pa.distance << " grown "
                    << pb.point.transpose() << " d " << pb.distance);
    CHECK(pa.point == pb.point);
    largest = std::max(largest, bounded.node_count());
    // After set_control_points the pool is within budget (queries may grow it again).
    CHECK((tick == 0 ||
           bounded.node_count() <= bounded.roots().size() + bounded.node_budget() + 4000));
  }
  CHECK(grown.node_count() > bounded.roots().size() + bounded.node_budget());  // exercised
  bounded.release_nodes();
  CHECK(bounded.node_count() == bounded.roots().size());
}

TEST_CASE("a rigid motion of surface and tool moves the contacts with it") {
  const BSplineSurface s = argil::test::asymmetric_surface(true);
  const Eigen::Vector3d centre = argil::evaluate(s, 0.6, 0.2) + Eigen::Vector3d(0.3, -0.2, 1.5);
  const Eigen::Matrix3d R =
      Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  const Eigen::Vector3d t(120.0, -45.0, 300.0);
  BSplineSurface moved = s;
  moved.control_points = ((s.control_points * R.transpose()).rowwise() + t.transpose()).eval();
  argil::SurfaceHierarchy a = argil::test::hierarchy_for(s);
  argil::SurfaceHierarchy b = argil::test::hierarchy_for(moved);
  const double eps = 1e-5;
  const auto ra = argil::collide(a, *argil::make_sphere(centre, 3.0), {.tolerance = eps});
  const auto rb = argil::collide(b, *argil::make_sphere(R * centre + t, 3.0), {.tolerance = eps});
  REQUIRE(!ra.contacts.empty());
  REQUIRE(ra.region_count == rb.region_count);
  const argil::Contact& ca = ra.contacts.front();
  const argil::Contact& cb = rb.contacts.front();
  CHECK((R * ca.point + t - cb.point).norm() <
        1e-8);  // Newton converges to rounding of 300 mm coordinates
  CHECK(ca.depth == Approx(cb.depth).margin(1e-9));
  CHECK((R * ca.normal - cb.normal).norm() < 1e-9);
}

TEST_CASE("nodes are built only where the query reaches") {
  std::mt19937_64 rng(9);
  const BSplineSurface s =
      argil::test::random_surface(rng, {.min_degree = 3, .max_degree = 3, .max_extra_poles = 12});
  argil::SurfaceHierarchy h = argil::test::hierarchy_for(s);
  const std::size_t roots = h.node_count();
  const auto corner =
      argil::evaluate(s, s.domain_start(Direction::u), s.domain_start(Direction::v));
  const auto r = argil::collide(h, *argil::make_sphere(corner, 0.5), {.tolerance = 1e-4});
  CHECK(r.region_count == 1);
  // A small tool at a corner refines a handful of nodes, not the surface.
  CHECK(h.node_count() < roots + 400);
  CHECK(r.counters.nodes_refreshed <= static_cast<long>(h.node_count()));
  CHECK(r.counters.nodes_visited > 0);
  CHECK(r.counters.leaf_pairs > 0);
}

TEST_CASE("two separate touches give two contact regions") {
  const BSplineSurface s = flat_surface();
  argil::SurfaceHierarchy h = argil::test::hierarchy_for(s);
  // A capsule lying across the plane, dipping in at both ends (a bent tool
  // modelled as two spheres through a user SDF).
  const Eigen::Vector3d a = argil::evaluate(s, 0.2, 0.0) + Eigen::Vector3d(0, 0, 0.9);
  const Eigen::Vector3d b = argil::evaluate(s, 0.8, 1.5) + Eigen::Vector3d(0, 0, 0.9);
  const auto two = argil::make_user_sdf(
      [a, b](const Eigen::Vector3d& x) { return std::min((x - a).norm(), (x - b).norm()) - 1.0; },
      1.0);
  const auto r = argil::collide(h, *two, {.tolerance = 1e-6});
  REQUIRE(r.region_count == 2);
  // Each region lists its deepest contact first: 0.1 mm at the bottom of each sphere.
  int region = -1;
  for (const auto& c : r.contacts) {
    if (c.region == region) continue;
    region = c.region;
    CHECK(c.depth == Approx(0.1).margin(1e-9));
  }
  CHECK(region == 1);
}

TEST_CASE("the closest point agrees with brute force on a dense sampling") {
  std::mt19937_64 rng(41);
  std::normal_distribution<double> gauss(0.0, 1.0);
  for (int trial = 0; trial < 40; ++trial) {
    argil::test::RandomSurfaceOptions options;
    options.rational = trial % 2 == 0;
    options.max_degree = 4;
    const BSplineSurface s = argil::test::random_surface(rng, options);
    argil::SurfaceHierarchy h = argil::test::hierarchy_for(s);
    const double size = model_size(s);
    const Eigen::Vector3d q = argil::control_point_box(s).min +
                              Eigen::Vector3d(size * 0.5, size * 0.4, 0) +
                              0.3 * size * Eigen::Vector3d(gauss(rng), gauss(rng), gauss(rng));
    const double eps = 1e-6 * size;
    const argil::ClosestPoint cp = argil::closest_point(h, q, {.tolerance = eps});
    const auto to_q = argil::make_sphere(q, 0.0);
    const double brute = brute_force_minimum(s, *to_q, 300);
    INFO("trial " << trial << " ours " << cp.distance << " brute force " << brute);
    CHECK(cp.distance <= brute + eps);  // the sampled minimum is an upper bound of the truth
    CHECK(std::abs(cp.signed_distance) == cp.distance);
    CHECK((argil::evaluate(s, cp.uv[0], cp.uv[1]) - cp.point).norm() < 1e-12 * size);
  }
}
