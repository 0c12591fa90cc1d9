// Faces that lie on each other (a face against itself, or against the same
// surface with other knots, as coincident faces of an assembly are) meet
// everywhere within eps: one contact region, and no curve along the leaf
// edges where their corner triangles happen to cross.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>

#include "argil/core.hpp"
#include "core/collision/surface_pairs.hpp"

using argil::BSplineSurface;
using argil::CollisionResult;
using argil::Contact;
using argil::Direction;
using argil::test::hierarchy_for;
using argil::test::unit_net;

namespace {

constexpr double kPi = 3.14159265358979323846;

/// The wavy pair's first surface: a bicubic 16x16 net over the unit square.
BSplineSurface wavy() {
  return unit_net(
      16, [](double x, double y) { return 0.08 * std::sin(2 * kPi * x) * std::cos(2 * kPi * y); });
}

/// The same surface with a knot inserted off the knot grid in u and in v:
/// other elements, so other leaves, whose triangles cross the original's.
BSplineSurface with_extra_knots(const BSplineSurface& s) {
  argil::Result<BSplineSurface> u = argil::insert_knot(s, Direction::u, 0.4321, 1);
  REQUIRE(u.ok());
  argil::Result<BSplineSurface> uv = argil::insert_knot(u.value(), Direction::v, 0.6789, 2);
  REQUIRE(uv.ok());
  return std::move(uv).value();
}

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
  const BSplineSurface a = wavy();
  const bool same = GENERATE(true, false);
  const BSplineSurface b = same ? a : with_extra_knots(a);
  const auto ha = hierarchy_for(a);
  const auto hb = hierarchy_for(b);
  const double eps = GENERATE(1e-3, 1e-4);
  const bool refine = GENERATE(false, true);
  INFO((same ? "itself" : "re-knotted copy") << ", eps " << eps << (refine ? " refined" : ""));
  const CollisionResult r = argil::collide(ha, hb, {.tolerance = eps, .refine = refine});
  REQUIRE(r.status.ok());
  CHECK(r.curves.empty());
  CHECK(r.region_count == 1);
  REQUIRE_FALSE(r.contacts.empty());
  check_contacts_on_both(a, b, r, eps);
}

TEST_CASE("a face lying on another over part of it still gives the curve where they cross") {
  // b is a re-knotted copy of a with the poles of columns 8 to 15 moved by
  // 0.05 (i - 10.3) in z: it lies on a below the support of column 8 (u below
  // knot 5/13), dips under a, and crosses back up through it near column
  // 10, steeply (slope about 0.75), in one line from v = 0 to 1. (Off the
  // knot u = 9/13, where 0.05 (i - 10) would cross along the leaf edges.)
  const BSplineSurface a = wavy();
  BSplineSurface b = a;
  for (int i = 8; i < 16; ++i)
    for (int j = 0; j < 16; ++j) b.control_points(b.pole_index(i, j), 2) += 0.05 * (i - 10.3);
  b = with_extra_knots(b);
  const auto ha = hierarchy_for(a);
  const auto hb = hierarchy_for(b);
  const double eps = GENERATE(1e-3, 1e-4);
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
