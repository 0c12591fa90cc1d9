#include "support/transposed_surface.hpp"

namespace argil::test {

BSplineSurface transposed(const BSplineSurface& surface) {
  const int nu = surface.count(Direction::u);
  const int nv = surface.count(Direction::v);
  BSplineSurface t;
  t.degree = {surface.degree[1], surface.degree[0]};
  t.knots = {surface.knots[1], surface.knots[0]};
  t.control_points = transposed_rows(surface.control_points, nu, nv);
  if (surface.is_rational()) t.weights = transposed_rows(surface.weights, nu, nv);
  return t;
}

}  // namespace argil::test
