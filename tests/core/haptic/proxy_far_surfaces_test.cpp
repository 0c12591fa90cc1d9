// The sphere proxy does not query a surface that cannot have come within
// reach since it last looked (docs/deformation.md, "Faces that cannot be
// reached are not queried"): the lower bound it keeps is the distance then, less the path the
// centre travelled and the motion the surface was told of since. These tests
// check that the surfaces it leaves out are the ones that cannot matter: the
// moves are the same as when every surface is queried, a surface that moves
// into the sphere still pushes it, and the side is still followed round an
// edge.
#include <catch2/catch.hpp>
#include <cmath>
#include <vector>

#include "argil/core.hpp"
#include "support/random_surface.hpp"

namespace {

using argil::BSplineSurface;
using Eigen::Vector3d;

/// The u/v-asymmetric structure (degree 3x2, a double knot, weights) laid
/// flat over [0, size]^2 at height z.
BSplineSurface sheet_at(double z, double size = 10.0) {
  BSplineSurface s = argil::test::asymmetric_surface(true);
  const Eigen::VectorXd gu = argil::greville_abscissae(s.degree[0], s.knots[0]);
  const Eigen::VectorXd gv = argil::greville_abscissae(s.degree[1], s.knots[1]);
  for (Eigen::Index i = 0; i < gu.size(); ++i)
    for (Eigen::Index j = 0; j < gv.size(); ++j)
      s.control_points.row(s.pole_index(static_cast<int>(i), static_cast<int>(j)))
          << size * (gu[i] - gu[0]) / (gu[gu.size() - 1] - gu[0]),
          size * (gv[j] - gv[0]) / (gv[gv.size() - 1] - gv[0]), z;
  return s;
}

struct Sheets {
  argil::OperatorCache cache;
  std::vector<argil::SurfaceHierarchy> hierarchies;
  std::vector<argil::TrimmedSurface> surfaces() const {
    std::vector<argil::TrimmedSurface> out;
    for (const argil::SurfaceHierarchy& h : hierarchies) out.push_back({&h, nullptr});
    return out;
  }
};

/// A near sheet at z = 0 and `far` sheets stacked below it from z = -12.
void stack(Sheets& s, int far) {
  s.hierarchies.reserve(static_cast<std::size_t>(far) + 1);
  s.hierarchies.push_back(argil::SurfaceHierarchy::build(sheet_at(0.0), s.cache).value());
  for (int k = 0; k < far; ++k)
    s.hierarchies.push_back(
        argil::SurfaceHierarchy::build(sheet_at(-12.0 - 3.0 * k), s.cache).value());
}

}  // namespace

TEST_CASE("the proxy queries a far surface again only once it could have come within reach",
          "[haptic][proxy]") {
  const double eps = 0.01, radius = 1.0;
  const int far = 12;
  Sheets sheets;
  stack(sheets, far);
  const std::vector<argil::TrimmedSurface> surfaces = sheets.surfaces();
  argil::SphereProxy proxy(radius, eps);
  // A slide along the near sheet, pressed 0.1 into it: 13 projections of
  // substeps of r / 2 over 6 mm, each pushed out of the near sheet.
  const Vector3d from(2.0, 5.0, radius), to(8.0, 5.0, radius - 0.1);
  const argil::SphereMove slid = proxy.move(surfaces, from, to);
  REQUIRE(slid.status.ok());
  CHECK(slid.p_WT.z() >= radius - 0.25 * eps);
  CHECK(std::abs(slid.p_WT.x() - 8.0) < 0.25 * eps);
  const long slide_queries = proxy.closest_point_queries();
  // Every far sheet is at least 11 mm below the sphere over a 6 mm path: each
  // is queried once. The near sheet is queried in every round (one to three
  // a projection); queried every round, the far sheets alone would cost 12
  // times that.
  CHECK(slide_queries >= 13 + far);
  CHECK(slide_queries <= 3 * 13 + far);
  // The nearest surface, at the centre the move ended on: the near sheet's
  // closest point is the one the last round found, and no far sheet can be
  // within eps of it.
  const argil::ProxyContact near = proxy.nearest(surfaces, slid.p_WT);
  REQUIRE(near.status.ok());
  CHECK(near.body == 0);
  CHECK(proxy.closest_point_queries() == slide_queries);
  CHECK((near.outward_normal - Vector3d::UnitZ()).norm() < 1e-9);

  // The same slide by a proxy that sees only the near sheet ends at the same
  // place, bit for bit: the far sheets left out could not push.
  argil::SphereProxy alone(radius, eps);
  const argil::SphereMove alone_slid = alone.move({surfaces[0]}, from, to);
  REQUIRE(alone_slid.status.ok());
  CHECK(alone_slid.p_WT == slid.p_WT);

  // Back and forth until the path exceeds the far sheets' clearance: the
  // first far sheet (11 mm below the sphere) is then queried again.
  long queries = proxy.closest_point_queries();
  argil::SphereMove back = proxy.move(surfaces, slid.p_WT, from);
  REQUIRE(back.status.ok());
  CHECK(proxy.closest_point_queries() - queries <= 3 * 13 + 1);
  queries = proxy.closest_point_queries();
  REQUIRE(proxy.move(surfaces, back.p_WT, to).status.ok());
  CHECK(proxy.closest_point_queries() - queries > 13);  // 18 mm travelled: the first is looked at
}

TEST_CASE("a far surface that moves into the sphere still pushes it, when the proxy is told",
          "[haptic][proxy]") {
  const double eps = 0.01, radius = 1.0;
  argil::OperatorCache cache;
  const BSplineSurface low = sheet_at(-3.0);
  argil::SurfaceHierarchy h = argil::SurfaceHierarchy::build(low, cache).value();
  const std::vector<argil::TrimmedSurface> surfaces{{&h, nullptr}};
  argil::SphereProxy proxy(radius, eps);
  const Vector3d centre(5.0, 5.0, 0.0);
  REQUIRE(proxy.project(surfaces, centre).p_WT == centre);  // 3 mm above the sheet
  // The sheet springs 3.5 mm up, past the centre. Told, the proxy cannot
  // vouch that it stayed clear: it queries it, sees the crossing and
  // pushes the sphere back on top.
  h.set_control_points(sheet_at(0.5).control_points);
  proxy.set_surface_motion({3.5});
  const argil::SphereMove out = proxy.project(surfaces, centre);
  REQUIRE(out.status.ok());
  CHECK(out.p_WT.z() >= 0.5 + radius - 0.25 * eps);
  // The same with a motion told in steps over several calls.
  argil::SphereProxy stepwise(radius, eps);
  h.set_control_points(low.control_points);
  Vector3d at = stepwise.project(surfaces, centre).p_WT;
  REQUIRE(at == centre);
  for (int k = 1; k <= 7; ++k) {
    CAPTURE(k);
    h.set_control_points(sheet_at(-3.0 + 0.5 * k).control_points);
    stepwise.set_surface_motion({0.5});
    const argil::SphereMove pushed = stepwise.project(surfaces, at);
    REQUIRE(pushed.status.ok());
    at = pushed.p_WT;
    CHECK(at.z() >= -3.0 + 0.5 * k + radius - 0.25 * eps);
  }
}

TEST_CASE("the proxy follows its side round a far surface's edge", "[haptic][proxy]") {
  // A point tool starts above a sheet, beyond its edge, goes under the
  // sheet's plane out there and then slides in under the sheet: it stays
  // under it, pushed down, not thrown through to the top. The sheet is left
  // out of the queries along the way (far, for a point).
  const double eps = 0.01;
  for (const double radius : {0.0, 0.05}) {
    CAPTURE(radius);
    argil::OperatorCache cache;
    const argil::SurfaceHierarchy h = argil::SurfaceHierarchy::build(sheet_at(0.0), cache).value();
    const std::vector<argil::TrimmedSurface> surfaces{{&h, nullptr}};
    argil::SphereProxy proxy(radius, eps);
    const Vector3d start(5.0, 12.0, 0.05), below(5.0, 12.0, -0.05), under(5.0, 9.0, -0.05);
    REQUIRE(proxy.project(surfaces, start).p_WT == start);
    const argil::SphereMove down = proxy.move(surfaces, start, below);
    REQUIRE(down.status.ok());
    CHECK(down.p_WT == below);
    const argil::SphereMove in = proxy.move(surfaces, down.p_WT, under);
    REQUIRE(in.status.ok());
    CHECK(in.p_WT.z() < 0.0);
    CHECK(in.p_WT.z() <= -radius + 0.25 * eps);
    CHECK(std::abs(in.p_WT.y() - 9.0) < 1e-9);
    CHECK(proxy.closest_point_queries() < 1 + 1 + 31);
  }
}

TEST_CASE("the side is read where the proxy last passed a surface by before meeting it",
          "[haptic][proxy]") {
  // A point or small sphere starts above a sheet, beyond its edge, drops
  // under the sheet's plane just beyond the edge in one move, and slides in
  // under the sheet. The drop is one substep longer than what the sheet's
  // bound allows, so the sheet is passed by until the centre is under it:
  // its side is then read where it was last passed, under the plane, and the
  // centre stays under the sheet. Read from the record (above), the centre
  // was taken to have crossed and was put back on top.
  const double eps = 0.01;
  argil::OperatorCache cache;
  const argil::SurfaceHierarchy h = argil::SurfaceHierarchy::build(sheet_at(0.0), cache).value();
  const std::vector<argil::TrimmedSurface> surfaces{{&h, nullptr}};
  int cases = 0;
  for (const double radius : {0.0, 0.01, 0.02})
    for (const double a : {0.2, 0.5, 1.0})
      for (const double height : {0.05, 0.5, 1.0})
        for (const double b : {0.05, 0.2})
          for (const double depth : {0.005, 0.01, 0.03}) {
            CAPTURE(radius, a, height, b, depth);
            argil::SphereProxy proxy(radius, eps);
            const Vector3d start(5.0, 10.0 + a, height);
            REQUIRE(proxy.project(surfaces, start).p_WT == start);
            const argil::SphereMove down =
                proxy.move(surfaces, start, Vector3d(5.0, 10.0 + b, -depth));
            REQUIRE(down.status.ok());
            REQUIRE(down.p_WT.z() < 0.0);
            const argil::SphereMove in =
                proxy.move(surfaces, down.p_WT, Vector3d(5.0, 9.0, -depth));
            REQUIRE(in.status.ok());
            CHECK(in.p_WT.z() < 0.0);
            ++cases;
          }
  CHECK(cases == 162);
}
