// Surface against surface: the triangle-triangle test against an
// edge-crossing oracle, analytic intersections (planes, cylinders), and
// brute force on graph surfaces where crossings are sign changes of z_a - z_b.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "argil/core.hpp"
#include "argil/core/geometry/triangle_distance.hpp"
#include "core/collision/surface_pairs.hpp"
#include "support/random_surface.hpp"

using argil::BSplineSurface;
using argil::CollisionResult;
using argil::Triangle;
using argil::test::hierarchy_for;

namespace {

Eigen::Vector3d random_point(std::mt19937_64& rng, double size) {
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  return size * Eigen::Vector3d(unit(rng), unit(rng), unit(rng));
}

Eigen::Vector3d on_triangle(const Triangle& t, const Eigen::Vector3d& w) {
  return w[0] * t[0] + w[1] * t[1] + w[2] * t[2];
}

/// Oracle: non-coplanar triangles meet iff an edge of one crosses the
/// other. Returns +1 (meet), -1 (apart) or 0 (within 1e-9 of a decision:
/// a grazing configuration where either answer is right).
int edges_cross(const Triangle& a, const Triangle& b) {
  int verdict = -1;
  for (int pass = 0; pass < 2; ++pass) {
    const Triangle& e = pass == 0 ? a : b;
    const Triangle& t = pass == 0 ? b : a;
    const Eigen::Vector3d n = (t[1] - t[0]).cross(t[2] - t[0]).normalized();
    for (std::size_t k = 0; k < 3; ++k) {
      const Eigen::Vector3d& p = e[k];
      const Eigen::Vector3d& q = e[(k + 1) % 3];
      const double sp = n.dot(p - t[0]), sq = n.dot(q - t[0]);
      if (std::abs(sp) < 1e-9 || std::abs(sq) < 1e-9) return 0;
      if ((sp > 0) == (sq > 0)) continue;
      const Eigen::Vector3d x = p + (q - p) * (sp / (sp - sq));
      // Signed sub-areas of x against the three edges, relative to the whole.
      double inside = std::numeric_limits<double>::infinity();
      for (std::size_t m = 0; m < 3; ++m)
        inside = std::min(inside, n.dot((t[(m + 1) % 3] - t[m]).cross(x - t[m])));
      if (std::abs(inside) < 1e-9) return 0;
      if (inside > 0) verdict = 1;
    }
  }
  return verdict;
}

double distance_to_triangle(const Eigen::Vector3d& p, const Triangle& t) {
  return (argil::closest_point_on_triangle(p, t[0], t[1], t[2]) - p).norm();
}

/// Every curve point and contact: parameters map back within `bound` of the point on both surfaces.
double worst_parameter_gap(const BSplineSurface& a, const BSplineSurface& b,
                           const CollisionResult& r, bool curves) {
  double worst = 0.0;
  if (curves) {
    for (const auto& c : r.curves)
      for (std::size_t k = 0; k < c.points.size(); ++k)
        worst =
            std::max({worst, (argil::evaluate(a, c.uv_a[k][0], c.uv_a[k][1]) - c.points[k]).norm(),
                      (argil::evaluate(b, c.uv_b[k][0], c.uv_b[k][1]) - c.points[k]).norm()});
  } else {
    for (const auto& c : r.contacts) {
      if (c.depth > 0.0) continue;  // penetration: b's deepest point and its foot on a
      worst = std::max({worst, (argil::evaluate(a, c.uv_a[0], c.uv_a[1]) - c.point).norm(),
                        (argil::evaluate(b, c.uv_b[0], c.uv_b[1]) - c.point).norm()});
    }
  }
  return worst;
}

/// Crossings of z_a - z_b along the edges of a g x g parameter grid, each
/// bisected to a point on both graphs.
std::vector<Eigen::Vector3d> brute_force_crossings(const BSplineSurface& a, const BSplineSurface& b,
                                                   int g) {
  const auto h = [&](double u, double v) {
    return argil::evaluate(a, u, v).z() - argil::evaluate(b, u, v).z();
  };
  std::vector<Eigen::Vector3d> out;
  std::vector<double> values(static_cast<std::size_t>((g + 1) * (g + 1)));
  for (int i = 0; i <= g; ++i)
    for (int j = 0; j <= g; ++j)
      values[static_cast<std::size_t>(i * (g + 1) + j)] = h(double(i) / g, double(j) / g);
  const auto bisect = [&](Eigen::Vector2d p, Eigen::Vector2d q, double hp) {
    for (int it = 0; it < 60; ++it) {
      const Eigen::Vector2d m = 0.5 * (p + q);
      const double hm = h(m[0], m[1]);
      if ((hm > 0) == (hp > 0)) {
        p = m;
        hp = hm;
      } else {
        q = m;
      }
    }
    return argil::evaluate(a, p[0], p[1]);
  };
  for (int i = 0; i <= g; ++i) {
    for (int j = 0; j <= g; ++j) {
      const double here = values[static_cast<std::size_t>(i * (g + 1) + j)];
      const Eigen::Vector2d p(double(i) / g, double(j) / g);
      if (i < g) {
        const double there = values[static_cast<std::size_t>((i + 1) * (g + 1) + j)];
        if (here * there < 0)
          out.push_back(bisect(p, Eigen::Vector2d(double(i + 1) / g, double(j) / g), here));
      }
      if (j < g) {
        const double there = values[static_cast<std::size_t>(i * (g + 1) + j + 1)];
        if (here * there < 0)
          out.push_back(bisect(p, Eigen::Vector2d(double(i) / g, double(j + 1) / g), here));
      }
    }
  }
  return out;
}

}  // namespace

TEST_CASE(
    "triangle intersection agrees with the edge-crossing oracle and its segment lies on both "
    "triangles") {
  std::mt19937_64 rng(11);
  int crossing = 0, apart = 0;
  for (int trial = 0; trial < 20000; ++trial) {
    const Triangle a{random_point(rng, 1.0), random_point(rng, 1.0), random_point(rng, 1.0)};
    const Triangle b{random_point(rng, 1.0), random_point(rng, 1.0), random_point(rng, 1.0)};
    const argil::TriangleIntersection x = argil::intersect_triangles(a, b);
    const int oracle = edges_cross(a, b);
    if (oracle == 0) continue;  // grazing: both answers are right
    INFO("trial " << trial);
    REQUIRE((x.kind != argil::TriangleIntersection::Kind::none) == (oracle > 0));
    if (x.kind == argil::TriangleIntersection::Kind::none) {
      ++apart;
      CHECK(argil::triangle_distance(a, b).distance > 0.0);  // disjoint triangles are apart
      continue;
    }
    ++crossing;
    for (std::size_t k = 0; k < 2; ++k) {
      CHECK(distance_to_triangle(x.points[k], a) < 1e-12);  // rounding of unit-size coordinates
      CHECK(distance_to_triangle(x.points[k], b) < 1e-12);
      CHECK((on_triangle(a, x.bary_a[k]) - x.points[k]).norm() < 1e-12);
      CHECK((on_triangle(b, x.bary_b[k]) - x.points[k]).norm() < 1e-12);
    }
  }
  CHECK(crossing > 1000);
  CHECK(apart > 1000);
}

TEST_CASE(
    "triangle distance of disjoint triangles lies between the true one and a dense sampling's, "
    "at points its barycentric coordinates give") {
  // Its points lie on the triangles, so it is at least the true distance; a
  // sampling's nearest pair is at most the true distance plus the spacing.
  std::mt19937_64 rng(12);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  static constexpr int kSteps = 24;
  const auto samples = [](const Triangle& t) {
    std::vector<Eigen::Vector3d> out;
    for (int i = 0; i <= kSteps; ++i)
      for (int j = 0; i + j <= kSteps; ++j)
        out.push_back(on_triangle(t, Eigen::Vector3d(kSteps - i - j, i, j) / kSteps));
    return out;
  };
  int disjoint = 0;
  for (int trial = 0; trial < 300; ++trial) {
    const Triangle a{random_point(rng, 1.0), random_point(rng, 1.0), random_point(rng, 1.0)};
    Triangle b{random_point(rng, 1.0), random_point(rng, 1.0), random_point(rng, 1.0)};
    if (trial % 2 == 0) {
      // Nearly parallel: a lifted along its normal by up to 0.1, corners jittered.
      const Eigen::Vector3d n = (a[1] - a[0]).cross(a[2] - a[0]).normalized();
      for (std::size_t k = 0; k < 3; ++k)
        b[k] = a[k] + 0.1 * unit(rng) * n + 0.01 * random_point(rng, 1.0);
    }
    // Meant for disjoint triangles (crossing ones are found by intersect_triangles).
    if (argil::intersect_triangles(a, b).kind != argil::TriangleIntersection::Kind::none) continue;
    ++disjoint;
    const argil::TriangleDistance d = argil::triangle_distance(a, b);
    INFO("trial " << trial);
    for (const Eigen::Vector3d& w : {d.bary_a, d.bary_b}) {
      CHECK(w.minCoeff() >= 0.0);
      CHECK(std::abs(w.sum() - 1.0) < 1e-15);
    }
    CHECK((on_triangle(a, d.bary_a) - d.point_a).norm() < 1e-12);
    CHECK((on_triangle(b, d.bary_b) - d.point_b).norm() < 1e-12);
    CHECK(std::abs((d.point_a - d.point_b).norm() - d.distance) < 1e-15);
    double sampled = std::numeric_limits<double>::infinity();
    const std::vector<Eigen::Vector3d> on_b = samples(b);
    for (const Eigen::Vector3d& p : samples(a))
      for (const Eigen::Vector3d& q : on_b) sampled = std::min(sampled, (p - q).norm());
    CHECK(d.distance <= sampled + 1e-12);
    // A point of a triangle is within its longest edge / kSteps of a sample.
    const auto longest_edge = [](const Triangle& t) {
      return std::max({(t[1] - t[0]).norm(), (t[2] - t[1]).norm(), (t[0] - t[2]).norm()});
    };
    CHECK(d.distance >= sampled - (longest_edge(a) + longest_edge(b)) / kSteps);
  }
  CHECK(disjoint > 150);
}

TEST_CASE("triangle intersection handles touching and coplanar triangles deterministically") {
  const Triangle base{Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 0, 0), Eigen::Vector3d(0, 1, 0)};
  // A corner resting on the face: touching counts, at that corner.
  const Triangle corner{Eigen::Vector3d(0.25, 0.25, 0), Eigen::Vector3d(0.3, 0.2, 1),
                        Eigen::Vector3d(0.2, 0.4, 1)};
  const auto t = argil::intersect_triangles(base, corner);
  REQUIRE(t.kind == argil::TriangleIntersection::Kind::segment);
  CHECK((t.points[0] - Eigen::Vector3d(0.25, 0.25, 0)).norm() <
        1e-16);                                      // rounding of the barycentric evaluation
  CHECK((t.points[1] - t.points[0]).norm() == 0.0);  // both ends come from the same cut point
  // An edge lying in the face: the shared segment.
  const Triangle edge{Eigen::Vector3d(0.1, 0.1, 0), Eigen::Vector3d(0.5, 0.1, 0),
                      Eigen::Vector3d(0.3, 0.1, 1)};
  const auto e = argil::intersect_triangles(base, edge);
  REQUIRE(e.kind == argil::TriangleIntersection::Kind::segment);
  CHECK(std::abs((e.points[1] - e.points[0]).norm() - 0.4) <
        1e-15);  // segment from exact corner coordinates
  // Coplanar overlap: the overlap polygon's centroid, the same on every call.
  const Triangle shifted{Eigen::Vector3d(0.2, 0.2, 0), Eigen::Vector3d(1.2, 0.2, 0),
                         Eigen::Vector3d(0.2, 1.2, 0)};
  const auto c1 = argil::intersect_triangles(base, shifted);
  const auto c2 = argil::intersect_triangles(base, shifted);
  REQUIRE(c1.kind == argil::TriangleIntersection::Kind::coplanar);
  CHECK(c1.points[0] == c2.points[0]);
  CHECK(std::abs(c1.points[0].z()) == 0.0);
  CHECK(c1.points[0].x() + c1.points[0].y() <= 1.0);
  // Coplanar but apart, and parallel planes: nothing.
  const Triangle far{Eigen::Vector3d(2, 2, 0), Eigen::Vector3d(3, 2, 0), Eigen::Vector3d(2, 3, 0)};
  CHECK(argil::intersect_triangles(base, far).kind == argil::TriangleIntersection::Kind::none);
  const Triangle above{Eigen::Vector3d(0, 0, 1e-100), Eigen::Vector3d(1, 0, 1e-100),
                       Eigen::Vector3d(0, 1, 1e-100)};
  CHECK(argil::intersect_triangles(base, above).kind == argil::TriangleIntersection::Kind::none);
  CHECK(argil::triangle_distance(base, above).distance == 1e-100);
}

TEST_CASE("two crossing planar patches intersect in the exact line, end to end") {
  // Plane a: z = 0 over [0, 100]^2 (bicubic with a Greville net); plane b:
  // x + 0.5 z = 40.3 (tilted), crossing a along x = 40.3.
  std::mt19937_64 rng(3);
  BSplineSurface a = argil::test::graph_surface(rng, 100.0, 0.0, 0.0, 3, 3);
  BSplineSurface b = a;
  for (Eigen::Index k = 0; k < b.control_points.rows(); ++k) {
    const Eigen::Vector3d p = a.control_points.row(k);
    // Rotate about the line x = 40.3, z = 0 by 63.4 degrees (tan = 2).
    const double c = 1 / std::sqrt(5.0), s = 2 / std::sqrt(5.0);
    const double x = p.x() - 40.3 - 7.0;
    b.control_points.row(k) << 40.3 + c * x - 0.0, p.y() + 3.0, s * x;
  }
  auto ha = hierarchy_for(a);
  auto hb = hierarchy_for(b);
  const double eps = 1e-6;
  const CollisionResult r = argil::collide(ha, hb, {.tolerance = eps, .refine = false});
  REQUIRE(r.curves.size() == 1);
  const auto& curve = r.curves.front();
  REQUIRE(curve.points.size() >= 2);
  for (std::size_t k = 0; k < curve.points.size(); ++k) {
    CHECK(std::abs(curve.points[k].x() - 40.3) <
          1e-12);  // planes are exact triangles: rounding only
    CHECK(std::abs(curve.points[k].z()) < 1e-12);
    CHECK(std::abs(curve.uv_a[k][0] - 0.403) < 1e-13);
  }
  // The line runs across a from v = 0 (where b starts, y = 3) to v = 1.
  const auto [lo, hi] = std::minmax(curve.points.front().y(), curve.points.back().y());
  CHECK(lo == Approx(3.0).margin(1e-12));
  CHECK(hi == Approx(100.0).margin(1e-12));
  CHECK(r.region_count == 1);
}

TEST_CASE("two exact cylinder patches intersect on both cylinders; refined points to 1e-12") {
  // y^2 + z^2 = 100 (axis x) against x^2 + z^2 = 64 (axis y), both z <= 0.
  const BSplineSurface a = argil::test::cylinder_x(10.0, -20.0, 20.0);
  const Eigen::Matrix3d swap_xy = (Eigen::Matrix3d() << 0, 1, 0, 1, 0, 0, 0, 0, 1).finished();
  BSplineSurface b = argil::test::moved(argil::test::cylinder_x(8.0, -20.0, 20.0), swap_xy,
                                        Eigen::Vector3d::Zero());
  // The quarter arc of b runs over x in [0, 8]; extend it to a half cylinder by mirroring is not
  // needed.
  auto ha = hierarchy_for(a);
  auto hb = hierarchy_for(b);
  for (double eps : {1e-2, 1e-4, 1e-6}) {
    const CollisionResult raw = argil::collide(ha, hb, {.tolerance = eps, .refine = false});
    const CollisionResult fine = argil::collide(ha, hb, {.tolerance = eps, .refine = true});
    INFO("eps " << eps);
    REQUIRE(raw.curves.size() == 1);
    REQUIRE(fine.curves.size() == 1);
    const auto on_a = [](const Eigen::Vector3d& p) {
      return std::abs(std::hypot(p.y(), p.z()) - 10.0);
    };
    const auto on_b = [](const Eigen::Vector3d& p) {
      return std::abs(std::hypot(p.x(), p.z()) - 8.0);
    };
    for (const auto& p : raw.curves.front().points) {
      CHECK(on_a(p) <= eps / 3 * (1 + 1e-9));  // triangles within eps/3 of each surface
      CHECK(on_b(p) <= eps / 3 * (1 + 1e-9));
    }
    for (const auto& p : fine.curves.front().points) {
      CHECK(on_a(p) <= 1e-12 * 20);  // refinement stops at 1e-14 of the model size (about 28 mm)
      CHECK(on_b(p) <= 1e-12 * 20);
    }
    CHECK(worst_parameter_gap(a, b, fine, true) <=
          1e-12 * 28);  // refined (u, v) evaluate to the point
  }
}

TEST_CASE(
    "random graph pairs: no crossing missed, reported points within eps of both surfaces, gaps "
    "beyond eps report nothing",
    "[slow]") {
  std::mt19937_64 rng(2025);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const double size = 100.0;
  const double eps = 5e-3 * size;  // moderate: 1000 pairs stay within seconds
  int crossing_pairs = 0, near_pairs = 0, apart_pairs = 0;
  double worst_miss = 0.0, worst_raw = 0.0, worst_refined = 0.0;
  for (int trial = 0; trial < 1000; ++trial) {
    const int kind = trial % 4;  // crossing, near-parallel within eps/3, gap of 3 eps, disjoint
    const BSplineSurface a = argil::test::graph_surface(rng, size, 2.0, 0.0, 5, 3);
    BSplineSurface b;
    if (kind == 0) {
      b = argil::test::graph_surface(rng, size, 2.0, 2.0 * (unit(rng) - 0.5), 5, 3);
    } else {
      b = a;
      const double gap = kind == 1 ? 0.2 * eps : (kind == 2 ? 3.0 * eps : 0.4 * size);
      b.control_points.col(2).array() += gap;
    }
    auto ha = hierarchy_for(a);
    auto hb = hierarchy_for(b);
    const bool refine = trial % 8 < 4;
    const CollisionResult r =
        argil::collide(ha, hb, {.tolerance = eps, .max_contacts = 1 << 20, .refine = refine});
    INFO("trial " << trial << " kind " << kind << " refine " << refine);
    if (!refine) {
      const double raw = worst_parameter_gap(a, b, r, true);
      worst_raw = std::max(worst_raw, raw);
      CHECK(raw <= eps / 3 * (1 + 1e-9));  // curve points: on both triangles, each within eps/3
      CHECK(worst_parameter_gap(a, b, r, false) <=
            5 * eps / 6 * (1 + 1e-9));  // near-touch midpoints
    } else {
      for (const auto& c : r.curves)
        for (std::size_t k = 0; k < c.points.size(); ++k) {
          const double gap = (argil::evaluate(a, c.uv_a[k][0], c.uv_a[k][1]) -
                              argil::evaluate(b, c.uv_b[k][0], c.uv_b[k][1]))
                                 .norm();
          // Refined (to 1e-12 of the size), or kept unrefined where Newton found no crossing (then
          // at most 2 eps/3 apart).
          if (gap <= 1e-10 * size) worst_refined = std::max(worst_refined, gap);
          CHECK((gap <= 1e-10 * size || gap <= 2 * eps / 3));
        }
    }
    // Every contact pairs surface points at most eps/3 + eps + eps/3 apart,
    // but penetration contacts: b's point lies behind a, depth from its foot.
    for (const auto& c : r.contacts) {
      const Eigen::Vector3d on_a = argil::evaluate(a, c.uv_a[0], c.uv_a[1]);
      const Eigen::Vector3d on_b = argil::evaluate(b, c.uv_b[0], c.uv_b[1]);
      if (c.depth > 0.0) {
        CHECK(std::abs((on_b - on_a).norm() - c.depth) <= 1e-9 * size);
        CHECK((on_b - on_a).dot(c.normal) < 0.0);
        CHECK(c.point == on_a);
        continue;
      }
      CHECK((on_a - on_b).norm() <= 5 * eps / 3 * (1 + 1e-9));
    }
    if (kind == 0) {
      const auto truth = brute_force_crossings(a, b, 30);
      if (!truth.empty()) ++crossing_pairs;
      for (const auto& p : truth) {
        const double miss = argil::test::distance_to_result(p, r);
        worst_miss = std::max(worst_miss, miss);
        // The leaf pair holding a crossing reports a segment or a contact
        // inside its leaves, whose diameter stays below 0.1 size at this eps;
        // a crossing is not always within eps of them where triangles graze
        // (see docs/collision.md, "Limits").
        CHECK(miss <= 0.1 * size);
      }
    } else if (kind == 1) {
      ++near_pairs;
      CHECK(r.region_count >= 1);  // surfaces within eps/3 everywhere: must touch
    } else if (kind == 3) {
      ++apart_pairs;
      CHECK(r.contacts.empty());
      CHECK(r.curves.empty());
    }
  }
  WARN("crossing pairs " << crossing_pairs << ", near " << near_pairs << ", disjoint "
                         << apart_pairs << "; worst miss " << worst_miss << ", worst raw curve gap "
                         << worst_raw << ", worst refined gap " << worst_refined << " (eps " << eps
                         << ")");
  CHECK(crossing_pairs > 150);
}

TEST_CASE(
    "after control points move, surface-surface results equal those on freshly built hierarchies") {
  std::mt19937_64 rng(8);
  std::normal_distribution<double> jitter(0.0, 1.0);
  BSplineSurface a = argil::test::asymmetric_surface(true);
  std::mt19937_64 rng_b(21);
  BSplineSurface b = argil::test::graph_surface(rng_b, 60.0, 3.0, 0.0, 3, 3);
  b.control_points.col(0).array() -= 5.0;
  b.control_points.col(1).array() -= 10.0;
  auto persistent_a = hierarchy_for(a);
  auto persistent_b = hierarchy_for(b);
  for (int move = 0; move < 40; ++move) {
    for (int k = 0; k < 3; ++k) {
      const auto row_a =
          static_cast<Eigen::Index>(rng() % static_cast<std::uint64_t>(a.control_points.rows()));
      a.control_points.row(row_a) += Eigen::RowVector3d(jitter(rng), jitter(rng), jitter(rng));
      const auto row_b =
          static_cast<Eigen::Index>(rng() % static_cast<std::uint64_t>(b.control_points.rows()));
      b.control_points(row_b, 2) += jitter(rng);
    }
    persistent_a.set_control_points(a.control_points, a.weights);
    persistent_b.set_control_points(b.control_points);
    auto fresh_a = hierarchy_for(a);
    auto fresh_b = hierarchy_for(b);
    const argil::CollisionRequest request{.tolerance = 1e-3, .refine = move % 2 == 0};
    const CollisionResult x = argil::collide(persistent_a, persistent_b, request);
    const CollisionResult y = argil::collide(fresh_a, fresh_b, request);
    INFO("move " << move);
    REQUIRE(x.curves.size() == y.curves.size());
    for (std::size_t c = 0; c < x.curves.size(); ++c) {
      REQUIRE(x.curves[c].points.size() == y.curves[c].points.size());
      for (std::size_t k = 0; k < x.curves[c].points.size(); ++k) {
        CHECK(x.curves[c].points[k] ==
              y.curves[c].points[k]);  // same nets, same arithmetic: bit-identical
        CHECK(x.curves[c].uv_b[k] == y.curves[c].uv_b[k]);
      }
    }
    REQUIRE(x.contacts.size() == y.contacts.size());
    for (std::size_t k = 0; k < x.contacts.size(); ++k)
      CHECK(x.contacts[k].point == y.contacts[k].point);
    CHECK(x.region_count == y.region_count);
    CHECK(x.counters.leaf_pairs == y.counters.leaf_pairs);
  }
}

TEST_CASE("a rigid motion of both surfaces moves the intersection curves with them", "[slow]") {
  const BSplineSurface a = argil::test::asymmetric_surface(true);
  std::mt19937_64 rng(4);
  BSplineSurface b = argil::test::graph_surface(rng, 60.0, 3.0, 0.5, 3, 3);
  b.control_points.col(0).array() -= 5.0;
  b.control_points.col(1).array() -= 10.0;
  const Eigen::Matrix3d R =
      Eigen::AngleAxisd(0.9, Eigen::Vector3d(1, -2, 3).normalized()).toRotationMatrix();
  const Eigen::Vector3d t(150.0, -40.0, 220.0);
  auto ha = hierarchy_for(a);
  auto hb = hierarchy_for(b);
  auto ma = hierarchy_for(argil::test::moved(a, R, t));
  auto mb = hierarchy_for(argil::test::moved(b, R, t));
  const argil::CollisionRequest request{.tolerance = 1e-4, .refine = true};
  const CollisionResult x = argil::collide(ha, hb, request);
  const CollisionResult y = argil::collide(ma, mb, request);
  REQUIRE(!x.curves.empty());
  CHECK(x.curves.size() == y.curves.size());
  CHECK(x.region_count == y.region_count);
  // Refined points lie on the exact curve in both frames: each moved point is
  // on the other result's polyline up to its chord tolerance (eps/3).
  CollisionResult x_moved = x;
  for (auto& c : x_moved.curves)
    for (auto& p : c.points) p = R * p + t;
  x_moved.contacts.clear();
  CollisionResult y_curves = y;
  y_curves.contacts.clear();
  for (const auto& c : y.curves)
    for (const auto& p : c.points)
      CHECK(argil::test::distance_to_result(p, x_moved) <= 1e-4 / 3 + 1e-9);
  for (const auto& c : x_moved.curves)
    for (const auto& p : c.points)
      CHECK(argil::test::distance_to_result(p, y_curves) <= 1e-4 / 3 + 1e-9);
}

TEST_CASE("conforming contact: leaf pairs stop growing with depth once the flatness meets eps") {
  // Two copies of a gently curved surface eps/2 apart: every leaf is in contact.
  std::mt19937_64 rng(12);
  const BSplineSurface a = argil::test::graph_surface(rng, 100.0, 1.0, 0.0, 3, 3);
  BSplineSurface b = a;
  const double eps = 1e-2;
  b.control_points.col(2).array() += 0.5 * eps;
  auto ha = hierarchy_for(a);
  auto hb = hierarchy_for(b);
  std::vector<long> leaf_pairs;
  for (int max_level = 0; max_level <= 14; ++max_level) {
    const CollisionResult r =
        argil::collide(ha, hb, {.tolerance = eps, .refine = false, .max_level = max_level});
    leaf_pairs.push_back(r.counters.leaf_pairs);
    CHECK(r.region_count == 1);  // one conforming region
  }
  // Size-based refinement would multiply leaf pairs by about 4 per level; here
  // they settle at the flat level and stay put however deep we allow.
  const std::size_t n = leaf_pairs.size();
  INFO("leaf pairs by max level: " << ::Catch::Detail::stringify(leaf_pairs));
  CHECK(leaf_pairs[n - 1] == leaf_pairs[n - 2]);
  CHECK(leaf_pairs[n - 1] == leaf_pairs[n - 5]);
  CHECK(leaf_pairs[n - 1] < 16 * leaf_pairs[4]);
  WARN("conforming contact leaf pairs by max level: " << ::Catch::Detail::stringify(leaf_pairs));
}

TEST_CASE("the first-crossing test agrees with the full query on crossing and on near pairs") {
  std::mt19937_64 rng(99);
  const double eps = 0.1;
  int crossing = 0, clear = 0;
  for (int trial = 0; trial < 200; ++trial) {
    const auto [a, b] = argil::test::random_offset_pair(rng, trial);
    auto ha = hierarchy_for(a);
    auto hb = hierarchy_for(b);
    const CollisionResult full = argil::collide(
        ha, hb,
        {.tolerance = eps, .max_contacts = 1 << 20, .refine = false, .compute_depth = false});
    bool full_crosses = !full.curves.empty();
    for (const auto& c : full.contacts) full_crosses = full_crosses || c.depth >= 0.0;
    const CollisionResult first = argil::collide(ha, hb,
                                                 {.tolerance = eps,
                                                  .max_contacts = 1,
                                                  .refine = false,
                                                  .compute_depth = false,
                                                  .first_crossing_only = true});
    INFO("trial " << trial);
    CHECK((!first.contacts.empty()) == full_crosses);
    CHECK(first.contacts.size() <= 1);
    CHECK(first.counters.leaf_pairs <= full.counters.leaf_pairs);
    for (const auto& c : first.contacts) CHECK(c.depth == 0.0);
    (full_crosses ? crossing : clear) += 1;
  }
  CHECK(crossing >= 40);
  CHECK(clear >= 40);
}

TEST_CASE("a contact query that stops at the first crossing agrees with the full one") {
  std::mt19937_64 rng(199);
  const double eps = 0.1;
  int crossing = 0, clear = 0;
  long full_leaves = 0, stopped_leaves = 0;  // over the crossing pairs
  for (int trial = 0; trial < 120; ++trial) {
    const auto [a, b] = argil::test::random_offset_pair(rng, trial);
    auto ha = hierarchy_for(a);
    auto hb = hierarchy_for(b);
    argil::CollisionRequest request{.tolerance = eps,
                                    .max_contacts = 1 << 20,
                                    .refine = false,
                                    .compute_depth = false,
                                    .curves = false};
    const CollisionResult full = argil::collide(ha, hb, request);
    request.stop_at_crossing = true;
    const CollisionResult stopped = argil::collide(ha, hb, request);
    REQUIRE(full.status.ok());
    REQUIRE(stopped.status.ok());
    const auto crosses = [](const CollisionResult& r) {
      return std::any_of(r.contacts.begin(), r.contacts.end(),
                         [](const argil::Contact& c) { return c.depth >= 0.0; });
    };
    INFO("trial " << trial);
    REQUIRE(crosses(stopped) == crosses(full));
    CHECK(stopped.counters.leaf_pairs <= full.counters.leaf_pairs);
    if (crosses(full)) {
      ++crossing;
      full_leaves += full.counters.leaf_pairs;
      stopped_leaves += stopped.counters.leaf_pairs;
      continue;
    }
    // Nothing crosses: the very same contacts.
    ++clear;
    CHECK(argil::test::same_contacts(stopped, full));
  }
  CAPTURE(crossing, clear, full_leaves, stopped_leaves);
  CHECK(crossing >= 30);
  CHECK(clear >= 30);
  // A crossing costs a part of the full descent.
  CHECK(4 * stopped_leaves < full_leaves);
}

TEST_CASE("a query with b placed by a pose finds what the query on b moved by that pose finds") {
  const BSplineSurface a = argil::test::asymmetric_surface(true);
  std::mt19937_64 rng(9);
  BSplineSurface b = argil::test::graph_surface(rng, 60.0, 3.0, 0.5, 3, 3);
  b.control_points.col(0).array() -= 5.0;
  b.control_points.col(1).array() -= 10.0;
  // b in its own frame B, far from a; X_AB puts it back across a, turned.
  const Eigen::Matrix3d R =
      Eigen::AngleAxisd(0.35, Eigen::Vector3d(2, 1, -1).normalized()).toRotationMatrix();
  const Eigen::Vector3d t(4.0, -3.0, 2.0);
  argil::Pose X_AB;
  X_AB.R = Eigen::Quaterniond(R);
  X_AB.p = t;
  const BSplineSurface moved_b = argil::test::moved(b, R, t);
  auto ha = hierarchy_for(a);
  auto hb = hierarchy_for(b);
  auto hm = hierarchy_for(moved_b);
  const bool refine = GENERATE(false, true);
  const double eps = 1e-3;
  const argil::CollisionRequest request{.tolerance = eps, .refine = refine, .compute_depth = true};
  const CollisionResult placed = argil::collide(ha, hb, X_AB, request);
  const CollisionResult moved = argil::collide(ha, hm, request);
  REQUIRE(placed.status.ok());
  REQUIRE(!moved.curves.empty());
  CHECK(placed.curves.size() == moved.curves.size());
  CHECK(placed.region_count == moved.region_count);
  // Both are within eps/3 of both surfaces at their parameters (to rounding
  // when refined), so each curve lies within 2 eps / 3 of the other's.
  const double on_surface = refine ? 1e-9 : eps / 3.0 + 1e-9;
  for (const auto& c : placed.curves) {
    for (std::size_t k = 0; k < c.points.size(); ++k) {
      CHECK((argil::evaluate(a, c.uv_a[k][0], c.uv_a[k][1]) - c.points[k]).norm() <= on_surface);
      CHECK((argil::evaluate(moved_b, c.uv_b[k][0], c.uv_b[k][1]) - c.points[k]).norm() <=
            on_surface);
    }
  }
  CollisionResult moved_curves = moved;
  moved_curves.contacts.clear();
  CollisionResult placed_curves = placed;
  placed_curves.contacts.clear();
  for (const auto& c : placed.curves)
    for (const auto& p : c.points)
      CHECK(argil::test::distance_to_result(p, moved_curves) <= 2.0 * eps / 3.0 + 1e-9);
  for (const auto& c : moved.curves)
    for (const auto& p : c.points)
      CHECK(argil::test::distance_to_result(p, placed_curves) <= 2.0 * eps / 3.0 + 1e-9);
  // The deepest penetration of each region agrees (it is refined on the exact surfaces).
  const auto deepest = [](const CollisionResult& r) {
    double d = -1.0;
    for (const auto& c : r.contacts) d = std::max(d, c.depth);
    return d;
  };
  CHECK(std::abs(deepest(placed) - deepest(moved)) <= 1e-9);
}
