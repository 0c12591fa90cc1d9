// Intersection curves of real faces that meet at a CAD edge: one whole curve
// per edge, not pieces broken wherever rounding puts the edge on either side.

#include <catch2/catch.hpp>
#include <cmath>

#include "argil/core.hpp"
#include "argil/io.hpp"
#include "support/built_hierarchy.hpp"
#include "test_files.hpp"

namespace argil::io {
namespace {

/// Collides screw.step's cone (face 8) with the bottom plane (face 9), whose
/// trim is the cone's boundary circle v = v1: the corner points of the cone's
/// boundary leaves lie in the plane only up to rounding.
void check_cone_meets_plane(double eps, bool refine) {
  Result<Model> read = read_model(test::shared_data("screw.step"));
  REQUIRE(read.ok());
  const Model& model = read.value();
  REQUIRE(model.faces.size() == 10);
  const BSplineSurface& cone = model.faces[8].surface;
  const BSplineSurface& plane = model.faces[9].surface;
  const SurfaceHierarchy hc = test::hierarchy_for(cone);
  const SurfaceHierarchy hp = test::hierarchy_for(plane);
  INFO("eps " << eps << (refine ? " refined" : ""));
  const CollisionResult r = collide(hc, hp, {.tolerance = eps, .refine = refine});
  REQUIRE(r.status.ok());
  REQUIRE(r.curves.size() == 1);
  const IntersectionCurve& c = r.curves[0];
  CHECK(c.points.front() == c.points.back());
  double length = 0.0;
  for (std::size_t k = 0; k < c.points.size(); ++k) {
    CHECK((evaluate(cone, c.uv_a[k][0], c.uv_a[k][1]) - c.points[k]).norm() <= eps);
    CHECK((evaluate(plane, c.uv_b[k][0], c.uv_b[k][1]) - c.points[k]).norm() <= eps);
    if (k > 0) length += (c.points[k] - c.points[k - 1]).norm();
  }
  // The whole circle: its length from the cone's boundary, sampled densely.
  const double v1 = cone.domain_end(Direction::v);
  const double u0 = cone.domain_start(Direction::u), u1 = cone.domain_end(Direction::u);
  double circle = 0.0;
  constexpr int kSamples = 20000;
  for (int k = 1; k <= kSamples; ++k) {
    const double ua = u0 + (u1 - u0) * (k - 1) / kSamples, ub = u0 + (u1 - u0) * k / kSamples;
    circle += (evaluate(cone, ub, v1) - evaluate(cone, ua, v1)).norm();
  }
  CHECK(std::abs(length - circle) <= 1e-3 * circle);
}

}  // namespace

TEST_CASE("a cone and the plane its boundary lies in meet in one closed curve (screw.step)",
          "[io][collision]") {
  check_cone_meets_plane(2e-3, false);
  check_cone_meets_plane(2e-3, true);
  check_cone_meets_plane(1e-4, false);
}

}  // namespace argil::io
