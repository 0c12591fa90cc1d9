// The documented range of collision requests (docs/range.md).
#include <cmath>

#include "argil/core/base/number_text.hpp"
#include "argil/core/collision/contact.hpp"

namespace argil {

namespace {

Status out_of_range(const std::string& what) {
  return Status::error(StatusCode::invalid_argument, "collision request: " + what);
}

/// "1e-20 mm": a length as the caller gave it, in mm, exactly.
std::string mm(double x) { return number_text(x) + " mm"; }

/// "1.63e-11 mm": a bound derived from the surface, rounded so that the
/// printed value is itself allowed.
std::string limit_mm(double x, LimitSide side) { return limit_text(x, side) + " mm"; }

/// "16.2 mm": a size for reading, 3 significant digits.
std::string approx_mm(double x) { return approx_text(x) + " mm"; }

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
  // Every bound is stated in mm, the unit the caller gave eps in, then as the
  // fraction of the surface it derives from.
  const double eps = request.tolerance;
  if (!std::isfinite(eps) || !(eps > 0.0)) {
    return out_of_range("tolerance " + mm(eps) + " must be positive and finite");
  }
  const Box3& box = surface.block(0).bound.box;
  const double size = box.diagonal();
  const double magnitude = box.min.cwiseAbs().cwiseMax(box.max.cwiseAbs()).maxCoeff();
  if (eps > size) {
    return out_of_range("tolerance " + mm(eps) +
                        " is above the largest this surface allows, its size " +
                        limit_mm(size, LimitSide::upper));
  }
  if (eps < kMinRelativeTolerance * size) {
    return out_of_range("tolerance " + mm(eps) + " is below the smallest this surface allows, " +
                        limit_mm(kMinRelativeTolerance * size, LimitSide::lower) + " (" +
                        number_text(kMinRelativeTolerance) + " of its " + approx_mm(size) +
                        " size)");
  }
  if (eps < kMinRelativeTolerance * magnitude) {
    return out_of_range(
        "tolerance " + mm(eps) + " is below the smallest this surface's position allows, " +
        limit_mm(kMinRelativeTolerance * magnitude, LimitSide::lower) + " (" +
        number_text(kMinRelativeTolerance) + " of its coordinates' magnitude " +
        approx_mm(magnitude) + ", which rounding alone exceeds; move the model nearer the origin)");
  }
  return Status::success();
}

}  // namespace argil
