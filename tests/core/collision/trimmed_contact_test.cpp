// Contact with material only: the closest point of a trimmed face and a
// sphere's contacts with it, against brute force on a dense sampling of the
// material and of the face's edge, on the u/v-asymmetric rational surface.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <random>

#include "argil/core.hpp"
#include "support/polyline_distance.hpp"
#include "support/random_surface.hpp"
#include "support/trim_loops.hpp"

namespace argil {
namespace {

/// The material and the edge of a trimmed face as dense point samples.
struct Samples {
  std::vector<Eigen::Vector3d> material;  // S(u, v) on a grid, inside the trims
  std::vector<Eigen::Vector3d> edge;      // S(c(t)) along every trim curve, in order per curve
  std::vector<int> curve_end;             // edge[curve_end[k - 1] .. curve_end[k]) is curve k
};

Samples sample(const BSplineSurface& s, const std::vector<TrimLoop>& loops,
               const TrimRegion& region) {
  Samples out;
  const ParamRect d = domain_of(s);
  constexpr int kGrid = 300;
  for (int i = 0; i <= kGrid; ++i)
    for (int j = 0; j <= kGrid; ++j) {
      const Eigen::Vector2d uv(d.u0 + d.width() * i / kGrid, d.v0 + d.height() * j / kGrid);
      if (region.contains(uv)) out.material.push_back(evaluate(s, uv.x(), uv.y()));
    }
  for (const TrimLoop& loop : loops)
    for (const BSplineCurve& c : loop.curves) {
      constexpr int kAlong = 3000;
      for (int k = 0; k <= kAlong; ++k) {
        const Eigen::Vector2d uv =
            evaluate(c, c.domain_start() + (c.domain_end() - c.domain_start()) * k / kAlong);
        out.edge.push_back(evaluate(s, uv.x(), uv.y()));
      }
      out.curve_end.push_back(static_cast<int>(out.edge.size()));
    }
  return out;
}

double nearest(const std::vector<Eigen::Vector3d>& points, const Eigen::Vector3d& p) {
  double best = std::numeric_limits<double>::infinity();
  for (const Eigen::Vector3d& x : points) best = std::min(best, (x - p).norm());
  return best;
}

/// Distance from p to the edge polyline (segments between consecutive samples of a curve).
double edge_distance(const Samples& s, const Eigen::Vector3d& p) {
  double best = std::numeric_limits<double>::infinity();
  int begin = 0;
  for (const int end : s.curve_end) {
    for (int k = begin; k + 1 < end; ++k)
      best = std::min(best, test::distance_to_segment(p, s.edge[static_cast<std::size_t>(k)],
                                                      s.edge[static_cast<std::size_t>(k) + 1]));
    begin = end;
  }
  return best;
}

struct Fixture {
  BSplineSurface surface = test::asymmetric_surface(true);
  std::vector<TrimLoop> loops = test::asymmetric_trims(domain_of(surface));
  TrimRegion region = TrimRegion::create(loops).value();
  OperatorCache cache;
  SurfaceHierarchy hierarchy = SurfaceHierarchy::build(surface, cache).value();
  Samples samples = sample(surface, loops, region);
  double size = control_point_box(surface).diagonal();
  TrimmedSurface trimmed() { return {&hierarchy, &region}; }
};

/// Query points: random in the face's box grown by a third, and near its edge.
std::vector<Eigen::Vector3d> query_points(const Fixture& f, std::mt19937_64& rng, int count) {
  const Box3 box = control_point_box(f.surface);
  const Eigen::Vector3d grow = box.extent() / 3.0;
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<Eigen::Vector3d> out;
  for (int k = 0; k < count; ++k) {
    if (k % 2 == 0) {
      const Eigen::Vector3d r(unit(rng), unit(rng), unit(rng));
      out.push_back(box.min - grow + (box.extent() + 2 * grow).cwiseProduct(r));
    } else {
      const auto e =
          static_cast<std::size_t>(unit(rng) * static_cast<double>(f.samples.edge.size() - 1));
      const Eigen::Vector3d dir =
          Eigen::Vector3d(unit(rng), unit(rng), unit(rng)) - Eigen::Vector3d::Constant(0.5);
      out.push_back(f.samples.edge[e] + 6.0 * unit(rng) * dir.normalized());
    }
  }
  return out;
}

}  // namespace

TEST_CASE("the closest point of a trimmed face is material and as near as brute force",
          "[collision][trim]") {
  Fixture f;
  const double eps = 1e-4 * f.size;
  std::mt19937_64 rng(5);
  int on_edge = 0, inside = 0, second_search = 0;
  for (const Eigen::Vector3d& p : query_points(f, rng, 600)) {
    CAPTURE(p.x(), p.y(), p.z());
    const ClosestPoint cp = closest_point(f.trimmed(), p, {.tolerance = eps});
    REQUIRE(cp.status.ok());
    const double brute = std::min(nearest(f.samples.material, p), nearest(f.samples.edge, p));
    // Never worse than any sample of the material or its edge, within eps.
    CHECK(cp.distance <= brute + eps);
    CHECK(cp.distance == Approx((p - cp.point).norm()).epsilon(1e-12));
    if (cp.on_edge) {
      ++on_edge;
      // On the edge: within the edge polyline's chord error (spacing about 0.03 mm).
      CHECK(edge_distance(f.samples, cp.point) < 1e-3);
    } else {
      ++inside;
      CHECK(f.region.contains(cp.uv));
      const ClosestPoint whole = closest_point(f.hierarchy, p, {.tolerance = eps});
      if (!f.region.contains(whole.uv)) ++second_search;
    }
  }
  WARN(on_edge << " answers on the edge, " << inside << " inside (" << second_search
               << " of them past a whole-surface answer outside the trims)");
  CHECK(on_edge > 100);
  CHECK(inside > 100);
}

TEST_CASE("a sphere touches a trimmed face inside its trims or on its edge, as brute force says",
          "[collision][trim]") {
  Fixture f;
  const double eps = 0.01, radius = 3.0;
  // The material's sampling is about 0.2 mm apart on this 62 mm face: a
  // sphere within that of touching may go either way.
  const double sampling = 0.3;
  std::mt19937_64 rng(9);
  int touching = 0, edge_contacts = 0, clear = 0;
  for (const Eigen::Vector3d& centre : query_points(f, rng, 400)) {
    CAPTURE(centre.x(), centre.y(), centre.z());
    const CollisionResult hit =
        collide_sphere(f.trimmed(), centre, radius, {.tolerance = eps, .max_contacts = 256});
    REQUIRE(hit.status.ok());
    const double brute =
        std::min(nearest(f.samples.material, centre), nearest(f.samples.edge, centre));
    if (brute > radius + eps + sampling) {
      CHECK(hit.contacts.empty());
      ++clear;
    }
    if (brute < radius - sampling) CHECK_FALSE(hit.contacts.empty());
    touching += hit.contacts.empty() ? 0 : 1;
    int regions = 0;
    for (const Contact& c : hit.contacts) {
      regions = std::max(regions, c.region + 1);
      const double distance = (centre - c.point).norm();
      CHECK(c.depth == Approx(radius - distance).margin(1e-9));
      CHECK(c.depth >= -eps - 1e-12);
      if (f.region.contains(c.uv_a)) continue;
      // Not inside the trims: the edge contact, on the edge, facing the centre.
      ++edge_contacts;
      CHECK(edge_distance(f.samples, c.point) < 1e-3);
      CHECK((c.normal - (centre - c.point) / distance).norm() < 1e-12);
    }
    CHECK(regions == hit.region_count);
  }
  WARN(touching << " of 400 spheres touch, " << edge_contacts << " edge contacts, " << clear
                << " clear of the material by brute force");
  CHECK(edge_contacts > 20);
  CHECK(clear > 50);
}

TEST_CASE("a sphere keeps max_contacts contacts on the material, not before the trims",
          "[collision][trim]") {
  // Kept to max_contacts after the trims leave out the contacts off the
  // material: as many as the material has, up to max_contacts, and each of
  // them one of the material's.
  Fixture f;
  const double eps = 0.01, radius = 3.0;
  std::mt19937_64 rng(21);
  int capped = 0;
  for (const Eigen::Vector3d& centre : query_points(f, rng, 400)) {
    CAPTURE(centre.x(), centre.y(), centre.z());
    const CollisionResult all =
        collide_sphere(f.trimmed(), centre, radius, {.tolerance = eps, .max_contacts = 100000});
    const CollisionResult few =
        collide_sphere(f.trimmed(), centre, radius, {.tolerance = eps, .max_contacts = 2});
    REQUIRE(all.status.ok());
    REQUIRE(few.status.ok());
    CHECK(few.contacts.size() == std::min<std::size_t>(2, all.contacts.size()));
    for (const Contact& c : few.contacts)
      CHECK(std::any_of(all.contacts.begin(), all.contacts.end(),
                        [&c](const Contact& a) { return a.uv_a == c.uv_a; }));
    capped += all.contacts.size() > 2 ? 1 : 0;
  }
  WARN(capped << " of 400 spheres have more than 2 contacts on the material");
  CHECK(capped > 20);
}

TEST_CASE("an untrimmed TrimmedSurface answers as the whole surface", "[collision][trim]") {
  Fixture f;
  const TrimRegion whole;
  const TrimmedSurface untrimmed{&f.hierarchy, &whole};
  const Eigen::Vector3d p(20.0, 10.0, 8.0);
  const ClosestPoint a = closest_point(untrimmed, p, {.tolerance = 1e-3});
  const ClosestPoint b = closest_point(f.hierarchy, p, {.tolerance = 1e-3});
  CHECK(a.uv == b.uv);
  CHECK_FALSE(a.on_edge);
  const CollisionResult ca = collide_sphere(untrimmed, p, 9.0, {.tolerance = 1e-3});
  const CollisionResult cb = collide(f.hierarchy, *make_sphere(p, 9.0), {.tolerance = 1e-3});
  REQUIRE(ca.contacts.size() == cb.contacts.size());
  for (std::size_t k = 0; k < ca.contacts.size(); ++k)
    CHECK(ca.contacts[k].uv_a == cb.contacts[k].uv_a);
}

}  // namespace argil

namespace argil {

TEST_CASE("under a hole the closest material may be another valley, not the hole's rim",
          "[collision][trim]") {
  // A plate raised along its ends and middle: two valleys. From a point far
  // below, the nearer valley wins untrimmed; a hole then removes it, and the
  // answer is the other valley, nearer than the hole's rim (the second search).
  BSplineSurface plate = test::asymmetric_plate(90.0, 0.0);
  for (int j = 0; j < 5; ++j)
    for (const int i : {0, 3, 6}) plate.control_points(plate.pole_index(i, j), 2) = 10.0;
  OperatorCache cache;
  SurfaceHierarchy h = SurfaceHierarchy::build(plate, cache).value();
  const double eps = 1e-4;
  const Eigen::Vector3d p(44.0, 45.0, -60.0);
  const ClosestPoint whole = closest_point(h, p, {.tolerance = eps});
  REQUIRE(whole.point.x() > 50.0);  // the right valley
  const ParamRect d = domain_of(plate);
  const std::vector<TrimLoop> loops{test::rectangle_loop(d.lower(), d.upper(), true),
                                    test::ellipse_loop(whole.uv, 0.2, 0.3, false)};
  const TrimRegion region = TrimRegion::create(loops).value();
  REQUIRE_FALSE(region.contains(whole.uv));
  const ClosestPoint cp = closest_point(TrimmedSurface{&h, &region}, p, {.tolerance = eps});
  CHECK_FALSE(cp.on_edge);
  CHECK(region.contains(cp.uv));
  CHECK(cp.point.x() < 40.0);  // the left valley
  const Samples s = sample(plate, loops, region);
  CHECK(cp.distance < nearest(s.edge, p));  // nearer than the rim
  CHECK(cp.distance <= nearest(s.material, p) + eps);
}

}  // namespace argil
