// The curve value type, the parameter rectangle, and the direction-generic
// net map, on asymmetric inputs (degrees differ in u and v).
#include <catch2/catch.hpp>
#include <random>

#include "argil/core.hpp"
#include "support/random_surface.hpp"

namespace {

using argil::BSplineCurve;
using argil::Direction;

/// Degree 3, 7 rational control points in 3D, non-uniform knots with a double knot.
BSplineCurve rational_curve() {
  BSplineCurve c;
  c.degree = 3;
  c.knots.resize(11);
  c.knots << -1, -1, -1, -1, 0.2, 0.2, 1.5, 2, 2, 2, 2;
  c.points.resize(7, 3);
  c.points << 0, 0, 0, 1, 2, 0, 2, -1, 1, 4, 3, 0, 5, 0, -2, 7, 1, 1, 8, 4, 0;
  c.weights.resize(7);
  c.weights << 1, 0.5, 2, 1.5, 0.7, 3, 1;
  return c;
}

}  // namespace

TEST_CASE("knot insertion leaves a rational curve unchanged") {
  const BSplineCurve c = rational_curve();
  REQUIRE(argil::validate(c).ok());
  for (const double t : {-0.5, 0.2, 1.0}) {
    const int times = t == 0.2 ? 1 : 2;  // 0.2 is already double: one more reaches the degree
    const BSplineCurve refined = argil::insert_knot(c, t, times);
    REQUIRE(argil::validate(refined).ok());
    CHECK(refined.count() == c.count() + times);
    CHECK(refined.is_rational());
    for (int k = 0; k <= 60; ++k) {
      const double s = -1.0 + 3.0 * k / 60.0;
      // Rounding of a few quotients of O(10) values.
      CHECK((argil::evaluate(refined, s) - argil::evaluate(c, s)).norm() < 1e-12);
    }
  }
}

TEST_CASE("a curve's validation names the field, index and value of its first defect") {
  BSplineCurve c = rational_curve();
  c.weights[4] = 0.0;
  CHECK(argil::validate(c).code == argil::StatusCode::invalid_surface);
  CHECK_THAT(argil::validate(c).message, Catch::StartsWith("weights[4] is 0"));
  c = rational_curve();
  c.points.conservativeResize(6, 3);
  CHECK(argil::validate(c).code == argil::StatusCode::invalid_surface);
  CHECK_THAT(argil::validate(c).message, Catch::Contains("points has 6 rows, the knots need 7"));
}

TEST_CASE("hierarchy node rectangles are quarters of their parent, corners in bound order") {
  const argil::BSplineSurface s = argil::test::asymmetric_surface(true);
  argil::OperatorCache cache;
  auto built = argil::SurfaceHierarchy::build(s, cache);
  REQUIRE(built.ok());
  const argil::SurfaceHierarchy& h = built.value();  // nodes grow through const access
  const argil::ParamRect domain = argil::domain_of(s);
  for (const int root : h.roots()) {
    const argil::ParamRect parent = h.node(root).rect;
    CHECK(domain.contains(parent.lower()));
    CHECK(domain.contains(parent.upper()));
    double area = 0.0;
    for (int hu = 0; hu < 2; ++hu) {
      for (int hv = 0; hv < 2; ++hv) {
        const argil::HierarchyNode& child = h.node(h.child(root, hu, hv));
        CHECK(child.rect == parent.quarter(hu, hv));
        CHECK(parent.contains(child.rect.centre()));
        area += child.rect.width() * child.rect.height();
        for (int k = 0; k < 4; ++k) {
          const Eigen::Vector2d uv = child.rect.corner(k);
          // Bezier patch corners against B-spline evaluation: rounding only.
          CHECK(
              (argil::evaluate(s, uv[0], uv[1]) - child.bound.corners[static_cast<std::size_t>(k)])
                  .norm() < 1e-9);
        }
      }
    }
    CHECK(area == Approx(parent.width() * parent.height()).epsilon(1e-12));
  }
}

TEST_CASE("map_along in u then v equals the dense product M_u B M_v^T on a 3x2 patch") {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> value(-1.0, 1.0);
  const int p = 3, q = 2;
  argil::BezierPatch patch{p, q, Eigen::MatrixX4d((p + 1) * (q + 1), 4)};
  for (Eigen::Index k = 0; k < patch.points.size(); ++k) patch.points.data()[k] = value(rng);
  Eigen::MatrixXd m_u(p + 1, p + 1), m_v(q + 1, q + 1);
  for (Eigen::Index k = 0; k < m_u.size(); ++k) m_u.data()[k] = value(rng);
  for (Eigen::Index k = 0; k < m_v.size(); ++k) m_v.data()[k] = value(rng);
  const argil::BezierPatch mapped =
      argil::map_along(argil::map_along(patch, Direction::u, m_u), Direction::v, m_v);
  for (int c = 0; c < 4; ++c) {
    Eigen::MatrixXd net(p + 1, q + 1);
    for (int a = 0; a <= p; ++a)
      for (int b = 0; b <= q; ++b) net(a, b) = patch.points(a * (q + 1) + b, c);
    const Eigen::MatrixXd expected = m_u * net * m_v.transpose();
    for (int a = 0; a <= p; ++a)
      for (int b = 0; b <= q; ++b)
        CHECK(mapped.points(a * (q + 1) + b, c) == Approx(expected(a, b)).margin(1e-14));
  }
}
