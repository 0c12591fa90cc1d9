// Properties of the surface kernel, in both u and v on the asymmetric surface
// (docs/conventions.md, Testing) and on generated surfaces.
#include <catch2/catch.hpp>
#include <cmath>
#include <limits>
#include <random>

#include "argil/core.hpp"
#include "support/random_surface.hpp"

using argil::BSplineSurface;
using argil::Direction;

namespace {

double model_size(const BSplineSurface& s) { return argil::control_point_box(s).diagonal(); }

/// Parameters spread over the domain in direction d, including both ends and
/// every distinct knot (where derivatives are one-sided).
std::vector<double> parameters(const BSplineSurface& s, Direction d, int count) {
  std::vector<double> t;
  const double a = s.domain_start(d);
  const double b = s.domain_end(d);
  for (int k = 0; k <= count; ++k) t.push_back(a + (b - a) * k / count);
  for (Eigen::Index k = 0; k < s.knots_in(d).size(); ++k) t.push_back(s.knots_in(d)[k]);
  return t;
}

Eigen::Vector3d point_at(const BSplineSurface& s, Direction d, double along, double across) {
  return d == Direction::u ? argil::evaluate(s, along, across) : argil::evaluate(s, across, along);
}

}  // namespace

TEST_CASE("basis functions form a partition of unity with non-negative values") {
  const BSplineSurface s = argil::test::asymmetric_surface();
  for (Direction d : argil::kDirections) {
    const int p = s.degree_in(d);
    for (double t : parameters(s, d, 37)) {
      const int span = argil::find_span(p, s.knots_in(d), s.count(d), t);
      const Eigen::MatrixXd n = argil::basis_derivatives(p, s.knots_in(d), span, t, 2);
      INFO("direction " << argil::to_string(d) << ", t = " << t);
      CHECK(n.row(0).minCoeff() >= 0.0);
      // Sums of a few positive terms below 1: rounding only.
      CHECK(std::abs(n.row(0).sum() - 1.0) < 1e-15 * 8);
      // The derivatives of a constant sum vanish.
      CHECK(std::abs(n.row(1).sum()) < 1e-12);
      CHECK(std::abs(n.row(2).sum()) < 1e-10);
    }
  }
}

TEST_CASE("the surface interpolates its corner control points and boundary curves") {
  for (bool rational : {false, true}) {
    const BSplineSurface s = argil::test::asymmetric_surface(rational);
    const int nu = s.count(Direction::u);
    const int nv = s.count(Direction::v);
    const double tol = 1e-13 * model_size(s);  // a few roundings of mm-sized sums
    const double u0 = s.domain_start(Direction::u), u1 = s.domain_end(Direction::u);
    const double v0 = s.domain_start(Direction::v), v1 = s.domain_end(Direction::v);
    CHECK(
        (argil::evaluate(s, u0, v0) - s.control_points.row(s.pole_index(0, 0)).transpose()).norm() <
        tol);
    CHECK((argil::evaluate(s, u1, v0) - s.control_points.row(s.pole_index(nu - 1, 0)).transpose())
              .norm() < tol);
    CHECK((argil::evaluate(s, u0, v1) - s.control_points.row(s.pole_index(0, nv - 1)).transpose())
              .norm() < tol);
    CHECK((argil::evaluate(s, u1, v1) -
           s.control_points.row(s.pole_index(nu - 1, nv - 1)).transpose())
              .norm() < tol);
  }
}

TEST_CASE("knot insertion leaves the surface unchanged, in u and in v") {
  std::mt19937_64 rng(11);
  for (bool rational : {false, true}) {
    const BSplineSurface s = argil::test::asymmetric_surface(rational);
    const double tol = 1e-13 * model_size(s);  // refinement is a convex combination
    for (Direction d : argil::kDirections) {
      // A new knot, an existing single knot, and one inserted to full multiplicity.
      const double a = s.domain_start(d), b = s.domain_end(d);
      const Eigen::VectorXd& U = s.knots_in(d);
      const std::vector<std::pair<double, int>> inserts = {{a + 0.37 * (b - a), 1},
                                                           {U[s.degree_in(d) + 1], 1},
                                                           {a + 0.61 * (b - a), s.degree_in(d)}};
      for (auto [t, times] : inserts) {
        argil::Result<BSplineSurface> refined = argil::insert_knot(s, d, t, times);
        INFO("direction " << argil::to_string(d) << " t = " << t << " times " << times << ": "
                          << refined.status().message);
        REQUIRE(refined.ok());
        const BSplineSurface& r = refined.value();
        REQUIRE(argil::validate(r).ok());
        CHECK(r.count(d) == s.count(d) + times);
        CHECK(r.count(argil::other(d)) == s.count(argil::other(d)));
        double worst = 0.0;
        for (double along : parameters(s, d, 23))
          for (double across : parameters(s, argil::other(d), 19))
            worst = std::max(
                worst, (point_at(r, d, along, across) - point_at(s, d, along, across)).norm());
        CHECK(worst < tol);
      }
    }
  }
}

TEST_CASE("knot insertion rejects parameters outside the domain and excess multiplicity") {
  const BSplineSurface s = argil::test::asymmetric_surface();
  CHECK(argil::insert_knot(s, Direction::u, 1.5).status().code ==
        argil::StatusCode::invalid_argument);
  CHECK(argil::insert_knot(s, Direction::v, -1.0).status().code ==
        argil::StatusCode::invalid_argument);
  // u has 0.3 twice already and degree 3: two more copies would make 4.
  CHECK(argil::insert_knot(s, Direction::u, 0.3, 2).status().code ==
        argil::StatusCode::invalid_argument);
  CHECK(argil::insert_knot(s, Direction::u, 0.3, 1).ok());
}

TEST_CASE("Bezier extraction reproduces the surface on every element") {
  std::mt19937_64 rng(5);
  argil::OperatorCache cache;
  for (int trial = 0; trial < 40; ++trial) {
    argil::test::RandomSurfaceOptions options;
    options.max_degree = 6;
    options.rational = trial % 2 == 1;
    const BSplineSurface s =
        trial == 0 ? argil::test::asymmetric_surface() : argil::test::random_surface(rng, options);
    const auto ops = argil::surface_operators(s, cache);
    REQUIRE(ops.ok());
    const double tol = 1e-12 * model_size(s);  // extraction and Bernstein sums: rounding
    for (int eu = 0; eu < ops.value().u->element_count(); ++eu) {
      for (int ev = 0; ev < ops.value().v->element_count(); ++ev) {
        const argil::BezierPatch patch = argil::bezier_patch(s, ops.value(), eu, ev);
        const int su = ops.value().u->extraction().spans[static_cast<std::size_t>(eu)];
        const int sv = ops.value().v->extraction().spans[static_cast<std::size_t>(ev)];
        for (double a : {0.0, 0.25, 0.5, 0.9, 1.0}) {
          for (double b : {0.0, 0.33, 0.8, 1.0}) {
            const double u = s.knots[0][su] + a * (s.knots[0][su + 1] - s.knots[0][su]);
            const double v = s.knots[1][sv] + b * (s.knots[1][sv + 1] - s.knots[1][sv]);
            INFO("trial " << trial << " element (" << eu << ", " << ev << ") at (" << a << ", " << b
                          << ")");
            CHECK((argil::evaluate(patch, a, b) - argil::evaluate(s, u, v)).norm() < tol);
          }
        }
      }
    }
  }
}

TEST_CASE("a Bezier patch's derivatives equal its B-spline's, at every degree and order") {
  // The patch's Bernstein rows set only entries 0 to degree: a derivative row
  // left unset at low degree, or a wrong entry read, shows here as a value off
  // the B-spline's (reads of unset entries only surely under a sanitizer).
  std::mt19937_64 rng(12);
  std::uniform_real_distribution<double> pole(-50.0, 50.0), weight(0.5, 2.0), unit(0.0, 1.0);
  for (int p = 1; p <= argil::kMaxDegree; ++p) {
    for (const int q : {1, 2, 3, p}) {
      const bool rational = (p + q) % 3 == 0;
      BSplineSurface s;
      s.degree = {p, q};
      for (int d = 0; d < 2; ++d) {
        const int n = s.degree[static_cast<std::size_t>(d)] + 1;
        s.knots[static_cast<std::size_t>(d)].resize(2 * n);
        s.knots[static_cast<std::size_t>(d)] << Eigen::VectorXd::Zero(n), Eigen::VectorXd::Ones(n);
      }
      s.control_points.resize((p + 1) * (q + 1), 3);
      for (Eigen::Index k = 0; k < s.control_points.size(); ++k)
        s.control_points.data()[k] = pole(rng);
      if (rational) {
        s.weights.resize(s.control_points.rows());
        for (Eigen::Index k = 0; k < s.weights.size(); ++k) s.weights[k] = weight(rng);
      }
      REQUIRE(argil::validate(s).ok());
      argil::BezierPatch patch{p, q, argil::PatchNet((p + 1) * (q + 1), 4)};
      for (Eigen::Index k = 0; k < s.control_points.rows(); ++k) {
        const double w = rational ? s.weights[k] : 1.0;
        patch.points.row(k) << w * s.control_points.row(k), w;
      }
      // Rounding scales with the terms: |B^(k)| sums to at most (2 deg)^k,
      // enlarged by the weights' spread (at most 4) when rational.
      const double terms = 50.0 * (rational ? 4.0 : 1.0);
      for (double st : {0.0, 1.0, unit(rng), unit(rng)}) {
        const double t = unit(rng);
        INFO("degree " << p << "x" << q << (rational ? " rational" : "") << " at (" << st << ", "
                       << t << ")");
        for (int order = 0; order <= 2; ++order) {
          const argil::SurfaceDerivatives b = argil::evaluate_derivatives(patch, st, t, order);
          const argil::SurfaceDerivatives d = argil::evaluate_derivatives(s, st, t, order);
          CHECK(b.point == argil::evaluate_derivatives(patch, st, t, 0).point);
          CHECK((b.point - d.point).norm() <= 1e-13 * terms);
          if (order >= 1) {
            CHECK((b.du - d.du).norm() <= 1e-13 * terms * 2 * p);
            CHECK((b.dv - d.dv).norm() <= 1e-13 * terms * 2 * q);
          }
          if (order >= 2) {
            CHECK((b.duu - d.duu).norm() <= 1e-13 * terms * 4 * p * p);
            CHECK((b.dvv - d.dvv).norm() <= 1e-13 * terms * 4 * q * q);
            CHECK((b.duv - d.duv).norm() <= 1e-13 * terms * 4 * p * q);
          }
        }
      }
    }
  }
}

TEST_CASE("subdivision matrices split a Bezier patch into halves of the same surface") {
  const BSplineSurface s = argil::test::asymmetric_surface(true);
  argil::OperatorCache cache;
  const auto ops = argil::surface_operators(s, cache).value();
  const argil::BezierPatch parent = argil::bezier_patch(s, ops, 1, 2);
  const auto& su = ops.u->subdivision();
  const auto& sv = ops.v->subdivision();
  const double tol = 1e-13 * model_size(s);  // de Casteljau: convex combinations
  for (int hu = 0; hu < 2; ++hu) {
    for (int hv = 0; hv < 2; ++hv) {
      const argil::BezierPatch child = argil::subdivide(parent, su, sv, {hu, hv});
      const argil::BezierPatch strip = argil::subdivide(parent, su, sv, {std::nullopt, hv});
      // Into a patch that holds another net (as a refreshed node does): the same net.
      argil::BezierPatch reused{1, 1, argil::PatchNet::Constant(4, 4, 7.0)};
      argil::subdivide_into(parent, su, sv, {hu, hv}, reused);
      CHECK(reused.degree_u == child.degree_u);
      CHECK(reused.degree_v == child.degree_v);
      CHECK(reused.points == child.points);
      for (double a : {0.0, 0.2, 0.7, 1.0}) {
        for (double b : {0.0, 0.45, 1.0}) {
          CHECK((argil::evaluate(child, a, b) -
                 argil::evaluate(parent, 0.5 * (hu + a), 0.5 * (hv + b)))
                    .norm() < tol);
          CHECK((argil::evaluate(strip, a, b) - argil::evaluate(parent, a, 0.5 * (hv + b))).norm() <
                tol);
        }
      }
    }
  }
}

TEST_CASE("first and second derivatives agree with central finite differences, in u and v") {
  std::mt19937_64 rng(7);
  for (int trial = 0; trial < 30; ++trial) {
    argil::test::RandomSurfaceOptions options;
    options.min_degree = 2;
    options.rational = trial % 2 == 0;
    options.repeated_knots = false;
    const BSplineSurface s = trial < 2 ? argil::test::asymmetric_surface(trial == 0)
                                       : argil::test::random_surface(rng, options);
    std::uniform_real_distribution<double> unit(0.05, 0.95);
    for (int sample = 0; sample < 10; ++sample) {
      const double u = s.domain_start(Direction::u) +
                       unit(rng) * (s.domain_end(Direction::u) - s.domain_start(Direction::u));
      const double v = s.domain_start(Direction::v) +
                       unit(rng) * (s.domain_end(Direction::v) - s.domain_start(Direction::v));
      // Stay inside one knot span so the difference quotients see a polynomial.
      const double hu = 1e-5 * (s.domain_end(Direction::u) - s.domain_start(Direction::u));
      const double hv = 1e-5 * (s.domain_end(Direction::v) - s.domain_start(Direction::v));
      const int su = argil::find_span(s.degree[0], s.knots[0], s.count(Direction::u), u);
      const int sv = argil::find_span(s.degree[1], s.knots[1], s.count(Direction::v), v);
      if (u - hu < s.knots[0][su] || u + hu > s.knots[0][su + 1] || v - hv < s.knots[1][sv] ||
          v + hv > s.knots[1][sv + 1])
        continue;
      const argil::SurfaceDerivatives d = argil::evaluate_derivatives(s, u, v, 2);
      const argil::SurfaceDerivatives pu = argil::evaluate_derivatives(s, u + hu, v, 1);
      const argil::SurfaceDerivatives mu = argil::evaluate_derivatives(s, u - hu, v, 1);
      const argil::SurfaceDerivatives pv = argil::evaluate_derivatives(s, u, v + hv, 1);
      const argil::SurfaceDerivatives mv = argil::evaluate_derivatives(s, u, v - hv, 1);
      INFO("trial " << trial << " (u, v) = (" << u << ", " << v << ")");
      // Central differences: O(h^2) truncation plus rounding / h; scale by the derivative size.
      const auto close = [](const Eigen::Vector3d& fd, const Eigen::Vector3d& exact) {
        return (fd - exact).norm() <= 1e-5 * (1.0 + exact.norm());
      };
      CHECK(close((pu.point - mu.point) / (2 * hu), d.du));
      CHECK(close((pv.point - mv.point) / (2 * hv), d.dv));
      CHECK(close((pu.du - mu.du) / (2 * hu), d.duu));
      CHECK(close((pv.dv - mv.dv) / (2 * hv), d.dvv));
      CHECK(close((pv.du - mv.du) / (2 * hv), d.duv));
      CHECK(close((pu.dv - mu.dv) / (2 * hu), d.duv));
    }
  }
}

TEST_CASE("a rational surface with unit weights equals the polynomial one") {
  std::mt19937_64 rng(3);
  for (int trial = 0; trial < 20; ++trial) {
    BSplineSurface poly =
        trial == 0 ? argil::test::asymmetric_surface(false) : argil::test::random_surface(rng);
    BSplineSurface rational = poly;
    rational.weights = Eigen::VectorXd::Ones(poly.control_points.rows());
    for (double a : {0.0, 0.3, 0.77, 1.0}) {
      for (double b : {0.0, 0.5, 1.0}) {
        const double u = poly.domain_start(Direction::u) +
                         a * (poly.domain_end(Direction::u) - poly.domain_start(Direction::u));
        const double v = poly.domain_start(Direction::v) +
                         b * (poly.domain_end(Direction::v) - poly.domain_start(Direction::v));
        const auto dp = argil::evaluate_derivatives(poly, u, v, 2);
        const auto dr = argil::evaluate_derivatives(rational, u, v, 2);
        // Dividing by w = 1 (up to the rounding of sum N = 1).
        const double tol = 1e-13 * (1.0 + dp.duu.norm() + dp.dvv.norm() + model_size(poly));
        CHECK((dp.point - dr.point).norm() < tol);
        CHECK((dp.du - dr.du).norm() < tol);
        CHECK((dp.dv - dr.dv).norm() < tol);
        CHECK((dp.duu - dr.duu).norm() < tol);
        CHECK((dp.duv - dr.duv).norm() < tol);
        CHECK((dp.dvv - dr.dvv).norm() < tol);
      }
    }
  }
}

TEST_CASE("the normal is the unit cross product of the tangents and zero at a collapsed edge") {
  BSplineSurface s = argil::test::asymmetric_surface(false);
  const auto d = argil::evaluate_derivatives(s, 0.4, 0.5, 1);
  const Eigen::Vector3d n = argil::unit_normal(d);
  CHECK(std::abs(n.norm() - 1.0) < 1e-15 * 4);
  CHECK(std::abs(n.dot(d.du)) < 1e-12 * d.du.norm());
  CHECK(std::abs(n.dot(d.dv)) < 1e-12 * d.dv.norm());
  // Collapse the u = start edge to one point: S_v vanishes there.
  for (int j = 0; j < s.count(Direction::v); ++j)
    s.control_points.row(s.pole_index(0, j)) << 1.0, 2.0, 3.0;
  const auto pole = argil::evaluate_derivatives(s, 0.0, 0.5, 1);
  CHECK(argil::unit_normal(pole).isZero());
}

TEST_CASE("Greville abscissae are knot averages, ordered, and end on the domain ends") {
  const BSplineSurface s = argil::test::asymmetric_surface();
  const Eigen::VectorXd xi = argil::greville_abscissae(3, s.knots[0]);
  REQUIRE(xi.size() == 7);
  CHECK(xi[0] == 0.0);
  CHECK(xi[6] == 1.0);
  CHECK(xi[3] == Approx((0.3 + 0.3 + 0.75) / 3.0).epsilon(1e-15));
  for (Eigen::Index i = 1; i < xi.size(); ++i) CHECK(xi[i] >= xi[i - 1]);
}

TEST_CASE("the control point box encloses the surface") {
  std::mt19937_64 rng(21);
  for (int trial = 0; trial < 20; ++trial) {
    argil::test::RandomSurfaceOptions options;
    options.rational = true;
    const BSplineSurface s = argil::test::random_surface(rng, options);
    const argil::Box3 box = argil::control_point_box(s);
    for (double a : {0.0, 0.13, 0.5, 0.81, 1.0}) {
      for (double b : {0.0, 0.29, 0.64, 1.0}) {
        const Eigen::Vector3d p =
            argil::evaluate(s,
                            s.domain_start(Direction::u) +
                                a * (s.domain_end(Direction::u) - s.domain_start(Direction::u)),
                            s.domain_start(Direction::v) +
                                b * (s.domain_end(Direction::v) - s.domain_start(Direction::v)));
        const double slack = 1e-12 * box.diagonal();  // rounding of the convex combination
        CHECK((p.array() >= box.min.array() - slack).all());
        CHECK((p.array() <= box.max.array() + slack).all());
      }
    }
  }
}

TEST_CASE("invalid surfaces are rejected with the status that names the defect") {
  const BSplineSurface good = argil::test::asymmetric_surface(true);
  REQUIRE(argil::validate(good).ok());
  const double nan = std::numeric_limits<double>::quiet_NaN();

  struct Case {
    const char* name;
    void (*spoil)(BSplineSurface&);
    const char* says;   // the defect, in the message's words
    const char* names;  // the field the message must name
  };
  static double nan_value;
  nan_value = nan;
  const Case cases[] = {
      {"degree 0", [](BSplineSurface& s) { s.degree[1] = 0; }, "expected 1 to", "degree_v"},
      {"degree too high", [](BSplineSurface& s) { s.degree[0] = argil::kMaxDegree + 1; },
       "expected 1 to", "degree_u"},
      {"too few knots", [](BSplineSurface& s) { s.knots[1] = Eigen::VectorXd::LinSpaced(4, 0, 1); },
       "needs at least", "knots_v"},
      {"nan knot", [](BSplineSurface& s) { s.knots[0][5] = nan_value; }, "is nan", "knots_u[5]"},
      {"decreasing knots", [](BSplineSurface& s) { s.knots[1][4] = -0.5; }, "is below",
       "knots_v[4]"},
      {"unclamped", [](BSplineSurface& s) { s.knots[0][0] = -0.1; }, "is not clamped", "knots_u"},
      {"multiplicity",
       [](BSplineSurface& s) {
         s.degree[1] = 1;
         s.knots[1].resize(6);
         s.knots[1] << -1.0, -1.0, 0.1, 0.1, 2.0, 2.0;
       },
       "allows at most", "knots_v"},
      {"empty domain", [](BSplineSurface& s) { s.knots[1].setConstant(2.0); }, "empty domain",
       "knots_v"},
      {"wrong count", [](BSplineSurface& s) { s.control_points.conservativeResize(34, 3); },
       "the knots need", "control_points"},
      {"nan point", [](BSplineSurface& s) { s.control_points(12, 2) = nan_value; }, "is not finite",
       "control_points[12]"},
      {"weight count", [](BSplineSurface& s) { s.weights.conservativeResize(3); }, "expected 0 or",
       "weights"},
      {"inf weight",
       [](BSplineSurface& s) { s.weights[9] = std::numeric_limits<double>::infinity(); }, "is inf",
       "weights[9]"},
      {"zero weight", [](BSplineSurface& s) { s.weights[4] = 0.0; }, "must be positive",
       "weights[4]"},
      {"negative weight", [](BSplineSurface& s) { s.weights[0] = -1.0; }, "must be positive",
       "weights[0]"},
  };
  for (const Case& c : cases) {
    BSplineSurface s = good;
    c.spoil(s);
    const argil::Status v = argil::validate(s);
    INFO(c.name << ": " << v.message);
    CHECK(v.message.find(c.says) != std::string::npos);
    CHECK(v.message.find(c.names) != std::string::npos);
    CHECK(v.code == argil::StatusCode::invalid_surface);
    // Never evaluated: building operators refuses the surface with the same message.
    argil::OperatorCache cache;
    const auto ops = argil::surface_operators(s, cache);
    CHECK_FALSE(ops.ok());
    CHECK(ops.status().message == v.message);
    CHECK(cache.size() == 0);
  }
}
