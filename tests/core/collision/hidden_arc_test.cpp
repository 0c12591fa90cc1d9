// Short arcs that bulge across a leaf edge by less than the leaves' flatness:
// the coarse leaf triangles of a refined query pass over them (or cross where
// the surfaces do not), and the curve must still come out, whole and on both
// surfaces. Oracle: the analytic curve.
#include <Eigen/Dense>
#include <catch2/catch.hpp>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "argil/core.hpp"
#include "core/collision/surface_pairs.hpp"
#include "support/polyline_distance.hpp"

using argil::BSplineSurface;
using argil::CollisionResult;

namespace {

/// The plane z = 0 over [-20, 30]^2.
BSplineSurface floor_plane() {
  BSplineSurface s;
  s.degree = {1, 1};
  s.knots = {Eigen::Vector4d(0, 0, 1, 1), Eigen::Vector4d(0, 0, 1, 1)};
  s.control_points.resize(4, 3);
  s.control_points << -20, -20, 0, -20, 30, 0, 30, -20, 0, 30, 30, 0;
  return s;
}

/// A sheet z = slope x + bend (y - y_c)^2 - dip over x in [0, 10], y in
/// [-3, 7], exact in degree 1 x 2. It crosses the floor in the arc
/// x = (dip - bend (y - y_c)^2) / slope, which bulges in from the edge x = 0
/// by dip / slope; at 27 degrees to the floor, a transversal crossing.
struct Cap {
  double bend = 0.0075, dip = 0.005, y_c = 0.0;
  static constexpr double kSlope = 0.5;

  BSplineSurface sheet() const {
    BSplineSurface s;
    s.degree = {1, 2};
    s.knots = {Eigen::Vector4d(0, 0, 1, 1), (Eigen::VectorXd(6) << 0, 0, 0, 1, 1, 1).finished()};
    s.control_points.resize(6, 3);
    const double y0 = -3.0, y1 = 7.0;
    // The Bezier poles of (y - y_c)^2 on [y0, y1].
    const double square[3] = {(y0 - y_c) * (y0 - y_c), (y0 - y_c) * (y1 - y_c),
                              (y1 - y_c) * (y1 - y_c)};
    const double ys[3] = {y0, 0.5 * (y0 + y1), y1};
    for (int i = 0; i < 2; ++i)
      for (int j = 0; j < 3; ++j) {
        const double x = 10.0 * i;
        s.control_points.row(i * 3 + j) << x, ys[j], kSlope * x + bend * square[j] - dip;
      }
    return s;
  }

  double half_width() const { return std::sqrt(dip / bend); }
  Eigen::Vector3d at(double y) const {
    return {(dip - bend * (y - y_c) * (y - y_c)) / kSlope, y, 0.0};
  }
  /// Arc length by the midpoint rule on 20000 pieces (error ~1e-12 mm here).
  double length() const {
    double sum = 0.0;
    const int n = 20000;
    const double h = 2.0 * half_width() / n;
    for (int k = 0; k < n; ++k) {
      const double y = y_c - half_width() + (k + 0.5) * h;
      const double slope = 2.0 * bend * (y - y_c) / kSlope;
      sum += h * std::sqrt(1.0 + slope * slope);
    }
    return sum;
  }
};

/// A sheet z = x / 2 + bend ((y - y1)(y - y2))^2 - dip over x in [0, 10],
/// y in [-3, 7] (degree 1 x 4, its Bezier poles interpolating the quartic),
/// with y2 - y1 = 2: it meets the plane z = 0 where
/// x = 2 (dip - bend q^2) >= 0, q = (y - y1)(y - y2) = (y - m)^2 - 1 about
/// the middle m. With dip = bend that is one arc touching the sheet's edge
/// x = 0 at y = m; with dip below bend, two arcs from that edge, one around
/// y1 and one around y2, apart by 2 sqrt(1 - sqrt(dip / bend)) at the edge.
struct EdgeArcs {
  double bend = 5e-4, y1 = 1.0, dip = 5e-4;

  double y2() const { return y1 + 2.0; }
  double middle() const { return y1 + 1.0; }
  double x_at(double y) const {
    const double q = (y - y1) * (y - y2());
    return 2.0 * (dip - bend * q * q);
  }
  BSplineSurface sheet() const {
    const double y0 = -3.0, y4 = 7.0;
    // Bernstein values of degree 4 at five parameters, solved for the poles.
    Eigen::Matrix<double, 5, 5> basis;
    Eigen::Matrix<double, 5, 1> values;
    const double binomial[5] = {1, 4, 6, 4, 1};
    for (int r = 0; r < 5; ++r) {
      const double t = r / 4.0;
      for (int i = 0; i < 5; ++i)
        basis(r, i) = binomial[i] * std::pow(t, i) * std::pow(1.0 - t, 4 - i);
      values[r] = -0.5 * x_at(y0 + t * (y4 - y0));  // z at x = 0
    }
    const Eigen::Matrix<double, 5, 1> poles = basis.lu().solve(values);
    BSplineSurface s;
    s.degree = {1, 4};
    s.knots = {Eigen::Vector4d(0, 0, 1, 1),
               (Eigen::VectorXd(10) << 0, 0, 0, 0, 0, 1, 1, 1, 1, 1).finished()};
    s.control_points.resize(10, 3);
    for (int i = 0; i < 2; ++i)
      for (int j = 0; j < 5; ++j)
        s.control_points.row(i * 5 + j) << 10.0 * i, y0 + (y4 - y0) * j / 4.0,
            0.5 * 10.0 * i + poles[j];
    return s;
  }
  /// The y intervals of the arcs: |q| <= r = sqrt(dip / bend), so
  /// (y - m)^2 between 1 - r and 1 + r.
  std::vector<std::pair<double, double>> spans() const {
    const double r = std::sqrt(dip / bend);
    const double inner = std::sqrt(std::max(0.0, 1.0 - r)), outer = std::sqrt(1.0 + r);
    if (inner == 0.0) return {{middle() - outer, middle() + outer}};
    return {{middle() - outer, middle() - inner}, {middle() + inner, middle() + outer}};
  }
  /// Arc length of every arc by the midpoint rule on 20000 pieces each.
  double length() const {
    double sum = 0.0;
    for (const auto& [lo, hi] : spans()) {
      const int n = 20000;
      const double h = (hi - lo) / n;
      for (int k = 0; k < n; ++k) {
        const double y = lo + (k + 0.5) * h;
        const double q = (y - y1) * (y - y2());
        const double slope = -4.0 * bend * q * (2.0 * y - y1 - y2());
        sum += h * std::sqrt(1.0 + slope * slope);
      }
    }
    return sum;
  }
};

}  // namespace

TEST_CASE("arcs bulging across a leaf edge within the flatness come out whole in refined queries") {
  const BSplineSurface floor = floor_plane();
  const argil::SurfaceHierarchy hf = argil::test::hierarchy_for(floor);
  int cases = 0;
  // Caps centred on leaf edges and inside leaves; 0.5 to 2.3 mm long, bulging
  // 1e-3 to 2e-2 mm in: far longer than eps, within the coarse leaves' flatness.
  for (const double y_c : {0.0, 0.75, -1.75, 3.1, 5.75}) {
    for (const double dip : {0.01, 0.005, 0.002, 0.0005}) {
      const Cap cap{0.0075, dip, y_c};
      const BSplineSurface sheet = cap.sheet();
      const argil::SurfaceHierarchy hs = argil::test::hierarchy_for(sheet);
      for (const double relative : {1e-6, 1e-8}) {
        const double eps = relative * 70.0;
        INFO("y_c " << y_c << " dip " << dip << " eps " << eps);
        const CollisionResult r =
            argil::collide(hf, hs, argil::CollisionRequest{.tolerance = eps, .refine = true});
        REQUIRE(r.status.ok());
        REQUIRE(r.curves.size() == 1);
        const argil::IntersectionCurve& c = r.curves[0];
        for (std::size_t k = 0; k < c.points.size(); ++k) {
          CHECK(std::abs(c.points[k].z()) <= 1e-12 * 70.0);
          CHECK((argil::evaluate(sheet, c.uv_b[k][0], c.uv_b[k][1]) - c.points[k]).norm() <=
                1e-12 * 70.0);
        }
        // Coverage: the analytic arc within eps of the reported curve.
        double farthest = 0.0;
        for (int k = 0; k <= 400; ++k) {
          const double y = cap.y_c - cap.half_width() + 2.0 * cap.half_width() * k / 400;
          farthest = std::max(farthest, argil::test::distance_to_curves(cap.at(y), r));
        }
        CHECK(farthest <= eps);
        CHECK(std::abs(c.length() - cap.length()) <= 2.0 * eps);
        ++cases;
      }
    }
  }
  CHECK(cases == 40);
}

TEST_CASE("arcs from a face edge, touching it or side by side, come out whole") {
  // The arc touching the edge: the triangles meet the floor only at a leaf
  // corner on the edge (no crossing segment); refined, the pair is split
  // until the arc shows. Two arcs 0.2 mm apart: a transversal leaf pair's
  // triangles can show one and pass over the other, whose ends on the edge
  // x = 0 the edge's single crossing with the floor does not explain.
  const BSplineSurface floor = floor_plane();
  const argil::SurfaceHierarchy hf = argil::test::hierarchy_for(floor);
  for (const double y1 : {1.0, -1.0, 0.3, -2.2, 2.6, -0.45, 4.1}) {
    for (const double dip : {5e-4, 4.9e-4}) {
      const EdgeArcs arcs{5e-4, y1, dip};
      const BSplineSurface sheet = arcs.sheet();
      const argil::SurfaceHierarchy hs = argil::test::hierarchy_for(sheet);
      for (const double relative : {1e-6, 1e-8}) {
        const double eps = relative * 70.0;
        INFO("y1 " << y1 << " dip " << dip << " eps " << eps);
        const CollisionResult r =
            argil::collide(hf, hs, argil::CollisionRequest{.tolerance = eps, .refine = true});
        REQUIRE(r.status.ok());
        CHECK(r.curves.size() == arcs.spans().size());
        double farthest = 0.0, length = 0.0;
        for (const auto& [lo, hi] : arcs.spans()) {
          for (int k = 0; k <= 400; ++k) {
            const double y = lo + (hi - lo) * k / 400;
            farthest = std::max(farthest, argil::test::distance_to_curves(
                                              Eigen::Vector3d(arcs.x_at(y), y, 0.0), r));
          }
        }
        for (const argil::IntersectionCurve& c : r.curves) length += c.length();
        CHECK(farthest <= eps);
        CHECK(std::abs(length - arcs.length()) <= 2.0 * eps);
      }
    }
  }
}
