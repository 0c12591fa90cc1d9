// Oracle: points and derivatives up to second order agree with OpenCASCADE's
// Geom_BSplineSurface on generated surfaces (degrees 1 to 9, non-uniform
// knots with multiplicities, random weights), evaluated directly and through
// the elements' Bezier patches (PatchEvaluator).
#include <GeomAPI_ProjectPointOnSurf.hxx>
#include <Geom_BSplineSurface.hxx>
#include <TColStd_Array1OfInteger.hxx>
#include <TColStd_Array1OfReal.hxx>
#include <TColStd_Array2OfReal.hxx>
#include <TColgp_Array2OfPnt.hxx>
#include <gp_Pnt.hxx>
#include <gp_Vec.hxx>

#include <catch2/catch.hpp>
#include <random>
#include <vector>

#include "argil/core.hpp"
#include "support/occt_surface.hpp"
#include "support/random_surface.hpp"

using argil::BSplineSurface;
using argil::Direction;

namespace {

using argil::test::to_occt;

/// (sum |N'_i(t)|, sum |N''_i(t)|) in direction d: how large derivative terms get.
std::pair<double, double> term_scale(const BSplineSurface& s, Direction d, double t) {
  const int p = s.degree_in(d);
  const int span = argil::find_span(p, s.knots_in(d), s.count(d), t);
  const Eigen::MatrixXd n = argil::basis_derivatives(p, s.knots_in(d), span, t, 2);
  return {n.row(1).cwiseAbs().sum(), n.row(2).cwiseAbs().sum()};
}

Eigen::Vector3d eig(const gp_Pnt& p) { return {p.X(), p.Y(), p.Z()}; }
Eigen::Vector3d eig(const gp_Vec& v) { return {v.X(), v.Y(), v.Z()}; }

}  // namespace

TEST_CASE("points and derivatives up to order 2 agree with OpenCASCADE to 1e-12 relative") {
  std::mt19937_64 rng(2024);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  argil::OperatorCache cache;
  double worst[3] = {0, 0, 0}, worst_patch[2] = {0, 0};
  int surfaces = 0;
  for (int degree = 1; degree <= 9; ++degree) {
    for (int trial = 0; trial < 24; ++trial) {
      argil::test::RandomSurfaceOptions options;
      options.min_degree = trial % 3 == 0 ? 1 : degree;
      options.max_degree = degree;
      options.rational = trial % 2 == 1;
      options.max_extra_poles = 8;
      const BSplineSurface s = argil::test::random_surface(rng, options);
      REQUIRE(argil::validate(s).ok());
      const Handle(Geom_BSplineSurface) oc = to_occt(s);
      ++surfaces;
      const double size = argil::control_point_box(s).diagonal();
      const double pole_size = s.control_points.rowwise().norm().maxCoeff();
      // Sample inside the domain, on its ends and exactly on the knots.
      std::vector<double> us, vs;
      for (int k = 0; k < 12; ++k) {
        us.push_back(s.domain_start(Direction::u) +
                     unit(rng) * (s.domain_end(Direction::u) - s.domain_start(Direction::u)));
        vs.push_back(s.domain_start(Direction::v) +
                     unit(rng) * (s.domain_end(Direction::v) - s.domain_start(Direction::v)));
      }
      for (Eigen::Index k = s.degree[0]; k <= s.count(Direction::u); ++k)
        us.push_back(s.knots[0][k]);
      for (Eigen::Index k = s.degree[1]; k <= s.count(Direction::v); ++k)
        vs.push_back(s.knots[1][k]);
      double d1_scale = 0.0, d2_scale = 0.0;
      double err[3] = {0, 0, 0}, err_patch[2] = {0, 0};
      // One evaluator for all samples: each row of v crosses every element,
      // so its few kept patches are replaced again and again.
      const argil::SurfaceOperators ops = argil::surface_operators(s, cache).value();
      argil::PatchEvaluator patches(s, ops);
      for (double u : us) {
        for (double v : vs) {
          gp_Pnt p;
          gp_Vec du, dv, duu, dvv, duv;
          oc->D2(u, v, p, du, dv, duu, dvv, duv);
          const argil::SurfaceDerivatives d = argil::evaluate_derivatives(s, u, v, 2);
          err[0] = std::max(err[0], (d.point - eig(p)).norm());
          err[1] = std::max({err[1], (d.du - eig(du)).norm(), (d.dv - eig(dv)).norm()});
          err[2] = std::max({err[2], (d.duu - eig(duu)).norm(), (d.duv - eig(duv)).norm(),
                             (d.dvv - eig(dvv)).norm()});
          // Through the element's Bezier patch, orders 0 and 1 (the element
          // at a knot is the one whose one-sided derivatives OCCT gives).
          const argil::SurfaceDerivatives e1 = patches.evaluate(u, v, 1);
          const argil::SurfaceDerivatives e0 = patches.evaluate(u, v, 0);
          err_patch[0] =
              std::max({err_patch[0], (e1.point - eig(p)).norm(), (e0.point - eig(p)).norm()});
          err_patch[1] =
              std::max({err_patch[1], (e1.du - eig(du)).norm(), (e1.dv - eig(dv)).norm()});
          // Rounding in a derivative scales with its terms, sum |N'| |P|, not with
          // the (possibly cancelling) result: measure relative to that.
          const auto pu = term_scale(s, Direction::u, u);
          const auto pv = term_scale(s, Direction::v, v);
          d1_scale = std::max({d1_scale, eig(du).norm(), eig(dv).norm(), pole_size * pu.first,
                               pole_size * pv.first});
          d2_scale = std::max({d2_scale, eig(duu).norm(), eig(duv).norm(), eig(dvv).norm(),
                               pole_size * pu.second, pole_size * pv.second,
                               pole_size * pu.first * pv.first});
          // D0 and D1 through their own entry points agree with D2's.
          gp_Pnt p0;
          oc->D0(u, v, p0);
          CHECK((eig(p0) - d.point).norm() <= 1e-12 * size);
          // Ours too, to the bit: first order alone takes its own basis path.
          const argil::SurfaceDerivatives d1 = argil::evaluate_derivatives(s, u, v, 1);
          CHECK(d1.point == d.point);
          CHECK(d1.du == d.du);
          CHECK(d1.dv == d.dv);
          CHECK(argil::evaluate(s, u, v) == d.point);
        }
      }
      const double rel[3] = {err[0] / size, err[1] / d1_scale, err[2] / d2_scale};
      const double rel_patch[2] = {err_patch[0] / size, err_patch[1] / d1_scale};
      INFO("degree " << s.degree[0] << "x" << s.degree[1] << (s.is_rational() ? " rational" : "")
                     << " poles " << s.count(Direction::u) << "x" << s.count(Direction::v)
                     << ": relative errors " << rel[0] << ", " << rel[1] << ", " << rel[2]
                     << "; through the patches " << rel_patch[0] << ", " << rel_patch[1]);
      // Two independent implementations of the same sums: rounding only.
      CHECK(rel[0] <= 1e-12);
      CHECK(rel[1] <= 1e-12);
      CHECK(rel[2] <= 1e-12);
      CHECK(rel_patch[0] <= 1e-12);
      CHECK(rel_patch[1] <= 1e-12);
      for (int o = 0; o < 3; ++o) worst[o] = std::max(worst[o], rel[o]);
      for (int o = 0; o < 2; ++o) worst_patch[o] = std::max(worst_patch[o], rel_patch[o]);
    }
  }
  WARN(surfaces << " surfaces; worst relative error vs OpenCASCADE: D0 " << worst[0] << ", D1 "
                << worst[1] << ", D2 " << worst[2] << "; through the patches D0 " << worst_patch[0]
                << ", D1 " << worst_patch[1]);
}

TEST_CASE("the closest point is within eps of OpenCASCADE's global projection") {
  std::mt19937_64 rng(99);
  std::normal_distribution<double> gauss(0.0, 1.0);
  argil::OperatorCache cache;
  double worst = 0.0;
  int compared = 0;
  for (int trial = 0; trial < 60; ++trial) {
    argil::test::RandomSurfaceOptions options;
    options.rational = trial % 2 == 1;
    options.max_degree = 5;
    const BSplineSurface s = argil::test::random_surface(rng, options);
    auto h = argil::SurfaceHierarchy::build(s, cache);
    REQUIRE(h.ok());
    const Handle(Geom_BSplineSurface) oc = to_occt(s);
    const argil::Box3 box = argil::control_point_box(s);
    const double size = box.diagonal();
    const double eps = 1e-7 * size;
    for (int k = 0; k < 5; ++k) {
      const Eigen::Vector3d q =
          0.5 * (box.min + box.max) +
          0.4 * size * Eigen::Vector3d(gauss(rng), gauss(rng), 0.5 * gauss(rng));
      const argil::ClosestPoint ours = argil::closest_point(h.value(), q, {.tolerance = eps});
      GeomAPI_ProjectPointOnSurf projection(gp_Pnt(q.x(), q.y(), q.z()), oc);
      if (projection.NbPoints() == 0) continue;  // OCCT found no orthogonal foot
      const double theirs = projection.LowerDistance();
      ++compared;
      INFO("trial " << trial << " point (" << q.transpose() << ") ours " << ours.distance
                    << " OCCT " << theirs);
      // Ours is certified within eps of the global minimum; OCCT's extrema
      // report orthogonal feet only, so a boundary minimum can make it larger.
      CHECK(ours.distance <= theirs + eps);
      worst = std::max(worst, std::abs(ours.distance - theirs) / size);
    }
  }
  CHECK(compared > 100);
  WARN(compared << " projections; largest |ours - OCCT| relative to size: " << worst);
}
