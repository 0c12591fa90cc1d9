#pragma once
// Surfaces shared by the benchmarks, and their OpenCASCADE copies.

#include <Geom_BSplineSurface.hxx>
#include <TColStd_Array1OfInteger.hxx>
#include <TColStd_Array1OfReal.hxx>
#include <TColgp_Array2OfPnt.hxx>
#include <gp_Pnt.hxx>

#include <algorithm>
#include <cmath>

#include "argil/core.hpp"

namespace argil::bench {

/// Uniform clamped knots on [0, 1].
inline Eigen::VectorXd uniform_knots(int degree, int poles) {
  Eigen::VectorXd k(poles + degree + 1);
  for (Eigen::Index i = 0; i < k.size(); ++i) {
    k[i] = std::clamp(static_cast<double>(i - degree) / (poles - degree), 0.0, 1.0);
  }
  return k;
}

/// A wavy bicubic panel with n x n poles on a 10 mm pitch (n = 32: 310 mm wide).
inline BSplineSurface bicubic_panel(int n) {
  BSplineSurface s;
  s.degree = {3, 3};
  s.knots = {uniform_knots(3, n), uniform_knots(3, n)};
  s.control_points.resize(static_cast<Eigen::Index>(n) * n, 3);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      s.control_points.row(s.pole_index(i, j)) << 10.0 * i, 10.0 * j,
          20.0 * std::sin(0.3 * i) * std::cos(0.2 * j);
  return s;
}

/// The same polynomial surface as an OpenCASCADE Geom_BSplineSurface (uniform knots).
inline Handle(Geom_BSplineSurface) to_occt(const BSplineSurface& s) {
  const int nu = s.count(Direction::u), nv = s.count(Direction::v);
  TColgp_Array2OfPnt poles(1, nu, 1, nv);
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j < nv; ++j) {
      const auto p = s.control_points.row(s.pole_index(i, j));
      poles.SetValue(i + 1, j + 1, gp_Pnt(p[0], p[1], p[2]));
    }
  const auto distinct = [](const Eigen::VectorXd& k, TColStd_Array1OfReal& values,
                           TColStd_Array1OfInteger& mults) {
    std::vector<double> v;
    std::vector<int> m;
    for (Eigen::Index i = 0; i < k.size(); ++i) {
      if (v.empty() || k[i] != v.back()) {
        v.push_back(k[i]);
        m.push_back(1);
      } else {
        ++m.back();
      }
    }
    values.Resize(1, static_cast<int>(v.size()), false);
    mults.Resize(1, static_cast<int>(v.size()), false);
    for (std::size_t i = 0; i < v.size(); ++i) {
      values.SetValue(static_cast<int>(i) + 1, v[i]);
      mults.SetValue(static_cast<int>(i) + 1, m[i]);
    }
  };
  TColStd_Array1OfReal uk(1, 1), vk(1, 1);
  TColStd_Array1OfInteger um(1, 1), vm(1, 1);
  distinct(s.knots[0], uk, um);
  distinct(s.knots[1], vk, vm);
  return new Geom_BSplineSurface(poles, uk, vk, um, vm, s.degree[0], s.degree[1]);
}

}  // namespace argil::bench
