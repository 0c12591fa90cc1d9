// Trim regions: validation names the loop and curve; contains() agrees with a
// dense polygon far from the boundary and with the side of the exact curve
// right next to it (where any fixed polygon fails); its cost at haptic rate.
#include <catch2/catch.hpp>
#include <chrono>
#include <cmath>
#include <random>

#include "argil/core.hpp"
#include "support/random_surface.hpp"
#include "support/trim_loops.hpp"

namespace argil {
namespace {

const ParamRect kDomain = domain_of(test::asymmetric_surface());  // [0, 1] x [-1, 2]

std::vector<std::vector<Eigen::Vector2d>> polygons_of(const std::vector<TrimLoop>& loops,
                                                      int per_curve) {
  std::vector<std::vector<Eigen::Vector2d>> out;
  for (const TrimLoop& loop : loops) out.push_back(test::dense_polygon(loop, per_curve));
  return out;
}

/// The unit normal on the material side (left of the curve's direction) at t.
Eigen::Vector2d left_normal(const BSplineCurve& c, double t) {
  const double h = 1e-7 * (c.domain_end() - c.domain_start());
  const Eigen::Vector2d tangent = evaluate(c, t + h) - evaluate(c, t - h);
  return Eigen::Vector2d(-tangent.y(), tangent.x()).normalized();
}

}  // namespace

TEST_CASE("contains agrees with a dense polygon away from the curves", "[trim][slow]") {
  const std::vector<TrimLoop> loops = test::asymmetric_trims(kDomain);
  const Result<TrimRegion> region = TrimRegion::create(loops);
  INFO(region.status().message);
  REQUIRE(region.ok());
  // 4000 points per curve: the polygon is within 1e-6 of the domain of the
  // curves (chord error of spans this short), far below the 1e-4 margin kept.
  const auto polygons = polygons_of(loops, 4000);
  const double margin = 1e-4 * std::hypot(kDomain.width(), kDomain.height());
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(kDomain.u0 - 0.1, kDomain.u1 + 0.1);
  std::uniform_real_distribution<double> v(kDomain.v0 - 0.1, kDomain.v1 + 0.1);
  int checked = 0, inside = 0;
  for (int k = 0; k < 20000; ++k) {
    const Eigen::Vector2d uv(u(rng), v(rng));
    if (test::polygon_distance(polygons, uv) < margin) continue;
    CAPTURE(uv.x(), uv.y());
    const bool expected = test::inside_polygons(polygons, uv);
    CHECK(region.value().contains(uv) == expected);
    ++checked;
    inside += expected ? 1 : 0;
  }
  CHECK(checked > 15000);
  CHECK(inside > 3000);  // both answers are exercised
  CHECK(checked - inside > 3000);
}

TEST_CASE("contains follows the exact curves down to 1e-12 of the loop from them", "[trim]") {
  const std::vector<TrimLoop> loops = test::asymmetric_trims(kDomain);
  const TrimRegion region = TrimRegion::create(loops).value();
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> unit(0.05, 0.95);  // away from curve ends (corners)
  const double size = std::hypot(kDomain.width(), kDomain.height());
  int checked = 0, curves = 0;
  for (std::size_t l = 0; l < loops.size(); ++l) {
    curves += static_cast<int>(loops[l].curves.size());
    for (std::size_t c = 0; c < loops[l].curves.size(); ++c) {
      const BSplineCurve& curve = loops[l].curves[c];
      for (int k = 0; k < 200; ++k) {
        const double t =
            curve.domain_start() + unit(rng) * (curve.domain_end() - curve.domain_start());
        const Eigen::Vector2d on = evaluate(curve, t);
        const Eigen::Vector2d n = left_normal(curve, t);
        for (const double offset : {1e-3, 1e-6, 1e-9, 1e-12}) {
          CAPTURE(l, c, t, offset);
          // The material lies on the left of every curve (outer loops
          // counter-clockwise, holes clockwise).
          CHECK(region.contains(on + offset * size * n));
          CHECK_FALSE(region.contains(on - offset * size * n));
          ++checked;
        }
      }
    }
  }
  CHECK(checked == 4 * 200 * curves);
  // The gap segment closes the loop: points beside it are decided by it.
  const BSplineCurve& arc = loops[0].curves[2];
  const BSplineCurve& top = loops[0].curves[3];
  const Eigen::Vector2d gap_mid =
      0.5 * (Eigen::Vector2d(arc.points.row(2).transpose()) + top.points.row(0).transpose());
  CHECK(region.contains(gap_mid - Eigen::Vector2d(0, 1e-9)));
  CHECK_FALSE(region.contains(gap_mid + Eigen::Vector2d(0, 1e-9)));
  CHECK_FALSE(region.contains(Eigen::Vector2d(std::nan(""), 0.0)));
  CHECK(TrimRegion().contains(Eigen::Vector2d(1e9, -1e9)));  // untrimmed: everything
}

TEST_CASE("contains costs well under a microsecond at haptic rate", "[trim][timing]") {
  const TrimRegion region = TrimRegion::create(test::asymmetric_trims(kDomain)).value();
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(kDomain.u0, kDomain.u1), v(kDomain.v0, kDomain.v1);
  std::vector<Eigen::Vector2d> points(100000);
  for (Eigen::Vector2d& p : points) p = {u(rng), v(rng)};
  int inside = 0;
  const auto start = std::chrono::steady_clock::now();
  for (const Eigen::Vector2d& p : points) inside += region.contains(p) ? 1 : 0;
  const double ns =
      std::chrono::duration<double, std::nano>(std::chrono::steady_clock::now() - start).count() /
      static_cast<double>(points.size());
  WARN("contains: " << ns << " ns per call over " << region.piece_count() << " pieces (" << inside
                    << " of " << points.size() << " inside)");
  CHECK(inside > 0);
  CHECK(ns < 5000.0);  // generous: a loaded CI machine; measured about 0.1 us
}

TEST_CASE("trim loop validation names the loop, the curve and the values", "[trim]") {
  const std::vector<TrimLoop> good = test::asymmetric_trims(kDomain);
  REQUIRE(validate_trim_loops(good).ok());
  REQUIRE(validate_trim_loops({}).ok());

  std::vector<TrimLoop> open = good;
  open[0].curves[3].points(0, 0) += 0.05;  // 5e-2 of the domain: beyond the gap allowed
  const Status gap = validate_trim_loops(open);
  CHECK(gap.code == StatusCode::invalid_surface);
  CHECK_THAT(gap.message, Catch::StartsWith("loop 0 curve 2 ends at (u, v) = ("));
  CHECK_THAT(gap.message, Catch::Contains("from the start of curve 3"));
  CHECK_THAT(gap.message, Catch::Contains("gaps must be at most"));

  std::vector<TrimLoop> empty = good;
  empty[1].curves.clear();
  CHECK(validate_trim_loops(empty).message == "loop 1 has no curves");

  std::vector<TrimLoop> bad_curve = good;
  bad_curve[2].curves[1].knots[0] = std::nan("");
  CHECK_THAT(validate_trim_loops(bad_curve).message, Catch::StartsWith("loop 2 curve 1: knots"));

  std::vector<TrimLoop> three_d = good;
  three_d[0].curves[0].points.conservativeResize(Eigen::NoChange, 3);
  three_d[0].curves[0].points.col(2).setZero();
  CHECK_THAT(validate_trim_loops(three_d).message,
             Catch::Contains("loop 0 curve 0: points has 3 columns, expected 2 (u, v)"));

  std::vector<TrimLoop> turned = good;
  turned[1].outer = true;  // a clockwise loop marked outer
  CHECK_THAT(validate_trim_loops(turned).message,
             Catch::StartsWith("loop 1 is an outer loop but runs clockwise"));
  turned = good;
  turned[0].outer = false;
  CHECK_THAT(validate_trim_loops(turned).message,
             Catch::StartsWith("loop 0 is a hole but runs counter-clockwise"));

  TrimLoop flat;
  flat.curves = {test::trim_line({0, 0}, {1, 0}), test::trim_line({1, 0}, {0, 0})};
  CHECK_THAT(validate_trim_loops({flat}).message, Catch::StartsWith("loop 0 encloses no area"));

  const Result<TrimRegion> refused = TrimRegion::create(open);
  CHECK(refused.status().message == gap.message);
}

}  // namespace argil
