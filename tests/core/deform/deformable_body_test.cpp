// The deformable body's step (docs/deformation.md) on the u/v-asymmetric
// rational surface: energy never grows without input, held control points
// never move, plasticity bounds every stretch by the yield, the static
// equilibrium matches a direct solve of K u = f, a free body conserves
// momentum, the load preview is the step's own response, and the transposed
// surface behaves identically with its rows transposed.
#include <Eigen/Dense>
#include <catch2/catch.hpp>
#include <cmath>
#include <limits>
#include <random>

#include "argil/core.hpp"
#include "support/point_load.hpp"
#include "support/random_surface.hpp"
#include "support/transposed_surface.hpp"

namespace {

using argil::BSplineSurface;
using argil::ControlNet;
using argil::Direction;
using argil::test::pattern_at;

constexpr int kCountU = 7;
constexpr int kCountV = 5;

/// Clay, elastic unless a yield is given.
argil::Material clay(double damping = 1e-3,
                     double yield = std::numeric_limits<double>::infinity()) {
  argil::Material m = *argil::material_preset("clay");
  m.damping = damping;
  m.yield = yield;
  return m;
}

argil::DeformableBody make_body(const BSplineSurface& s, const argil::Material& m,
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

ControlNet random_forces(Eigen::Index n, double scale, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> normal(0.0, scale);
  ControlNet f(n, 3);
  for (Eigen::Index i = 0; i < f.size(); ++i) f.data()[i] = normal(rng);
  return f;
}

double model_size(const BSplineSurface& s) { return argil::control_point_box(s).diagonal(); }

}  // namespace

TEST_CASE("without input the energy never grows, with or without damping", "[deformation][body]") {
  const BSplineSurface s = argil::test::asymmetric_surface();
  for (const double beta : {0.0, 1e-3}) {
    for (const double dt : {1e-3, 2e-2}) {
      CAPTURE(beta, dt);
      argil::DeformableBody b = make_body(s, clay(beta));
      const ControlNet kick = random_forces(s.control_points.rows(), 0.5, 3);
      for (int t = 0; t < 5; ++t) REQUIRE(b.step(dt, kick).ok());
      const double start = total_energy(b);
      REQUIRE(start > 0.0);
      double previous = start, largest_rise = 0.0;
      for (int t = 0; t < 400; ++t) {
        REQUIRE(b.step(dt).ok());
        const double e = total_energy(b);
        largest_rise = std::max(largest_rise, (e - previous) / start);
        previous = e;
      }
      CAPTURE(start, previous, largest_rise);
      CHECK(largest_rise <= 1e-13);  // rounding of the energy sums
      CHECK(previous < start);       // implicit Euler dissipates even without damping
    }
  }
}

TEST_CASE("held control points never move, bit for bit", "[deformation][body]") {
  const BSplineSurface s = argil::test::asymmetric_surface();
  const argil::BoundaryConditions bc{.fixed_v0 = true, .fixed_corners = true};
  argil::DeformableBody b = make_body(s, clay(1e-3, 0.05), bc);
  const ControlNet rest = b.control_points();
  const ControlNet load = random_forces(rest.rows(), 2.0, 5);
  const Eigen::VectorXd g = pattern_at(s, 0.1, 0.05);  // near the held edge and corner
  for (int t = 0; t < 60; ++t) {
    REQUIRE(b.begin_step(1e-3, load, g).ok());
    b.finish_step(Eigen::Vector3d(0.3, -0.2, -3.0));
  }
  int held = 0;
  for (int i = 0; i < kCountU; ++i)
    for (int j = 0; j < kCountV; ++j) {
      const Eigen::Index k = s.pole_index(i, j);
      const bool corner = (i == 0 || i == kCountU - 1) && (j == 0 || j == kCountV - 1);
      CAPTURE(i, j);
      CHECK(static_cast<bool>(b.fixed()[static_cast<std::size_t>(k)]) == (j == 0 || corner));
      if (j == 0 || corner) {
        ++held;
        CHECK(b.control_points().row(k) == rest.row(k));
        CHECK(b.rest_control_points().row(k) == rest.row(k));
        CHECK(b.velocities().row(k).norm() == 0.0);
      } else {
        CHECK((b.control_points().row(k) - rest.row(k)).norm() > 1e-4);  // the load moved it
      }
    }
  CHECK(held == kCountU + 2);
  // The held edge v = v_min is a curve of held poles only: it has not moved.
  for (double u = 0.0; u <= 1.0; u += 0.125)
    CHECK(argil::evaluate(b.surface(), u, -1.0) == argil::evaluate(s, u, -1.0));
}

TEST_CASE("plasticity keeps every control point within its stretch cap and keeps what went beyond",
          "[deformation][body]") {
  const BSplineSurface s = argil::test::asymmetric_surface();
  const double yield = 0.05;
  argil::DeformableBody b = make_body(s, clay(2e-2, yield));
  const Eigen::VectorXd g = pattern_at(s, 0.62, 0.27);
  double largest_stretch = 0.0;
  for (int t = 0; t < 200; ++t) {
    REQUIRE(b.begin_step(1e-3, {}, g).ok());
    b.finish_step(Eigen::Vector3d(0.0, 0.5, -20.0));
    const double stretch =
        (b.control_points() - b.rest_control_points()).rowwise().norm().maxCoeff();
    largest_stretch = std::max(largest_stretch, stretch);
  }
  // Rounding of the rescaled stretch; the load did reach the cap.
  CHECK(largest_stretch <= argil::kPlasticStretchCap * yield * (1.0 + 1e-12));
  CHECK(largest_stretch > 0.9 * yield);
  const double flowed = (b.rest_control_points() - s.control_points).rowwise().norm().maxCoeff();
  CHECK(flowed > 10.0 * yield);  // well past the yield: the dent is the new rest
  // Released, the body returns to its moved rest, not to the original.
  for (int t = 0; t < 400; ++t) REQUIRE(b.step(1e-2).ok());
  CHECK((b.control_points() - b.rest_control_points()).cwiseAbs().maxCoeff() < 1e-9);
}

TEST_CASE("static equilibrium matches a direct solve of K u = f on the free control points",
          "[deformation][body]") {
  const BSplineSurface s = argil::test::asymmetric_surface();
  const argil::BoundaryConditions bc{.fixed_u0 = true};
  argil::DeformableBody b = make_body(s, clay(1e-3), bc);
  const ControlNet f = random_forces(s.control_points.rows(), 0.05, 9);
  for (int t = 0; t < 300; ++t) REQUIRE(b.step(0.05, f).ok());
  // Oracle: the dense stiffness, held rows and columns removed.
  const Eigen::Index n = s.control_points.rows();
  Eigen::MatrixXd k = b.stiffness().multiply(Eigen::MatrixXd::Identity(n, n));
  Eigen::MatrixXd rhs = f;
  for (Eigen::Index i = 0; i < n; ++i)
    if (b.fixed()[static_cast<std::size_t>(i)]) {
      k.row(i).setZero();
      k.col(i).setZero();
      k(i, i) = 1.0;
      rhs.row(i).setZero();
    }
  const Eigen::MatrixXd expected = k.ldlt().solve(rhs);
  const ControlNet u = b.control_points() - b.rest_control_points();
  CAPTURE(expected.cwiseAbs().maxCoeff());
  CHECK((u - expected).cwiseAbs().maxCoeff() <= 1e-9 * expected.cwiseAbs().maxCoeff());
}

TEST_CASE("a free body without foundation conserves momentum", "[deformation][body]") {
  const BSplineSurface s = argil::test::asymmetric_surface();
  argil::Material m = clay(1e-3);
  m.foundation_stiffness = 0.0;
  argil::DeformableBody b = make_body(s, m);
  const ControlNet kick = random_forces(s.control_points.rows(), 1.0, 4);
  const double h = 1e-3;
  REQUIRE(b.step(h, kick).ok());
  const auto momentum = [&] {
    Eigen::Vector3d p = Eigen::Vector3d::Zero();
    for (Eigen::Index i = 0; i < b.velocities().rows(); ++i)
      p += argil::kMassToNewtonSecond2PerMm * b.masses()[i] * b.velocities().row(i).transpose();
    return p;
  };
  const Eigen::Vector3d impulse = h * kick.colwise().sum().transpose();
  CHECK((momentum() - impulse).norm() <= 1e-10 * impulse.norm());
  for (int t = 0; t < 300; ++t) REQUIRE(b.step(h).ok());
  CHECK((momentum() - impulse).norm() <= 1e-9 * impulse.norm());  // 300 steps of rounding
}

TEST_CASE("the load preview is the loaded point's own motion and compliance",
          "[deformation][body]") {
  const BSplineSurface s = argil::test::asymmetric_surface();
  const Eigen::VectorXd g = pattern_at(s, 0.71, 0.38);
  const auto loaded_point_after = [&](const Eigen::Vector3d& force, argil::LoadPreview& preview) {
    argil::DeformableBody body = make_body(s, clay(1e-3), {.fixed_v1 = true});
    for (int t = 0; t < 3; ++t) {  // moving, with velocities
      REQUIRE(body.begin_step(1e-3, {}, g).ok());
      body.finish_step(Eigen::Vector3d(0.0, 0.1, -0.4));
    }
    const Eigen::Vector3d before = body.control_points().transpose() * g;
    preview = body.begin_step(1e-3, {}, g).value();
    body.finish_step(force);
    return Eigen::Vector3d(body.control_points().transpose() * g - before);
  };
  argil::LoadPreview p0, p1;
  const Eigen::Vector3d free = loaded_point_after(Eigen::Vector3d::Zero(), p0);
  CHECK((free - p0.free_motion).norm() <= 1e-12 * (1.0 + free.norm()));
  const double df = 0.25;  // [N]; the step is linear in the force
  for (int c = 0; c < 3; ++c) {
    const Eigen::Vector3d moved = loaded_point_after(df * Eigen::Vector3d::Unit(c), p1);
    const Eigen::Vector3d slope = (moved - free) / df;
    CAPTURE(c, p0.compliance);
    CHECK(p1.compliance == p0.compliance);
    CHECK(slope[c] == Approx(p0.compliance).epsilon(1e-9));
    CHECK((slope - slope[c] * Eigen::Vector3d::Unit(c)).norm() <= 1e-9 * p0.compliance);
  }
}

TEST_CASE("transposing the surface transposes every step, the plastic rest and the velocities",
          "[deformation][body]") {
  const BSplineSurface s = argil::test::asymmetric_surface();
  const BSplineSurface t = argil::test::transposed(s);
  const double size = model_size(s);
  argil::DeformableBody a = make_body(s, clay(5e-3, 0.05), {.fixed_u0 = true});
  argil::DeformableBody b = make_body(t, clay(5e-3, 0.05), {.fixed_v0 = true});
  const ControlNet f = random_forces(s.control_points.rows(), 0.2, 8);
  const ControlNet f_t = argil::test::transposed_rows(f, kCountU, kCountV);
  const Eigen::Vector3d force(0.6, -0.4, -3.0);
  for (int tick = 0; tick < 40; ++tick) {
    // The pattern follows the moving surface, as in the haptic tick.
    std::vector<argil::Contact> c(1);
    c[0].uv_a = {0.62, 0.27};
    std::vector<argil::Contact> c_t = c;
    c_t[0].uv_a = c[0].uv_a.reverse().eval();
    const argil::LoadPreview pa =
        a.begin_step(1e-3, f, argil::contact_load_pattern(a.surface(), c, {1.0})).value();
    const argil::LoadPreview pb =
        b.begin_step(1e-3, f_t, argil::contact_load_pattern(b.surface(), c_t, {1.0})).value();
    CHECK(std::abs(pa.compliance - pb.compliance) <= 1e-11 * pa.compliance);
    CHECK((pa.free_motion - pb.free_motion).norm() <= 1e-11 * size);
    a.finish_step(force);
    b.finish_step(force);
  }
  const auto tr = [](const ControlNet& n) {
    return argil::test::transposed_rows(n, kCountU, kCountV);
  };
  CHECK((a.control_points() - s.control_points).cwiseAbs().maxCoeff() > 0.1);  // past the yield
  CHECK((tr(a.control_points()) - b.control_points()).cwiseAbs().maxCoeff() <= 1e-11 * size);
  CHECK((tr(a.rest_control_points()) - b.rest_control_points()).cwiseAbs().maxCoeff() <=
        1e-11 * size);
  CHECK((tr(a.velocities()) - b.velocities()).cwiseAbs().maxCoeff() <= 1e-11 * size / 1e-3);
  CHECK(std::abs(a.kinetic_energy() - b.kinetic_energy()) <= 1e-11 * a.kinetic_energy());
  CHECK(std::abs(a.potential_energy() - b.potential_energy()) <= 1e-11 * a.potential_energy());
}

TEST_CASE("an elastic body returns to rest once the load is gone", "[deformation][body]") {
  const BSplineSurface s = argil::test::asymmetric_surface();
  argil::DeformableBody b = make_body(s, clay(2e-2));
  const Eigen::VectorXd g = pattern_at(s, 0.62, 0.27);
  for (int t = 0; t < 100; ++t) {
    REQUIRE(b.begin_step(1e-3, {}, g).ok());
    b.finish_step(Eigen::Vector3d(0.0, 0.5, -5.0));
  }
  REQUIRE((b.control_points() - s.control_points).cwiseAbs().maxCoeff() > 0.1);
  CHECK(b.rest_control_points() == s.control_points);  // no yield, no flow
  for (int t = 0; t < 400; ++t) REQUIRE(b.step(1e-2).ok());
  CHECK((b.control_points() - s.control_points).cwiseAbs().maxCoeff() < 1e-9);
}

TEST_CASE("a point load dents the surface at its point, not at mirrored points",
          "[deformation][body]") {
  const BSplineSurface s = argil::test::asymmetric_surface();
  const double fs = 0.22, ft = 0.74;  // off-centre, away from both diagonals
  argil::DeformableBody body = make_body(s, clay(1e-3));
  const Eigen::VectorXd g = pattern_at(s, fs, ft);
  for (int t = 0; t < 50; ++t) {
    REQUIRE(body.begin_step(1e-3, {}, g).ok());
    body.finish_step(Eigen::Vector3d(0.0, 0.0, -3.0));
  }
  const auto dent = [&](double a, double b) {
    const double u = a, v = -1.0 + 3.0 * b;  // the domain is [0, 1] x [-1, 2]
    return (argil::evaluate(body.surface(), u, v) - argil::evaluate(s, u, v)).norm();
  };
  const double at_load = dent(fs, ft);
  CAPTURE(at_load, dent(ft, fs), dent(1.0 - fs, ft), dent(fs, 1.0 - ft));
  CHECK(at_load > 2.0 * dent(ft, fs));        // the u/v mirror
  CHECK(at_load > 2.0 * dent(1.0 - fs, ft));  // the u mirror
  CHECK(at_load > 2.0 * dent(fs, 1.0 - ft));  // the v mirror
  // The deepest dent on a 41 x 41 grid lies within a knot span of the load.
  double deepest = -1.0;
  Eigen::Vector2d where = Eigen::Vector2d::Zero();
  for (int i = 0; i <= 40; ++i)
    for (int j = 0; j <= 40; ++j)
      if (const double d = dent(i / 40.0, j / 40.0); d > deepest) {
        deepest = d;
        where = {i / 40.0, j / 40.0};
      }
  CAPTURE(where.transpose());
  CHECK((where - Eigen::Vector2d(fs, ft)).norm() < 0.15);
}

TEST_CASE("an affine change of the knots leaves the pattern, the masses and the step alone",
          "[deformation][body]") {
  const BSplineSurface s = argil::test::asymmetric_surface();
  BSplineSurface r = s;  // u' = 3 u - 2, v' = 0.25 v + 7
  r.knots[0] = (3.0 * s.knots[0].array() - 2.0).matrix();
  r.knots[1] = (0.25 * s.knots[1].array() + 7.0).matrix();
  const double size = model_size(s);
  CHECK((pattern_at(s, 0.41, 0.83) - pattern_at(r, 0.41, 0.83)).cwiseAbs().maxCoeff() < 1e-14);
  argil::DeformableBody a = make_body(s, clay(1e-3));
  argil::DeformableBody b = make_body(r, clay(1e-3));
  CHECK(((a.masses() - b.masses()).array().abs() / a.masses().array()).maxCoeff() < 1e-12);
  for (int t = 0; t < 5; ++t) {
    REQUIRE(a.begin_step(1e-3, {}, pattern_at(a.surface(), 0.41, 0.83)).ok());
    REQUIRE(b.begin_step(1e-3, {}, pattern_at(b.surface(), 0.41, 0.83)).ok());
    a.finish_step(Eigen::Vector3d(0.5, 0.2, -1.0));
    b.finish_step(Eigen::Vector3d(0.5, 0.2, -1.0));
  }
  CHECK((a.control_points() - s.control_points).cwiseAbs().maxCoeff() > 1e-3);
  CHECK((a.control_points() - b.control_points()).cwiseAbs().maxCoeff() < 1e-11 * size);
}

TEST_CASE("the elastic force is minus the gradient of the potential energy",
          "[deformation][body]") {
  const BSplineSurface s = argil::test::asymmetric_surface();
  argil::DeformableBody b = make_body(s, clay(1e-3));
  const ControlNet u = random_forces(s.control_points.rows(), 0.1, 12);  // a displacement [mm]
  const Eigen::MatrixXd force = -b.stiffness().multiply(u);
  const double h = 1e-4;  // [mm]; the energy is quadratic, so central differences are exact
  for (Eigen::Index i = 0; i < u.rows(); i += 3)
    for (int c = 0; c < 3; ++c) {
      ControlNet up = u, down = u;
      up(i, c) += h;
      down(i, c) -= h;
      const double slope =
          0.5 * (b.stiffness().quadratic_form(up) - b.stiffness().quadratic_form(down)) / (2 * h);
      CAPTURE(i, c);
      CHECK(-slope == Approx(force(i, c)).margin(1e-8 * b.stiffness().diagonal(i)));
    }
}

TEST_CASE("the stability sweep: the ends of the material range stay finite and lose energy",
          "[deformation][body]") {
  const BSplineSurface s = argil::test::asymmetric_surface();
  const argil::MaterialRange& r = argil::kMaterialRange;
  int accepted = 0, refused = 0;
  for (const double e : {0.0, 1.0, 1e4, r.youngs_modulus.high})
    for (const double density : {1.0, 1e4})
      for (const double thickness : {1e-3, 1.0, 1e3})
        for (const double foundation : {0.0, 1e3}) {
          const argil::Material m{.density = density,
                                  .thickness = thickness,
                                  .youngs_modulus = e,
                                  .poisson_ratio = 0.3,
                                  .foundation_stiffness = foundation,
                                  .damping = 0.0};
          CAPTURE(e, density, thickness, foundation);
          argil::OperatorCache cache;
          auto created = argil::DeformableBody::create(s, m, {}, cache);
          if (!created.ok()) {
            ++refused;  // refused by conditioning, naming the ratio
            CHECK(created.status().message.find("(m + h^2 k_a) / (h^2 k)") != std::string::npos);
            continue;
          }
          ++accepted;
          argil::DeformableBody b = std::move(created).value();
          // Without foundation the body drifts; a translation costs no energy
          // (tested above), so it is taken out before the quadratic form,
          // whose rounding would otherwise grow with the drift.
          const auto energy = [&] {
            ControlNet u = b.control_points() - b.rest_control_points();
            u.rowwise() -= u.colwise().mean();
            return b.kinetic_energy() + 0.5 * b.stiffness().quadratic_form(u);
          };
          REQUIRE(b.step(1e-3, random_forces(s.control_points.rows(), 1.0, 2)).ok());
          double previous = energy();
          const double start = previous;
          double largest_rise = 0.0;
          for (int t = 0; t < 100; ++t) {
            REQUIRE(b.step(1e-3).ok());
            REQUIRE(b.control_points().allFinite());
            const double now = energy();
            largest_rise = std::max(largest_rise, (now - previous) / start);
            previous = now;
          }
          // The step resolves a pole's motion to about eps / ratio, ratio its
          // (m' + h^2 k_a) / (h^2 k) (what create() checks against
          // min_inertia_ratio): the energy may rise by that rounding, no more.
          double ratio = std::numeric_limits<double>::infinity();
          for (Eigen::Index i = 0; i < b.masses().size(); ++i) {
            const double h2 = 1e-6;
            const double inertia = argil::kMassToNewtonSecond2PerMm * b.masses()[i] +
                                   h2 * m.foundation_stiffness * b.shell().area[i];
            ratio = std::min(ratio, inertia / (h2 * b.stiffness().diagonal(i)));
          }
          const double rounding =
              64.0 * std::numeric_limits<double>::epsilon() / std::min(ratio, 1.0);
          CAPTURE(start, previous, largest_rise, ratio, rounding);
          CHECK(largest_rise <= rounding);
        }
  CAPTURE(accepted, refused);
  CHECK(accepted > refused);
}

TEST_CASE("last_step_travel bounds every pole's move over a step and the joint corrections after",
          "[deformation][body]") {
  // A loaded step moves the poles; three joint corrections then move one pole
  // again and again (a corner where several faces meet). last_step_motion
  // takes the largest of the step's moves and of single corrections;
  // last_step_travel bounds every pole's whole move since the step began.
  const BSplineSurface s = argil::test::asymmetric_surface();
  argil::DeformableBody b = make_body(s, clay());
  const ControlNet load = random_forces(s.control_points.rows(), 2.0, 11);
  const ControlNet before = b.control_points();
  REQUIRE(b.step(1e-3, load).ok());
  const Eigen::Index corner = s.pole_index(kCountU - 1, kCountV - 1);
  const ControlNet nudge = ControlNet::Constant(1, 3, 0.6);  // about 1 mm, like the step
  const ControlNet still = ControlNet::Zero(1, 3);
  for (int k = 0; k < 3; ++k) b.displace({corner}, nudge, still);
  double farthest = 0.0;
  for (Eigen::Index p = 0; p < before.rows(); ++p)
    farthest = std::max(farthest, (b.control_points().row(p) - before.row(p)).norm());
  CHECK(farthest > b.last_step_motion());
  CHECK(b.last_step_travel() >= farthest * (1.0 - 1e-12));
  CHECK(b.last_step_travel() >= 3.0 * nudge.row(0).norm() * (1.0 - 1e-12));
  // The next step starts the count afresh.
  REQUIRE(b.step(1e-3).ok());
  CHECK(b.last_step_travel() == Approx(b.last_step_motion()));
}
