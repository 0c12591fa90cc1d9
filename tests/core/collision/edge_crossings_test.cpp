// The memo of leaf-edge crossings: a start found again within rounding on the
// same held parameter gets the kept refinement; anything else does not.
#include <catch2/catch.hpp>
#include <cmath>
#include <limits>

#include "argil/core.hpp"
#include "argil/core/collision/detail/edge_crossings.hpp"
#include "support/random_surface.hpp"

using argil::BSplineSurface;
using argil::Direction;
using argil::PairPoint;

namespace {

PairPoint start_at(double ua, double va, double ub, double vb) {
  return {Eigen::Vector3d::Zero(), {ua, va}, {ub, vb}};
}

argil::RefinedPair refined_to(double ua) {
  argil::RefinedPair r;
  r.uv_a = {ua, 0.0};
  return r;
}

}  // namespace

TEST_CASE("edge crossings are found again within rounding on the same held parameter only") {
  const BSplineSurface a = argil::test::asymmetric_surface();
  std::mt19937_64 rng(3);
  const BSplineSurface b = argil::test::random_surface(rng);
  argil::OperatorCache cache;
  const argil::SurfaceOperators ops_a = argil::surface_operators(a, cache).value();
  const argil::SurfaceOperators ops_b = argil::surface_operators(b, cache).value();
  argil::PatchEvaluator eval_a(a, ops_a), eval_b(b, ops_b);
  const argil::SurfacePair pair{eval_a, eval_b, 1.0};
  const double length_ub = b.domain_end(Direction::u) - b.domain_start(Direction::u);
  const double length_va = a.domain_end(Direction::v) - a.domain_start(Direction::v);

  const double ua = 0.3 * a.domain_start(Direction::u) + 0.7 * a.domain_end(Direction::u);
  const double va = a.domain_start(Direction::v) + 0.25 * length_va;
  const double ub = b.domain_start(Direction::u) + 0.5 * length_ub;
  const double vb = 0.9 * b.domain_start(Direction::v) + 0.1 * b.domain_end(Direction::v);
  // Held: v on surface a (parameter 1), on a leaf edge.
  const PairPoint start = start_at(ua, va, ub, vb);
  argil::detail::EdgeCrossings crossings(pair);
  CHECK(crossings.find(start, 1) == nullptr);
  crossings.keep(start, 1, refined_to(42.0));
  // A second crossing on the same edge line, elsewhere along it.
  crossings.keep(start_at(ua, va, b.domain_start(Direction::u), vb), 1, refined_to(7.0));

  const argil::RefinedPair* same = crossings.find(start, 1);
  REQUIRE(same != nullptr);
  CHECK(same->uv_a[0] == 42.0);
  // The other leaf's corners, rounded differently: within 1e-12 of each domain.
  const argil::RefinedPair* rounded =
      crossings.find(start_at(ua, va, ub + 0.5e-12 * length_ub, vb), 1);
  REQUIRE(rounded != nullptr);
  CHECK(rounded->uv_a[0] == 42.0);
  const argil::RefinedPair* other =
      crossings.find(start_at(ua, va, b.domain_start(Direction::u), vb), 1);
  REQUIRE(other != nullptr);
  CHECK(other->uv_a[0] == 7.0);
  // Farther than rounding, another held parameter, or the held value one ulp off: not kept.
  CHECK(crossings.find(start_at(ua, va, ub + 2e-12 * length_ub, vb), 1) == nullptr);
  CHECK(crossings.find(start, 0) == nullptr);
  CHECK(crossings.find(start_at(ua, std::nextafter(va, 1e9), ub, vb), 1) == nullptr);
}
