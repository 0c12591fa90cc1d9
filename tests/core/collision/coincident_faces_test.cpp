// Faces that lie on each other (a face against itself, or against the same
// surface with other knots, as coincident faces of an assembly are) meet
// everywhere within eps: one contact region, and no curve along the leaf
// edges where their corner triangles happen to cross.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>

#include "argil/core.hpp"
#include "core/collision/surface_pairs.hpp"
#include "support/random_surface.hpp"

using argil::BSplineSurface;
using argil::CollisionResult;
using argil::Contact;
using argil::Direction;
using argil::test::hierarchy_for;

namespace {

/// The wavy pair's first surface: a uniform bicubic 16x16 net, polynomial.
BSplineSurface wavy() { return argil::test::wavy_pair().first; }

/// The same surface with knots inserted off its knot grid in u (once) and v
/// (twice): other elements, so other leaves, whose triangles cross the original's.
BSplineSurface with_extra_knots(const BSplineSurface& s) {
  const auto at = [&](Direction d, double share) {
    return s.domain_start(d) + share * (s.domain_end(d) - s.domain_start(d));
  };
  argil::Result<BSplineSurface> u =
      argil::insert_knot(s, Direction::u, at(Direction::u, 0.4321), 1);
  REQUIRE(u.ok());
  argil::Result<BSplineSurface> uv =
      argil::insert_knot(u.value(), Direction::v, at(Direction::v, 0.6789), 2);
  REQUIRE(uv.ok());
  return std::move(uv).value();
}

double size_of(const BSplineSurface& s) { return argil::control_point_box(s).diagonal(); }

/// Every contact lies within `within` of a at its parameters, and of b but for
/// a penetration's depth (that contact is a's point deepest behind b).
void check_contacts_on_both(const BSplineSurface& a, const BSplineSurface& b,
                            const CollisionResult& r, double within) {
  for (const Contact& c : r.contacts) {
    CHECK((argil::evaluate(a, c.uv_a[0], c.uv_a[1]) - c.point).norm() <= within);
    CHECK((argil::evaluate(b, c.uv_b[0], c.uv_b[1]) - c.point).norm() <=
          within + std::max(c.depth, 0.0));
  }
}

}  // namespace

TEST_CASE("a face against itself or a re-knotted copy is one contact region and no curve") {
  // The wavy net, and the rational asymmetric surface (uneven knots, weights,
  // uneven parameter speed: the two ends of a crossing segment map to
  // different points of the two copies).
  const bool rational = GENERATE(false, true);
  const BSplineSurface a = rational ? argil::test::asymmetric_surface(true) : wavy();
  const bool same = GENERATE(true, false);
  const BSplineSurface b = same ? a : with_extra_knots(a);
  const auto ha = hierarchy_for(a);
  const auto hb = hierarchy_for(b);
  // A face on a face touches over its whole area: the work is (area) / (leaf
  // area), so the coarse eps keeps this to seconds (sanitized: a minute).
  const double eps = 1e-3 * size_of(a);
  const bool refine = GENERATE(false, true);
  INFO((rational ? "asymmetric rational" : "wavy")
       << (same ? ", itself" : ", re-knotted copy") << ", eps " << eps
       << (refine ? " refined" : ""));
  const CollisionResult r = argil::collide(ha, hb, {.tolerance = eps, .refine = refine});
  REQUIRE(r.status.ok());
  CHECK(r.curves.empty());
  CHECK(r.region_count == 1);
  REQUIRE_FALSE(r.contacts.empty());
  check_contacts_on_both(a, b, r, eps);
}

TEST_CASE("a face against a copy a rigid pose places onto it is one contact region and no curve") {
  // b is a held in its own frame: the query's pose X_AB puts it back onto a,
  // so b's normals must turn with the pose to be found parallel to a's.
  const BSplineSurface a = wavy();
  const Eigen::Matrix3d R =
      Eigen::AngleAxisd(0.7, Eigen::Vector3d(1.0, 2.0, 3.0).normalized()).toRotationMatrix();
  const Eigen::Vector3d p(0.3, -0.2, 0.5);
  const BSplineSurface b =
      argil::test::moved(with_extra_knots(a), R.transpose(), -(R.transpose() * p));
  const auto ha = hierarchy_for(a);
  const auto hb = hierarchy_for(b);
  const double eps = 1e-3 * size_of(a);
  const bool refine = GENERATE(false, true);
  INFO((refine ? "refined" : "unrefined"));
  const argil::Pose X_AB{Eigen::Quaterniond(R), p};
  const CollisionResult r = argil::collide(ha, hb, X_AB, {.tolerance = eps, .refine = refine});
  REQUIRE(r.status.ok());
  CHECK(r.curves.empty());
  CHECK(r.region_count == 1);
  REQUIRE_FALSE(r.contacts.empty());
}

TEST_CASE("a face lying on another over part of it still gives the curve where they cross") {
  // b is a re-knotted copy of a with the poles of columns 8 to 15 moved by
  // 0.05 (i - 10.3) in z: it lies on a below the support of column 8 (u below
  // knot 5/13), dips under a, and crosses back up through it near column
  // 10 at about 37 degrees (slope 0.75), in one line from v = 0 to 1. (Off the
  // knot u = 9/13, where 0.05 (i - 10) would cross along the leaf edges.)
  const BSplineSurface a = wavy();
  BSplineSurface b = a;
  for (int i = 8; i < 16; ++i)
    for (int j = 0; j < 16; ++j) b.control_points(b.pole_index(i, j), 2) += 0.05 * (i - 10.3);
  b = with_extra_knots(b);
  const auto ha = hierarchy_for(a);
  const auto hb = hierarchy_for(b);
  const double eps = 1e-3;
  const bool refine = GENERATE(false, true);
  INFO("eps " << eps << (refine ? " refined" : ""));
  const CollisionResult r = argil::collide(ha, hb, {.tolerance = eps, .refine = refine});
  REQUIRE(r.status.ok());
  if (refine) REQUIRE(r.curves.size() == 1);  // unrefined: may break at leaf T-junctions
  REQUIRE_FALSE(r.curves.empty());
  for (const argil::IntersectionCurve& c : r.curves) {
    for (std::size_t k = 0; k < c.points.size(); ++k) {
      // On both surfaces (refined: to rounding), where b has left a.
      const double within = refine ? 1e-12 : eps / 3.0;
      CHECK((argil::evaluate(a, c.uv_a[k][0], c.uv_a[k][1]) - c.points[k]).norm() <= within);
      CHECK((argil::evaluate(b, c.uv_b[k][0], c.uv_b[k][1]) - c.points[k]).norm() <= within);
      CHECK(c.uv_a[k][0] > 5.0 / 13.0);
    }
  }
  if (refine) {
    const argil::IntersectionCurve& c = r.curves.front();
    // Its ends are refined onto the domain edges v = 0 and v = 1 (to rounding
    // of the edge-constrained Gauss-Newton step).
    const auto [lo, hi] = std::minmax(c.uv_a.front()[1], c.uv_a.back()[1]);
    CHECK(lo <= 1e-9);
    CHECK(hi >= 1.0 - 1e-9);
  }
  // The overlap is reported too, as contacts.
  bool overlap_reported = false;
  for (const Contact& c : r.contacts) overlap_reported = overlap_reported || c.uv_a[0] < 5.0 / 13.0;
  CHECK(overlap_reported);
  check_contacts_on_both(a, b, r, eps);
}
