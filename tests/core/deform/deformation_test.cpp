// Deformation and haptic force (docs/deformation.md): material ranges, the exact node load
// pattern, static equilibrium against a direct solve, momentum and energy of
// the implicit step, elasticity, plasticity, boundary conditions, determinism
// and a stability sweep.
#include <Eigen/Dense>
#include <catch2/catch.hpp>
#include <cmath>
#include <limits>
#include <random>

#include "argil/core.hpp"

namespace {

using argil::ControlNet;

Eigen::VectorXd uniform_knots(int degree, int poles) {
  Eigen::VectorXd k(poles + degree + 1);
  for (Eigen::Index i = 0; i < k.size(); ++i)
    k[i] = std::clamp(static_cast<double>(i - degree) / (poles - degree), 0.0, 1.0);
  return k;
}

/// A bicubic panel in z = 0 (plus an optional wave), n x n poles, `pitch` [mm] apart.
argil::BSplineSurface panel(int n, double pitch = 10.0, double wave = 0.0) {
  argil::BSplineSurface s;
  s.degree = {3, 3};
  s.knots = {uniform_knots(3, n), uniform_knots(3, n)};
  s.control_points.resize(static_cast<Eigen::Index>(n) * n, 3);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      s.control_points.row(s.pole_index(i, j)) << pitch * i, pitch * j,
          wave * std::sin(0.7 * i) * std::cos(0.5 * j);
  return s;
}

/// Density that gives the panel's heaviest node `mass` [kg] (its lightest
/// with `lightest`: corner nodes carry a quarter of an interior node's area).
double density_for(const argil::BSplineSurface& s, double mass, bool lightest = false) {
  argil::OperatorCache cache;
  const auto ops = argil::surface_operators(s, cache).value();
  const Eigen::VectorXd unit = argil::node_masses(s, ops, 1.0);
  // The factors keep the products inside the range despite rounding.
  return lightest ? mass / unit.minCoeff() * (1 + 1e-12) : mass / unit.maxCoeff() * (1 - 1e-12);
}

argil::DeformableBody body(const argil::BSplineSurface& s, const argil::Material& m,
                           const argil::BoundaryConditions& bc = {}) {
  static argil::OperatorCache cache;
  auto b = argil::DeformableBody::create(s, m, bc, cache);
  INFO(b.status().message);
  REQUIRE(b.ok());
  return std::move(b).value();
}

double total_energy(const argil::DeformableBody& b) {
  return b.kinetic_energy() + b.potential_energy();
}

}  // namespace

TEST_CASE("validate(Material) names the field outside its range", "[deformation]") {
  CHECK(argil::validate(argil::Material{}).ok());
  const auto fails_on = [](argil::Material m, const char* field) {
    const argil::Status s = argil::validate(m);
    CHECK(s.code == argil::StatusCode::invalid_argument);
    CHECK(s.message.find(field) != std::string::npos);
  };
  const double nan = std::numeric_limits<double>::quiet_NaN();
  argil::Material m;
  m.density = 0.0;
  fails_on(m, "density");
  m = {};
  m.stiffness = 2e9;
  fails_on(m, "stiffness");
  m = {};
  m.damping = -1.0;
  fails_on(m, "damping");
  m = {};
  m.anchor_stiffness = nan;
  fails_on(m, "anchor_stiffness");
  m = {};
  m.yield = 0.0;
  fails_on(m, "yield");
  m = {};
  m.yield = std::numeric_limits<double>::infinity();  // purely elastic is valid
  CHECK(argil::validate(m).ok());
}

TEST_CASE("validate(Material) states the range and the value in the field's unit",
          "[deformation]") {
  argil::Material m;
  m.stiffness = 2e9;
  CHECK(argil::validate(m).message ==
        "material.stiffness must be in [0, 1e+09] N/mm, got 2e+09 N/mm");
  m = {};
  m.damping = -0.1;
  CHECK(argil::validate(m).message == "material.damping must be in [0, " +
                                          argil::number_text(argil::kMaterialRange.damping.high) +
                                          "] s, got -0.1 s");
}

TEST_CASE("node masses outside the documented range are rejected naming density", "[deformation]") {
  const auto s = panel(6);
  argil::Material m;
  m.density = 1e-12;  // valid density, but 100 mm^2 nodes weigh 1e-10 kg
  argil::OperatorCache cache;
  const auto b = argil::DeformableBody::create(s, m, {}, cache);
  REQUIRE_FALSE(b.ok());
  CHECK(b.status().message.find("density") != std::string::npos);
}

TEST_CASE("a contact load pattern carries the force and its moment exactly to the nodes",
          "[deformation]") {
  // Asymmetric rational surface: degree 3 x 2, 7 x 5 poles, a double knot.
  argil::BSplineSurface s;
  s.degree = {3, 2};
  s.knots[0].resize(11);
  s.knots[0] << 0, 0, 0, 0, 0.2, 0.45, 0.45, 1, 1, 1, 1;
  s.knots[1].resize(8);
  s.knots[1] << 0, 0, 0, 0.3, 0.7, 1, 1, 1;
  s.control_points.resize(35, 3);
  s.weights.resize(35);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> jitter(-2.0, 2.0), w(0.5, 2.0);
  for (int i = 0; i < 7; ++i)
    for (int j = 0; j < 5; ++j) {
      s.control_points.row(s.pole_index(i, j)) << 10.0 * i + jitter(rng), 8.0 * j + jitter(rng),
          jitter(rng);
      s.weights[s.pole_index(i, j)] = w(rng);
    }
  argil::OperatorCache cache;
  const auto ops = argil::surface_operators(s, cache).value();
  std::vector<argil::Contact> contacts(3);
  contacts[0].uv_a = {0.1, 0.2};
  contacts[1].uv_a = {0.45, 0.9};
  contacts[2].uv_a = {0.77, 0.31};
  const std::vector<double> shares{0.5, 0.3, 0.2};
  const Eigen::VectorXd g = argil::contact_load_pattern(s, ops, contacts, shares);
  // sum g_i = 1 (the force) and sum g_i x_i = the shared point (the moment),
  // for the surface's own nodes and for any other node positions.
  CHECK(g.sum() == Approx(1.0).epsilon(1e-12));  // rounding of two banded solves
  const ControlNet nodes = argil::evaluate_nodes(s, ops);
  Eigen::Vector3d shared = Eigen::Vector3d::Zero();
  for (int k = 0; k < 3; ++k)
    shared += shares[static_cast<std::size_t>(k)] *
              argil::evaluate(s, contacts[static_cast<std::size_t>(k)].uv_a.x(),
                              contacts[static_cast<std::size_t>(k)].uv_a.y());
  CHECK((nodes.transpose() * g - shared).norm() < 1e-10 * 60.0);  // rounding, 60 mm model
  ControlNet moved = nodes;
  for (Eigen::Index i = 0; i < moved.rows(); ++i)
    moved(i, 2) += std::sin(0.3 * static_cast<double>(i));
  argil::BSplineSurface fitted = s;
  fitted.control_points = argil::fit_control_points(s, ops, moved);
  Eigen::Vector3d shared_moved = Eigen::Vector3d::Zero();
  for (int k = 0; k < 3; ++k)
    shared_moved += shares[static_cast<std::size_t>(k)] *
                    argil::evaluate(fitted, contacts[static_cast<std::size_t>(k)].uv_a.x(),
                                    contacts[static_cast<std::size_t>(k)].uv_a.y());
  CHECK((moved.transpose() * g - shared_moved).norm() < 1e-10 * 60.0);
}

TEST_CASE("anchor-only equilibrium under a uniform load is F / k_anchor", "[deformation]") {
  const auto s = panel(8);
  argil::Material m;
  m.density = density_for(s, 1e-3);
  m.stiffness = 3.0;  // springs carry nothing under a uniform displacement
  m.anchor_stiffness = 2.0;
  m.damping = 0.02;
  argil::DeformableBody b = body(s, m);
  const Eigen::RowVector3d f(0.1, -0.2, 0.5);  // [N] per node
  ControlNet load(b.nodes().rows(), 3);
  load.rowwise() = f;
  for (int t = 0; t < 400; ++t) REQUIRE(b.step(0.01, load).ok());
  const ControlNet u = b.nodes() - b.rest_nodes();
  for (Eigen::Index i = 0; i < u.rows(); ++i)
    CHECK((u.row(i) - f / m.anchor_stiffness).norm() < 1e-9);  // converged to 1e-9 mm
}

TEST_CASE("static equilibrium with springs and fixed edges matches a direct solve",
          "[deformation]") {
  const int n = 7;
  const auto s = panel(n);
  argil::Material m;
  m.density = density_for(s, 1e-3);
  m.stiffness = 5.0;
  m.anchor_stiffness = 0.5;
  m.damping = 0.05;
  argil::BoundaryConditions bc;
  bc.fixed_u0 = true;
  bc.fixed_v1 = true;
  argil::DeformableBody b = body(s, m, bc);
  ControlNet load = ControlNet::Zero(n * n, 3);
  load.row(4 * n + 3) << 0.0, 0.0, -1.0;
  load.row(2 * n + 2) << 0.3, 0.0, 0.2;
  for (int t = 0; t < 2000; ++t) REQUIRE(b.step(0.02, load).ok());

  // Oracle: K u = f on the free nodes, K assembled here from the stencil
  // (neighbours at offsets (1,0), (0,1), (1,1), (1,-1), (2,0), (0,2)).
  const auto fixed = [&](int i, int j) { return i == 0 || j == n - 1; };
  Eigen::MatrixXd k = Eigen::MatrixXd::Zero(n * n, n * n);
  const int offsets[6][2] = {{1, 0}, {0, 1}, {1, 1}, {1, -1}, {2, 0}, {0, 2}};
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      k(i * n + j, i * n + j) += m.anchor_stiffness;
      for (const auto& o : offsets) {
        const int i2 = i + o[0], j2 = j + o[1];
        if (i2 < 0 || j2 < 0 || i2 >= n || j2 >= n) continue;
        const int a = i * n + j, c = i2 * n + j2;
        k(a, a) += m.stiffness;
        k(c, c) += m.stiffness;
        k(a, c) -= m.stiffness;
        k(c, a) -= m.stiffness;
      }
    }
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      if (fixed(i, j)) {
        k.row(i * n + j).setZero();
        k.col(i * n + j).setZero();
        k(i * n + j, i * n + j) = 1.0;
      }
  Eigen::MatrixXd rhs = load;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      if (fixed(i, j)) rhs.row(i * n + j).setZero();
  const Eigen::MatrixXd expected = k.ldlt().solve(rhs);
  const ControlNet u = b.nodes() - b.rest_nodes();
  CHECK((u - expected).cwiseAbs().maxCoeff() < 1e-8);  // converged to 1e-8 mm
  CHECK((u - expected).cwiseAbs().maxCoeff() < 1e-6 * expected.cwiseAbs().maxCoeff());
}

TEST_CASE("fixed edges and corners stay exactly at rest and the edge curve keeps its shape",
          "[deformation]") {
  const int n = 6;
  const auto s = panel(n, 10.0, 3.0);
  argil::Material m;
  m.density = density_for(s, 1e-3);
  m.anchor_stiffness = 0.1;
  argil::BoundaryConditions bc;
  bc.fixed_v0 = true;
  bc.fixed_corners = true;
  argil::DeformableBody b = body(s, m, bc);
  ControlNet load = ControlNet::Constant(n * n, 3, 0.7);
  for (int t = 0; t < 50; ++t) REQUIRE(b.step(1e-3, load).ok());
  const ControlNet rest0 = b.rest_nodes();
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const bool held = j == 0 || ((i == 0 || i == n - 1) && j == n - 1);
      const Eigen::Index k = i * n + j;
      if (held) {
        CHECK(b.nodes().row(k) == rest0.row(k));  // bit-exact
        CHECK(b.velocities().row(k).norm() == 0.0);
      } else {
        CHECK((b.nodes().row(k) - rest0.row(k)).norm() > 1e-3);  // the load moved it
      }
    }
  // The surface's v = v_min edge depends only on the held nodes.
  for (double u = 0.0; u <= 1.0; u += 0.125)
    CHECK((argil::evaluate(b.surface(), u, 0.0) - argil::evaluate(s, u, 0.0)).norm() < 1e-12 * 50);
  CHECK((argil::evaluate(b.surface(), 0.0, 1.0) - argil::evaluate(s, 0.0, 1.0)).norm() <
        1e-12 * 50);
}

TEST_CASE("every step refits the control points exactly through the nodes", "[deformation]") {
  const auto s = panel(6, 10.0, 2.0);
  argil::Material m;
  m.density = density_for(s, 1e-3);
  argil::DeformableBody b = body(s, m);
  ControlNet load = ControlNet::Zero(36, 3);
  load.row(14) << 0.0, 0.0, 2.0;
  for (int t = 0; t < 20; ++t) REQUIRE(b.step(1e-3, load).ok());
  const ControlNet at_nodes = argil::evaluate_nodes(b.surface(), b.operators());
  CHECK((at_nodes - b.nodes()).cwiseAbs().maxCoeff() < 1e-12 * 60);  // rounding, 60 mm model
  CHECK(b.hierarchy().surface().control_points == b.surface().control_points);
}

TEST_CASE("a free body conserves momentum under its internal springs", "[deformation]") {
  const auto s = panel(6, 10.0, 2.0);
  argil::Material m;
  m.density = density_for(s, 1e-2);
  m.stiffness = 20.0;
  m.anchor_stiffness = 0.0;
  m.damping = 0.01;
  argil::DeformableBody b = body(s, m);
  std::mt19937 rng(3);
  std::normal_distribution<double> normal(0.0, 1.0);
  ControlNet kick(36, 3);
  for (Eigen::Index i = 0; i < kick.rows(); ++i)
    kick.row(i) << normal(rng), normal(rng), normal(rng);
  const double h = 1e-3;
  REQUIRE(b.step(h, kick).ok());
  const auto momentum = [&] {
    Eigen::Vector3d p = Eigen::Vector3d::Zero();
    for (Eigen::Index i = 0; i < b.velocities().rows(); ++i)
      p += argil::kMassToNewtonSecond2PerMm * b.masses()[i] * b.velocities().row(i).transpose();
    return p;
  };
  // One step of the kick adds h * sum f; nothing else changes it afterwards.
  const Eigen::Vector3d impulse = h * kick.colwise().sum().transpose();
  CHECK((momentum() - impulse).norm() < 1e-12 * (1.0 + impulse.norm()));
  for (int t = 0; t < 300; ++t) REQUIRE(b.step(h).ok());
  CHECK((momentum() - impulse).norm() < 1e-11 * (1.0 + impulse.norm()));  // 300 steps of rounding
  CHECK(b.kinetic_energy() > 0.0);
}

TEST_CASE("without input the energy never increases, with or without damping", "[deformation]") {
  for (const double beta : {0.0, 1e-3}) {
    const auto s = panel(7, 10.0, 2.0);
    argil::Material m;
    m.density = density_for(s, 1e-3);
    m.stiffness = 50.0;
    m.anchor_stiffness = 2.0;
    m.damping = beta;
    argil::DeformableBody b = body(s, m);
    ControlNet kick = ControlNet::Zero(49, 3);
    kick.row(24) << 5.0, -3.0, 20.0;
    for (int t = 0; t < 5; ++t) REQUIRE(b.step(1e-3, kick).ok());
    double previous = total_energy(b);
    REQUIRE(previous > 0.0);
    const double start = previous;
    for (int t = 0; t < 500; ++t) {
      REQUIRE(b.step(1e-3).ok());
      const double e = total_energy(b);
      CHECK(e <= previous * (1.0 + 1e-12) + 1e-15 * start);  // rounding of the energy sums
      previous = e;
    }
    CHECK(previous < start);
  }
}

TEST_CASE("an elastic body returns to rest and a plastic one keeps what went beyond yield",
          "[deformation]") {
  const auto s = panel(6);
  argil::Material m;
  m.density = density_for(s, 1e-3);
  m.stiffness = 0.0;
  m.anchor_stiffness = 1.0;
  m.damping = 0.02;                            // overdamped: no overshoot after release
  const Eigen::RowVector3d f(0.0, 0.0, -2.0);  // 2 N per node against a 1 N/mm anchor
  ControlNet load(36, 3);
  load.rowwise() = f;
  for (const double yield : {std::numeric_limits<double>::infinity(), 0.5}) {
    CAPTURE(yield);
    m.yield = yield;
    argil::DeformableBody b = body(s, m);
    const ControlNet original = b.nodes();
    for (int t = 0; t < 30; ++t) REQUIRE(b.step(0.01, load).ok());
    const ControlNet at_release = b.nodes();
    const ControlNet rest_at_release = b.rest_nodes();
    for (int t = 0; t < 600; ++t) REQUIRE(b.step(0.01).ok());
    for (Eigen::Index i = 0; i < 36; ++i) {
      const double reached = (at_release.row(i) - original.row(i)).norm();
      REQUIRE(reached > 1.0);  // well beyond the yield
      if (!std::isfinite(yield)) {
        CHECK((b.nodes().row(i) - original.row(i)).norm() < 1e-8);  // converged to rest
      } else {
        // Past yield the rest followed the node at exactly `yield` behind it,
        // and the unloaded node settles there: the part beyond yield stays.
        CHECK((at_release.row(i) - rest_at_release.row(i)).norm() == Approx(yield).epsilon(1e-12));
        CHECK((b.nodes().row(i) - rest_at_release.row(i)).norm() < 1e-8);
        CHECK((b.nodes().row(i) - original.row(i)).norm() == Approx(reached - yield).epsilon(1e-9));
      }
    }
  }
}

TEST_CASE("the stability sweep: stiffness 1e0..1e9 N/mm, node mass 1e-6..1e3 kg", "[deformation]") {
  const auto s = panel(6, 10.0, 2.0);
  for (const double k : {1.0, 1e3, 1e6, 1e9}) {
    for (const double mass : {1e-6, 1e-3, 1.0, 1e3}) {
      CAPTURE(k, mass);
      argil::Material m;
      m.density = density_for(s, mass, mass < 1.0);  // every node mass inside the sweep
      m.stiffness = k;
      m.anchor_stiffness = k;
      m.damping = 0.0;
      argil::DeformableBody b = body(s, m);
      ControlNet kick = ControlNet::Zero(36, 3);
      kick.row(14) << 1.0, 2.0, k;  // a 1 mm stretch's worth of force, and a skew
      REQUIRE(b.step(1e-3, kick).ok());
      double previous = total_energy(b);
      for (int t = 0; t < 200; ++t) {
        REQUIRE(b.step(1e-3).ok());
        REQUIRE(b.nodes().allFinite());
        const double e = total_energy(b);
        CHECK(e <= previous * (1.0 + 1e-9) + 1e-300);  // rounding at extreme ratios
        previous = e;
      }
      CHECK((b.nodes() - b.rest_nodes()).cwiseAbs().maxCoeff() < 2.0);  // bounded
    }
  }
  // Just outside the range: clear errors naming the field.
  argil::Material m;
  m.stiffness = 1e10;
  CHECK(argil::validate(m).message.find("stiffness") != std::string::npos);
  m = {};
  m.density = density_for(s, 1e4);
  argil::OperatorCache cache;
  const auto heavy = argil::DeformableBody::create(s, m, {}, cache);
  REQUIRE_FALSE(heavy.ok());
  CHECK(heavy.status().message.find("density") != std::string::npos);
}
