// Deformation on the asymmetric test net (docs/conventions.md; degree 3 x 2, 7 x 5
// rational poles, non-uniform knots with a double knot in u): a u/v swap bug
// in the load pattern, the body step, the refit or the sphere contacts shows
// up as a mismatch against the transposed surface or as a load acting at the
// mirrored point.
#include <Eigen/Dense>
#include <algorithm>
#include <catch2/catch.hpp>
#include <random>
#include <vector>

#include "argil/core.hpp"
#include "support/random_surface.hpp"
#include "support/transposed_surface.hpp"

namespace {

using argil::BSplineSurface;
using argil::ControlNet;
using argil::Direction;

/// Parameters at fractions (s, t) of the domain in u and v.
Eigen::Vector2d at_fraction(const BSplineSurface& surface, double s, double t) {
  const auto lerp = [&](Direction d, double f) {
    return surface.domain_start(d) + f * (surface.domain_end(d) - surface.domain_start(d));
  };
  return {lerp(Direction::u, s), lerp(Direction::v, t)};
}

Eigen::Vector3d point_at(const BSplineSurface& surface, const Eigen::Vector2d& uv) {
  return argil::evaluate(surface, uv.x(), uv.y());
}

argil::SurfaceOperators operators_of(const BSplineSurface& surface) {
  static argil::OperatorCache cache;
  auto ops = argil::surface_operators(surface, cache);
  REQUIRE(ops.ok());
  return ops.value();
}

/// One unit-share contact at uv (what the tick builds from one sphere contact).
Eigen::VectorXd point_load_pattern(const BSplineSurface& surface, const Eigen::Vector2d& uv) {
  std::vector<argil::Contact> contacts(1);
  contacts[0].uv_a = uv;
  return argil::contact_load_pattern(surface, operators_of(surface), contacts, {1.0});
}

/// A soft, slightly plastic sheet: a 1.5 N press moves the nodes by about a millimetre per
/// millisecond, and the yield makes plastic flow part of every compared step.
argil::Material sheet_material() {
  argil::Material m;
  m.density = 2e-5;
  m.stiffness = 0.8;
  m.anchor_stiffness = 0.5;
  m.damping = 5e-3;
  m.yield = 0.2;
  return m;
}

argil::DeformableBody make_body(const BSplineSurface& surface,
                                const argil::BoundaryConditions& bc = {}) {
  static argil::OperatorCache cache;
  auto b = argil::DeformableBody::create(surface, sheet_material(), bc, cache);
  INFO(b.status().message);
  REQUIRE(b.ok());
  return std::move(b).value();
}

/// `steps` steps of 1 ms with force F [N] at uv through the exact load pattern.
void press(argil::DeformableBody& body, const Eigen::Vector2d& uv, const Eigen::Vector3d& force,
           int steps) {
  const Eigen::VectorXd g = point_load_pattern(body.surface(), uv);
  for (int t = 0; t < steps; ++t) {
    REQUIRE(body.begin_step(1e-3, {}, g).ok());
    body.finish_step(force);
  }
}

/// The model size tolerances scale with [mm].
double model_size(const BSplineSurface& s) { return argil::control_point_box(s).diagonal(); }

constexpr int kCountU = 7;
constexpr int kCountV = 5;

}  // namespace

TEST_CASE(
    "the asymmetric test net has degree 3x2, 7x5 poles, non-uniform knots, a double knot, non-unit "
    "weights",
    "[deformation][asymmetric]") {
  const BSplineSurface s = argil::test::asymmetric_surface();
  REQUIRE(argil::validate(s).ok());
  CHECK(s.degree == std::array<int, 2>{3, 2});
  CHECK(s.count(Direction::u) == kCountU);
  CHECK(s.count(Direction::v) == kCountV);
  CHECK(s.is_rational());
  CHECK(s.weights.minCoeff() < s.weights.maxCoeff());
  // Exactly one interior knot value with multiplicity 2, in u.
  const Eigen::VectorXd& ku = s.knots[0];
  int doubles = 0;
  for (Eigen::Index k = 4; k + 1 < ku.size() - 4; ++k) doubles += ku[k] == ku[k + 1] ? 1 : 0;
  CHECK(doubles == 1);
  // Not the same under u <-> v or u -> 1 - u: the mirrored points differ.
  const double size = model_size(s);
  const Eigen::Vector3d p = point_at(s, at_fraction(s, 0.2, 0.7));
  CHECK((p - point_at(s, at_fraction(s, 0.7, 0.2))).norm() > 0.1 * size);
  CHECK((p - point_at(s, at_fraction(s, 0.8, 0.7))).norm() > 0.1 * size);
}

TEST_CASE("transposing the net transposes the load pattern", "[deformation][asymmetric]") {
  const BSplineSurface s = argil::test::asymmetric_surface();
  const BSplineSurface t = argil::test::transposed(s);
  REQUIRE(argil::validate(t).ok());
  // Off-centre, on the double knot, on an edge, at a corner.
  for (const auto& st : {Eigen::Vector2d(0.21, 0.67), Eigen::Vector2d(0.3, 0.45),
                         Eigen::Vector2d(0.88, 0.0), Eigen::Vector2d(1.0, 1.0)}) {
    const Eigen::Vector2d uv = at_fraction(s, st.x(), st.y());
    CAPTURE(uv.transpose());
    const Eigen::VectorXd g = point_load_pattern(s, uv);
    const Eigen::VectorXd g_t = point_load_pattern(t, uv.reverse());
    // Entries of order 1; the banded solves run in the other order on the transpose.
    CHECK((argil::test::transposed_rows(g, kCountU, kCountV) - g_t).cwiseAbs().maxCoeff() < 1e-12);
  }
}

TEST_CASE("transposing the net transposes every step, the refit and the plastic rest state",
          "[deformation][asymmetric]") {
  const BSplineSurface s = argil::test::asymmetric_surface();
  const BSplineSurface t = argil::test::transposed(s);
  const double size = model_size(s);
  // Held edge u = u_min on the original is v = v_min on the transpose.
  argil::DeformableBody a = make_body(s, {.fixed_u0 = true});
  argil::DeformableBody b = make_body(t, {.fixed_v0 = true});
  const Eigen::Vector2d uv = at_fraction(s, 0.62, 0.27);
  const Eigen::Vector3d force(0.6, -0.4, -3.0);
  for (int t_ms = 0; t_ms < 12; ++t_ms) {
    const Eigen::VectorXd g = point_load_pattern(a.surface(), uv);
    const Eigen::VectorXd g_t = point_load_pattern(b.surface(), uv.reverse());
    const argil::LoadPreview pa = a.begin_step(1e-3, {}, g).value();
    const argil::LoadPreview pb = b.begin_step(1e-3, {}, g_t).value();
    // Rounding of banded solves of the same system in another node order.
    CHECK(std::abs(pa.compliance - pb.compliance) < 1e-11 * pa.compliance);
    CHECK((pa.free_motion - pb.free_motion).norm() < 1e-11 * size);
    a.finish_step(force);
    b.finish_step(force);
  }
  const auto transposed_nodes = [](const ControlNet& n) {
    return argil::test::transposed_rows(n, kCountU, kCountV);
  };
  const ControlNet start = argil::evaluate_nodes(s, a.operators());
  CHECK((a.nodes() - start).cwiseAbs().maxCoeff() > 0.3);  // it moved, past the 0.2 mm yield
  CHECK((transposed_nodes(a.nodes()) - b.nodes()).cwiseAbs().maxCoeff() < 1e-11 * size);
  CHECK((transposed_nodes(a.rest_nodes()) - b.rest_nodes()).cwiseAbs().maxCoeff() < 1e-11 * size);
  CHECK((transposed_nodes(a.velocities()) - b.velocities()).cwiseAbs().maxCoeff() <
        1e-11 * size / 1e-3);  // the same rounding over one 1 ms step
  CHECK((transposed_nodes(a.surface().control_points) - b.surface().control_points)
            .cwiseAbs()
            .maxCoeff() < 1e-11 * size);
  for (const double su : {0.0, 0.13, 0.3, 0.71, 1.0})
    for (const double sv : {0.0, 0.4, 0.93}) {
      const Eigen::Vector2d p = at_fraction(s, su, sv);
      CHECK((point_at(a.surface(), p) - point_at(b.surface(), p.reverse())).norm() < 1e-11 * size);
    }
}

TEST_CASE("transposing the net transposes the contacts of a pressed sphere",
          "[deformation][asymmetric]") {
  const BSplineSurface s = argil::test::asymmetric_surface();
  const BSplineSurface t = argil::test::transposed(s);
  argil::OperatorCache cache;
  argil::SurfaceHierarchy hs = argil::SurfaceHierarchy::build(s, cache).value();
  argil::SurfaceHierarchy ht = argil::SurfaceHierarchy::build(t, cache).value();
  const double size = model_size(s);
  for (const auto& st : {Eigen::Vector2d(0.23, 0.71), Eigen::Vector2d(0.8, 0.35)}) {
    const Eigen::Vector2d uv = at_fraction(s, st.x(), st.y());
    CAPTURE(uv.transpose());
    const double radius = 4.0, depth = 0.6;
    const Eigen::Vector3d centre =
        point_at(s, uv) + (radius - depth) * argil::unit_normal(s, uv.x(), uv.y());
    const auto sphere = argil::make_sphere(centre, radius);
    const argil::CollisionRequest request{.tolerance = 1e-3};
    const argil::CollisionResult rs = argil::collide(hs, *sphere, request);
    const argil::CollisionResult rt = argil::collide(ht, *sphere, request);
    REQUIRE(rs.status.ok());
    REQUIRE(rt.status.ok());
    REQUIRE_FALSE(rs.contacts.empty());
    CHECK(rs.region_count == 1);
    CHECK(rt.region_count == rs.region_count);
    const argil::Contact& a = rs.contacts.front();  // the deepest
    const argil::Contact& b = rt.contacts.front();
    // Newton refinement converges to the same point from transposed starts.
    const double tol = 1e-9 * size;
    CHECK(a.depth == Approx(depth).margin(1e-6));  // certified depth, refined
    CHECK(std::abs(a.depth - b.depth) < tol);
    CHECK((a.point - b.point).norm() < tol);
    CHECK((a.uv_a - b.uv_a.reverse()).norm() < 1e-9);
    CHECK((a.normal + b.normal).norm() < 1e-9);  // S^T_u x S^T_v = -(S_u x S_v)
    CHECK((a.tangent_u - b.tangent_v).norm() < tol);
    CHECK((a.tangent_v - b.tangent_u).norm() < tol);
  }
}

TEST_CASE("a point load off the centre dents the surface at its point, not at mirrored points",
          "[deformation][asymmetric]") {
  const BSplineSurface s = argil::test::asymmetric_surface();
  const double fs = 0.22, ft = 0.74;  // off-centre, away from both diagonals
  argil::DeformableBody body = make_body(s);
  press(body, at_fraction(s, fs, ft), Eigen::Vector3d(0.0, 0.0, -1.5), 20);
  const auto dent = [&](double a, double b) {
    const Eigen::Vector2d uv = at_fraction(s, a, b);
    return (point_at(body.surface(), uv) - point_at(s, uv)).norm();
  };
  const double at_load = dent(fs, ft);
  CHECK(at_load > 0.2);  // [mm]: the press went past the yield
  // The springs spread the dent over about two node spacings (mirrors dent
  // 0.24 to 0.34 times as deep); a swapped or flipped load dents the mirror most.
  CHECK(at_load > 2.0 * dent(ft, fs));        // the u/v mirror
  CHECK(at_load > 2.0 * dent(1.0 - fs, ft));  // the u mirror
  CHECK(at_load > 2.0 * dent(fs, 1.0 - ft));  // the v mirror
  // The deepest dent on a 41 x 41 sample grid lies near the load.
  double deepest = -1.0;
  Eigen::Vector2d where = Eigen::Vector2d::Zero();
  for (int i = 0; i <= 40; ++i)
    for (int j = 0; j <= 40; ++j)
      if (const double d = dent(i / 40.0, j / 40.0); d > deepest) {
        deepest = d;
        where = {i / 40.0, j / 40.0};
      }
  CAPTURE(where.transpose());
  CHECK((where - Eigen::Vector2d(fs, ft)).norm() < 0.15);  // within one node spacing
}

TEST_CASE("the load pattern does virtual work only through the poles whose support holds the load",
          "[deformation][asymmetric]") {
  // g . dx = R_ab(u, v) delta when pole (a, b) alone moves by delta and the
  // nodes follow (dx): the pattern is the exact adjoint of the local basis.
  const BSplineSurface s = argil::test::asymmetric_surface();
  const argil::SurfaceOperators ops = operators_of(s);
  const ControlNet nodes = argil::evaluate_nodes(s, ops);
  for (const auto& st : {Eigen::Vector2d(0.17, 0.62), Eigen::Vector2d(0.66, 0.08)}) {
    const Eigen::Vector2d uv = at_fraction(s, st.x(), st.y());
    CAPTURE(uv.transpose());
    const Eigen::VectorXd g = point_load_pattern(s, uv);
    int carrying = 0;
    for (int i = 0; i < kCountU; ++i)
      for (int j = 0; j < kCountV; ++j) {
        BSplineSurface moved = s;
        moved.control_points.row(moved.pole_index(i, j)) += Eigen::RowVector3d(0.0, 0.0, 1.0);
        const double basis = (point_at(moved, uv) - point_at(s, uv)).z();  // R_ij(u, v)
        const double work = g.dot((argil::evaluate_nodes(moved, ops) - nodes).col(2));
        CAPTURE(i, j);
        const Eigen::VectorXd& ku = s.knots[0];
        const Eigen::VectorXd& kv = s.knots[1];
        const bool supports =
            ku[i] < uv.x() && uv.x() < ku[i + 4] && kv[j] < uv.y() && uv.y() < kv[j + 3];
        if (supports) {
          ++carrying;
          CHECK(basis > 0.0);
          CHECK(work == Approx(basis).margin(1e-12));  // rounding of the node evaluations
        } else {
          CHECK(basis == 0.0);
          CHECK(std::abs(work) < 1e-12);
        }
      }
    CHECK(carrying == 4 * 3);  // (p + 1)(q + 1) poles off the knots
  }
}

TEST_CASE("the load pattern carries the whole force wherever the contacts are",
          "[deformation][asymmetric]") {
  const BSplineSurface s = argil::test::asymmetric_surface();
  const argil::SurfaceOperators ops = operators_of(s);
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int trial = 0; trial < 20; ++trial) {
    std::vector<argil::Contact> contacts(1 + trial % 4);
    for (argil::Contact& c : contacts) {
      // Every third contact on an edge or the double knot u = 0.3.
      const double a = trial % 3 == 0 ? 0.3 : unit(rng);
      const double b = trial % 3 == 1 ? 1.0 : unit(rng);
      c.uv_a = at_fraction(s, a, b);
      c.depth = 0.01 * unit(rng);
    }
    const std::vector<double> shares = argil::contact_shares(contacts, 0.01);
    const Eigen::VectorXd g = argil::contact_load_pattern(s, ops, contacts, shares);
    CAPTURE(trial);
    CHECK(g.sum() == Approx(1.0).epsilon(1e-12));  // rounding of two banded solves
  }
}

TEST_CASE("an affine change of the knots leaves the load pattern, the masses and the step alone",
          "[deformation][asymmetric]") {
  const BSplineSurface s = argil::test::asymmetric_surface();
  BSplineSurface r = s;  // u' = 3 u - 2, v' = 0.25 v + 7
  r.knots[0] = (3.0 * s.knots[0].array() - 2.0).matrix();
  r.knots[1] = (0.25 * s.knots[1].array() + 7.0).matrix();
  const double size = model_size(s);
  const Eigen::Vector2d uv = at_fraction(s, 0.41, 0.83);
  const Eigen::Vector2d uv_r = at_fraction(r, 0.41, 0.83);
  REQUIRE((point_at(s, uv) - point_at(r, uv_r)).norm() < 1e-12 * size);  // the same surface
  // Entries of order 1; knot rounding of the affine map only.
  CHECK((point_load_pattern(s, uv) - point_load_pattern(r, uv_r)).cwiseAbs().maxCoeff() < 1e-12);
  const Eigen::VectorXd ms = argil::node_masses(s, operators_of(s), 2e-5);
  const Eigen::VectorXd mr = argil::node_masses(r, operators_of(r), 2e-5);
  CHECK(((ms - mr).array().abs() / ms.array()).maxCoeff() < 1e-12);
  argil::DeformableBody a = make_body(s);
  argil::DeformableBody b = make_body(r);
  press(a, uv, Eigen::Vector3d(0.5, 0.2, -1.0), 5);
  press(b, uv_r, Eigen::Vector3d(0.5, 0.2, -1.0), 5);
  CHECK((a.nodes() - a.rest_nodes()).cwiseAbs().maxCoeff() > 0.1);
  CHECK((a.nodes() - b.nodes()).cwiseAbs().maxCoeff() < 1e-11 * size);
}

TEST_CASE("the 7 x 5 spring stencil is the transpose of the 5 x 7 one, its band as documented",
          "[deformation][asymmetric]") {
  const std::vector<argil::Spring> a = argil::grid_springs(kCountU, kCountV);
  const std::vector<argil::Spring> b = argil::grid_springs(kCountV, kCountU);
  REQUIRE(a.size() == b.size());
  const auto transposed = [](int node) { return (node % kCountV) * kCountU + node / kCountV; };
  std::vector<std::pair<int, int>> mapped, other;
  for (const argil::Spring& sp : a)
    mapped.emplace_back(std::min(transposed(sp.a), transposed(sp.b)),
                        std::max(transposed(sp.a), transposed(sp.b)));
  for (const argil::Spring& sp : b) other.emplace_back(sp.a, sp.b);
  std::sort(mapped.begin(), mapped.end());
  std::sort(other.begin(), other.end());
  CHECK(mapped == other);
  const auto widest = [](const std::vector<argil::Spring>& springs) {
    int w = 0;
    for (const argil::Spring& sp : springs) w = std::max(w, std::abs(sp.a - sp.b));
    return w;
  };
  CHECK(argil::grid_bandwidth(kCountU, kCountV) == widest(a));
  CHECK(argil::grid_bandwidth(kCountV, kCountU) == widest(b));
}

TEST_CASE("the elastic forces are minus the gradient of the elastic energy (finite differences)",
          "[deformation][asymmetric]") {
  const std::vector<argil::Spring> springs = argil::grid_springs(kCountU, kCountV);
  const double k = 0.8, k_anchor = 0.5;
  std::mt19937_64 rng(5);
  std::normal_distribution<double> normal(0.0, 1.0);
  ControlNet u(kCountU * kCountV, 3);
  for (Eigen::Index i = 0; i < u.rows(); ++i) u.row(i) << normal(rng), normal(rng), normal(rng);
  const std::vector<char> free(static_cast<std::size_t>(u.rows()), 0);
  const ControlNet f = argil::elastic_forces(springs, {k, k_anchor}, u, free);
  const double h = 1e-4;  // [mm]; the energy is quadratic, so central differences are exact
  for (Eigen::Index i = 0; i < u.rows(); ++i)
    for (int c = 0; c < 3; ++c) {
      ControlNet up = u, down = u;
      up(i, c) += h;
      down(i, c) -= h;
      const double slope = (argil::elastic_energy(springs, {k, k_anchor}, up) -
                            argil::elastic_energy(springs, {k, k_anchor}, down)) /
                           (2 * h);
      CAPTURE(i, c);
      CHECK(-slope == Approx(f(i, c)).margin(1e-8));  // energy ~ 1e2 mJ, rounding / h
    }
}

TEST_CASE("the step's compliance is the loaded point's motion per newton (finite differences)",
          "[deformation][asymmetric]") {
  const BSplineSurface s = argil::test::asymmetric_surface();
  const Eigen::Vector2d uv = at_fraction(s, 0.71, 0.38);
  const Eigen::VectorXd g = point_load_pattern(s, uv);
  const auto loaded_point_after = [&](const Eigen::Vector3d& force, argil::LoadPreview& preview) {
    argil::DeformableBody body = make_body(s, {.fixed_v1 = true});
    press(body, uv, Eigen::Vector3d(0.0, 0.1, -0.4), 3);  // moving, with velocities
    const Eigen::Vector3d before = body.nodes().transpose() * g;
    preview = body.begin_step(1e-3, {}, g).value();
    body.finish_step(force);
    return Eigen::Vector3d(body.nodes().transpose() * g - before);
  };
  argil::LoadPreview p0, p1;
  const Eigen::Vector3d free = loaded_point_after(Eigen::Vector3d::Zero(), p0);
  CHECK((free - p0.free_motion).norm() < 1e-12);  // [mm], rounding
  const double df = 0.25;                         // [N]; the step is linear in the force
  for (int c = 0; c < 3; ++c) {
    const Eigen::Vector3d moved = loaded_point_after(df * Eigen::Vector3d::Unit(c), p1);
    const Eigen::Vector3d slope = (moved - free) / df;
    CAPTURE(c);
    CHECK(p1.compliance == p0.compliance);
    CHECK(slope[c] == Approx(p0.compliance).epsilon(1e-9));
    CHECK((slope - slope[c] * Eigen::Vector3d::Unit(c)).norm() < 1e-9 * p0.compliance);
  }
}
