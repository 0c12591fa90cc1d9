#include "argil/core/collision/surface_contact.hpp"

namespace argil {

Contact contact_at(const BSplineSurface& a, const Eigen::Vector2d& uv_a,
                   const SurfaceDerivatives& d, double depth) {
  Contact c;
  c.point = d.point;
  c.uv_a = uv_a;
  c.normal = unit_normal(d);
  // The limit normal needs second derivatives: evaluated only at poles.
  if (c.normal.squaredNorm() == 0.0) c.normal = unit_normal(a, uv_a[0], uv_a[1]);
  c.tangent_u = d.du;
  c.tangent_v = d.dv;
  c.depth = depth;
  return c;
}

}  // namespace argil
