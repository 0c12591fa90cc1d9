#include "argil/sculpt/script/stroke_script.hpp"

#include <algorithm>
#include <cmath>
#include <optional>

#include "argil/core/base/number_text.hpp"
#include "argil/core/geometry/evaluate.hpp"
#include "argil/core/geometry/trim_region.hpp"

namespace argil::sculpt {
namespace {

std::string uv_text(const Eigen::Vector2d& uv) {
  return "(u, v) = (" + number_text(uv.x()) + ", " + number_text(uv.y()) + ")";
}

/// The surface point and outward unit normal at a (u, v) the face holds.
struct SurfacePlace {
  Eigen::Vector3d point, normal;
};

class FacePlaces {
 public:
  FacePlaces(const io::FaceRecord& face, std::string label)
      : face_(face), label_(std::move(label)) {}

  Status init() {
    if (!face_.trimmed()) return Status::success();
    Result<TrimRegion> region = TrimRegion::create(face_.loops);
    if (!region.ok()) return error(region.status().message);
    region_ = std::move(region.value());
    return Status::success();
  }

  Result<SurfacePlace> at(const Eigen::Vector2d& uv) const {
    const BSplineSurface& s = face_.surface;
    const bool in_domain =
        uv.x() >= s.domain_start(Direction::u) && uv.x() <= s.domain_end(Direction::u) &&
        uv.y() >= s.domain_start(Direction::v) && uv.y() <= s.domain_end(Direction::v);
    if (!in_domain) {
      return error(uv_text(uv) + " is outside the surface's domain [" +
                   number_text(s.domain_start(Direction::u)) + ", " +
                   number_text(s.domain_end(Direction::u)) + "] x [" +
                   number_text(s.domain_start(Direction::v)) + ", " +
                   number_text(s.domain_end(Direction::v)) + "]");
    }
    if (region_ && !region_->contains(uv)) {
      return error(uv_text(uv) + " is outside the face's trims: there is no material there");
    }
    const Eigen::Vector3d n = unit_normal(s, uv.x(), uv.y());
    if (!(n.squaredNorm() > 0.5)) return error(uv_text(uv) + " has no normal (a pole)");
    return SurfacePlace{evaluate(s, uv.x(), uv.y()), face_.reversed ? Eigen::Vector3d(-n) : n};
  }

 private:
  Status error(const std::string& what) const {
    return Status::error(StatusCode::invalid_argument, label_ + ": " + what);
  }

  const io::FaceRecord& face_;
  std::string label_;
  std::optional<TrimRegion> region_;
};

Status check_request(const StrokeRequest& r) {
  const auto bad = [](const std::string& what) {
    return Status::error(StatusCode::invalid_argument, what);
  };
  if (r.uv.empty()) return bad("a stroke needs at least one (u, v)");
  if (!(r.depth_mm > 0.0) || !std::isfinite(r.depth_mm))
    return bad("depth " + number_text(r.depth_mm) + " mm must be positive and finite");
  if (!(r.speed_mm_s > 0.0) || !std::isfinite(r.speed_mm_s))
    return bad("speed " + number_text(r.speed_mm_s) + " mm/s must be positive and finite");
  if (!(r.approach_mm > 0.0) || !std::isfinite(r.approach_mm))
    return bad("approach " + number_text(r.approach_mm) + " mm must be positive and finite");
  if (!(r.hold_s >= 0.0) || !std::isfinite(r.hold_s))
    return bad("hold " + number_text(r.hold_s) + " s must be non-negative and finite");
  if (!(r.tool_offset_mm >= 0.0) || !std::isfinite(r.tool_offset_mm))
    return bad("tool offset " + number_text(r.tool_offset_mm) + " mm must be >= 0");
  for (const Eigen::Vector2d& uv : r.uv)
    if (!uv.allFinite()) return bad(uv_text(uv) + " is not finite");
  return Status::success();
}

/// Appends a keyframe reached at the request's speed from the last one.
void move_to(Script& script, const Eigen::Vector3d& position, double speed,
             ScriptEvent event = ScriptEvent::none) {
  Keyframe k;
  k.X_WD.p = position;
  k.event = event;
  if (!script.keyframes.empty()) {
    const Keyframe& last = script.keyframes.back();
    // At least a microsecond apart: times must increase strictly.
    k.t = last.t + std::max((position - last.X_WD.p).norm() / speed, 1e-6);
  }
  script.keyframes.push_back(k);
}

}  // namespace

Result<Script> stroke_script(const io::FaceRecord& face, const StrokeRequest& request,
                             const std::string& face_label, double step_mm) {
  if (const Status ok = check_request(request); !ok.ok()) {
    return Status::error(ok.code, face_label + ": " + ok.message);
  }
  FacePlaces places(face, face_label);
  if (const Status ok = places.init(); !ok.ok()) return ok;
  // The device point sits this far above the surface along the normal.
  const double engage = request.tool_offset_mm + 0.1 * request.approach_mm;
  const double top = request.tool_offset_mm + request.approach_mm;
  const double working = request.tool_offset_mm - request.depth_mm;

  Result<SurfacePlace> first = places.at(request.uv.front());
  if (!first.ok()) return first.status();
  Script script;
  script.tool = request.tool;
  const double v = request.speed_mm_s;
  const SurfacePlace& p0 = first.value();
  move_to(script, p0.point + top * p0.normal, v);
  move_to(script, p0.point + engage * p0.normal, v, ScriptEvent::engage);
  move_to(script, p0.point + working * p0.normal, v);
  SurfacePlace last = p0;
  if (request.uv.size() == 1) {
    Keyframe hold = script.keyframes.back();
    hold.t += std::max(request.hold_s, 1e-6);
    script.keyframes.push_back(hold);
  }
  // A drag: keyframes along each (u, v) segment, no chord longer than step_mm
  // (the device moves straight between keyframes, the surface bends away).
  for (std::size_t k = 1; k < request.uv.size(); ++k) {
    const Eigen::Vector2d a = request.uv[k - 1], b = request.uv[k];
    std::vector<Eigen::Vector2d> pending{b};
    Eigen::Vector2d at = a;
    while (!pending.empty()) {
      const Eigen::Vector2d target = pending.back();
      Result<SurfacePlace> place = places.at(target);
      if (!place.ok()) return place.status();
      const Eigen::Vector3d device = place.value().point + working * place.value().normal;
      if ((device - script.keyframes.back().X_WD.p).norm() > step_mm &&
          (target - at).norm() > 1e-12 * (1.0 + at.norm())) {
        pending.push_back(0.5 * (at + target));
        continue;
      }
      move_to(script, device, v);
      last = place.value();
      at = target;
      pending.pop_back();
    }
  }
  move_to(script, last.point + engage * last.normal, v, ScriptEvent::release);
  move_to(script, last.point + top * last.normal, v);
  if (const Status ok = validate(script, face_label); !ok.ok()) return ok;
  return script;
}

}  // namespace argil::sculpt
