// The precomputed operators: grid evaluation through them agrees with direct
// evaluation, fitting at the Greville abscissae inverts node evaluation, and
// they are built once per structure.
#include <Eigen/Dense>
#include <catch2/catch.hpp>
#include <cmath>
#include <random>

#include "argil/core.hpp"
#include "support/random_surface.hpp"
#include "support/tool_shapes.hpp"

using argil::BSplineSurface;
using argil::Direction;

namespace {

double model_size(const BSplineSurface& s) { return argil::control_point_box(s).diagonal(); }

/// Largest |a - b| over rows, relative to `scale`.
double relative_gap(const argil::ControlNet& a, const argil::ControlNet& b, double scale) {
  return (a - b).rowwise().norm().maxCoeff() / scale;
}

using argil::test::uniform_knots;

}  // namespace

TEST_CASE("a grid evaluated through the operators agrees with direct evaluation to 1e-12") {
  std::mt19937_64 rng(17);
  argil::OperatorCache cache;
  for (int trial = 0; trial < 60; ++trial) {
    argil::test::RandomSurfaceOptions options;
    options.max_degree = 7;
    options.rational = trial % 2 == 1;
    const BSplineSurface s =
        trial == 0 ? argil::test::asymmetric_surface() : argil::test::random_surface(rng, options);
    const auto ops = argil::surface_operators(s, cache).value();
    const int level = trial % 3;
    const argil::SamplingRows& ru = ops.u->level_rows(level);
    const argil::SamplingRows& rv = ops.v->level_rows(level + 1);
    argil::SurfaceGrid grid;
    argil::evaluate_grid(s, ru, rv, 2, grid);
    REQUIRE(grid.count_u == ops.u->element_count() * (1 << level) + 1);
    double worst_point = 0, worst_d1 = 0, worst_d2 = 0, d1_scale = 0, d2_scale = 0;
    for (int a = 0; a < grid.count_u; ++a) {
      for (int b = 0; b < grid.count_v; ++b) {
        const auto d = argil::evaluate_derivatives(s, ru.params[a], rv.params[b], 2);
        const Eigen::Index r = a * grid.count_v + b;
        worst_point = std::max(worst_point, (grid.points.row(r).transpose() - d.point).norm());
        worst_d1 = std::max({worst_d1, (grid.du.row(r).transpose() - d.du).norm(),
                             (grid.dv.row(r).transpose() - d.dv).norm()});
        worst_d2 = std::max({worst_d2, (grid.duu.row(r).transpose() - d.duu).norm(),
                             (grid.duv.row(r).transpose() - d.duv).norm(),
                             (grid.dvv.row(r).transpose() - d.dvv).norm()});
        d1_scale = std::max({d1_scale, d.du.norm(), d.dv.norm()});
        d2_scale = std::max({d2_scale, d.duu.norm(), d.duv.norm(), d.dvv.norm()});
        if (d.du.cross(d.dv).norm() > 1e-9 * d.du.norm() * d.dv.norm()) {
          CHECK((grid.normals.row(r).transpose() - argil::unit_normal(d)).norm() < 1e-12);
        }
      }
    }
    INFO("trial " << trial << " degrees " << s.degree[0] << "x" << s.degree[1]);
    // Same sums in another order: agreement to 1e-12 relative to each quantity's scale.
    CHECK(worst_point <= 1e-12 * model_size(s));
    CHECK(worst_d1 <= 1e-12 * d1_scale);
    CHECK(worst_d2 <= 1e-12 * d2_scale);
  }
}

TEST_CASE(
    "fitting nodes to control points and evaluating back reproduces the nodes, degrees 1 to 10") {
  std::mt19937_64 rng(29);
  argil::OperatorCache cache;
  double worst = 0.0;
  for (int p = 1; p <= 10; ++p) {
    for (int n : {4, 5, 9, 16, 33, 64, 120, 200}) {
      if (n < p + 1) continue;
      // Second direction: another degree and count, so u/v mix-ups show.
      const int q = 1 + (p * 7) % 10;
      const int m = std::max(q + 1, std::min(200, (n * 3) / 2 % 201 + 4));
      BSplineSurface s;
      s.degree = {p, q};
      s.knots = {uniform_knots(p, n), uniform_knots(q, m)};
      // Zero until fitted: validation reads them (resize() leaves them uninitialised).
      s.control_points.setZero(static_cast<Eigen::Index>(n) * m, 3);
      if (n % 2 == 0) s.weights = Eigen::VectorXd::Constant(static_cast<Eigen::Index>(n) * m, 1.0);
      for (Eigen::Index k = 0; k < s.weights.size(); ++k)
        s.weights[k] = 0.5 + std::fmod(0.37 * static_cast<double>(k), 1.5);
      const auto ops = argil::surface_operators(s, cache);
      INFO("degree " << p << "x" << q << " poles " << n << "x" << m << " " << ops.status().message);
      REQUIRE(ops.ok());
      // Nodes: a smooth field over the Greville grid, sized like a 100 mm part.
      argil::ControlNet nodes(s.control_points.rows(), 3);
      std::uniform_real_distribution<double> noise(-1.0, 1.0);
      for (int i = 0; i < n; ++i) {
        for (int j = 0; j < m; ++j) {
          const double u = ops.value().u->greville()[i];
          const double v = ops.value().v->greville()[j];
          nodes.row(s.pole_index(i, j)) << 100.0 * u, 80.0 * v + 5.0 * u * u,
              10.0 * std::sin(4.0 * u) * std::cos(3.0 * v) + 0.5 * noise(rng);
        }
      }
      s.control_points = argil::fit_control_points(s, ops.value(), nodes);
      const argil::ControlNet back = argil::evaluate_nodes(s, ops.value());
      const double gap = relative_gap(back, nodes, 128.0);
      worst = std::max(worst, gap);
      CHECK(gap <= 1e-12);
    }
  }
  WARN("largest relative node error after fit and evaluation: " << worst);
}

TEST_CASE("the collocation at Greville abscissae stays well conditioned") {
  // docs/operators.md: below 40 up to degree 6 for long nets; in the
  // 1-norm we measure up to 43 at degree 7 (n >= 16) and 302 for the single
  // Bezier span n = 8. Uniform sampling reaches 1e5 (cubic) to 1e13 (quintic).
  for (int p = 1; p <= 7; ++p) {
    for (int n : {8, 16, 64, 200}) {
      auto ops = argil::CurveOperators::build(p, uniform_knots(p, n));
      REQUIRE(ops.ok());
      const double condition = ops.value()->collocation_condition();
      INFO("degree " << p << " poles " << n << " condition " << condition);
      CHECK(condition >= 1.0);
      if (n >= 2 * (p + 1)) {
        CHECK(condition < (p <= 6 ? 40.0 : 50.0));
      } else {
        CHECK(condition < 400.0);
      }
    }
  }
}

TEST_CASE("the banded LU solves agree with a dense solve of the collocation matrix") {
  std::mt19937_64 rng(2);
  const BSplineSurface s =
      argil::test::random_surface(rng, {.min_degree = 4, .max_degree = 6, .max_extra_poles = 20});
  for (Direction d : argil::kDirections) {
    auto built = argil::CurveOperators::build(s.degree_in(d), s.knots_in(d));
    REQUIRE(built.ok());
    const argil::CurveOperators& ops = *built.value();
    const int n = ops.count();
    Eigen::MatrixXd dense = Eigen::MatrixXd::Zero(n, n);
    for (int i = 0; i < n; ++i)
      for (int r = 0; r <= ops.degree(); ++r)
        dense(i, ops.greville_rows().first_pole[static_cast<std::size_t>(i)] + r) =
            ops.greville_rows().values(i, r);
    const Eigen::MatrixXd rhs = Eigen::MatrixXd::Random(n, 3);
    Eigen::MatrixXd x = rhs;
    ops.collocation().solve_in_place(x);
    // Backward error of the banded solve: rounding times the condition number.
    CHECK((dense * x - rhs).norm() <= 1e-13 * rhs.norm() * ops.collocation_condition());
    const double exact_condition = dense.cwiseAbs().colwise().sum().maxCoeff() *
                                   dense.inverse().cwiseAbs().colwise().sum().maxCoeff();
    CHECK(ops.collocation_condition() == Approx(exact_condition).epsilon(1e-9));
  }
}

TEST_CASE("operators are built once per structure and survive control point changes") {
  argil::OperatorCache cache;
  BSplineSurface s = argil::test::asymmetric_surface();
  const auto first = argil::surface_operators(s, cache).value();
  CHECK(cache.size() == 2);
  const argil::SamplingRows* level2 = &first.u->level_rows(2);
  // Deform: new control points and weights, same degrees and knots.
  s.control_points.array() += 3.0;
  s.control_points.col(2) *= -2.0;
  s.weights *= 1.7;
  const auto second = argil::surface_operators(s, cache).value();
  CHECK(second.u.get() == first.u.get());
  CHECK(second.v.get() == first.v.get());
  CHECK(&second.u->level_rows(2) == level2);
  CHECK(cache.size() == 2);
  // A surface sharing the v structure as its u structure reuses it too.
  BSplineSurface swapped = s;
  swapped.degree = {s.degree[1], s.degree[1]};
  swapped.knots = {s.knots[1], s.knots[1]};
  swapped.control_points.resize(25, 3);
  swapped.control_points.setRandom();
  swapped.weights.resize(0);
  const auto third = argil::surface_operators(swapped, cache).value();
  CHECK(third.u.get() == first.v.get());
  CHECK(cache.size() == 2);
  // The deformed surface evaluated through the shared operators is the deformed surface.
  argil::SurfaceGrid grid;
  argil::evaluate_grid(s, second.u->level_rows(1), second.v->level_rows(1), 0, grid);
  const auto& ru = second.u->level_rows(1);
  const auto& rv = second.v->level_rows(1);
  CHECK((grid.points.row(3 * grid.count_v + 2).transpose() -
         argil::evaluate(s, ru.params[3], rv.params[2]))
            .norm() < 1e-12 * model_size(s));
}

TEST_CASE("level rows put every element's start on its knot and end on the domain end") {
  const BSplineSurface s = argil::test::asymmetric_surface();
  auto ops = argil::CurveOperators::build(3, s.knots[0]).value();
  CHECK(ops->element_count() == 3);  // the double knot adds no element
  const argil::SamplingRows& rows = ops->level_rows(3);
  REQUIRE(rows.size() == 3 * 8 + 1);
  CHECK(rows.params[0] == 0.0);
  CHECK(rows.params[8] == 0.3);
  CHECK(rows.params[16] == 0.75);
  CHECK(rows.params[24] == 1.0);
  for (Eigen::Index k = 1; k < rows.size(); ++k) CHECK(rows.params[k] > rows.params[k - 1]);
}

TEST_CASE("hierarchy patches evaluate points and derivatives as the B-spline does") {
  std::mt19937_64 rng(31);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  argil::OperatorCache cache;
  double worst = 0.0;
  for (int trial = 0; trial < 60; ++trial) {
    argil::test::RandomSurfaceOptions options;
    options.max_degree = 7;
    options.rational = trial % 2 == 1;
    const BSplineSurface s = argil::test::random_surface(rng, options);
    auto built = argil::SurfaceHierarchy::build(s, cache);
    REQUIRE(built.ok());
    argil::SurfaceHierarchy h = std::move(built).value();
    // A random path down to level 3 below a random element.
    int id = h.roots()[static_cast<std::size_t>(rng() % h.roots().size())];
    for (int level = 0; level < 3; ++level) {
      id = h.child(id, static_cast<int>(rng() % 2), static_cast<int>(rng() % 2));
    }
    const argil::HierarchyNode& n = h.node(id);
    const double wu = n.rect.u1 - n.rect.u0, wv = n.rect.v1 - n.rect.v0;
    const double size = model_size(s);
    for (int k = 0; k < 20; ++k) {
      const double a = k < 4 ? static_cast<double>(k % 2) : unit(rng);
      const double b = k < 4 ? static_cast<double>(k / 2) : unit(rng);
      const auto local = argil::evaluate_derivatives(n.patch, a, b, 2);
      const auto exact = argil::evaluate_derivatives(s, n.rect.u0 + a * wu, n.rect.v0 + b * wv, 2);
      // Derivatives relative to the size over the element width (their scale).
      const double e0 = (local.point - exact.point).norm() / size;
      const double e1 =
          std::max((local.du / wu - exact.du).norm() * wu, (local.dv / wv - exact.dv).norm() * wv) /
          size;
      const double e2 = std::max({(local.duu / (wu * wu) - exact.duu).norm() * wu * wu,
                                  (local.duv / (wu * wv) - exact.duv).norm() * wu * wv,
                                  (local.dvv / (wv * wv) - exact.dvv).norm() * wv * wv}) /
                        size;
      INFO("trial " << trial << " degrees " << s.degree[0] << "x" << s.degree[1]);
      CHECK(e0 <= 1e-12);
      worst = std::max(worst, e0);
      // On the patch edges (the first four samples are its corners) the
      // B-spline may take its derivatives from the neighbouring element: at a
      // repeated knot they differ. Inside, both are one polynomial.
      if (k < 4) continue;
      CHECK(e1 <= 1e-11);
      CHECK(e2 <= 1e-10);
      worst = std::max({worst, e1, e2});
    }
  }
  WARN("worst relative gap, Bezier patch against B-spline evaluation: " << worst);
}
