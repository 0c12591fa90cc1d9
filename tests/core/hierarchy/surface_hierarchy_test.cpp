// SurfaceHierarchy and its PatchBound on generated surfaces and the asymmetric
// one: bounds are conservative against dense samples of the B-spline itself,
// children tile their parent, and bounds follow new control points.
#include <catch2/catch.hpp>
#include <random>
#include <vector>

#include "argil/core/geometry/evaluate.hpp"
#include "argil/core/hierarchy/surface_hierarchy.hpp"
#include "support/random_surface.hpp"

namespace argil {
namespace {

constexpr int kSamples = 9;  // per side of a node's rectangle
constexpr int kDepth = 2;    // levels grown below each root

// Bounds are computed from control points with a few roundings; the samples
// come from an independent evaluation path. 1e-10 of the model size covers both.
double tolerance_mm(const BSplineSurface& s) { return 1e-10 * control_point_box(s).diagonal(); }

// The generated surfaces: the asymmetric one (polynomial and rational) and
// random ones of degrees 1..5 with repeated knots, half of them rational.
std::vector<BSplineSurface> test_surfaces() {
  std::vector<BSplineSurface> out{test::asymmetric_surface(false), test::asymmetric_surface(true)};
  std::mt19937_64 rng(2718);
  for (int k = 0; k < 8; ++k) {
    test::RandomSurfaceOptions options;
    options.rational = k % 2 == 1;
    options.max_extra_poles = 3;
    out.push_back(test::random_surface(rng, options));
  }
  return out;
}

// Every node from the roots down to kDepth levels, created on the way.
std::vector<int> grow(const SurfaceHierarchy& h) {
  std::vector<int> ids = h.roots();
  for (std::size_t k = 0; k < ids.size(); ++k) {
    const HierarchyNode& n = h.node(ids[k]);
    if (n.level == kDepth) continue;
    const int id = ids[k];
    for (int hu = 0; hu < 2; ++hu) {
      for (int hv = 0; hv < 2; ++hv) ids.push_back(h.child(id, hu, hv));
    }
  }
  return ids;
}

// The surface at local (s, t) in [0, 1]^2 of `rect`.
Eigen::Vector3d sample(const BSplineSurface& s, const ParamRect& rect, double a, double b) {
  return evaluate(s, rect.u0 + a * rect.width(), rect.v0 + b * rect.height());
}

// The two corner triangles (c00, c10, c11) and (c00, c11, c01) at the same (s, t).
Eigen::Vector3d corner_triangles(const PatchBound& bound, double s, double t) {
  const auto& [c00, c10, c01, c11] = bound.corners;
  if (s >= t) return c00 + s * (c10 - c00) + t * (c11 - c10);
  return c00 + t * (c01 - c00) + s * (c11 - c01);
}

// Checks sphere, box and flatness of node `id` against samples of `surface`.
void check_node_contains_samples(const SurfaceHierarchy& h, int id, const BSplineSurface& surface) {
  const HierarchyNode n = h.node(id);
  const double tol = tolerance_mm(surface);
  INFO("node " << id << " level " << n.level << " rect [" << n.rect.u0 << ", " << n.rect.u1
               << "] x [" << n.rect.v0 << ", " << n.rect.v1 << "]");
  double worst_sphere = -1e300, worst_box = -1e300, worst_flat = -1e300;
  for (int i = 0; i < kSamples; ++i) {
    for (int j = 0; j < kSamples; ++j) {
      const double a = i / (kSamples - 1.0), b = j / (kSamples - 1.0);
      const Eigen::Vector3d x = sample(surface, n.rect, a, b);
      worst_sphere = std::max(worst_sphere, (x - n.bound.center).norm() - n.bound.radius);
      worst_box = std::max(worst_box, (n.bound.box.min - x).maxCoeff());
      worst_box = std::max(worst_box, (x - n.bound.box.max).maxCoeff());
      worst_flat =
          std::max(worst_flat, (x - corner_triangles(n.bound, a, b)).norm() - n.bound.flatness);
    }
  }
  CHECK(worst_sphere <= tol);
  CHECK(worst_box <= tol);
  CHECK(worst_flat <= tol);
}

double area(const ParamRect& r) { return r.width() * r.height(); }

bool interiors_overlap(const ParamRect& a, const ParamRect& b) {
  return a.u0 < b.u1 && b.u0 < a.u1 && a.v0 < b.v1 && b.v0 < a.v1;
}

}  // namespace

TEST_CASE("every node's sphere, box and flatness contain dense samples of its sub-patch",
          "[hierarchy]") {
  OperatorCache cache;
  int index = 0;
  for (const BSplineSurface& s : test_surfaces()) {
    INFO("surface " << index++ << " degree " << s.degree[0] << "x" << s.degree[1]
                    << (s.is_rational() ? " rational" : ""));
    const Result<SurfaceHierarchy> h = SurfaceHierarchy::build(s, cache);
    REQUIRE(h.status().message == "");
    for (int id : grow(h.value())) check_node_contains_samples(h.value(), id, s);
  }
}

TEST_CASE("the block over every element bounds the whole surface", "[hierarchy]") {
  OperatorCache cache;
  for (const BSplineSurface& s : test_surfaces()) {
    const Result<SurfaceHierarchy> h = SurfaceHierarchy::build(s, cache);
    REQUIRE(h.ok());
    const ElementBlock& top = h.value().block(0);
    const double tol = tolerance_mm(s);
    for (int i = 0; i <= 20; ++i) {
      for (int j = 0; j <= 20; ++j) {
        const Eigen::Vector3d x = sample(s, domain_of(s), i / 20.0, j / 20.0);
        CHECK((x - top.bound.center).norm() <= top.bound.radius + tol);
        CHECK((top.bound.box.min - x).maxCoeff() <= tol);
        CHECK((x - top.bound.box.max).maxCoeff() <= tol);
      }
    }
  }
}

TEST_CASE("roots tile the domain and children's rectangles tile their parent", "[hierarchy]") {
  OperatorCache cache;
  for (const BSplineSurface& s : test_surfaces()) {
    const Result<SurfaceHierarchy> built = SurfaceHierarchy::build(s, cache);
    REQUIRE(built.ok());
    const SurfaceHierarchy& h = built.value();
    // Roots: disjoint interiors whose areas add up to the domain's.
    double root_area = 0.0;
    for (int a : h.roots()) {
      root_area += area(h.node(a).rect);
      for (int b : h.roots()) {
        if (a < b) CHECK_FALSE(interiors_overlap(h.node(a).rect, h.node(b).rect));
      }
    }
    CHECK(root_area == Approx(area(domain_of(s))).epsilon(1e-12));  // sums of knot products
    for (int id : grow(h)) {
      const HierarchyNode parent = h.node(id);
      if (parent.level == kDepth) continue;
      std::array<ParamRect, 4> quarters;
      for (int hu = 0; hu < 2; ++hu) {
        for (int hv = 0; hv < 2; ++hv) {
          const HierarchyNode c = h.node(h.child(id, hu, hv));
          CHECK(c.parent == id);
          CHECK(c.level == parent.level + 1);
          quarters[static_cast<std::size_t>(hu * 2 + hv)] = c.rect;
        }
      }
      // Exact tiling: the outer corners are the parent's, the inner ones meet at its centre.
      const auto& [q00, q01, q10, q11] = quarters;
      CHECK(q00.lower() == parent.rect.lower());
      CHECK(q11.upper() == parent.rect.upper());
      CHECK(q00.upper() == parent.rect.centre());
      CHECK(q11.lower() == parent.rect.centre());
      CHECK(Eigen::Vector2d(q10.u0, q10.v1) == Eigen::Vector2d(parent.rect.centre()[0], q00.v1));
      CHECK(Eigen::Vector2d(q01.u1, q01.v0) == Eigen::Vector2d(q00.u1, parent.rect.centre()[1]));
      CHECK(q10.u1 == parent.rect.u1);
      CHECK(q10.v0 == parent.rect.v0);
      CHECK(q01.u0 == parent.rect.u0);
      CHECK(q01.v1 == parent.rect.v1);
    }
  }
}

TEST_CASE("after set_control_points the grown nodes bound the new net's samples", "[hierarchy]") {
  OperatorCache cache;
  std::mt19937_64 rng(314);
  std::normal_distribution<double> push(0.0, 1.0);
  std::uniform_real_distribution<double> weight(0.5, 2.0);
  for (const BSplineSurface& s : test_surfaces()) {
    const Result<SurfaceHierarchy> built = SurfaceHierarchy::build(s, cache);
    REQUIRE(built.ok());
    SurfaceHierarchy h = built.value();
    const std::vector<int> ids = grow(h);  // nodes exist and are fresh for the old net
    BSplineSurface moved = s;
    const double scale = 0.2 * control_point_box(s).diagonal();
    moved.control_points +=
        scale * ControlNet::NullaryExpr(s.control_points.rows(), 3, [&] { return push(rng); });
    if (s.is_rational()) {
      moved.weights = Eigen::VectorXd::NullaryExpr(s.weights.size(), [&] { return weight(rng); });
    }
    const std::uint64_t before = h.version();
    h.set_control_points(moved.control_points, moved.weights);
    CHECK(h.version() != before);
    for (int id : ids) check_node_contains_samples(h, id, moved);
  }
}

TEST_CASE("moving one control point makes only the elements of its support stale", "[hierarchy]") {
  OperatorCache cache;
  std::mt19937_64 rng(99);
  std::normal_distribution<double> push(0.0, 1.0);
  for (const BSplineSurface& s : test_surfaces()) {
    Result<SurfaceHierarchy> built = SurfaceHierarchy::build(s, cache);
    REQUIRE(built.ok());
    SurfaceHierarchy h = std::move(built).value();
    const std::vector<int> ids = grow(h);
    // The same points again: nothing is stale, nothing refreshes.
    const std::uint64_t version = h.version();
    h.set_control_points(s.control_points, s.weights);
    CHECK(h.version() == version);
    CHECK(h.stale_elements() == 0);
    QueryCounters same;
    for (int id : ids) (void)h.node(id, &same);
    CHECK(same.nodes_refreshed == 0);
    // One interior pole moved: the elements whose span holds it go stale.
    const int nu = s.count(Direction::u), nv = s.count(Direction::v);
    const int pi = nu / 2, pj = nv / 2;
    BSplineSurface moved = s;
    moved.control_points.row(moved.pole_index(pi, pj)) +=
        0.1 * control_point_box(s).diagonal() * Eigen::RowVector3d(push(rng), push(rng), push(rng));
    h.set_control_points(moved.control_points, moved.weights);
    int expected = 0;
    const int p = s.degree[0], q = s.degree[1];
    std::vector<char> touched;
    for (int eu = p; eu < nu; ++eu) {
      if (!(s.knots[0][eu] < s.knots[0][eu + 1])) continue;
      for (int ev = q; ev < nv; ++ev) {
        if (!(s.knots[1][ev] < s.knots[1][ev + 1])) continue;
        const bool in = eu - p <= pi && pi <= eu && ev - q <= pj && pj <= ev;
        expected += in ? 1 : 0;
        touched.push_back(in ? 1 : 0);
      }
    }
    CHECK(h.stale_elements() == expected);
    CHECK(expected < static_cast<int>(h.roots().size()) + 1);
    // Nodes of untouched elements refresh nothing; every bound holds the moved surface.
    QueryCounters untouched;
    for (int id : ids) {
      const HierarchyNode& n = h.node(id);
      const std::size_t element = static_cast<std::size_t>(n.element_u) *
                                      static_cast<std::size_t>(h.operators().v->element_count()) +
                                  static_cast<std::size_t>(n.element_v);
      if (!touched[element]) (void)h.node(id, &untouched);
    }
    CHECK(untouched.nodes_refreshed == 0);
    for (int id : ids) check_node_contains_samples(h, id, moved);
    const ElementBlock& top = h.block(0);
    const Eigen::Vector3d far = moved.control_points.row(moved.pole_index(pi, pj)).transpose();
    CHECK((top.bound.box.min.array() <= far.array()).all());
    CHECK((far.array() <= top.bound.box.max.array()).all());
  }
}

}  // namespace argil
