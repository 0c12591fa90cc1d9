// Numerical extremes (docs/range.md): every case either stays finite
// and agrees with OpenCASCADE (and brute force) within its stated tolerance,
// or is refused by validate() because it lies outside the documented range.
// Each TEST_CASE is one row of the list; each SECTION names the value.
#include <GeomAPI_ProjectPointOnSurf.hxx>
#include <GeomLib.hxx>
#include <Geom_BSplineSurface.hxx>
#include <gp_Dir.hxx>
#include <gp_Pnt.hxx>
#include <gp_Pnt2d.hxx>
#include <gp_Vec.hxx>

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "argil/core.hpp"
#include "support/occt_surface.hpp"
#include "support/random_surface.hpp"

namespace argil {
namespace {

using test::to_occt;

Eigen::Vector3d eig(const gp_Pnt& p) { return {p.X(), p.Y(), p.Z()}; }
Eigen::Vector3d eig(const gp_Vec& v) { return {v.X(), v.Y(), v.Z()}; }
Eigen::Vector3d eig(const gp_Dir& v) { return {v.X(), v.Y(), v.Z()}; }

bool finite(const SurfaceDerivatives& d) {
  return d.point.allFinite() && d.du.allFinite() && d.dv.allFinite() && d.duu.allFinite() &&
         d.duv.allFinite() && d.dvv.allFinite();
}

/// Clamped knots of `degree` on [a, b] with the given interior knots.
Eigen::VectorXd clamped(int degree, double a, double b, const std::vector<double>& interior) {
  Eigen::VectorXd k(static_cast<Eigen::Index>(interior.size()) + 2 * (degree + 1));
  Eigen::Index i = 0;
  for (int c = 0; c <= degree; ++c) k[i++] = a;
  for (double t : interior) k[i++] = t;
  for (int c = 0; c <= degree; ++c) k[i++] = b;
  return k;
}

/// `n` - degree - 1 uniform interior knots on [a, b].
std::vector<double> uniform_interior(int degree, int count, double a, double b) {
  std::vector<double> t;
  const int spans = count - degree;
  for (int s = 1; s < spans; ++s) t.push_back(a + (b - a) * s / spans);
  return t;
}

/// A wavy net over [0, size]^2 (z amplitude size / 5), asymmetric in u and v.
ControlNet wavy_net(int nu, int nv, double size) {
  ControlNet net(static_cast<Eigen::Index>(nu) * nv, 3);
  for (int i = 0; i < nu; ++i) {
    for (int j = 0; j < nv; ++j) {
      const double x = nu > 1 ? double(i) / (nu - 1) : 0.0;
      const double y = nv > 1 ? double(j) / (nv - 1) : 0.0;
      net.row(static_cast<Eigen::Index>(i) * nv + j) << size * (x + 0.03 * std::sin(7.0 * y)),
          size * (y + 0.02 * std::cos(5.0 * x)),
          0.2 * size * std::sin(3.1 * x + 0.4) * std::cos(2.3 * y - 0.2);
    }
  }
  return net;
}

BSplineSurface surface(int p, int q, Eigen::VectorXd ku, Eigen::VectorXd kv, double size = 100.0) {
  BSplineSurface s;
  s.degree = {p, q};
  s.knots = {std::move(ku), std::move(kv)};
  s.control_points = wavy_net(s.count(Direction::u), s.count(Direction::v), size);
  return s;
}

/// Parameters to test in direction d: domain ends, every distinct knot (at
/// most ~40 of them, evenly chosen), midpoints of the shortest span, random.
std::vector<double> sample_params(const BSplineSurface& s, Direction d, std::mt19937_64& rng,
                                  int random_count) {
  const Eigen::VectorXd& k = s.knots_in(d);
  const double a = s.domain_start(d), b = s.domain_end(d);
  std::vector<double> t{a, b};
  std::vector<double> distinct;
  for (Eigen::Index i = 0; i < k.size(); ++i) {
    if (distinct.empty() || k[i] != distinct.back()) distinct.push_back(k[i]);
  }
  const std::size_t stride = std::max<std::size_t>(1, distinct.size() / 40);
  for (std::size_t i = 0; i < distinct.size(); i += stride) t.push_back(distinct[i]);
  double shortest = b - a, at = a;
  for (std::size_t i = 0; i + 1 < distinct.size(); ++i) {
    if (distinct[i + 1] - distinct[i] < shortest) {
      shortest = distinct[i + 1] - distinct[i];
      at = distinct[i];
    }
  }
  t.push_back(at + 0.5 * shortest);
  t.push_back(at + 0.25 * shortest);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int r = 0; r < random_count; ++r) t.push_back(a + (b - a) * unit(rng));
  return t;
}

/// (sum |N'_i(t)|, sum |N''_i(t)|): the size of derivative terms in direction d.
std::pair<double, double> term_scale(const BSplineSurface& s, Direction d, double t) {
  const int p = s.degree_in(d);
  const int span = find_span(p, s.knots_in(d), s.count(d), t);
  const Eigen::MatrixXd n = basis_derivatives(p, s.knots_in(d), span,
                                              std::clamp(t, s.domain_start(d), s.domain_end(d)), 2);
  return {n.row(1).cwiseAbs().sum(), n.row(2).cwiseAbs().sum()};
}

/// Worst errors against OpenCASCADE over the sample grid, each relative to the
/// scale its rounding grows with.
struct OracleErrors {
  double point = 0.0;   // / largest |P| (coordinates far from the origin round at their size)
  double d1 = 0.0;      // / (sum |N'| max |P|), the terms that cancel into S_u
  double d2 = 0.0;      // / (sum |N''| max |P|, sum |N'| sum |N'| max |P|)
  double normal = 0.0;  // angle [rad] minus the bound that the D1 error allows
  double normal_angle = 0.0;
  int normals = 0;        // normals compared (OpenCASCADE's defined)
  int limit_normals = 0;  // of which at singular points (OpenCASCADE from D2)
  bool finite = true;
};

OracleErrors compare_with_occt(const BSplineSurface& s, std::mt19937_64& rng, int random_count,
                               double weight_ratio = 1.0) {
  const Handle(Geom_BSplineSurface) oc = to_occt(s);
  const double pole_size = s.control_points.cwiseAbs().maxCoeff();
  OracleErrors e;
  for (double u : sample_params(s, Direction::u, rng, random_count)) {
    for (double v : sample_params(s, Direction::v, rng, random_count)) {
      gp_Pnt p;
      gp_Vec du, dv, duu, dvv, duv;
      oc->D2(u, v, p, du, dv, duu, dvv, duv);
      const SurfaceDerivatives d = evaluate_derivatives(s, u, v, 2);
      const Eigen::Vector3d n = unit_normal(s, u, v);
      e.finite = e.finite && finite(d) && n.allFinite();
      const auto [su1, su2] = term_scale(s, Direction::u, u);
      const auto [sv1, sv2] = term_scale(s, Direction::v, v);
      // Rational quotients amplify rounding by up to the weight ratio.
      const double d1_scale = weight_ratio * pole_size * std::max(su1, sv1);
      const double d2_scale = weight_ratio * weight_ratio * pole_size *
                              std::max({su2, sv2, su1 * sv1, su1 * su1, sv1 * sv1});
      e.point = std::max(e.point, (d.point - eig(p)).norm() / pole_size);
      e.d1 =
          std::max({e.d1, (d.du - eig(du)).norm() / d1_scale, (d.dv - eig(dv)).norm() / d1_scale});
      e.d2 = std::max({e.d2, (d.duu - eig(duu)).norm() / d2_scale,
                       (d.duv - eig(duv)).norm() / d2_scale, (d.dvv - eig(dvv)).norm() / d2_scale});
      gp_Dir on;
      // NormEstim takes a tangent of length below tol as vanished (and uses D2
      // there), and |D1U x D1V| below tol^2 as no normal: scale it to the model.
      const double tol = 1e-8 * std::max(eig(du).norm(), eig(dv).norm());
      const int status = GeomLib::NormEstim(oc, gp_Pnt2d(u, v), tol, on);
      if (status > 1) continue;  // OpenCASCADE has no normal here either
      ++e.normals;
      if (status == 1) ++e.limit_normals;
      REQUIRE(n.norm() > 0.5);  // ours is defined wherever OpenCASCADE's is
      const double angle = std::atan2(n.cross(eig(on)).norm(), n.dot(eig(on)));
      e.normal_angle = std::max(e.normal_angle, angle);
      // The angle a D1 error of 1e-12 of its scale can cause, plus rounding.
      const double cross = eig(du).cross(eig(dv)).norm();
      const double allowed =
          status == 0 ? 1e-12 * d1_scale * (eig(du).norm() + eig(dv).norm()) / cross + 1e-13
                      : 1e-6;  // a limit normal: OpenCASCADE estimates it from D2 numerically
      e.normal = std::max(e.normal, angle - allowed);
    }
  }
  return e;
}

/// Largest |fitted - original| / max |P| of fit_control_points(evaluate_nodes()).
double fit_round_trip_error(const BSplineSurface& s, OperatorCache& cache, double* condition) {
  const Result<SurfaceOperators> ops = surface_operators(s, cache);
  REQUIRE(ops.ok());
  const ControlNet nodes = evaluate_nodes(s, ops.value());
  const ControlNet fitted = fit_control_points(s, ops.value(), nodes);
  REQUIRE(fitted.allFinite());
  *condition = ops.value().u->collocation_condition() * ops.value().v->collocation_condition();
  return (fitted - s.control_points).cwiseAbs().maxCoeff() / s.control_points.cwiseAbs().maxCoeff();
}

/// Largest distance by which sampled surface points stick out of their node's
/// sphere or box (negative: inside), relative to max |P|, over every element
/// root (at most `max_elements`) and its children down to `levels`.
double worst_bound_violation(SurfaceHierarchy& h, int max_elements, int levels) {
  const BSplineSurface& s = h.surface();
  const double pole_size = s.control_points.cwiseAbs().maxCoeff();
  double worst = -std::numeric_limits<double>::infinity();
  std::vector<int> stack;
  const std::size_t stride =
      std::max<std::size_t>(1, h.roots().size() / static_cast<std::size_t>(max_elements));
  for (std::size_t r = 0; r < h.roots().size(); r += stride) stack.push_back(h.roots()[r]);
  while (!stack.empty()) {
    const int id = stack.back();
    stack.pop_back();
    const HierarchyNode& node = h.node(id);
    const PatchBound bound = node.bound;
    REQUIRE(std::isfinite(bound.radius));
    REQUIRE(std::isfinite(bound.flatness));
    for (int a = 0; a <= 4; ++a) {
      for (int b = 0; b <= 4; ++b) {
        const double u = node.rect.u0 + (node.rect.u1 - node.rect.u0) * a / 4.0;
        const double v = node.rect.v0 + (node.rect.v1 - node.rect.v0) * b / 4.0;
        const Eigen::Vector3d p = evaluate(s, u, v);
        worst = std::max(worst, ((p - bound.center).norm() - bound.radius) / pole_size);
        const Eigen::Vector3d out = (p - bound.box.max).cwiseMax(bound.box.min - p).cwiseMax(0.0);
        worst = std::max(worst, out.maxCoeff() / pole_size);
      }
    }
    const int level = node.level;
    if (level < levels) {
      for (int hu = 0; hu < 2; ++hu) {
        for (int hv = 0; hv < 2; ++hv) stack.push_back(h.child(id, hu, hv));
      }
    }
  }
  return worst;
}

/// Closest points from points off the surface: certified within eps of
/// OpenCASCADE's projection and of a dense brute-force sampling, distance
/// consistent with the point returned. Returns the worst |ours - OCCT| / size.
double check_closest_points(SurfaceHierarchy& h, double eps, std::mt19937_64& rng,
                            bool with_occt = true) {
  const BSplineSurface& s = h.surface();
  const double size = control_point_box(s).diagonal();
  const Handle(Geom_BSplineSurface) oc = to_occt(s);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  double worst = 0.0;
  for (int k = 0; k < 4; ++k) {
    const double u =
        s.domain_start(Direction::u) +
        (0.1 + 0.8 * unit(rng)) * (s.domain_end(Direction::u) - s.domain_start(Direction::u));
    const double v =
        s.domain_start(Direction::v) +
        (0.1 + 0.8 * unit(rng)) * (s.domain_end(Direction::v) - s.domain_start(Direction::v));
    const SurfaceDerivatives d = evaluate_derivatives(s, u, v, 1);
    const Eigen::Vector3d n = unit_normal(d);
    const Eigen::Vector3d q = d.point + (k % 2 == 0 ? 0.01 : -0.003) * size * n;
    const ClosestPoint ours = closest_point(h, q, {.tolerance = eps});
    INFO("query (" << q.transpose() << ") eps " << eps);
    REQUIRE(ours.point.allFinite());
    REQUIRE(std::isfinite(ours.distance));
    REQUIRE(std::isfinite(ours.signed_distance));
    CHECK(std::abs((evaluate(s, ours.uv.x(), ours.uv.y()) - q).norm() - ours.distance) <=
          1e-12 * size + 1e-15 * s.control_points.cwiseAbs().maxCoeff());
    // The foot we started from is a candidate: ours is at most its distance + eps.
    CHECK(ours.distance <= (d.point - q).norm() + eps);
    if (with_occt) {
      GeomAPI_ProjectPointOnSurf projection(gp_Pnt(q.x(), q.y(), q.z()), oc);
      if (projection.NbPoints() > 0) {
        CHECK(ours.distance <= projection.LowerDistance() + eps);
        worst = std::max(worst, std::abs(ours.distance - projection.LowerDistance()) / size);
      }
    }
  }
  return worst;
}

/// All the per-surface checks of one case; `eval_tol` is the stated tolerance
/// of the relative evaluation errors (docs/range.md).
struct CaseReport {
  OracleErrors oracle;
  double fit = 0.0, condition = 0.0, bound = 0.0, closest = 0.0;
};

CaseReport check_surface(const BSplineSurface& s, std::mt19937_64& rng, double eval_tol = 1e-12,
                         double weight_ratio = 1.0, bool occt_projection = true) {
  INFO("degree " << s.degree[0] << "x" << s.degree[1] << " poles " << s.count(Direction::u) << "x"
                 << s.count(Direction::v) << (s.is_rational() ? " rational" : ""));
  REQUIRE(validate(s).ok());
  CaseReport r;
  r.oracle = compare_with_occt(s, rng, 6, weight_ratio);
  CHECK(r.oracle.finite);
  CHECK(r.oracle.point <= eval_tol);
  CHECK(r.oracle.d1 <= eval_tol);
  CHECK(r.oracle.d2 <= eval_tol);
  CHECK(r.oracle.normal <= 0.0);
  OperatorCache cache;
  r.fit = fit_round_trip_error(s, cache, &r.condition);
  // Two banded solves per direction: rounding grows with the condition numbers.
  CHECK(r.fit <= 1e-14 * r.condition * weight_ratio);
  Result<SurfaceHierarchy> h = SurfaceHierarchy::build(s, cache);
  REQUIRE(h.ok());
  r.bound = worst_bound_violation(h.value(), 64, 2);
  CHECK(r.bound <= 1e-13);  // conservative up to rounding of the Bezier nets
  const double size = control_point_box(s).diagonal();
  r.closest = check_closest_points(h.value(), 1e-6 * size, rng, occt_projection);
  return r;
}

void report(const std::string& name, const CaseReport& r) {
  WARN(name << ": vs OCCT D0 " << r.oracle.point << " D1 " << r.oracle.d1 << " D2 " << r.oracle.d2
            << " normal angle " << r.oracle.normal_angle << " rad (" << r.oracle.normals
            << " normals, " << r.oracle.limit_normals << " limits); fit " << r.fit << " (cond "
            << r.condition << "); bound excess " << r.bound << "; closest |ours-OCCT|/size "
            << r.closest);
}

}  // namespace

TEST_CASE("extremes: degrees 1 to 15 in both directions agree with OpenCASCADE", "[extremes]") {
  std::mt19937_64 rng(7);
  for (int p = 1; p <= 15; ++p) {
    DYNAMIC_SECTION("degree " << p) {
      const int q = 16 - p;  // every degree appears in u and in v
      const int nu = p + 4;  // and q + 4 in v
      BSplineSurface s = surface(p, q, clamped(p, -1.0, 2.5, uniform_interior(p, nu, -1.0, 2.5)),
                                 clamped(q, 0.0, 7.0, {0.5, 1.0, 3.5}));
      report("degree " + std::to_string(p) + "x" + std::to_string(q), check_surface(s, rng));
      s.weights = Eigen::VectorXd::LinSpaced(s.control_points.rows(), 0.5, 2.0);
      report("degree " + std::to_string(p) + "x" + std::to_string(q) + " rational",
             check_surface(s, rng, 1e-12, 4.0));
    }
  }
  SECTION("degree above kMaxDegree is refused") {
    BSplineSurface s = surface(2, 2, clamped(2, 0, 1, {}), clamped(2, 0, 1, {}));
    s.degree[0] = kMaxDegree + 1;
    s.knots[0] = clamped(kMaxDegree + 1, 0, 1, {});
    s.control_points = wavy_net(s.count(Direction::u), 3, 1.0);
    CHECK_THAT(validate(s).message, Catch::Contains("expected 1 to"));
  }
}

TEST_CASE("extremes: interior knots of full multiplicity (C0 seams) agree with OpenCASCADE",
          "[extremes]") {
  std::mt19937_64 rng(11);
  for (int p : {1, 2, 3, 5, 8}) {
    DYNAMIC_SECTION("C0 seams, degree " << p) {
      const int q = p == 1 ? 2 : p - 1;
      std::vector<double> ku, kv;
      for (int c = 0; c < p; ++c) ku.push_back(0.4);  // multiplicity p: C0 in u
      ku.push_back(0.7);
      for (int c = 0; c < q; ++c) kv.push_back(1.5);  // multiplicity q: C0 in v
      for (int c = 0; c < q; ++c) kv.push_back(2.0);
      BSplineSurface s = surface(p, q, clamped(p, 0.0, 1.0, ku), clamped(q, 0.0, 3.0, kv));
      report("C0 seams degree " + std::to_string(p) + "x" + std::to_string(q),
             check_surface(s, rng));
    }
  }
  SECTION("multiplicity degree + 1 (a discontinuity) is refused") {
    BSplineSurface s =
        surface(3, 2, clamped(3, 0.0, 1.0, {0.5, 0.5, 0.5, 0.5}), clamped(2, 0.0, 1.0, {}));
    CHECK_THAT(validate(s).message, Catch::Contains("allows at most"));
  }
}

TEST_CASE("extremes: knot spans down to 1e-9 of the domain agree with OpenCASCADE", "[extremes]") {
  std::mt19937_64 rng(13);
  for (double ratio : {1e-3, 1e-6, 1e-9}) {
    DYNAMIC_SECTION("shortest span " << ratio << " of the domain") {
      const double a = 2.0, b = 12.0, t = a + 0.37 * (b - a);
      BSplineSurface s = surface(
          3, 4, clamped(3, a, b, {a + 0.2 * (b - a), t, t + ratio * (b - a), a + 0.8 * (b - a)}),
          clamped(4, 0.0, 1.0, {0.5, 0.5 + ratio, 0.5 + 2 * ratio}));
      report("span " + std::to_string(ratio), check_surface(s, rng));
    }
  }
}

TEST_CASE("extremes: coordinates from 1e-6 mm to 1e6 mm and 1e7 mm from the origin", "[extremes]") {
  std::mt19937_64 rng(17);
  struct Placement {
    const char* name;
    double scale;
    double offset;
  };
  for (const Placement& place :
       {Placement{"size 1e-6 mm", 1e-8, 0.0}, Placement{"size 1e6 mm", 1e4, 0.0},
        Placement{"size 100 mm at 1e7 mm", 1.0, 1e7},
        Placement{"size 1e6 mm at 1e7 mm", 1e4, 1e7}}) {
    DYNAMIC_SECTION(place.name) {
      for (bool rational : {false, true}) {
        BSplineSurface s = test::asymmetric_surface(rational);
        s.control_points *= place.scale;
        s.control_points.rowwise() +=
            Eigen::RowVector3d(place.offset, -0.5 * place.offset, 0.25 * place.offset);
        report(std::string(place.name) + (rational ? " rational" : ""), check_surface(s, rng));
      }
    }
  }
}

TEST_CASE("extremes: weights from 1e-4 to 1e4 agree with OpenCASCADE", "[extremes]") {
  std::mt19937_64 rng(19);
  for (double spread : {1e2, 1e4}) {
    DYNAMIC_SECTION("weights in [1/" << spread << ", " << spread << "]") {
      // Rational derivatives lose accuracy in proportion to the weight ratio
      // (quotient rule: w_u S / w), in any double implementation.
      const double ratio = spread * spread;
      BSplineSurface s =
          surface(3, 2, clamped(3, 0.0, 1.0, {0.3, 0.6}), clamped(2, 0.0, 2.0, {1.0}));
      std::uniform_real_distribution<double> exponent(-1.0, 1.0);
      s.weights.resize(s.control_points.rows());
      for (Eigen::Index k = 0; k < s.weights.size(); ++k)
        s.weights[k] = std::pow(spread, exponent(rng));
      s.weights[0] = 1.0 / spread;
      s.weights[s.weights.size() - 1] = spread;
      report("weights spread " + std::to_string(spread), check_surface(s, rng, 1e-12, ratio));
    }
  }
}

TEST_CASE("extremes: control nets from 2x2 to 1000x1000", "[extremes]") {
  std::mt19937_64 rng(23);
  for (int n : {2, 10, 100, 1000}) {
    DYNAMIC_SECTION(n << "x" << n << " control points") {
      const int p = std::min(3, n - 1);
      BSplineSurface s = surface(p, p, clamped(p, 0.0, 1.0, uniform_interior(p, n, 0.0, 1.0)),
                                 clamped(p, 0.0, 1.0, uniform_interior(p, n, 0.0, 1.0)), 1000.0);
      // OpenCASCADE's projection samples every span (gigabytes at 1000x1000):
      // brute force only there.
      report(std::to_string(n) + "x" + std::to_string(n),
             check_surface(s, rng, 1e-12, 1.0, n <= 100));
    }
  }
}

namespace {

/// A quarter dome whose pole row collapses to one point: on the u = start edge
/// (`at_end` false) or the u = end edge; `swap` exchanges u and v.
BSplineSurface dome(int p, int q, bool at_end, bool swap, bool rational) {
  const int nu = p + 3, nv = q + 2;
  BSplineSurface s;
  s.degree = {p, q};
  s.knots = {clamped(p, 0.0, 1.0, uniform_interior(p, nu, 0.0, 1.0)),
             clamped(q, 0.0, 2.0, uniform_interior(q, nv, 0.0, 2.0))};
  s.control_points.resize(nu * nv, 3);
  for (int i = 0; i < nu; ++i) {
    const int ring = at_end ? nu - 1 - i : i;  // 0: the pole
    const double r = 40.0 * ring / (nu - 1);
    for (int j = 0; j < nv; ++j) {
      const double theta = 1.3 * j / (nv - 1) + 0.1;
      s.control_points.row(i * nv + j) << r * std::cos(theta), r * std::sin(theta),
          30.0 - 0.01 * r * r + 0.5 * ring * j;
    }
  }
  if (rational) s.weights = Eigen::VectorXd::LinSpaced(nu * nv, 0.6, 1.7);
  if (!swap) return s;
  BSplineSurface t;
  t.degree = {q, p};
  t.knots = {s.knots[1], s.knots[0]};
  t.control_points.resize(nu * nv, 3);
  if (rational) t.weights.resize(nu * nv);
  for (int i = 0; i < nu; ++i) {
    for (int j = 0; j < nv; ++j) {
      t.control_points.row(j * nu + i) = s.control_points.row(i * nv + j);
      if (rational) t.weights[j * nu + i] = s.weights[i * nv + j];
    }
  }
  return t;
}

}  // namespace

TEST_CASE("extremes: collapsed edges (poles) have limit normals that agree with OpenCASCADE",
          "[extremes]") {
  std::mt19937_64 rng(29);
  for (int variant = 0; variant < 8; ++variant) {
    const bool at_end = variant & 1, swap = variant & 2, rational = variant & 4;
    DYNAMIC_SECTION("pole on the " << (swap ? "v" : "u") << (at_end ? " end" : " start")
                                   << (rational ? ", rational" : "")) {
      const BSplineSurface s = dome(3, 2, at_end, swap, rational);
      const CaseReport r = check_surface(s, rng);
      CHECK(r.oracle.limit_normals > 0);  // the pole edge was sampled
      report("pole variant " + std::to_string(variant), r);
      // Independently of OpenCASCADE: the limit normal is the limit of the
      // interior normals approaching the edge.
      const Direction d = swap ? Direction::v : Direction::u;
      const double edge = at_end ? s.domain_end(d) : s.domain_start(d);
      const double inward = at_end ? -1.0 : 1.0;
      for (double t : {0.0, 0.3, 0.77, 1.0}) {
        const Direction o = other(d);
        const double across = s.domain_start(o) + t * (s.domain_end(o) - s.domain_start(o));
        const auto at = [&](double along) {
          return d == Direction::u ? unit_normal(s, along, across) : unit_normal(s, across, along);
        };
        const Eigen::Vector3d limit = at(edge);
        REQUIRE(limit.norm() == Approx(1.0));
        const Eigen::Vector3d near = at(edge + inward * 1e-7);
        // The normal turns by O(h) over a parameter step h (curvature bounded).
        CHECK(std::acos(std::min(1.0, limit.dot(near))) <= 1e-5);
      }
    }
  }
}

namespace {

/// z = h (1 - (x/a)^2 - (y/a)^2) over [-a, a]^2, exactly, as a 2x2 Bezier
/// patch (x and y linear in u and v): its apex (0, 0, h) is the highest point.
BSplineSurface paraboloid(double a, double h) {
  BSplineSurface s;
  s.degree = {2, 2};
  s.knots = {clamped(2, 0.0, 1.0, {}), clamped(2, 0.0, 1.0, {})};
  s.control_points.resize(9, 3);
  // Bernstein coefficients of (1 - x^2) on x = -1 + 2u: 0, 2, 0 (sum of both axes).
  const double c[3] = {0.0, 2.0, 0.0};
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      s.control_points.row(i * 3 + j) << a * (i - 1), a * (j - 1), h * (c[i] + c[j] - 1.0);
    }
  }
  return s;
}

/// A quarter cylinder of `radius` along y (rational quadratic in u, linear in
/// v): exact, its top line z = radius at x = 0.
BSplineSurface quarter_cylinder(double radius, double length) {
  BSplineSurface s;
  s.degree = {2, 1};
  s.knots = {clamped(2, 0.0, 1.0, {}), clamped(1, 0.0, 1.0, {})};
  s.control_points.resize(6, 3);
  const double w = std::sqrt(0.5);
  const Eigen::Vector3d arc[3] = {{-radius, 0, 0}, {-radius, 0, radius}, {0, 0, radius}};
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 2; ++j) {
      s.control_points.row(i * 2 + j) = (arc[i] + Eigen::Vector3d(0, length * j, 0)).transpose();
    }
  }
  s.weights.resize(6);
  s.weights << 1, 1, w, w, 1, 1;
  return s;
}

void require_finite(const CollisionResult& r) {
  for (const Contact& c : r.contacts) {
    REQUIRE(c.point.allFinite());
    REQUIRE(c.normal.allFinite());
    REQUIRE(c.tangent_u.allFinite());
    REQUIRE(c.tangent_v.allFinite());
    REQUIRE(std::isfinite(c.depth));
    REQUIRE(c.uv_a.allFinite());
    REQUIRE(c.uv_b.allFinite());
  }
  for (const IntersectionCurve& curve : r.curves) {
    for (const Eigen::Vector3d& p : curve.points) REQUIRE(p.allFinite());
  }
}

/// Distance from p to the surface by OpenCASCADE's projection (infinity when
/// it finds no orthogonal foot).
double occt_distance(const Handle(Geom_BSplineSurface) & s, const Eigen::Vector3d& p) {
  GeomAPI_ProjectPointOnSurf projection(gp_Pnt(p.x(), p.y(), p.z()), s);
  return projection.NbPoints() > 0 ? projection.LowerDistance()
                                   : std::numeric_limits<double>::infinity();
}

}  // namespace

TEST_CASE("extremes: tools touching exactly, tangent contact and coincident surfaces",
          "[extremes]") {
  OperatorCache cache;
  SECTION("sphere touching a curved surface at distance 0") {
    const BSplineSurface s = test::asymmetric_surface(true);
    Result<SurfaceHierarchy> h = SurfaceHierarchy::build(s, cache);
    REQUIRE(h.ok());
    const double size = control_point_box(s).diagonal(), eps = 1e-6 * size;
    const Handle(Geom_BSplineSurface) oc = to_occt(s);
    // The sphere sits on the surface where it touches: its centre's distance
    // from the surface (OpenCASCADE) is its radius, up to rounding.
    const double u = 0.5 * (s.domain_start(Direction::u) + s.domain_end(Direction::u));
    const double v = 0.4 * s.domain_start(Direction::v) + 0.6 * s.domain_end(Direction::v);
    const Eigen::Vector3d n = unit_normal(s, u, v);
    for (double side : {1.0, -1.0}) {
      const Eigen::Vector3d centre = evaluate(s, u, v) + side * 0.02 * size * n;
      const double radius = occt_distance(oc, centre);  // exactly touching
      REQUIRE(std::isfinite(radius));
      const auto sphere = make_sphere(centre, radius);
      const CollisionResult r = collide(h.value(), *sphere, {.tolerance = eps});
      require_finite(r);
      REQUIRE_FALSE(r.contacts.empty());  // touching counts as contact
      double deepest = -std::numeric_limits<double>::infinity();
      for (const Contact& c : r.contacts) deepest = std::max(deepest, c.depth);
      CHECK(std::abs(deepest) <= eps);
      WARN("sphere touching at distance 0 (side " << side << "): deepest contact " << deepest
                                                  << " mm, eps " << eps);
    }
  }
  SECTION("plane tangent to a paraboloid at its apex") {
    const BSplineSurface s = paraboloid(50.0, 10.0);
    Result<SurfaceHierarchy> h = SurfaceHierarchy::build(s, cache);
    REQUIRE(h.ok());
    const double eps = 1e-6 * control_point_box(s).diagonal();
    const auto plane = make_plane(Eigen::Vector3d(0, 0, -1), -10.0);  // inside: z >= 10
    const CollisionResult r = collide(h.value(), *plane, {.tolerance = eps});
    require_finite(r);
    REQUIRE(r.contacts.size() >= 1);
    for (const Contact& c : r.contacts) {
      CHECK(c.depth >= -eps);
      CHECK(c.depth <= 1e-12);  // the apex touches, nothing is deeper
      // Within eps of the plane only near the apex: |x|, |y| <= a sqrt(eps / h).
      CHECK(std::hypot(c.point.x(), c.point.y()) <= 50.0 * std::sqrt(2.0 * eps / 10.0));
      CHECK(c.normal.z() == Approx(1.0).margin(1e-3));
    }
  }
  SECTION("plane tangent to a cylinder along a line") {
    const BSplineSurface s = quarter_cylinder(20.0, 80.0);
    Result<SurfaceHierarchy> h = SurfaceHierarchy::build(s, cache);
    REQUIRE(h.ok());
    const double eps = 1e-6 * control_point_box(s).diagonal();
    const auto plane = make_plane(Eigen::Vector3d(0, 0, -1), -20.0);  // z >= 20 inside
    const CollisionResult r = collide(h.value(), *plane, {.tolerance = eps});
    require_finite(r);
    REQUIRE_FALSE(r.contacts.empty());
    for (const Contact& c : r.contacts) {
      CHECK(c.depth >= -eps);
      CHECK(c.depth <= 1e-12 * 80.0);
      CHECK(std::abs(c.point.x()) <= std::sqrt(2.0 * 20.0 * eps) * 1.01);
    }
  }
  SECTION("a sphere tool touching at a pole") {
    const BSplineSurface s = dome(3, 2, false, false, true);
    Result<SurfaceHierarchy> h = SurfaceHierarchy::build(s, cache);
    REQUIRE(h.ok());
    const double eps = 1e-6 * control_point_box(s).diagonal();
    const Eigen::Vector3d pole = evaluate(s, 0.0, 1.0);
    const Eigen::Vector3d n = unit_normal(s, 0.0, 1.0);
    const auto sphere = make_sphere(pole + 5.0 * n, 5.0);
    const CollisionResult r = collide(h.value(), *sphere, {.tolerance = eps});
    require_finite(r);
    REQUIRE_FALSE(r.contacts.empty());
    for (const Contact& c : r.contacts) CHECK(c.normal.norm() == Approx(1.0));
    const ClosestPoint cp = closest_point(h.value(), pole + 5.0 * n, {.tolerance = eps});
    // Not the pole itself: the twisted net brings points next to it 1.6e-4
    // nearer than 5 (a dense sampling of the strip u <= 0.01 round it).
    double sampled = std::numeric_limits<double>::infinity();
    for (int a = 0; a <= 300; ++a)
      for (int b = 0; b <= 300; ++b)
        sampled = std::min(
            sampled,
            (evaluate(s, 0.01 * a / 300.0,
                      s.domain_start(Direction::v) +
                          (s.domain_end(Direction::v) - s.domain_start(Direction::v)) * b / 300.0) -
             (pole + 5.0 * n))
                .norm());
    CHECK(cp.distance <= sampled + eps);
    CHECK(cp.distance <= 5.0 + 1e-12);
    CHECK(cp.signed_distance > 0.0);  // the limit normal gives the side at the pole
  }
  SECTION("coincident surfaces: a surface against itself and against a refined copy") {
    const BSplineSurface s = test::asymmetric_surface(true);
    Result<BSplineSurface> refined =
        insert_knot(s, Direction::u,
                    0.5 * (s.domain_start(Direction::u) + s.domain_end(Direction::u)) + 0.01, 1);
    REQUIRE(refined.ok());
    for (const BSplineSurface* other : std::vector<const BSplineSurface*>{&s, &refined.value()}) {
      Result<SurfaceHierarchy> a = SurfaceHierarchy::build(s, cache);
      Result<SurfaceHierarchy> b = SurfaceHierarchy::build(*other, cache);
      REQUIRE(a.ok());
      REQUIRE(b.ok());
      // Coincident surfaces touch everywhere: the work is (area) / (leaf area),
      // so a coarse eps keeps this case to a fraction of a second.
      const double eps = 1e-2 * control_point_box(s).diagonal();
      const CollisionResult r = collide(a.value(), b.value(), {.tolerance = eps});
      require_finite(r);
      REQUIRE_FALSE(r.contacts.empty());
      CHECK(static_cast<int>(r.contacts.size()) <= CollisionRequest{}.max_contacts);
      const Handle(Geom_BSplineSurface) ob = to_occt(*other);
      for (const Contact& c : r.contacts) {
        CHECK(c.depth >= -eps);
        CHECK(occt_distance(ob, c.point) <= eps);  // on b too
      }
    }
  }
  SECTION("tangent surfaces: a paraboloid under a plane touching at its apex") {
    const BSplineSurface bump = paraboloid(50.0, 10.0);
    BSplineSurface lid = surface(1, 1, clamped(1, 0.0, 1.0, {}), clamped(1, 0.0, 1.0, {}));
    lid.control_points << -60, -60, 10, -60, 60, 10, 60, -60, 10, 60, 60, 10;
    Result<SurfaceHierarchy> a = SurfaceHierarchy::build(bump, cache);
    Result<SurfaceHierarchy> b = SurfaceHierarchy::build(lid, cache);
    REQUIRE(a.ok());
    REQUIRE(b.ok());
    const double eps = 1e-4 * control_point_box(bump).diagonal();
    const CollisionResult r = collide(a.value(), b.value(), {.tolerance = eps});
    require_finite(r);
    REQUIRE_FALSE(r.contacts.empty());
    for (const Contact& c : r.contacts) {
      CHECK(c.depth >= -eps);
      CHECK(std::abs(c.point.z() - 10.0) <= eps);
      CHECK(std::hypot(c.point.x(), c.point.y()) <= 50.0 * std::sqrt(2.0 * eps / 10.0));
    }
  }
}

TEST_CASE("extremes: tolerances from 1e-12 to 1 of the model size", "[extremes]") {
  OperatorCache cache;
  std::mt19937_64 rng(31);
  const BSplineSurface s = test::asymmetric_surface(true);
  const double size = control_point_box(s).diagonal();
  const Handle(Geom_BSplineSurface) oc = to_occt(s);
  for (double relative : {1e-12, 1e-9, 1e-6, 1e-3, 1.0}) {
    DYNAMIC_SECTION("eps " << relative << " of the model size") {
      const double eps = relative * size;
      Result<SurfaceHierarchy> h = SurfaceHierarchy::build(s, cache);
      REQUIRE(h.ok());
      const double closest = check_closest_points(h.value(), eps, rng);
      // A sphere sunk into the surface: its deepest contact is the radius less
      // OpenCASCADE's centre distance, to within eps. Shallow contact costs
      // about (contact area) / (eps / curvature) leaves, so at the tightest
      // tolerance the sphere sinks less (docs/range.md has the costs).
      const double sink = (relative < 1e-9 ? 1e-9 : 1e-2) * size;
      const double u = 0.3 * s.domain_start(Direction::u) + 0.7 * s.domain_end(Direction::u);
      const double v = 0.5 * (s.domain_start(Direction::v) + s.domain_end(Direction::v));
      const double radius = 0.05 * size;
      const Eigen::Vector3d centre = evaluate(s, u, v) + (radius - sink) * unit_normal(s, u, v);
      const CollisionResult r =
          collide(h.value(), *make_sphere(centre, radius), {.tolerance = eps});
      require_finite(r);
      REQUIRE_FALSE(r.contacts.empty());
      double deepest = -std::numeric_limits<double>::infinity();
      for (const Contact& c : r.contacts) deepest = std::max(deepest, c.depth);
      const double expected = radius - occt_distance(oc, centre);
      CHECK(deepest >= expected - eps);
      CHECK(deepest <= expected + 1e-12 * size);
      REQUIRE(r.status.ok());
      WARN("eps " << relative << " x size: closest |ours-OCCT|/size " << closest
                  << "; sphere depth error " << (deepest - expected) / size << " x size, "
                  << r.counters.nodes_visited << " nodes");
    }
  }
}

TEST_CASE("extremes: inputs outside the documented range are refused with a clear status",
          "[extremes]") {
  const BSplineSurface good = test::asymmetric_surface(true);
  REQUIRE(validate(good).ok());
  const auto refused = [](const BSplineSurface& s, const char* says, const char* word) {
    const Status v = validate(s);
    INFO(v.message);
    CHECK_THAT(v.message, Catch::Contains(says));
    CHECK_THAT(v.message, Catch::Contains(word));
    CHECK(v.code == StatusCode::invalid_surface);
  };
  SECTION("a coordinate beyond 1e12 mm") {
    BSplineSurface s = good;
    s.control_points(3, 1) = 2e12;
    refused(s, "beyond the supported", "control_points[3]");
  }
  SECTION("a knot beyond 1e12") {
    BSplineSurface s = good;
    s.knots[1] = s.knots[1].array() * 1e13;
    refused(s, "beyond the supported magnitude", "knots_v");
  }
  SECTION("a span shorter than 1e-12 of the domain") {
    BSplineSurface s =
        surface(3, 2, clamped(3, 0.0, 1.0, {0.5, 0.5 + 1e-13}), clamped(2, 0.0, 1.0, {}));
    refused(s, "shorter than", "merge");
  }
  SECTION("a domain shorter than 1e-12 of its knots' magnitude") {
    BSplineSurface s = surface(2, 2, clamped(2, 1e6, 1e6 + 1e-7, {}), clamped(2, 0.0, 1.0, {}));
    refused(s, "shorter than", "domain");
  }
  SECTION("weights with a ratio above 1e8, or beyond [1e-12, 1e12]") {
    BSplineSurface s = good;
    s.weights[0] = 1e-5;
    s.weights[1] = 1e4;
    refused(s, "supported", "ratio");
    s = good;
    s.weights.setConstant(1e13);
    refused(s, "supported", "weights[0]");
  }
  SECTION("tolerances outside [1e-12, 1] of the model size, or below the coordinates' rounding") {
    OperatorCache cache;
    Result<SurfaceHierarchy> h = SurfaceHierarchy::build(good, cache);
    REQUIRE(h.ok());
    const double size = control_point_box(good).diagonal();
    const auto tool = make_sphere(evaluate(good, 0.5, 0.5), 1.0);
    for (double eps : {1e-13 * size, 2.0 * size, 0.0, -1.0, std::nan("")}) {
      const CollisionResult r = collide(h.value(), *tool, {.tolerance = eps});
      INFO("eps " << eps << ": " << r.status.message);
      CHECK(r.status.code == StatusCode::invalid_argument);
      CHECK(r.contacts.empty());
      const ClosestPoint c = closest_point(h.value(), Eigen::Vector3d::Zero(), {.tolerance = eps});
      CHECK(c.status.code == StatusCode::invalid_argument);
      CHECK(std::isnan(c.distance));
      CHECK(collide(h.value(), h.value(), {.tolerance = eps}).status.code ==
            StatusCode::invalid_argument);
    }
    CHECK(collide(h.value(), *tool, {.tolerance = 1e-3, .max_contacts = 0}).status.code ==
          StatusCode::invalid_argument);
    // 100 mm at 1e7 mm from the origin: coordinates round at 2e-9 mm, so
    // 1e-10 mm (1e-12 of the size) cannot be honoured.
    BSplineSurface far = good;
    far.control_points.rowwise() += Eigen::RowVector3d(1e7, 0, 0);
    Result<SurfaceHierarchy> hf = SurfaceHierarchy::build(far, cache);
    REQUIRE(hf.ok());
    const ClosestPoint c = closest_point(hf.value(), far.control_points.row(0).transpose(),
                                         {.tolerance = 1e-12 * size});
    CHECK(c.status.code == StatusCode::invalid_argument);
    CHECK_THAT(c.status.message, Catch::Contains("magnitude"));
    CHECK(closest_point(hf.value(), far.control_points.row(0).transpose(), {.tolerance = 1e-4})
              .status.ok());
  }
}

}  // namespace argil
