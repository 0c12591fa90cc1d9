// The ties of G1 joins (docs/deformation.md, Joins): which rows are tied, the
// band form of T^T A T against the dense product, and a deformable body whose
// tied rows stay straight with their rest proportions under a press.
#include <Eigen/Cholesky>
#include <catch2/catch.hpp>
#include <cmath>
#include <random>
#include <vector>

#include "argil/core.hpp"
#include "support/test_plates.hpp"

namespace {

using argil::BSplineSurface;
using argil::Direction;

/// A flat degree p x q plate with C0 lines both ways (`pieces` x `pieces`
/// Bezier pieces), poles at the Greville abscissae (every row straight); with
/// `crease_v` a tent along v makes the first C0 v-line a crease.
BSplineSurface crossed_plate(int p, int q, int pieces, bool crease_v) {
  BSplineSurface s;
  s.degree = {p, q};
  s.knots = {argil::test::piece_knots(p, pieces, p), argil::test::piece_knots(q, pieces, q)};
  const Eigen::VectorXd gu = argil::greville_abscissae(p, s.knots[0]);
  const Eigen::VectorXd gv = argil::greville_abscissae(q, s.knots[1]);
  const int nu = s.count(Direction::u), nv = s.count(Direction::v);
  s.control_points.resize(nu * nv, 3);
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j < nv; ++j) {
      // A tent along v peaking on the first C0 v-line: a crease there.
      const double z = crease_v ? 0.3 * (1.0 - std::abs(gv[j] - 1.0 / pieces)) : 0.0;
      s.control_points.row(s.pole_index(i, j)) << 10.0 * gu[i], 7.0 * gv[j], z;
    }
  return s;
}

/// Rows across a line of one direction that no C0 line of the other crosses
/// within one pole: `count` rows, the other direction's lines on poles
/// degree, 2 degree, ... (pieces - 1) degree.
int uncrossed_rows(int count, int degree, int pieces) {
  int out = 0;
  for (int e = 0; e < count; ++e) {
    bool crossed = false;
    for (int k = 1; k < pieces; ++k) crossed = crossed || std::abs(e - k * degree) <= 1;
    out += crossed ? 0 : 1;
  }
  return out;
}

}  // namespace

TEST_CASE("join rows: straight rows are tied, creases and crossings are not",
          "[deformation][joins]") {
  const BSplineSurface flat = crossed_plate(3, 2, 3, false);
  REQUIRE(argil::validate(flat).ok());
  const std::vector<char> held(static_cast<std::size_t>(flat.control_points.rows()), 0);
  const std::vector<argil::JoinRow> rows = argil::join_rows(flat, held);
  // Two C0 lines each way: u-lines across nv rows, v-lines across nu rows.
  const int nu = flat.count(Direction::u), nv = flat.count(Direction::v);
  REQUIRE(rows.size() == static_cast<std::size_t>(2 * nv + 2 * nu));
  std::vector<int> on_count(static_cast<std::size_t>(nu * nv), 0);
  int tied = 0;
  for (const argil::JoinRow& r : rows) {
    CHECK(r.ratio == Approx(1.0));  // equal pieces
    if (!r.tied) continue;
    ++tied;
    ++on_count[static_cast<std::size_t>(r.on)];
  }
  // Rows through the three poles around a crossing line are left to the joint term.
  CHECK(tied == 2 * uncrossed_rows(nv, 2, 3) + 2 * uncrossed_rows(nu, 3, 3));
  for (const argil::JoinRow& r : rows) {
    if (!r.tied) continue;
    CHECK(on_count[static_cast<std::size_t>(r.on)] == 1);
    CHECK(on_count[static_cast<std::size_t>(r.before)] == 0);
    CHECK(on_count[static_cast<std::size_t>(r.after)] == 0);
  }
  // The creased v-line's rows are not tied; the other v-line's still are.
  const BSplineSurface creased = crossed_plate(3, 2, 3, true);
  int creased_tied = 0;
  for (const argil::JoinRow& r : argil::join_rows(creased, held))
    if (r.tied && r.direction == 1) ++creased_tied;
  CHECK(creased_tied == uncrossed_rows(nu, 3, 3));
  // A row with a held pole is not a join row at all.
  std::vector<char> edge = held;
  for (int j = 0; j < nv; ++j) edge[static_cast<std::size_t>(flat.pole_index(3, j))] = 1;
  for (const argil::JoinRow& r : argil::join_rows(flat, edge)) {
    CHECK(edge[static_cast<std::size_t>(r.on)] == 0);
    CHECK(edge[static_cast<std::size_t>(r.before)] == 0);
    CHECK(edge[static_cast<std::size_t>(r.after)] == 0);
  }
}

TEST_CASE("join rows: the band tie equals the dense T^T A T", "[deformation][joins]") {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> value(-1.0, 1.0);
  for (const auto& [p, q] : {std::pair{2, 2}, std::pair{3, 2}, std::pair{2, 4}}) {
    const BSplineSurface s = crossed_plate(p, q, 3, false);
    const int nu = s.count(Direction::u), nv = s.count(Direction::v);
    const int n = nu * nv;
    const std::vector<argil::JoinRow> rows =
        argil::join_rows(s, std::vector<char>(static_cast<std::size_t>(n), 0));
    const std::array<int, 2> extra = argil::tie_reach(rows);
    REQUIRE(extra[0] > 0);
    REQUIRE(extra[1] > 0);
    // A random symmetric matrix coupling poles within the basis reach, made
    // positive definite; unknowns ordered row-major in u.
    const int ru = p, rv = q;
    Eigen::MatrixXd a = Eigen::MatrixXd::Zero(n, n);
    for (int i = 0; i < nu; ++i)
      for (int j = 0; j < nv; ++j)
        for (int k = 0; k < nu; ++k)
          for (int l = 0; l < nv; ++l)
            if (std::abs(k - i) <= ru && std::abs(l - j) <= rv && i * nv + j < k * nv + l) {
              const double x = value(rng);
              a(i * nv + j, k * nv + l) = x;
              a(k * nv + l, i * nv + j) = x;
            }
    a.diagonal().array() += a.cwiseAbs().rowwise().sum().array() + 1.0;
    std::vector<int> rank(static_cast<std::size_t>(n));
    for (int i = 0; i < n; ++i) rank[static_cast<std::size_t>(i)] = i;
    const int band = (ru + extra[0]) * nv + rv + extra[1];
    argil::SymmetricBandMatrix b(n, band);
    for (int i = 0; i < n; ++i)
      for (int j = std::max(0, i - band); j <= i; ++j) b.at(i, j) = a(i, j);
    argil::tie_matrix(b, rows, rank);
    // The dense product, each tied `on` unknown given a unit diagonal.
    Eigen::MatrixXd t = Eigen::MatrixXd::Identity(n, n);
    for (const argil::JoinRow& r : rows) {
      if (!r.tied) continue;
      t(r.on, r.on) = 0.0;
      t(r.on, r.before) = r.lambda();
      t(r.on, r.after) = 1.0 - r.lambda();
    }
    Eigen::MatrixXd want = t.transpose() * a * t;
    for (const argil::JoinRow& r : rows)
      if (r.tied) want(r.on, r.on) = 1.0;
    double largest_miss = 0.0;
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j) {
        const double got = std::abs(i - j) <= band ? b.at(std::max(i, j), std::min(i, j)) : 0.0;
        largest_miss = std::max(largest_miss, std::abs(got - want(i, j)));
      }
    CAPTURE(p, q, band);
    CHECK(largest_miss <= 1e-12 * want.cwiseAbs().maxCoeff());
    // Loads and solutions: T^T b and T x.
    argil::RowMajorMatrix load = argil::RowMajorMatrix::Random(n, 3);
    const Eigen::MatrixXd want_load = t.transpose() * Eigen::MatrixXd(load);
    argil::tie_load(load, rows, rank);
    CHECK((Eigen::MatrixXd(load) - want_load).norm() <= 1e-14 * want_load.norm());
    argil::RowMajorMatrix x = argil::RowMajorMatrix::Random(n, 3);
    const Eigen::MatrixXd want_x = t * Eigen::MatrixXd(x);
    argil::untie_solution(x, rows, rank);
    CHECK((Eigen::MatrixXd(x) - want_x).norm() <= 1e-14 * want_x.norm());
  }
}

TEST_CASE("join rows: a pressed body keeps its tied rows straight in their rest proportions",
          "[deformation][joins]") {
  const BSplineSurface s = crossed_plate(3, 3, 3, false);
  const argil::Material clay = *argil::material_preset("clay");
  argil::OperatorCache cache;
  argil::Result<argil::DeformableBody> made = argil::DeformableBody::create(s, clay, {}, cache);
  REQUIRE(made.ok());
  argil::DeformableBody body = std::move(made).value();
  // Forces on every pole, uneven, pushing the middle down: the tied rows must
  // move with their rows whatever the load.
  argil::ControlNet forces = argil::ControlNet::Zero(s.control_points.rows(), 3);
  for (Eigen::Index i = 0; i < forces.rows(); ++i) {
    const double x = static_cast<double>(i);
    forces.row(i) << 0.01 * std::sin(1.7 * x), 0.02 * std::cos(0.9 * x),
        -0.05 * static_cast<double>((i % 5) + 1);
  }
  for (int tick = 0; tick < 200; ++tick) REQUIRE(body.step(1e-3, forces).ok());
  const argil::ControlNet& p = body.control_points();
  double largest_move = (p - s.control_points).rowwise().norm().maxCoeff();
  REQUIRE(largest_move > 1e-3);
  int tied = 0;
  for (const argil::JoinRow& r : argil::join_rows(s, body.fixed())) {
    if (!r.tied) continue;
    ++tied;
    const Eigen::RowVector3d miss =
        p.row(r.on) - r.lambda() * p.row(r.before) - (1.0 - r.lambda()) * p.row(r.after);
    CAPTURE(r.before, r.on, r.after);
    CHECK(miss.norm() <= 1e-12 * largest_move + 1e-12);
    const Eigen::RowVector3d rest_miss =
        body.rest_control_points().row(r.on) -
        r.lambda() * body.rest_control_points().row(r.before) -
        (1.0 - r.lambda()) * body.rest_control_points().row(r.after);
    CHECK(rest_miss.norm() <= 1e-12 * largest_move + 1e-12);
  }
  CHECK(tied > 0);
}
