// The sphere's contact disc (docs/deformation.md, Loads): its radius follows
// the conforming contact on the material's foundation, and the disc's load
// pattern is non-negative, sums to one, keeps the contact point as its centre
// on a flat face, ignores how the face is parametrised and carries nothing
// where there is no material.
#include <catch2/catch.hpp>
#include <cmath>
#include <vector>

#include "argil/core.hpp"
#include "argil/core/deform/contact_footprint.hpp"
#include "support/random_surface.hpp"
#include "support/transposed_surface.hpp"
#include "support/trim_loops.hpp"

namespace {

using argil::BSplineSurface;
using argil::Direction;

/// A contact at S(uv) as the collision queries report it.
argil::Contact contact_at(const BSplineSurface& s, const Eigen::Vector2d& uv) {
  const argil::SurfaceDerivatives d = argil::evaluate_derivatives(s, uv.x(), uv.y(), 1);
  argil::Contact c;
  c.uv_a = uv;
  c.point = d.point;
  c.tangent_u = d.du;
  c.tangent_v = d.dv;
  c.normal = d.du.cross(d.dv).normalized();
  return c;
}

/// sum_i g_i P_i: where the pattern's load acts on average.
Eigen::Vector3d centre_of(const Eigen::VectorXd& g, const BSplineSurface& s) {
  return (g.transpose() * s.control_points).transpose();
}

}  // namespace

TEST_CASE("the contact disc carries the force by the conforming contact on the foundation",
          "[deformation][load]") {
  for (const double r : {0.05, 2.0, 40.0})
    for (const double k : {1e-3, 0.1, 30.0})
      for (const double f : {1e-4, 0.5, 8.0}) {
        CAPTURE(r, k, f);
        const double a = argil::sphere_contact_radius(r, f, k);
        REQUIRE(a > 0.0);
        CHECK(a <= r);
        // Below the cap the paraboloid pressure over the disc carries the force.
        if (a < r) CHECK(M_PI * k * std::pow(a, 4) / (4.0 * r) == Approx(f).epsilon(1e-12));
        // More force, a wider disc (until the sphere's own radius).
        CHECK(argil::sphere_contact_radius(r, 2.0 * f, k) >= a);
      }
  CHECK(argil::sphere_contact_radius(2.0, 0.0, 0.1) == 0.0);  // no force, no disc
  CHECK(argil::sphere_contact_radius(2.0, 0.5, 0.0) == 2.0);  // no foundation: the sphere
}

TEST_CASE("a disc's load pattern is non-negative, sums to one and is centred on a flat face",
          "[deformation][load]") {
  // x = 12 u, y = 12 v exactly: the (u, v) map is linear, so the disc keeps its centre.
  const BSplineSurface s = argil::test::asymmetric_plate(12.0, 3.0);
  const argil::TrimRegion untrimmed;
  for (const double radius : {0.0, 0.3, 1.5, 4.0})
    for (const Eigen::Vector2d& uv :
         {Eigen::Vector2d(0.5, 0.5), Eigen::Vector2d(0.37, 0.61), Eigen::Vector2d(0.7, 0.2)}) {
      CAPTURE(radius, uv.transpose());
      const argil::Contact c = contact_at(s, uv);
      const Eigen::VectorXd g = argil::footprint_load_pattern(s, {c}, {1.0}, radius, untrimmed);
      CHECK(g.minCoeff() >= 0.0);
      CHECK(g.sum() == Approx(1.0).epsilon(1e-12));
      // A disc within the face keeps the contact point as its centre.
      const double reach = radius / 12.0;
      if (uv.minCoeff() > reach && uv.maxCoeff() < 1.0 - reach)
        CHECK((centre_of(g, s) - c.point).norm() < 1e-12 * 12.0);
      // A wide disc reaches poles a point does not.
      const Eigen::VectorXd point = argil::contact_load_pattern(s, {c}, {1.0});
      if (radius == 0.0) CHECK(g == point);
      if (radius >= 4.0) CHECK((g.array() > 0.0).count() > (point.array() > 0.0).count());
    }
  // Shares add up over several contacts.
  const std::vector<argil::Contact> two{contact_at(s, {0.3, 0.3}), contact_at(s, {0.6, 0.7})};
  const Eigen::VectorXd g = argil::footprint_load_pattern(s, two, {0.25, 0.75}, 1.0, untrimmed);
  CHECK(g.sum() == Approx(1.0).epsilon(1e-12));
  CHECK((centre_of(g, s) - (0.25 * two[0].point + 0.75 * two[1].point)).norm() < 1e-12 * 12.0);
}

TEST_CASE("a disc carries nothing outside the face's domain or trims", "[deformation][load]") {
  const BSplineSurface s = argil::test::asymmetric_plate(12.0, 0.0);
  // Material only for u <= 0.5: a disc centred on that edge leans to u < 0.5.
  std::vector<argil::TrimLoop> loops{argil::test::rectangle_loop({0.0, 0.0}, {0.5, 1.0}, true)};
  const argil::Result<argil::TrimRegion> half = argil::TrimRegion::create(loops);
  REQUIRE(half.ok());
  const argil::Contact c = contact_at(s, {0.49, 0.5});
  const Eigen::VectorXd g = argil::footprint_load_pattern(s, {c}, {1.0}, 2.0, half.value());
  CHECK(g.minCoeff() >= 0.0);
  CHECK(g.sum() == Approx(1.0).epsilon(1e-12));
  CHECK(centre_of(g, s).x() < c.point.x() - 0.3);  // the material's side of the edge
  // The same at the face's own edge u = 0, without trims.
  const argil::Contact edge = contact_at(s, {0.0, 0.5});
  const Eigen::VectorXd e = argil::footprint_load_pattern(s, {edge}, {1.0}, 2.0, {});
  CHECK(e.sum() == Approx(1.0).epsilon(1e-12));
  CHECK(centre_of(e, s).x() > edge.point.x() + 0.3);
}

TEST_CASE("a disc's load pattern transposes with the net", "[deformation][load]") {
  const BSplineSurface s = argil::test::asymmetric_surface(true);
  const BSplineSurface t = argil::test::transposed(s);
  const int nu = s.count(Direction::u), nv = s.count(Direction::v);
  for (const Eigen::Vector2d& uv : {Eigen::Vector2d(0.55, 0.7), Eigen::Vector2d(0.2, -0.4)}) {
    const Eigen::VectorXd g = argil::footprint_load_pattern(s, {contact_at(s, uv)}, {1.0}, 2.5, {});
    const Eigen::VectorXd h =
        argil::footprint_load_pattern(t, {contact_at(t, {uv.y(), uv.x()})}, {1.0}, 2.5, {});
    double gap = 0.0;
    for (int i = 0; i < nu; ++i)
      for (int j = 0; j < nv; ++j)
        gap = std::max(gap, std::abs(g[s.pole_index(i, j)] - h[t.pole_index(j, i)]));
    CHECK(gap < 1e-12);
    CHECK(g.minCoeff() >= 0.0);
    CHECK(g.sum() == Approx(1.0).epsilon(1e-12));
  }
}
