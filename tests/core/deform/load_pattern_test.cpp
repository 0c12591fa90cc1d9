// Contact loads on the control net (docs/deformation.md): the pattern of a
// unit force is non-negative, sums to 1, has the exact moment (sum g_i P_i =
// the shared contact point) on the rational asymmetric surface, acts only
// through the poles whose support holds the contact, and transposes with the
// net.
#include <catch2/catch.hpp>
#include <random>
#include <vector>

#include "argil/core.hpp"
#include "support/random_surface.hpp"
#include "support/transposed_surface.hpp"

namespace {

using argil::BSplineSurface;
using argil::Direction;

Eigen::Vector2d at_fraction(const BSplineSurface& s, double a, double b) {
  const auto lerp = [&](Direction d, double f) {
    return s.domain_start(d) + f * (s.domain_end(d) - s.domain_start(d));
  };
  return {lerp(Direction::u, a), lerp(Direction::v, b)};
}

/// Contacts at the given parameter fractions with depths, on the knots and edges too.
std::vector<argil::Contact> contacts_at(const BSplineSurface& s,
                                        const std::vector<Eigen::Vector3d>& fraction_depth) {
  std::vector<argil::Contact> out;
  for (const Eigen::Vector3d& f : fraction_depth) {
    argil::Contact c;
    c.uv_a = at_fraction(s, f.x(), f.y());
    c.depth = f.z();
    out.push_back(c);
  }
  return out;
}

}  // namespace

TEST_CASE("a load pattern is non-negative, sums to one and carries the moment exactly",
          "[deformation][load]") {
  const BSplineSurface s = argil::test::asymmetric_surface();
  const double size = argil::control_point_box(s).diagonal();
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int trial = 0; trial < 40; ++trial) {
    std::vector<Eigen::Vector3d> where;
    for (int k = 0; k < 1 + trial % 5; ++k) {
      // Every third contact on the double knot u = 0.3, every fifth on an edge.
      const double a = trial % 3 == 0 ? 0.3 : unit(rng);
      const double b = trial % 5 == 0 ? 1.0 : unit(rng);
      where.emplace_back(a, b, 0.01 * unit(rng) - 0.005);
    }
    const std::vector<argil::Contact> contacts = contacts_at(s, where);
    const std::vector<double> shares = argil::contact_shares(contacts, 0.01);
    const Eigen::VectorXd g = argil::contact_load_pattern(s, contacts, shares);
    CAPTURE(trial);
    double share_sum = 0.0;
    for (const double x : shares) {
      CHECK(x > 0.0);
      share_sum += x;
    }
    CHECK(share_sum == Approx(1.0).epsilon(1e-15));
    CHECK(g.minCoeff() >= 0.0);
    CHECK(g.sum() == Approx(1.0).epsilon(1e-14));
    // Virtual work: g . P is the shared contact point, for the surface's own
    // control points and for any other net on the same weights and knots.
    for (unsigned seed : {0u, 1u}) {
      BSplineSurface moved = s;
      if (seed > 0) {
        std::normal_distribution<double> normal(0.0, 5.0);
        for (Eigen::Index i = 0; i < moved.control_points.size(); ++i)
          moved.control_points.data()[i] += normal(rng);
      }
      Eigen::Vector3d shared = Eigen::Vector3d::Zero();
      for (std::size_t k = 0; k < contacts.size(); ++k)
        shared += shares[k] * argil::evaluate(moved, contacts[k].uv_a.x(), contacts[k].uv_a.y());
      CHECK((moved.control_points.transpose() * g - shared).norm() <= 1e-13 * size);
    }
  }
}

TEST_CASE("a load pattern acts only on the poles whose support holds the contact",
          "[deformation][load]") {
  const BSplineSurface s = argil::test::asymmetric_surface();
  const int nu = s.count(Direction::u), nv = s.count(Direction::v);
  for (const auto& f : {Eigen::Vector2d(0.17, 0.62), Eigen::Vector2d(0.66, 0.08)}) {
    const Eigen::Vector2d uv = at_fraction(s, f.x(), f.y());
    CAPTURE(uv.transpose());
    const Eigen::VectorXd g =
        argil::contact_load_pattern(s, contacts_at(s, {{f.x(), f.y(), 0}}), {1.0});
    int carrying = 0;
    for (int i = 0; i < nu; ++i)
      for (int j = 0; j < nv; ++j) {
        // R_ij(uv) measured as the move of S(uv) when pole (i, j) alone moves by 1 in z.
        BSplineSurface moved = s;
        moved.control_points(moved.pole_index(i, j), 2) += 1.0;
        const double basis =
            (argil::evaluate(moved, uv.x(), uv.y()) - argil::evaluate(s, uv.x(), uv.y())).z();
        CAPTURE(i, j);
        CHECK(g[s.pole_index(i, j)] == Approx(basis).margin(1e-13));
        const bool supports = s.knots[0][i] < uv.x() && uv.x() < s.knots[0][i + 4] &&
                              s.knots[1][j] < uv.y() && uv.y() < s.knots[1][j + 3];
        if (supports) {
          ++carrying;
          CHECK(g[s.pole_index(i, j)] > 0.0);
        } else {
          CHECK(g[s.pole_index(i, j)] == 0.0);
        }
      }
    CHECK(carrying == 4 * 3);  // (p + 1)(q + 1) poles away from the knots
  }
}

TEST_CASE("transposing the net transposes the load pattern", "[deformation][load]") {
  const BSplineSurface s = argil::test::asymmetric_surface();
  const BSplineSurface t = argil::test::transposed(s);
  for (const auto& f : {Eigen::Vector2d(0.21, 0.67), Eigen::Vector2d(0.3, 0.45),
                        Eigen::Vector2d(0.88, 0.0), Eigen::Vector2d(1.0, 1.0)}) {
    std::vector<argil::Contact> a = contacts_at(s, {{f.x(), f.y(), 0.0}, {0.5, 0.5, 0.002}});
    std::vector<argil::Contact> b = a;
    for (argil::Contact& c : b) c.uv_a = c.uv_a.reverse().eval();
    const std::vector<double> shares = argil::contact_shares(a, 0.01);
    const Eigen::VectorXd ga = argil::contact_load_pattern(s, a, shares);
    const Eigen::VectorXd gb = argil::contact_load_pattern(t, b, shares);
    CAPTURE(f.transpose());
    CHECK((argil::test::transposed_rows(ga, 7, 5) - gb).cwiseAbs().maxCoeff() <= 1e-15);
  }
}

TEST_CASE("contact shares follow depth + eps and count contacts touching within eps",
          "[deformation][load]") {
  std::vector<argil::Contact> c(3);
  c[0].depth = 0.01;   // 0.02 with eps
  c[1].depth = 0.0;    // 0.01
  c[2].depth = -0.01;  // touching at exactly -eps: the floor 1e-3 eps keeps it
  const std::vector<double> s = argil::contact_shares(c, 0.01);
  REQUIRE(s.size() == 3);
  const double total = 0.02 + 0.01 + 1e-5;
  CHECK(s[0] == Approx(0.02 / total).epsilon(1e-14));
  CHECK(s[1] == Approx(0.01 / total).epsilon(1e-14));
  CHECK(s[2] == Approx(1e-5 / total).epsilon(1e-12));
  CHECK(argil::contact_shares({}, 0.01).empty());
}

TEST_CASE("transposing the net transposes the contacts of a pressed sphere",
          "[deformation][load]") {
  const BSplineSurface s = argil::test::asymmetric_surface();
  const BSplineSurface t = argil::test::transposed(s);
  argil::OperatorCache cache;
  argil::SurfaceHierarchy hs = argil::SurfaceHierarchy::build(s, cache).value();
  argil::SurfaceHierarchy ht = argil::SurfaceHierarchy::build(t, cache).value();
  const double size = argil::control_point_box(s).diagonal();
  for (const auto& f : {Eigen::Vector2d(0.23, 0.71), Eigen::Vector2d(0.8, 0.35)}) {
    const Eigen::Vector2d uv = at_fraction(s, f.x(), f.y());
    CAPTURE(uv.transpose());
    const double radius = 4.0, depth = 0.6;
    const Eigen::Vector3d centre = argil::evaluate(s, uv.x(), uv.y()) +
                                   (radius - depth) * argil::unit_normal(s, uv.x(), uv.y());
    const auto sphere = argil::make_sphere(centre, radius);
    const argil::CollisionRequest request{.tolerance = 1e-3};
    const argil::CollisionResult rs = argil::collide(hs, *sphere, request);
    const argil::CollisionResult rt = argil::collide(ht, *sphere, request);
    REQUIRE(rs.status.ok());
    REQUIRE(rt.status.ok());
    REQUIRE_FALSE(rs.contacts.empty());
    CHECK(rt.region_count == rs.region_count);
    const argil::Contact& a = rs.contacts.front();  // the deepest
    const argil::Contact& b = rt.contacts.front();
    CHECK(a.depth == Approx(depth).margin(1e-6));
    CHECK(std::abs(a.depth - b.depth) < 1e-9 * size);
    CHECK((a.point - b.point).norm() < 1e-9 * size);
    CHECK((a.uv_a - b.uv_a.reverse()).norm() < 1e-9);
    // The patterns built from them are transposes of each other.
    const Eigen::VectorXd ga =
        argil::contact_load_pattern(s, rs.contacts, argil::contact_shares(rs.contacts, 1e-3));
    const Eigen::VectorXd gb =
        argil::contact_load_pattern(t, rt.contacts, argil::contact_shares(rt.contacts, 1e-3));
    CHECK((argil::test::transposed_rows(ga, 7, 5) - gb).cwiseAbs().maxCoeff() < 1e-9);
  }
}
