// HapticWorld's trims: which part of each body's domain is material.
#include <algorithm>
#include <string>

#include "argil/core/base/number_text.hpp"
#include "argil/core/haptic/haptic_tick.hpp"

namespace argil {

namespace {

std::string rect_text(const ParamRect& r) {
  return "[" + number_text(r.u0) + ", " + number_text(r.u1) + "] x [" + number_text(r.v0) + ", " +
         number_text(r.v1) + "]";
}

}  // namespace

Status HapticWorld::set_trim(int body, TrimRegion region) {
  if (body < 0 || body >= body_count()) {
    return Status::error(StatusCode::invalid_argument, "set_trim: body " + std::to_string(body) +
                                                           " is not in [0, " +
                                                           std::to_string(body_count()) + ")");
  }
  const ParamRect domain = domain_of(surface(body));
  if (!region.empty() && !region.box().touches(domain)) {
    return Status::error(StatusCode::invalid_argument,
                         "set_trim: body " + std::to_string(body) +
                             ": the trim loops' (u, v) box " + rect_text(region.box()) +
                             " misses the surface's domain " + rect_text(domain));
  }
  if (trims_.size() < bodies_.size()) trims_.resize(bodies_.size());
  trims_[static_cast<std::size_t>(body)] = std::move(region);
  // The proxy's side and last closest point were of the old material.
  if (sphere_) sphere_->forget_side(static_cast<std::size_t>(body));
  return Status::success();
}

const TrimRegion& HapticWorld::trim(int body) const {
  const auto b = static_cast<std::size_t>(body);
  return b < trims_.size() ? trims_[b] : untrimmed_;
}

std::vector<TrimmedSurface> HapticWorld::trimmed_surfaces(const std::vector<char>& reach) const {
  std::vector<TrimmedSurface> out;
  for (int b = 0; b < body_count(); ++b)
    out.push_back({reach[static_cast<std::size_t>(b)] ? &hierarchy(b) : nullptr, &trim(b)});
  return out;
}

}  // namespace argil
