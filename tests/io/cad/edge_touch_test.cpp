// Faces of a real solid that meet edge to edge: both end at the CAD edge, so
// neither crosses the other. The query reports the edge as contacts of depth
// 0, not as hundreds of curve pieces shorter than eps (screw.step's faces 3, 4
// and 5 against face 6 gave up to 350), and no point of the edge, found by
// OpenCASCADE's projection, is left far from what it reports. Refined, the
// edge is one curve on both surfaces (it once came out in 80 to 170 pieces).
#include <GeomAPI_ProjectPointOnSurf.hxx>
#include <Geom_BSplineSurface.hxx>

#include <algorithm>
#include <catch2/catch.hpp>
#include <limits>
#include <vector>

#include "argil/core.hpp"
#include "argil/io.hpp"
#include "support/built_hierarchy.hpp"
#include "support/occt_surface.hpp"
#include "support/polyline_distance.hpp"
#include "test_files.hpp"

namespace argil::io {
namespace {

/// Points of a's four boundary curves (`per_side` each) that lie within
/// `within` of b by OpenCASCADE's projection onto b: the shared edge.
std::vector<Eigen::Vector3d> shared_edge(const BSplineSurface& a, const BSplineSurface& b,
                                         int per_side, double within) {
  const Handle(Geom_BSplineSurface) ob = test::to_occt(b);
  const double u0 = a.domain_start(Direction::u), u1 = a.domain_end(Direction::u);
  const double v0 = a.domain_start(Direction::v), v1 = a.domain_end(Direction::v);
  std::vector<Eigen::Vector3d> edge;
  for (int k = 0; k <= per_side; ++k) {
    const double t = static_cast<double>(k) / per_side;
    const double u = u0 + t * (u1 - u0), v = v0 + t * (v1 - v0);
    for (const Eigen::Vector3d& p :
         {evaluate(a, u, v0), evaluate(a, u, v1), evaluate(a, u0, v), evaluate(a, u1, v)}) {
      GeomAPI_ProjectPointOnSurf projection(gp_Pnt(p.x(), p.y(), p.z()), ob);
      if (projection.NbPoints() > 0 && projection.LowerDistance() <= within) edge.push_back(p);
    }
  }
  return edge;
}

/// The largest sphere radius of the leaves the surface-pair descent stops at
/// (the first nodes flat to eps/3, or less than eps/3 across) among those
/// whose spheres reach one of `points`.
double largest_leaf_radius_near(const SurfaceHierarchy& h,
                                const std::vector<Eigen::Vector3d>& points, double eps) {
  double largest = 0.0;
  std::vector<int> open(h.roots().begin(), h.roots().end());
  while (!open.empty()) {
    const int id = open.back();
    open.pop_back();
    const PatchBound b = h.node(id).bound;  // child() may move the node
    const bool near = std::any_of(points.begin(), points.end(), [&](const Eigen::Vector3d& p) {
      return (p - b.center).norm() <= b.radius;
    });
    if (!near) continue;
    if (b.flatness <= eps / 3.0 || 2.0 * b.radius <= eps / 3.0 ||
        h.node(id).level >= SurfaceHierarchy::kMaxLevel) {
      largest = std::max(largest, b.radius);
      continue;
    }
    for (int half_u = 0; half_u < 2; ++half_u)
      for (int half_v = 0; half_v < 2; ++half_v) open.push_back(h.child(id, half_u, half_v));
  }
  return largest;
}

double distance_to_reported(const Eigen::Vector3d& p, const CollisionResult& r) {
  double best = std::numeric_limits<double>::infinity();
  for (const Contact& c : r.contacts) best = std::min(best, (c.point - p).norm());
  for (const IntersectionCurve& c : r.curves)
    for (const Eigen::Vector3d& q : c.points) best = std::min(best, (q - p).norm());
  return best;
}

/// How many points of curve i lie within `within` of another curve.
int points_beside_other_curves(const CollisionResult& r, std::size_t i, double within) {
  int beside = 0;
  for (const Eigen::Vector3d& p : r.curves[i].points)
    for (std::size_t j = 0; j < r.curves.size(); ++j)
      if (j != i && test::distance_to_polyline(p, r.curves[j].points) <= within) {
        ++beside;
        break;
      }
  return beside;
}

}  // namespace

TEST_CASE("faces that meet edge to edge touch along the edge, with no curve shorter than eps",
          "[io][collision]") {
  Result<Model> read = read_model(test::shared_data("screw.step"));
  REQUIRE(read.ok());
  const Model& model = read.value();
  REQUIRE(model.faces.size() == 10);
  const SurfaceHierarchy h6 = test::hierarchy_for(model.faces[6].surface);
  for (const int face : {3, 4, 5}) {
    const BSplineSurface& a = model.faces[static_cast<std::size_t>(face)].surface;
    const SurfaceHierarchy ha = test::hierarchy_for(a);
    const double eps = 1e-4 * std::max(control_point_box(a).diagonal(),
                                       control_point_box(model.faces[6].surface).diagonal());
    const std::vector<Eigen::Vector3d> edge =
        shared_edge(a, model.faces[6].surface, 2000, eps / 3.0);
    for (const bool refine : {false, true}) {
      INFO("face " << face << " against face 6, eps " << eps << (refine ? " refined" : ""));
      const CollisionResult r = collide(
          ha, h6,
          {.tolerance = eps, .max_contacts = std::numeric_limits<int>::max(), .refine = refine});
      REQUIRE(r.status.ok());
      for (const IntersectionCurve& c : r.curves) CHECK(c.length() > eps);
      // No stretch of the edge comes out twice, as pieces side by side (a
      // piece's end may touch its neighbour's).
      for (std::size_t i = 0; i < r.curves.size(); ++i)
        CHECK(points_beside_other_curves(r, i, eps / 2.0) <= 2);
      // The edge is a stretch, not a point, and the query found it.
      REQUIRE(edge.size() >= 100);
      REQUIRE_FALSE(r.contacts.empty());
      // Each edge point lies in a leaf pair that reports a contact on (or,
      // for a near touch, within eps of) its leaf of a: within that leaf's
      // sphere diameter plus eps.
      double farthest = 0.0;
      for (const Eigen::Vector3d& p : edge)
        farthest = std::max(farthest, distance_to_reported(p, r));
      const double leaf = largest_leaf_radius_near(ha, edge, eps);
      INFO("edge points " << edge.size() << ", farthest from the reported set " << farthest
                          << ", largest leaf radius " << leaf);
      CHECK(farthest <= 2.0 * leaf + eps);
      if (!refine) continue;
      // The refined edge: one curve through every edge point, each of its
      // points on both surfaces by OpenCASCADE's projection.
      REQUIRE(r.curves.size() == 1);
      double off_curve = 0.0;
      for (const Eigen::Vector3d& p : edge)
        off_curve = std::max(off_curve, test::distance_to_polyline(p, r.curves[0].points));
      CHECK(off_curve <= eps);
      double off_surfaces = 0.0;
      for (const BSplineSurface* s : {&a, &model.faces[6].surface}) {
        const Handle(Geom_BSplineSurface) os = test::to_occt(*s);
        for (const Eigen::Vector3d& q : r.curves[0].points) {
          GeomAPI_ProjectPointOnSurf projection(gp_Pnt(q.x(), q.y(), q.z()), os);
          REQUIRE(projection.NbPoints() > 0);
          off_surfaces = std::max(off_surfaces, projection.LowerDistance());
        }
      }
      CHECK(off_surfaces <= eps);
    }
  }
}

}  // namespace argil::io
