// Intersection curves come out whole: one curve per branch across leaf
// T-junctions and leaf corners, and no short duplicate pieces beside the
// curve, at every tolerance, refined or not.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <optional>
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

/// Every curve longer than eps, each point on both surfaces within `within`.
void check_curves(const BSplineSurface& a, const BSplineSurface& b, const CollisionResult& r,
                  double eps, double within) {
  for (const IntersectionCurve& c : r.curves) {
    INFO(c.points.size() << " points");
    CHECK(c.length() > eps);
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

/// A bilinear patch through four corners, in pole order (0,0), (1,0), (0,1), (1,1).
BSplineSurface bilinear(const Eigen::Matrix<double, 4, 3>& corners) {
  BSplineSurface b;
  b.degree = {1, 1};
  b.knots[0].resize(4);
  b.knots[0] << 0, 0, 1, 1;
  b.knots[1] = b.knots[0];
  b.control_points = corners;
  return b;
}

/// The plane z = h over [-0.2, 1.2]^2.
BSplineSurface flat_at(double h) {
  Eigen::Matrix<double, 4, 3> corners;
  corners << -0.2, -0.2, h, 1.2, -0.2, h, -0.2, 1.2, h, 1.2, 1.2, h;
  return bilinear(corners);
}

/// The oracle: where a graph surface a crosses height h, found by brute force.
/// Along every row and column of an n x n parameter grid, a sign change of
/// z - h is bisected to rounding, and the point on a is kept.
std::vector<Eigen::Vector3d> height_crossings(const BSplineSurface& a, double h, int n) {
  const auto at = [&](const Eigen::Vector2d& uv) { return argil::evaluate(a, uv[0], uv[1]); };
  std::vector<Eigen::Vector3d> out;
  for (int line = 0; line <= n; ++line) {
    for (int axis = 0; axis < 2; ++axis) {
      for (int k = 0; k < n; ++k) {
        const double fixed = static_cast<double>(line) / n;
        const auto uv = [&](double t) {
          return axis == 0 ? Eigen::Vector2d(t, fixed) : Eigen::Vector2d(fixed, t);
        };
        double t0 = static_cast<double>(k) / n, t1 = static_cast<double>(k + 1) / n;
        const double f0 = at(uv(t0)).z() - h, f1 = at(uv(t1)).z() - h;
        if ((f0 < 0) == (f1 < 0)) continue;
        for (int it = 0; it < 60; ++it) {
          const double tm = 0.5 * (t0 + t1);
          if ((at(uv(tm)).z() - h < 0) == (f0 < 0)) {
            t0 = tm;
          } else {
            t1 = tm;
          }
        }
        out.push_back(at(uv(0.5 * (t0 + t1))));
      }
    }
  }
  return out;
}

/// Refined curves: no intersection point of `truth` farther than eps from
/// them. (Unrefined curve points are only within eps/3 of both surfaces, which
/// near tangency lies up to eps / (3 sin angle) beside the intersection.)
void check_covers(const std::vector<Eigen::Vector3d>& truth, const CollisionResult& r, double eps,
                  bool refined) {
  if (!refined) return;
  double worst = 0.0;
  for (const Eigen::Vector3d& p : truth)
    worst = std::max(worst, argil::test::distance_to_curves(p, r));
  CHECK(worst <= eps);
}

}  // namespace

TEST_CASE("a closed loop inside one element comes out as one closed curve, near tangency too") {
  // One bicubic Bezier element: a bump of height 0.444 at the centre (the
  // four inner poles at 0.79), cut by planes well below its top and 1e-3 below it.
  const BSplineSurface a =
      unit_net(4, [](double x, double y) { return 16.0 * x * (1 - x) * y * (1 - y); });
  const double top = argil::evaluate(a, 0.5, 0.5).z();
  const auto ha = hierarchy_for(a);
  const double depth = GENERATE(0.15, 1e-3);
  const BSplineSurface b = flat_at(top - depth);
  const auto hb = hierarchy_for(b);
  const std::vector<Eigen::Vector3d> truth = height_crossings(a, top - depth, 400);
  REQUIRE(truth.size() > 8);
  const double eps = GENERATE(1e-3, 1e-4, 1e-6);
  const bool refine = GENERATE(false, true);
  INFO("depth " << depth << ", eps " << eps << (refine ? " refined" : ""));
  const CollisionResult r = argil::collide(ha, hb, {.tolerance = eps, .refine = refine});
  REQUIRE(r.curves.size() == 1);
  CHECK(r.curves[0].closed());
  check_curves(a, b, r, eps, refine ? 1e-12 : eps / 3.0);
  check_covers(truth, r, eps, refine);
}

/// The trough (poles at (y - 0.5)^2) and a plane 1e-4 above its floor: two
/// lines about 0.01 either side of y = 0.5, crossing the plane at about 0.02 rad.
struct NearTangentPair {
  BSplineSurface a = unit_net(8, [](double, double y) { return (y - 0.5) * (y - 0.5); });
  double h = argil::evaluate(a, 0.5, 0.5).z() + 1e-4;
  BSplineSurface b = flat_at(h);
};

TEST_CASE("a near-tangential crossing gives its two branches whole") {
  const NearTangentPair pair;
  const auto ha = hierarchy_for(pair.a);
  const auto hb = hierarchy_for(pair.b);
  const std::vector<Eigen::Vector3d> truth = height_crossings(pair.a, pair.h, 400);
  const double eps = GENERATE(1e-5, 1e-6, 1e-8);
  const bool refine = GENERATE(false, true);
  INFO("eps " << eps << (refine ? " refined" : ""));
  const CollisionResult r = argil::collide(ha, hb, {.tolerance = eps, .refine = refine});
  check_curves(pair.a, pair.b, r, eps, refine ? 1e-12 : eps / 3.0);
  check_covers(truth, r, eps, refine);
  if (!refine) return;  // unrefined branches break at leaf T-junctions (docs/collision.md)
  REQUIRE(r.curves.size() == 2);
  for (const IntersectionCurve& c : r.curves) {
    // Each branch runs across the net in u, on its own side of y = 0.5.
    const auto [lo, hi] = std::minmax(c.uv_a.front()[0], c.uv_a.back()[0]);
    CHECK(lo <= 1e-9);
    CHECK(hi >= 1.0 - 1e-9);
    const bool upper = c.points.front().y() > 0.5;
    for (const Eigen::Vector3d& p : c.points) CHECK((p.y() > 0.5) == upper);
  }
}

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
  Eigen::Matrix<double, 4, 3> corners;
  if (diagonal) {
    corners << -0.2, -0.2, -0.3, -0.2, -0.2, 0.3, 1.2, 1.2, -0.3, 1.2, 1.2, 0.3;
  } else {
    corners << 0.5, -0.2, -0.3, 0.5, -0.2, 0.3, 0.5, 1.2, -0.3, 0.5, 1.2, 0.3;
  }
  const BSplineSurface b = bilinear(corners);
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
  CHECK(c.length() >= (diagonal ? std::sqrt(2.0) : 1.0) - 1e-12);
}

TEST_CASE("a crossing along a knot line of both surfaces comes out refined as one curve") {
  // b is the wavy net with its poles raised by 0.05 (i - shift) and knots
  // inserted in v: b - a = 0.05 (sum of N_i(u) i - shift), zero exactly on the
  // knot line u = (shift - 1)/13 (the three cubic basis functions there are
  // 1/6, 2/3, 1/6), where b crosses a at about 33 degrees. The curve runs
  // along both surfaces' leaf edges, where leaves of different sizes meet:
  // their segments repeat one another and pass through the cracks between them.
  const BSplineSurface a = argil::test::wavy_pair().first;
  const int shift = GENERATE(4, 6, 10);
  BSplineSurface b = a;
  for (int i = 0; i < 16; ++i)
    for (int j = 0; j < 16; ++j) b.control_points(b.pole_index(i, j), 2) += 0.05 * (i - shift);
  argil::Result<BSplineSurface> reknotted = argil::insert_knot(b, argil::Direction::v, 0.6789, 2);
  REQUIRE(reknotted.ok());
  b = std::move(reknotted).value();
  const auto ha = hierarchy_for(a);
  const auto hb = hierarchy_for(b);
  const double eps = GENERATE(1e-3, 1e-4, 1e-5);
  INFO("knot line u = " << shift - 1 << "/13, eps " << eps);
  const CollisionResult r = argil::collide(ha, hb, {.tolerance = eps, .refine = true});
  REQUIRE(r.curves.size() == 1);
  check_curves(a, b, r, eps, 1e-12);
  const IntersectionCurve& c = r.curves.front();
  check_runs_across_v(c, 1e-9);
  // On the knot line, and one way along it (no stretch out and back).
  const double dv = c.uv_a.back()[1] - c.uv_a.front()[1];
  for (std::size_t k = 0; k < c.points.size(); ++k) {
    CHECK(std::abs(c.uv_a[k][0] - (shift - 1) / 13.0) <= 1e-9);
    if (k > 0) CHECK((c.uv_a[k][1] - c.uv_a[k - 1][1]) * dv > 0.0);
  }
}

TEST_CASE("curve tidying drops short pieces, opens out-and-back loops, joins and closes") {
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
  SECTION("pieces no longer than eps are dropped, on a curve or alone; longer ones stay") {
    // Alone, a piece no longer than eps is where the surfaces touch (the
    // query reports its leaf pair's contact instead).
    const auto out = argil::detail::tidy_curves(
        {curve({{0, 0, 0}, {1, 0, 0}, {2, 0, 0}}), curve({{0.5, 0, 0}, {0.5, 0, 0}}),
         curve({{5, 5, 5}, {5, 5, 5}}), curve({{7, 0, 0}, {7 + 0.99 * eps, 0, 0}}),
         curve({{9, 0, 0}, {9 + 1.01 * eps, 0, 0}})},
        eps);
    REQUIRE(out.size() == 2);
    CHECK(out[0].points.size() == 3);
    CHECK(out[1].points.front() == Eigen::Vector3d(9, 0, 0));
  }
  SECTION("a closed curve out to one point and back is the open curve out") {
    const auto out = argil::detail::tidy_curves({curve({{0, 0, 0}, {0.01, 0, 0}, {0, 0, 0}})}, eps);
    REQUIRE(out.size() == 1);
    CHECK_FALSE(out[0].closed());
    REQUIRE(out[0].points.size() == 2);
    CHECK((out[0].points.back() - out[0].points.front()).norm() == 0.01);
  }
  SECTION("a piece lying on another curve is dropped, but not before the joins") {
    // b (longer than eps) lies on a: dropped, once nothing is left to join.
    // d (zero length) and e lie within eps/2 of c: dropped, and c, which
    // covers them, stays.
    const auto out = argil::detail::tidy_curves(
        {curve({{0, 0, 0}, {1, 0, 0}}), curve({{0.2, 0, 0}, {0.2011, 0, 0}}),
         curve({{5, 0, 0}, {5, 0.0016, 0}}), curve({{5, 0.0004, 0}, {5, 0.0004, 0}}),
         curve({{5, 0.00045, 0}, {5, 0.0012, 0}})},
        eps);
    REQUIRE(out.size() == 2);
    CHECK(out[0].points.front() == Eigen::Vector3d(0, 0, 0));
    CHECK(out[1].points.front() == Eigen::Vector3d(5, 0, 0));
    CHECK(out[1].points.back() == Eigen::Vector3d(5, 0.0016, 0));
  }
  SECTION("of two curves side by side, the shorter goes when what leans on it stays near") {
    // b runs within eps/2 of a (two pieces of one curve along a tangential
    // edge); c, longer than eps, lies within eps/2 of b only. b is dropped
    // when c stays within 3/4 eps of a, and kept when c does not.
    const auto side_by_side = [&](double c_offset) {
      return argil::detail::tidy_curves(
          {curve({{0, 0, 0}, {1, 0, 0}}), curve({{0.1, 0.0004, 0}, {0.9, 0.0004, 0}}),
           curve({{0.5, c_offset, 0}, {0.5015, c_offset, 0}})},
          eps);
    };
    const auto near = side_by_side(0.0007);
    REQUIRE(near.size() == 1);
    CHECK(near[0].points.front() == Eigen::Vector3d(0, 0, 0));
    CHECK(side_by_side(0.0008).size() == 2);
    // A piece no longer than eps, dropped before the joins, leans on b too.
    CHECK(argil::detail::tidy_curves(
              {curve({{0, 0, 0}, {1, 0, 0}}), curve({{0.1, 0.0004, 0}, {0.9, 0.0004, 0}}),
               curve({{0.5, 0.0008, 0}, {0.5005, 0.0008, 0}})},
              eps)
              .size() == 2);
  }
  SECTION("a branch crossing another at a small angle stays whole") {
    // The second branch's middle piece runs within eps/2 of the first: it
    // joins its neighbours first, and the whole branch is not covered.
    const auto out = argil::detail::tidy_curves(
        {curve({{0, 0, 0}, {1, 0, 0}}), curve({{0.1, -0.01, 0}, {0.3, -0.0003, 0}}),
         curve({{0.3, -0.0003, 0}, {0.35, 0.0003, 0}}), curve({{0.35, 0.0003, 0}, {0.6, 0.01, 0}})},
        eps);
    REQUIRE(out.size() == 2);
    CHECK(out[1].points.size() == 4);
    // Partly within eps/2 of the first: stays.
    CHECK(argil::detail::tidy_curves(
              {curve({{0, 0, 0}, {1, 0, 0}}), curve({{0.2, -0.0004, 0}, {0.22, 0.0012, 0}})}, eps)
              .size() == 2);
  }
  SECTION("a curve that starts out and back over itself starts at its turn") {
    // Its first chord runs back over its next two (a larger leaf's segment
    // beside its smaller neighbours'): left out, so the piece before it joins.
    const auto out = argil::detail::tidy_curves(
        {curve({{0.02, 0, 0}, {0, 0, 0}, {0.01, 0, 0}, {0.02, 0, 0}, {1, 0, 0}}),
         curve({{-1, 0, 0}, {0, 0, 0}})},
        eps);
    REQUIRE(out.size() == 1);
    const std::vector<Eigen::Vector3d>& p = out[0].points;
    CHECK(p.size() == 5);
    for (std::size_t k = 0; k + 1 < p.size(); ++k)  // one way, either way
      CHECK((p[k + 1].x() - p[k].x()) * (p.back().x() - p.front().x()) > 0.0);
    CHECK(std::abs(p.back().x() - p.front().x()) == 2.0);
    // A turn back that does not retrace the curve stays.
    CHECK(argil::detail::tidy_curves({curve({{0.02, 0.01, 0}, {0, 0, 0}, {1, 0, 0}})}, eps)
              .front()
              .points.size() == 3);
  }
  SECTION("pieces that overlap, each end lying on the other, are joined without the overlap") {
    const auto out = argil::detail::tidy_curves({curve({{0, 0, 0}, {0.5, 0, 0}, {0.6, 0, 0}}),
                                                 curve({{0.55, 0, 0}, {0.65, 0, 0}, {1, 0, 0}})},
                                                eps);
    REQUIRE(out.size() == 1);
    const std::vector<Eigen::Vector3d>& p = out[0].points;
    CHECK(p.size() == 5);
    for (std::size_t k = 0; k + 1 < p.size(); ++k)
      CHECK((p[k + 1].x() - p[k].x()) * (p.back().x() - p.front().x()) > 0.0);
    // The chord past the first's end passes it farther than eps/2: not one curve.
    CHECK(argil::detail::tidy_curves({curve({{0, 0, 0}, {0.6, 0, 0}}),
                                      curve({{0.55, 0, 0}, {0.7, 0.01, 0}, {1, 0.01, 0}})},
                                     eps)
              .size() == 2);
  }
  SECTION("pieces whose ends meet within eps and run on are joined, in any orientation") {
    const auto out = argil::detail::tidy_curves(
        {curve({{0, 0, 0}, {1, 0, 0}}), curve({{2, 0, 0}, {1.0005, 0, 0}}),
         curve({{2.0002, 0, 0}, {3, 0, 0}})},
        eps);
    REQUIRE(out.size() == 1);
    CHECK(out[0].points.size() == 6);
    CHECK(out[0].length() <= 3.0 + 1e-12);
    CHECK(std::abs(out[0].points.back().x() - out[0].points.front().x()) == 3.0);
  }
  SECTION("ends within eps that turn back are not joined") {
    const auto out = argil::detail::tidy_curves(
        {curve({{0, 0, 0}, {1, 0, 0}}), curve({{1.0005, 0, 0}, {0, 1, 0}})}, eps);
    CHECK(out.size() == 2);
  }
  SECTION("pieces a few eps apart or overlapping are joined through the bridge") {
    // A bridge that returns the midpoint of the gap, as one straight branch would.
    int asked = 0;
    const argil::detail::GapBridge straight = [&asked](const argil::detail::CurvePoint& from,
                                                       const argil::detail::CurvePoint& to) {
      ++asked;
      IntersectionCurve mid;
      mid.points.push_back(0.5 * (from.point + to.point));
      mid.uv_a.push_back(0.5 * (from.uv_a + to.uv_a));
      mid.uv_b.push_back(0.5 * (from.uv_b + to.uv_b));
      return std::optional<IntersectionCurve>(mid);
    };
    const argil::detail::GapBridge none = [&asked](const argil::detail::CurvePoint&,
                                                   const argil::detail::CurvePoint&) {
      ++asked;
      return std::optional<IntersectionCurve>();
    };
    const std::vector<IntersectionCurve> gap{curve({{0, 0, 0}, {1, 0, 0}}),
                                             curve({{1.003, 0, 0}, {2, 0, 0}})};
    CHECK(argil::detail::tidy_curves(gap, eps).size() == 2);
    CHECK(argil::detail::tidy_curves(gap, eps, none).size() == 2);
    const auto bridged = argil::detail::tidy_curves(gap, eps, straight);
    REQUIRE(bridged.size() == 1);
    CHECK(bridged[0].points.size() == 5);
    CHECK(bridged[0].points[2].isApprox(Eigen::Vector3d(1.0015, 0, 0)));
    // Overlapping by 3 eps, each past the other's end: the overlapped points
    // of one go, and the curve runs on without turning back.
    const auto overlapped =
        argil::detail::tidy_curves({curve({{0, 0, 0}, {0.5, 0, 0}, {1, 0, 0}}),
                                    curve({{0.997, 0, 0}, {0.9985, 0, 0}, {1.5, 0, 0}, {2, 0, 0}})},
                                   eps, straight);
    REQUIRE(overlapped.size() == 1);
    const std::vector<Eigen::Vector3d>& p = overlapped[0].points;
    for (std::size_t k = 0; k + 1 < p.size(); ++k) CHECK(p[k + 1].x() > p[k].x());
    CHECK(p.back().x() == 2.0);
    // Side by side (the gap across the curves) or farther than the reach:
    // the bridge is not even asked.
    asked = 0;
    CHECK(argil::detail::tidy_curves(
              {curve({{0, 0, 0}, {1, 0, 0}}), curve({{1, 0.003, 0}, {2, 0.003, 0}})}, eps, straight)
              .size() == 2);
    CHECK(argil::detail::tidy_curves(
              {curve({{0, 0, 0}, {1, 0, 0}}),
               curve({{1.0 + 1.01 * argil::detail::kBridgeReach * eps, 0, 0}, {2, 0, 0}})},
              eps, straight)
              .size() == 2);
    CHECK(asked == 0);
    // Farther than that, as far as the ends' leaves reach.
    const std::vector<IntersectionCurve> far{curve({{0, 0, 0}, {1, 0, 0}}),
                                             curve({{1.05, 0, 0}, {2, 0, 0}})};
    CHECK(argil::detail::tidy_curves(far, eps, straight).size() == 2);
    CHECK(argil::detail::tidy_curves(far, eps, straight, {{0.0, 0.01}, {0.01, 0.0}}).size() == 2);
    CHECK(argil::detail::tidy_curves(far, eps, straight, {{0.0, 0.1}, {0.1, 0.0}}).size() == 1);
  }
  SECTION("a loop whose ends lie a few eps apart is closed through the bridge") {
    const argil::detail::GapBridge straight = [](const argil::detail::CurvePoint& from,
                                                 const argil::detail::CurvePoint& to) {
      IntersectionCurve mid;
      mid.points.push_back(0.5 * (from.point + to.point));
      mid.uv_a.push_back(0.5 * (from.uv_a + to.uv_a));
      mid.uv_b.push_back(0.5 * (from.uv_b + to.uv_b));
      return std::optional<IntersectionCurve>(mid);
    };
    const auto out = argil::detail::tidy_curves(
        {curve({{0.5, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 0}, {0.497, 0, 0}})}, eps,
        straight);
    REQUIRE(out.size() == 1);
    CHECK(out[0].closed());
    CHECK(out[0].points.size() == 8);
    CHECK(out[0].points[6].isApprox(Eigen::Vector3d(0.4985, 0, 0)));
    // However far its ends' leaves reach: the loop is longer than twice its gap.
    const auto far_reaching = argil::detail::tidy_curves(
        {curve({{0.5, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 0}, {0.497, 0, 0}})}, eps,
        straight, {{10.0, 10.0}});
    REQUIRE(far_reaching.size() == 1);
    CHECK(far_reaching[0].closed());
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
