// The shell matrices (docs/deformation.md): symmetric positive semi-definite,
// blind to rigid translations (all but the foundation), lumped areas that add
// up to the face's area measured by independent dense sampling, a bending and
// membrane energy that exact knot insertion leaves alone, and the
// Gauss-Legendre rule they are integrated with. Run on the u/v-asymmetric
// rational surface (docs/conventions.md) and its transpose.
#include <Eigen/Dense>
#include <catch2/catch.hpp>
#include <cmath>
#include <random>
#include <vector>

#include "argil/core.hpp"
#include "argil/core/deform/detail/gauss_legendre.hpp"
#include "support/random_surface.hpp"
#include "support/test_plates.hpp"
#include "support/transposed_surface.hpp"

namespace {

using argil::BSplineSurface;
using argil::Direction;
using argil::PoleStencilMatrix;

Eigen::MatrixXd dense(const PoleStencilMatrix& m) {
  return m.multiply(Eigen::MatrixXd::Identity(m.size(), m.size()));
}

/// The asymmetric surface with a third copy of its double knot u = 0.3: the
/// same surface, now with a C0 knot line (a join the joint terms see).
BSplineSurface with_c0_line() {
  const BSplineSurface s = argil::test::asymmetric_surface();
  auto r = argil::insert_knot(s, Direction::u, 0.3, 1);
  REQUIRE(r.ok());
  return r.value();
}

/// A face whose v = 0.5 knot line is a real crease: two flat degree-2 x 3
/// pieces meeting at 40 degrees.
BSplineSurface creased() {
  BSplineSurface s;
  s.degree = {2, 3};
  s.knots = {argil::test::piece_knots(2, 3, 1), argil::test::piece_knots(3, 2, 3)};
  const int nu = s.count(Direction::u), nv = s.count(Direction::v);
  const Eigen::VectorXd gv = argil::greville_abscissae(3, s.knots[1]);
  s.control_points.resize(nu * nv, 3);
  const double angle = 40.0 * M_PI / 180.0;
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j < nv; ++j) {
      const double y = 10.0 * gv[j];
      const double beyond = std::max(0.0, y - 5.0);
      s.control_points.row(s.pole_index(i, j)) << 3.0 * i,
          std::min(y, 5.0) + beyond * std::cos(angle), beyond * std::sin(angle);
    }
  return s;
}

/// The surfaces every property runs on, by name.
struct Case {
  const char* name;
  BSplineSurface surface;
};
std::vector<Case> cases() {
  const BSplineSurface a = argil::test::asymmetric_surface();
  return {{"asymmetric rational", a},
          {"asymmetric, transposed", argil::test::transposed(a)},
          {"asymmetric with a C0 line", with_c0_line()},
          {"40 degree crease", creased()}};
}

/// Area by composite Simpson's rule on n x n intervals per knot span, on
/// evaluate_derivatives (not the shell's own basis code). At 192 it has
/// converged to 1e-7 on the rational asymmetric surface (24: 1886.853, 48:
/// 1886.803, 96: 1886.8001, 192: 1886.7999 mm^2; BRepGProp: 1886.7998).
double sampled_area(const BSplineSurface& s, int n = 192) {
  const auto breaks = [&](int d) {
    std::vector<double> b;
    const Eigen::VectorXd& t = s.knots[static_cast<std::size_t>(d)];
    for (Eigen::Index k = 0; k < t.size(); ++k)
      if (b.empty() || t[k] > b.back()) b.push_back(t[k]);
    return b;
  };
  const std::vector<double> bu = breaks(0), bv = breaks(1);
  const auto simpson = [&](int k) { return k == 0 || k == n ? 1.0 : (k % 2 ? 4.0 : 2.0); };
  double area = 0.0;
  for (std::size_t a = 0; a + 1 < bu.size(); ++a)
    for (std::size_t b = 0; b + 1 < bv.size(); ++b) {
      const double hu = (bu[a + 1] - bu[a]) / n, hv = (bv[b + 1] - bv[b]) / n;
      double sum = 0.0;
      for (int i = 0; i <= n; ++i)
        for (int j = 0; j <= n; ++j) {
          // Nudged inside the span so the derivatives are the span's own.
          const double u = std::clamp(bu[a] + i * hu, bu[a] + 1e-13, bu[a + 1] - 1e-13);
          const double v = std::clamp(bv[b] + j * hv, bv[b] + 1e-13, bv[b + 1] - 1e-13);
          const argil::SurfaceDerivatives d = argil::evaluate_derivatives(s, u, v, 1);
          sum += simpson(i) * simpson(j) * d.du.cross(d.dv).norm();
        }
      area += sum * hu * hv / 9.0;
    }
  return area;
}

/// Random displacements, one row per pole.
Eigen::MatrixXd random_field(Eigen::Index poles, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> normal(0.0, 1.0);
  Eigen::MatrixXd d(poles, 3);
  for (Eigen::Index i = 0; i < d.size(); ++i) d.data()[i] = normal(rng);
  return d;
}

/// The displacement field d = sum R_i dp_i of `s` (same weights), refined
/// exactly by the knot insertions `refined` went through: the coefficients on
/// the refined net of the same field.
Eigen::MatrixXd refine_field(BSplineSurface s, const Eigen::MatrixXd& dp,
                             const std::vector<std::pair<Direction, double>>& insertions) {
  s.control_points = dp;
  for (const auto& [d, t] : insertions) {
    auto r = argil::insert_knot(s, d, t, 1);
    REQUIRE(r.ok());
    s = r.value();
  }
  return s.control_points;
}

/// Knot values halving every non-empty span of direction d.
std::vector<std::pair<Direction, double>> midpoints(const BSplineSurface& s, Direction d) {
  std::vector<std::pair<Direction, double>> out;
  const Eigen::VectorXd& t = s.knots_in(d);
  for (Eigen::Index k = 0; k + 1 < t.size(); ++k)
    if (t[k] < t[k + 1]) out.emplace_back(d, 0.5 * (t[k] + t[k + 1]));
  return out;
}

/// The energies of random fields on `s` and of the same fields refined exactly
/// (every span halved in one direction) agree to `tolerance` relative.
void check_refinement(const BSplineSurface& s, double tolerance) {
  for (const Direction d : {Direction::u, Direction::v}) {
    const auto insertions = midpoints(s, d);
    BSplineSurface refined = s;
    for (const auto& [dir, t] : insertions)
      refined = argil::insert_knot(refined, dir, t, 1).value();
    const argil::ShellMatrices a = argil::shell_matrices(s);
    const argil::ShellMatrices b = argil::shell_matrices(refined);
    CAPTURE(argil::to_string(d), a.total_area, b.total_area);
    CHECK(std::abs(b.total_area - a.total_area) <= tolerance * a.total_area);
    // The refined net has no C0 line the original lacked: no joint terms appear.
    CHECK(dense(b.joints).cwiseAbs().maxCoeff() == 0.0);
    for (unsigned seed : {1u, 2u, 3u}) {
      const Eigen::MatrixXd dp = random_field(a.area.size(), seed);
      const Eigen::MatrixXd dq = refine_field(s, dp, insertions);
      const double bend_a = a.bending.quadratic_form(dp), bend_b = b.bending.quadratic_form(dq);
      const double mem_a = a.membrane.quadratic_form(dp), mem_b = b.membrane.quadratic_form(dq);
      const double found_a = a.foundation.quadratic_form(dp),
                   found_b = b.foundation.quadratic_form(dq);
      CAPTURE(seed, bend_a, bend_b, mem_a, mem_b, found_a, found_b);
      CHECK(std::abs(bend_b - bend_a) <= tolerance * bend_a);
      CHECK(std::abs(mem_b - mem_a) <= tolerance * mem_a);
      CHECK(std::abs(found_b - found_a) <= tolerance * found_a);
    }
  }
}

}  // namespace

TEST_CASE("the shell matrices are symmetric positive semi-definite", "[deformation][shell]") {
  for (const Case& c : cases()) {
    CAPTURE(c.name);
    const argil::ShellMatrices m = argil::shell_matrices(c.surface);
    for (const auto& [name, matrix] :
         {std::pair{"foundation", &m.foundation}, std::pair{"membrane", &m.membrane},
          std::pair{"bending", &m.bending}, std::pair{"joints", &m.joints}}) {
      CAPTURE(name);
      const Eigen::MatrixXd k = dense(*matrix);
      const double scale = k.cwiseAbs().maxCoeff();
      if (scale == 0.0) {
        CHECK(std::string(name) == "joints");  // only a face without C0 lines has none
        continue;
      }
      CHECK((k - k.transpose()).cwiseAbs().maxCoeff() <= 1e-13 * scale);  // rounding
      const Eigen::VectorXd eig = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(
                                      0.5 * (k + k.transpose()), Eigen::EigenvaluesOnly)
                                      .eigenvalues();
      CAPTURE(eig.minCoeff(), eig.maxCoeff());
      CHECK(eig.minCoeff() >= -1e-12 * eig.maxCoeff());                    // rounding of the sums
      if (std::string(name) == "foundation") CHECK(eig.minCoeff() > 0.0);  // a Gram matrix
    }
  }
}

TEST_CASE(
    "rigid translations cost no membrane, bending or joint energy; the foundation's is "
    "its area",
    "[deformation][shell]") {
  for (const Case& c : cases()) {
    CAPTURE(c.name);
    const argil::ShellMatrices m = argil::shell_matrices(c.surface);
    const Eigen::Index n = m.area.size();
    // A translation t moves every control point by t (sum R_i = 1).
    Eigen::MatrixXd t(n, 3);
    t.rowwise() = Eigen::RowVector3d(0.3, -1.2, 0.7);
    const double t2 = t.row(0).squaredNorm();
    // Its energy against |t|^2 times each matrix's own size (rounding only).
    const auto size_of = [&](const PoleStencilMatrix& k) {
      double s = 0.0;
      for (Eigen::Index i = 0; i < n; ++i) s = std::max(s, std::abs(k.diagonal(i)));
      return s * static_cast<double>(n);
    };
    CHECK(std::abs(m.membrane.quadratic_form(t)) <= 1e-12 * t2 * size_of(m.membrane));
    CHECK(std::abs(m.bending.quadratic_form(t)) <= 1e-12 * t2 * size_of(m.bending));
    CHECK(std::abs(m.joints.quadratic_form(t)) <= 1e-12 * t2 * (1.0 + size_of(m.joints)));
    // The foundation: 1^T F 1 = integral (sum R_i)^2 dA, the area.
    CHECK(m.foundation.quadratic_form(t) == Approx(t2 * m.total_area).epsilon(1e-12));
  }
}

TEST_CASE("lumped masses add up to density x thickness x the face's area (dense sampling)",
          "[deformation][shell]") {
  for (const Case& c : cases()) {
    CAPTURE(c.name);
    const argil::ShellMatrices m = argil::shell_matrices(c.surface);
    CHECK(m.area.minCoeff() > 0.0);  // every pole carries mass
    const double area = sampled_area(c.surface);
    CAPTURE(area, m.total_area);
    // 1e-5: the Gauss rule's error on a curved face's area element, which is
    // no polynomial, is allowed; a lost span, weight or Jacobian is not.
    CHECK(std::abs(m.total_area - area) <= 1e-5 * area);
    CHECK(m.area.sum() == Approx(m.total_area).epsilon(1e-14));
    argil::OperatorCache cache;
    for (const argil::MaterialPreset& preset : argil::material_presets()) {
      CAPTURE(preset.name);
      auto body = argil::DeformableBody::create(c.surface, preset.material, {}, cache);
      REQUIRE(body.ok());
      const double expected =
          preset.material.density * argil::kKgPerM3ToKgPerMm3 * preset.material.thickness * area;
      CHECK(std::abs(body.value().masses().sum() - expected) <= 1e-5 * expected);
    }
  }
}

TEST_CASE("transposing the face transposes every shell matrix", "[deformation][shell]") {
  const BSplineSurface s = with_c0_line();
  const BSplineSurface t = argil::test::transposed(s);
  const argil::ShellMatrices a = argil::shell_matrices(s);
  const argil::ShellMatrices b = argil::shell_matrices(t);
  const int nu = s.count(Direction::u), nv = s.count(Direction::v);
  CHECK((argil::test::transposed_rows(Eigen::MatrixXd(a.area), nu, nv) - b.area)
            .cwiseAbs()
            .maxCoeff() <= 1e-13 * a.area.maxCoeff());
  // P K P^T for the pole permutation P.
  Eigen::MatrixXd perm = argil::test::transposed_rows(
      Eigen::MatrixXd(Eigen::MatrixXd::Identity(nu * nv, nu * nv)), nu, nv);
  for (const auto& [ka, kb] :
       {std::pair{&a.foundation, &b.foundation}, std::pair{&a.membrane, &b.membrane},
        std::pair{&a.bending, &b.bending}, std::pair{&a.joints, &b.joints}}) {
    const Eigen::MatrixXd da = dense(*ka), db = dense(*kb);
    CHECK((perm * da * perm.transpose() - db).cwiseAbs().maxCoeff() <=
          1e-12 * da.cwiseAbs().maxCoeff());
  }
}

TEST_CASE("exact knot insertion leaves the shell energies of a field alone: affine flat plate",
          "[deformation][shell]") {
  // An affine parametrisation makes every integrand a polynomial the Gauss
  // rule integrates exactly, so only rounding differs.
  BSplineSurface plate;
  plate.degree = {3, 2};
  plate.knots = {argil::test::piece_knots(3, 3, 1), argil::test::piece_knots(2, 4, 1)};
  const Eigen::VectorXd gu = argil::greville_abscissae(3, plate.knots[0]);
  const Eigen::VectorXd gv = argil::greville_abscissae(2, plate.knots[1]);
  plate.control_points.resize(gu.size() * gv.size(), 3);
  for (Eigen::Index i = 0; i < gu.size(); ++i)
    for (Eigen::Index j = 0; j < gv.size(); ++j)
      plate.control_points.row(plate.pole_index(static_cast<int>(i), static_cast<int>(j)))
          << 30.0 * gu[i] + 5.0 * gv[j],
          12.0 * gv[j], 0.0;
  check_refinement(plate, 1e-9);
}

TEST_CASE(
    "exact knot insertion leaves the shell energies of a field alone: curved rational "
    "asymmetric surface",
    "[deformation][shell]") {
  // The same field on the same surface has the same energy however the net
  // is refined; a difference is quadrature error of the shell integrals, which
  // on a rational face (quotient integrands, 2p + 2 Gauss points) measured up
  // to 6e-4 relative for bending.
  check_refinement(argil::test::asymmetric_surface(), 1e-3);
}

TEST_CASE("a smooth field costs no joint energy across a C0 line that only knot insertion made",
          "[deformation][shell]") {
  const BSplineSurface s = argil::test::asymmetric_surface();
  const argil::ShellMatrices a = argil::shell_matrices(s);
  const argil::ShellMatrices b = argil::shell_matrices(with_c0_line());
  REQUIRE(dense(b.joints).cwiseAbs().maxCoeff() > 0.0);  // the line is seen
  const Eigen::MatrixXd dp = random_field(a.area.size(), 7);
  const Eigen::MatrixXd dq = refine_field(s, dp, {{Direction::u, 0.3}});
  CHECK(b.joints.quadratic_form(dq) <= 1e-10 * a.bending.quadratic_form(dp));
  // A field that kinks along the line does cost joint energy.
  Eigen::MatrixXd kink = Eigen::MatrixXd::Zero(dq.rows(), 3);
  const int nv = s.count(Direction::v);
  for (int j = 0; j < nv; ++j) kink(3 * nv + j, 2) = 1.0;  // the row on the line (Greville 0.3)
  CHECK(b.joints.quadratic_form(kink) > 0.0);
}

TEST_CASE("gauss_legendre(n) integrates polynomials of degree 2n - 1 exactly, not 2n",
          "[deformation][shell]") {
  for (int n = 1; n <= 24; ++n) {
    CAPTURE(n);
    const argil::detail::QuadratureRule rule = argil::detail::gauss_legendre(n);
    REQUIRE(rule.points.size() == n);
    CHECK(rule.weights.minCoeff() > 0.0);
    CHECK(rule.weights.sum() == Approx(1.0).epsilon(1e-14));
    for (Eigen::Index k = 0; k < n; ++k) {
      CHECK(rule.points[k] > 0.0);
      CHECK(rule.points[k] < 1.0);
      if (k > 0) CHECK(rule.points[k] > rule.points[k - 1]);
      // Symmetric about 1/2.
      CHECK(rule.points[k] + rule.points[n - 1 - k] == Approx(1.0).epsilon(1e-14));
    }
    // The shifted Legendre-like test polynomials (2x - 1)^k integrate to
    // 1/(k+1) for even k, 0 for odd k on [0, 1]; entries of order 1.
    for (int k = 0; k <= 2 * n; ++k) {
      const double exact = k % 2 ? 0.0 : 1.0 / (k + 1);
      double sum = 0.0;
      for (Eigen::Index i = 0; i < n; ++i)
        sum += rule.weights[i] * std::pow(2.0 * rule.points[i] - 1.0, k);
      CAPTURE(k, sum, exact);
      if (k <= 2 * n - 1) {
        CHECK(std::abs(sum - exact) <= 1e-14);
      } else if (n <= 12) {
        // Degree 2n is beyond the rule by the textbook remainder
        // 2^(2n) (n!)^4 / ((2n + 1) ((2n)!)^2), 2e-1 .. 3e-9 here, far above rounding.
        const double remainder = std::exp(2 * n * std::log(2.0) + 4 * std::lgamma(n + 1.0) -
                                          std::log(2.0 * n + 1) - 2 * std::lgamma(2 * n + 1.0));
        CHECK(exact - sum == Approx(remainder).epsilon(1e-6));
      }
    }
  }
}
