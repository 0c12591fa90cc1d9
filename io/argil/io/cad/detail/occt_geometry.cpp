#include "argil/io/cad/detail/occt_geometry.hpp"

#include <TColStd_Array1OfInteger.hxx>
#include <TColStd_Array1OfReal.hxx>
#include <TColStd_Array2OfReal.hxx>
#include <TColgp_Array1OfPnt2d.hxx>
#include <TColgp_Array2OfPnt.hxx>

#include <cmath>
#include <vector>

namespace argil::io::detail {

double writable(double x) { return std::abs(x) < 1e-99 ? 0.0 : x; }

namespace {

struct OcctKnots {
  TColStd_Array1OfReal values;
  TColStd_Array1OfInteger multiplicities;
};

// Flat clamped knot vector to distinct values and multiplicities (exact comparison).
OcctKnots occt_knots(const Eigen::VectorXd& flat) {
  std::vector<double> values;
  std::vector<int> counts;
  for (Eigen::Index k = 0; k < flat.size(); ++k) {
    const double t = writable(flat[k]);
    if (!values.empty() && values.back() == t) {
      ++counts.back();
    } else {
      values.push_back(t);
      counts.push_back(1);
    }
  }
  const int n = static_cast<int>(values.size());
  OcctKnots out{TColStd_Array1OfReal(1, n), TColStd_Array1OfInteger(1, n)};
  for (int i = 0; i < n; ++i) {
    out.values(i + 1) = values[static_cast<std::size_t>(i)];
    out.multiplicities(i + 1) = counts[static_cast<std::size_t>(i)];
  }
  return out;
}

}  // namespace

Handle(Geom_BSplineSurface) to_occt(const BSplineSurface& s) {
  const int nu = s.count(Direction::u), nv = s.count(Direction::v);
  TColgp_Array2OfPnt poles(1, nu, 1, nv);
  TColStd_Array2OfReal weights(1, nu, 1, nv);
  for (int i = 0; i < nu; ++i) {
    for (int j = 0; j < nv; ++j) {
      const Eigen::Index row = s.pole_index(i, j);
      poles(i + 1, j + 1) =
          gp_Pnt(writable(s.control_points(row, 0)), writable(s.control_points(row, 1)),
                 writable(s.control_points(row, 2)));
      weights(i + 1, j + 1) = s.is_rational() ? s.weights[row] : 1.0;
    }
  }
  const OcctKnots u = occt_knots(s.knots[0]);
  const OcctKnots v = occt_knots(s.knots[1]);
  if (s.is_rational()) {
    return new Geom_BSplineSurface(poles, weights, u.values, v.values, u.multiplicities,
                                   v.multiplicities, s.degree[0], s.degree[1]);
  }
  return new Geom_BSplineSurface(poles, u.values, v.values, u.multiplicities, v.multiplicities,
                                 s.degree[0], s.degree[1]);
}

Handle(Geom2d_BSplineCurve) to_occt(const BSplineCurve& c) {
  const int n = c.count();
  TColgp_Array1OfPnt2d poles(1, n);
  TColStd_Array1OfReal weights(1, n);
  for (int i = 0; i < n; ++i) {
    poles(i + 1) = gp_Pnt2d(writable(c.points(i, 0)), writable(c.points(i, 1)));
    weights(i + 1) = c.is_rational() ? c.weights[i] : 1.0;
  }
  const OcctKnots k = occt_knots(c.knots);
  if (c.is_rational()) {
    return new Geom2d_BSplineCurve(poles, weights, k.values, k.multiplicities, c.degree);
  }
  return new Geom2d_BSplineCurve(poles, k.values, k.multiplicities, c.degree);
}

}  // namespace argil::io::detail
