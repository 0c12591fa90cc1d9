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

std::vector<Eigen::Vector2d> loop_polygon(const TrimLoop& loop, int samples_per_span) {
  std::vector<Eigen::Vector2d> polygon;
  for (const TrimCurve& curve : loop.curves) {
    // A degree-1 polynomial span is straight: its ends describe it exactly.
    const int samples = (curve.degree == 1 && !curve.is_rational()) ? 1 : samples_per_span;
    for (Eigen::Index k = curve.degree; k < curve.count(); ++k) {
      const double t0 = curve.knots[k];
      const double t1 = curve.knots[k + 1];
      if (t1 <= t0) continue;
      for (int s = 0; s < samples; ++s) {
        const double t = t0 + (t1 - t0) * static_cast<double>(s) / samples;
        polygon.push_back(evaluate_trim_curve(curve, t));
      }
    }
  }
  return polygon;
}

bool inside_trim(const std::vector<std::vector<Eigen::Vector2d>>& polygons,
                 const Eigen::Vector2d& uv) {
  bool inside = false;
  for (const auto& polygon : polygons) {
    const std::size_t n = polygon.size();
    for (std::size_t i = 0, j = n - 1; i < n; j = i++) {
      const Eigen::Vector2d& a = polygon[i];
      const Eigen::Vector2d& b = polygon[j];
      if ((a.y() > uv.y()) != (b.y() > uv.y())) {
        const double x_cross = a.x() + (uv.y() - a.y()) * (b.x() - a.x()) / (b.y() - a.y());
        if (uv.x() < x_cross) inside = !inside;
      }
    }
  }
  return inside;
}

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
