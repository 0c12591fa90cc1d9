// PatchEvaluator against direct evaluation: the same element at every knot
// (one-sided derivatives where continuity drops), results that do not depend
// on which patches it kept, clamping, and second order passed on.
#include <algorithm>
#include <catch2/catch.hpp>
#include <random>
#include <vector>

#include "argil/core.hpp"
#include "support/random_surface.hpp"

using argil::BSplineSurface;
using argil::Direction;

namespace {

/// Both domain ends, every knot (repeated ones too) and random parameters.
std::vector<double> parameters(const BSplineSurface& s, Direction d, std::mt19937_64& rng) {
  const double a = s.domain_start(d), b = s.domain_end(d);
  std::uniform_real_distribution<double> inside(a, b);
  std::vector<double> t{a, b};
  for (Eigen::Index k = 0; k < s.knots_in(d).size(); ++k) t.push_back(s.knots_in(d)[k]);
  for (int k = 0; k < 6; ++k) t.push_back(inside(rng));
  return t;
}

/// sum |N'_i(t)| in direction d: the size of a first derivative's terms per
/// unit pole, which rounding scales with (the result may cancel).
double first_derivative_terms(const BSplineSurface& s, Direction d, double t) {
  const int p = s.degree_in(d);
  const int span = argil::find_span(p, s.knots_in(d), s.count(d), t);
  return argil::basis_derivatives(p, s.knots_in(d), span, t, 1).row(1).cwiseAbs().sum();
}

/// Interior knots of full multiplicity (degree): the surface is only C0 there,
/// so the two sides' derivatives differ and the element choice shows.
int c0_knots(const BSplineSurface& s, Direction d) {
  const Eigen::VectorXd& k = s.knots_in(d);
  int found = 0;
  for (Eigen::Index i = 1; i + 1 < k.size(); ++i) {
    if (k[i] == k[0] || k[i] == k[k.size() - 1] || k[i] == k[i - 1]) continue;
    Eigen::Index j = i;
    while (j + 1 < k.size() && k[j + 1] == k[i]) ++j;
    if (j - i + 1 >= s.degree_in(d)) ++found;
  }
  return found;
}

bool same_bits(const argil::SurfaceDerivatives& x, const argil::SurfaceDerivatives& y) {
  return x.point == y.point && x.du == y.du && x.dv == y.dv;
}

}  // namespace

TEST_CASE("the patch evaluator gives evaluate_derivatives' values, one-sided at every knot") {
  std::mt19937_64 rng(31);
  argil::OperatorCache cache;
  int c0_lines = 0;
  for (int trial = 0; trial < 80; ++trial) {
    argil::test::RandomSurfaceOptions options;
    options.max_degree = 7;
    options.rational = trial % 2 == 1;
    const BSplineSurface s =
        trial == 0 ? argil::test::asymmetric_surface() : argil::test::random_surface(rng, options);
    c0_lines += c0_knots(s, Direction::u) + c0_knots(s, Direction::v);
    const argil::SurfaceOperators ops = argil::surface_operators(s, cache).value();
    argil::PatchEvaluator patches(s, ops);
    const double size = argil::control_point_box(s).diagonal();
    const double pole_size = s.control_points.cwiseAbs().maxCoeff();
    for (double u : parameters(s, Direction::u, rng)) {
      for (double v : parameters(s, Direction::v, rng)) {
        INFO("trial " << trial << " at (" << u << ", " << v << ")");
        const argil::SurfaceDerivatives d = argil::evaluate_derivatives(s, u, v, 1);
        const argil::SurfaceDerivatives p1 = patches.evaluate(u, v, 1);
        const argil::SurfaceDerivatives p0 = patches.evaluate(u, v, 0);
        CHECK((p1.point - d.point).norm() <= 1e-12 * size);
        CHECK(p0.point == p1.point);
        // Rational quotients enlarge the terms by the weight spread (at most 10).
        const double weight_spread = options.rational ? 10.0 : 1.0;
        CHECK((p1.du - d.du).norm() <=
              1e-12 * weight_spread * pole_size * first_derivative_terms(s, Direction::u, u));
        CHECK((p1.dv - d.dv).norm() <=
              1e-12 * weight_spread * pole_size * first_derivative_terms(s, Direction::v, v));
      }
    }
  }
  // The one-sided checks above mean something only where continuity drops.
  CHECK(c0_lines >= 20);
}

TEST_CASE("the patch evaluator's results do not depend on the patches it kept") {
  std::mt19937_64 rng(8);
  argil::OperatorCache cache;
  for (int trial = 0; trial < 20; ++trial) {
    argil::test::RandomSurfaceOptions options;
    options.rational = trial % 2 == 0;
    const BSplineSurface s = argil::test::random_surface(rng, options);
    const argil::SurfaceOperators ops = argil::surface_operators(s, cache).value();
    std::vector<std::pair<double, double>> at;
    for (double u : parameters(s, Direction::u, rng))
      for (double v : parameters(s, Direction::v, rng)) at.emplace_back(u, v);
    std::shuffle(at.begin(), at.end(), rng);
    // One evaluator through a shuffled walk (its four slots replaced again and
    // again) against a fresh one per point.
    argil::PatchEvaluator walked(s, ops);
    for (const auto& [u, v] : at) {
      argil::PatchEvaluator fresh(s, ops);
      INFO("trial " << trial << " at (" << u << ", " << v << ")");
      CHECK(same_bits(walked.evaluate(u, v, 1), fresh.evaluate(u, v, 1)));
    }
  }
}

TEST_CASE("the patch evaluator clamps to the domain and passes second order on") {
  const BSplineSurface s = argil::test::asymmetric_surface();
  argil::OperatorCache cache;
  const argil::SurfaceOperators ops = argil::surface_operators(s, cache).value();
  argil::PatchEvaluator patches(s, ops);
  const double u0 = s.domain_start(Direction::u), u1 = s.domain_end(Direction::u);
  const double v0 = s.domain_start(Direction::v), v1 = s.domain_end(Direction::v);
  CHECK(same_bits(patches.evaluate(u0 - 1.0, v1 + 2.0, 1), patches.evaluate(u0, v1, 1)));
  CHECK(same_bits(patches.evaluate(u1 + 0.5, v0 - 0.5, 1), patches.evaluate(u1, v0, 1)));
  for (double u : {u0, 0.3 * u0 + 0.7 * u1, u1}) {
    const double v = 0.6 * v0 + 0.4 * v1;
    const argil::SurfaceDerivatives direct = argil::evaluate_derivatives(s, u, v, 2);
    const argil::SurfaceDerivatives passed = patches.evaluate(u, v, 2);
    CHECK(same_bits(passed, direct));
    CHECK(passed.duu == direct.duu);
    CHECK(passed.duv == direct.duv);
    CHECK(passed.dvv == direct.dvv);
  }
}
