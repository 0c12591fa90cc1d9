#include "argil/io/model/trim_curve.hpp"

#include <string>

namespace argil::io {

Status validate_trim_curve(const TrimCurve& curve) {
  const Status check = validate(curve);
  if (!check.ok())
    return Status::error(StatusCode::invalid_surface, "trim curve: " + check.message);
  if (curve.points.cols() != 2) {
    return Status::error(StatusCode::invalid_surface, "trim curve: points has " +
                                                          std::to_string(curve.points.cols()) +
                                                          " columns, expected 2 (u, v)");
  }
  return Status::success();
}

Eigen::Vector2d evaluate_trim_curve(const TrimCurve& curve, double t) { return evaluate(curve, t); }

Status validate_face(const FaceRecord& face) {
  const Status check = validate(face.surface);
  if (!check.ok()) return Status::error(StatusCode::invalid_surface, "surface: " + check.message);
  for (std::size_t l = 0; l < face.loops.size(); ++l) {
    const std::string loop = "loop " + std::to_string(l);
    if (face.loops[l].curves.empty()) {
      return Status::error(StatusCode::invalid_surface, loop + " has no curves");
    }
    for (std::size_t c = 0; c < face.loops[l].curves.size(); ++c) {
      const Status status = validate_trim_curve(face.loops[l].curves[c]);
      if (!status.ok()) {
        return Status::error(status.code,
                             loop + " curve " + std::to_string(c) + ": " + status.message);
      }
    }
  }
  return Status::success();
}

Status validate_face(const FaceRecord& face, std::size_t face_index) {
  const Status check = validate_face(face);
  if (check.ok()) return check;
  return Status::error(check.code, "face " + std::to_string(face_index) + " " + check.message);
}

}  // namespace argil::io
