#include "support/tool_shapes.hpp"

#include <algorithm>
#include <cmath>

namespace argil::test {

Eigen::VectorXd uniform_knots(int degree, int poles) {
  Eigen::VectorXd k(poles + degree + 1);
  for (Eigen::Index i = 0; i < k.size(); ++i)
    k[i] = std::clamp(static_cast<double>(i - degree) / (poles - degree), 0.0, 1.0);
  return k;
}

BSplineSurface wavy_sheet(int n, double pitch, double wave) {
  BSplineSurface s;
  s.degree = {3, 3};
  s.knots = {uniform_knots(3, n), uniform_knots(3, n)};
  s.control_points.resize(static_cast<Eigen::Index>(n) * n, 3);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      s.control_points.row(s.pole_index(i, j)) << pitch * i, pitch * j,
          wave * std::sin(0.7 * i) * std::cos(0.5 * j);
  return s;
}

BSplineSurface bowl_cap() {
  BSplineSurface tool;
  tool.degree = {3, 3};
  tool.knots = {uniform_knots(3, 4), uniform_knots(3, 4)};
  tool.control_points.resize(16, 3);
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) {
      const double x = -6.0 + 4.0 * i, y = -6.0 + 4.0 * j;
      tool.control_points.row(tool.pole_index(i, j)) << x, y, 0.05 * (x * x + y * y);
    }
  return tool;
}

}  // namespace argil::test
