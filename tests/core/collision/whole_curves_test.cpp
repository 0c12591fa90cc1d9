// Intersection curves come out whole: one curve per branch across leaf
// T-junctions and leaf corners, and no short duplicate pieces beside the
// curve, at every tolerance, refined or not.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <string>

#include "argil/core.hpp"
#include "argil/core/collision/detail/curve_tidy.hpp"
#include "core/collision/surface_pairs.hpp"

using argil::BSplineSurface;
using argil::CollisionResult;
using argil::IntersectionCurve;
using argil::test::hierarchy_for;
using argil::test::unit_net;

namespace {

double length_of(const IntersectionCurve& c) {
  double l = 0.0;
  for (std::size_t k = 0; k + 1 < c.points.size(); ++k) l += (c.points[k + 1] - c.points[k]).norm();
  return l;
}

/// Every curve longer than eps, each point on both surfaces within `within`.
void check_curves(const BSplineSurface& a, const BSplineSurface& b, const CollisionResult& r,
                  double eps, double within) {
  for (const IntersectionCurve& c : r.curves) {
    INFO(c.points.size() << " points");
    CHECK(length_of(c) > eps);
    for (std::size_t k = 0; k < c.points.size(); ++k) {
      CHECK((argil::evaluate(a, c.uv_a[k][0], c.uv_a[k][1]) - c.points[k]).norm() <= within);
      CHECK((argil::evaluate(b, c.uv_b[k][0], c.uv_b[k][1]) - c.points[k]).norm() <= within);
    }
  }
}

/// The curve's ends lie on a's boundaries v = 0 and v = 1 (within `slack`).
void check_runs_across_v(const IntersectionCurve& c, double slack) {
  const auto [lo, hi] = std::minmax(c.uv_a.front()[1], c.uv_a.back()[1]);
  CHECK(lo <= slack);
  CHECK(hi >= 1.0 - slack);
}

}  // namespace

TEST_CASE("the wavy pair gives one whole curve at every tolerance, refined or not") {
  const auto [a, b] = argil::test::wavy_pair();
  const auto ha = hierarchy_for(a);
  const auto hb = hierarchy_for(b);
  const double eps = GENERATE(1e-3, 1e-4, 1e-5, 1e-6);
  const bool refine = GENERATE(false, true);
  INFO("eps " << eps << (refine ? " refined" : ""));
  const CollisionResult r = argil::collide(ha, hb, {.tolerance = eps, .refine = refine});
  REQUIRE(r.curves.size() == 1);
  check_curves(a, b, r, eps, refine ? 1e-12 : eps / 3.0);
  check_runs_across_v(r.curves.front(), 1e-12);
}

TEST_CASE("a curve through leaf corners and along leaf edges comes out as one curve") {
  // A flat uniform net: its leaves are its elements, and their corner
  // triangles share the diagonal (c00, c11). A vertical plane along the
  // diagonal x = y meets every leaf corner on it and runs along the triangles'
  // shared edge (both triangles of a leaf give the same segment); one along
  // x = 0.5 runs along the leaf edges of a 7-span net (knot 0.5 at x = 0.5 by symmetry).
  const BSplineSurface a = unit_net(10, [](double, double) { return 0.0; });
  const auto ha = hierarchy_for(a);
  const bool diagonal = GENERATE(true, false);
  // The cutting plane as a 2x2 bilinear patch, standing up through z = 0.
  BSplineSurface b;
  b.degree = {1, 1};
  b.knots[0].resize(4);
  b.knots[0] << 0, 0, 1, 1;
  b.knots[1] = b.knots[0];
  b.control_points.resize(4, 3);
  if (diagonal) {
    b.control_points << -0.2, -0.2, -0.3, -0.2, -0.2, 0.3, 1.2, 1.2, -0.3, 1.2, 1.2, 0.3;
  } else {
    b.control_points << 0.5, -0.2, -0.3, 0.5, -0.2, 0.3, 0.5, 1.2, -0.3, 0.5, 1.2, 0.3;
  }
  const auto hb = hierarchy_for(b);
  const double eps = GENERATE(1e-3, 1e-6);
  const bool refine = GENERATE(false, true);
  INFO((diagonal ? "diagonal" : "x = 0.5") << ", eps " << eps << (refine ? " refined" : ""));
  const CollisionResult r = argil::collide(ha, hb, {.tolerance = eps, .refine = refine});
  REQUIRE(r.curves.size() == 1);
  check_curves(a, b, r, eps, refine ? 1e-12 : eps / 3.0);
  const IntersectionCurve& c = r.curves.front();
  // The exact line, end to end across the net.
  for (const Eigen::Vector3d& p : c.points) {
    CHECK(std::abs(p.z()) <= 1e-12);
    CHECK(std::abs(diagonal ? p.x() - p.y() : p.x() - 0.5) <= 1e-12);
  }
  CHECK(length_of(c) >= (diagonal ? std::sqrt(2.0) : 1.0) - 1e-12);
}

TEST_CASE("curve tidying drops covered short pieces, keeps isolated ones, joins and closes") {
  const double eps = 1e-3;
  const auto curve = [](std::vector<Eigen::Vector3d> points) {
    IntersectionCurve c;
    for (std::size_t k = 0; k < points.size(); ++k) {
      c.points.push_back(points[k]);
      c.uv_a.emplace_back(static_cast<double>(k), 0.0);
      c.uv_b.emplace_back(0.0, static_cast<double>(k));
    }
    return c;
  };
  SECTION("a zero-length piece on a curve is dropped; an isolated one is kept") {
    const auto out = argil::detail::tidy_curves(
        {curve({{0, 0, 0}, {1, 0, 0}, {2, 0, 0}}), curve({{0.5, 0, 0}, {0.5, 0, 0}}),
         curve({{5, 5, 5}, {5, 5, 5}})},
        eps);
    REQUIRE(out.size() == 2);
    CHECK(out[0].points.size() == 3);
    CHECK(out[1].points.front() == Eigen::Vector3d(5, 5, 5));
  }
  SECTION("pieces covered along their whole length are dropped, whatever their length") {
    // b lies on a: dropped. d (zero length) and e lie within eps/2 of c:
    // dropped, and c, which covers them, stays. f's ends lie on g but its
    // chord passes 0.01 from g's peak: both stay.
    const auto out = argil::detail::tidy_curves(
        {curve({{0, 0, 0}, {1, 0, 0}}), curve({{0.2, 0, 0}, {0.9, 0, 0}}),
         curve({{5, 0, 0}, {5, 0.0008, 0}}), curve({{5, 0.0004, 0}, {5, 0.0004, 0}}),
         curve({{5, 0.00045, 0}, {5, 0.0012, 0}}), curve({{8, 0, 0}, {9, 0, 0}}),
         curve({{8, 0, 0}, {8.5, 0.01, 0}, {9, 0, 0}})},
        eps);
    REQUIRE(out.size() == 4);
    CHECK(out[0].points.front() == Eigen::Vector3d(0, 0, 0));
    CHECK(out[1].points.front() == Eigen::Vector3d(5, 0, 0));
    CHECK(out[1].points.back() == Eigen::Vector3d(5, 0.0008, 0));
    CHECK(out[2].points.size() == 2);
    CHECK(out[3].points.size() == 3);
  }
  SECTION("pieces whose ends meet within eps and run on are joined, in any orientation") {
    const auto out = argil::detail::tidy_curves(
        {curve({{0, 0, 0}, {1, 0, 0}}), curve({{2, 0, 0}, {1.0005, 0, 0}}),
         curve({{2.0002, 0, 0}, {3, 0, 0}})},
        eps);
    REQUIRE(out.size() == 1);
    CHECK(out[0].points.size() == 6);
    CHECK(length_of(out[0]) <= 3.0 + 1e-12);
    CHECK(std::abs(out[0].points.back().x() - out[0].points.front().x()) == 3.0);
  }
  SECTION("ends within eps that turn back are not joined") {
    const auto out = argil::detail::tidy_curves(
        {curve({{0, 0, 0}, {1, 0, 0}}), curve({{1.0005, 0, 0}, {0, 1, 0}})}, eps);
    CHECK(out.size() == 2);
  }
  SECTION("an open loop whose ends meet is closed; its first point repeated") {
    const auto out = argil::detail::tidy_curves(
        {curve({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0.0005, 0}})}, eps);
    REQUIRE(out.size() == 1);
    CHECK(out[0].points.size() == 6);
    CHECK(out[0].points.back() == out[0].points.front());
    CHECK(out[0].uv_a.back() == out[0].uv_a.front());
  }
}
