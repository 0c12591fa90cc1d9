// The documented range of collision requests (docs/range.md).
#include <cmath>
#include <sstream>

#include "argil/core/collision/contact.hpp"

namespace argil {

namespace {

Status out_of_range(const std::string& what) {
  return Status::error(StatusCode::invalid_argument, "collision request: " + what);
}

std::string number(double x) {
  std::ostringstream out;
  out.precision(17);
  out << x;
  return out.str();
}

}  // namespace

Status check_request(const CollisionRequest& request, const SurfaceHierarchy& surface) {
  if (request.max_contacts < 1) {
    return out_of_range("max_contacts " + std::to_string(request.max_contacts) +
                        " must be at least 1");
  }
  if (request.max_level < 0 || request.max_level > SurfaceHierarchy::kMaxLevel) {
    return out_of_range("max_level " + std::to_string(request.max_level) + " is outside [0, " +
                        std::to_string(SurfaceHierarchy::kMaxLevel) + "]");
  }
  const double eps = request.tolerance;
  if (!std::isfinite(eps) || !(eps > 0.0)) {
    return out_of_range("tolerance " + number(eps) + " mm must be positive and finite");
  }
  const Box3& box = surface.block(0).bound.box;
  const double size = box.diagonal();
  const double magnitude = box.min.cwiseAbs().cwiseMax(box.max.cwiseAbs()).maxCoeff();
  if (eps > size) {
    return out_of_range("tolerance " + number(eps) + " mm exceeds the surface's size " +
                        number(size) + " mm");
  }
  if (eps < kMinRelativeTolerance * size) {
    return out_of_range("tolerance " + number(eps) + " mm is below " +
                        number(kMinRelativeTolerance) + " of the surface's size " + number(size) +
                        " mm");
  }
  if (eps < kMinRelativeTolerance * magnitude) {
    return out_of_range("tolerance " + number(eps) + " mm is below " +
                        number(kMinRelativeTolerance) + " of the coordinates' magnitude " +
                        number(magnitude) +
                        " mm, which rounding alone exceeds (move the model nearer the origin)");
  }
  return Status::success();
}

}  // namespace argil
