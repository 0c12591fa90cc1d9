#pragma once
// argil surfaces as OpenCASCADE surfaces, for tests and benchmarks that use
// OpenCASCADE as the independent oracle or peer. Header-only: only targets
// that link argil_occt include it.

#include <Geom_BSplineSurface.hxx>
#include <TColStd_Array1OfInteger.hxx>
#include <TColStd_Array1OfReal.hxx>
#include <TColStd_Array2OfReal.hxx>
#include <TColgp_Array2OfPnt.hxx>
#include <gp_Pnt.hxx>

#include <vector>

#include "argil/core/geometry/bspline_surface.hpp"

namespace argil::test {

/// Distinct knot values and their multiplicities, 1-based as OCCT wants them.
inline void to_occt_knots(const Eigen::VectorXd& knots, TColStd_Array1OfReal& values,
                          TColStd_Array1OfInteger& mults) {
  std::vector<double> v;
  std::vector<int> m;
  for (Eigen::Index k = 0; k < knots.size(); ++k) {
    if (v.empty() || knots[k] != v.back()) {
      v.push_back(knots[k]);
      m.push_back(1);
    } else {
      ++m.back();
    }
  }
  values.Resize(1, static_cast<int>(v.size()), false);
  mults.Resize(1, static_cast<int>(m.size()), false);
  for (std::size_t i = 0; i < v.size(); ++i) {
    values.SetValue(static_cast<int>(i) + 1, v[i]);
    mults.SetValue(static_cast<int>(i) + 1, m[i]);
  }
}

/// The same surface as a Geom_BSplineSurface (rational when `s` is).
inline Handle(Geom_BSplineSurface) to_occt(const BSplineSurface& s) {
  const int nu = s.count(Direction::u);
  const int nv = s.count(Direction::v);
  TColgp_Array2OfPnt poles(1, nu, 1, nv);
  TColStd_Array2OfReal weights(1, nu, 1, nv);
  for (int i = 0; i < nu; ++i) {
    for (int j = 0; j < nv; ++j) {
      const Eigen::Index k = s.pole_index(i, j);
      poles.SetValue(
          i + 1, j + 1,
          gp_Pnt(s.control_points(k, 0), s.control_points(k, 1), s.control_points(k, 2)));
      weights.SetValue(i + 1, j + 1, s.is_rational() ? s.weights[k] : 1.0);
    }
  }
  TColStd_Array1OfReal uk(1, 1), vk(1, 1);
  TColStd_Array1OfInteger um(1, 1), vm(1, 1);
  to_occt_knots(s.knots[0], uk, um);
  to_occt_knots(s.knots[1], vk, vm);
  if (s.is_rational()) {
    return new Geom_BSplineSurface(poles, weights, uk, vk, um, vm, s.degree[0], s.degree[1]);
  }
  return new Geom_BSplineSurface(poles, uk, vk, um, vm, s.degree[0], s.degree[1]);
}

/// An OpenCASCADE surface back as an argil surface (knots expanded, poles row i * n_v + j).
inline BSplineSurface from_occt(const Handle(Geom_BSplineSurface) & g) {
  BSplineSurface s;
  s.degree = {g->UDegree(), g->VDegree()};
  const auto knots = [](const TColStd_Array1OfReal& values, const TColStd_Array1OfInteger& mults) {
    std::vector<double> k;
    for (int i = values.Lower(); i <= values.Upper(); ++i)
      for (int m = 0; m < mults(i); ++m) k.push_back(values(i));
    return Eigen::VectorXd(
        Eigen::Map<Eigen::VectorXd>(k.data(), static_cast<Eigen::Index>(k.size())));
  };
  s.knots = {knots(g->UKnots(), g->UMultiplicities()), knots(g->VKnots(), g->VMultiplicities())};
  const int nu = g->NbUPoles(), nv = g->NbVPoles();
  s.control_points.resize(nu * nv, 3);
  if (g->IsURational() || g->IsVRational()) s.weights.resize(nu * nv);
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j < nv; ++j) {
      const gp_Pnt p = g->Pole(i + 1, j + 1);
      s.control_points.row(s.pole_index(i, j)) << p.X(), p.Y(), p.Z();
      if (s.is_rational()) s.weights[s.pole_index(i, j)] = g->Weight(i + 1, j + 1);
    }
  return s;
}

}  // namespace argil::test
