#include "argil/io/model/trim_curve.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "argil/core/geometry/basis.hpp"

namespace argil::io {
namespace {

Status curve_error(const std::string& what) {
  return Status::error(StatusCode::invalid_surface, "trim curve: " + what);
}

std::string at(const char* field, Eigen::Index index, double value) {
  std::ostringstream out;
  out.precision(17);
  out << field << "[" << index << "] = " << value;
  return out.str();
}

}  // namespace

Status validate_trim_curve(const TrimCurve& curve) {
  const Eigen::Index p = curve.degree;
  if (curve.degree < 1 || curve.degree > kMaxDegree) {
    return curve_error("degree " + std::to_string(curve.degree) + " out of range [1, " +
                       std::to_string(kMaxDegree) + "]");
  }
  if (curve.knots.size() < 2 * (p + 1)) {
    return curve_error("needs at least " + std::to_string(2 * (p + 1)) + " knots, has " +
                       std::to_string(curve.knots.size()));
  }
  for (Eigen::Index k = 0; k < curve.knots.size(); ++k) {
    if (!std::isfinite(curve.knots[k])) return curve_error(at("knots", k, curve.knots[k]));
    if (k > 0 && curve.knots[k] < curve.knots[k - 1]) {
      return curve_error("knots decrease at " + at("knots", k, curve.knots[k]));
    }
  }
  const Eigen::Index last = curve.knots.size() - 1;
  for (Eigen::Index k = 1; k <= p; ++k) {
    if (curve.knots[k] != curve.knots[0] || curve.knots[last - k] != curve.knots[last]) {
      return curve_error("knots not clamped (end knots must repeat degree + 1 times)");
    }
  }
  if (curve.knots[0] == curve.knots[last]) return curve_error("empty parameter range");
  if (curve.poles.rows() != curve.count()) {
    return curve_error("has " + std::to_string(curve.poles.rows()) + " poles, knots imply " +
                       std::to_string(curve.count()));
  }
  for (Eigen::Index i = 0; i < curve.poles.rows(); ++i) {
    if (!curve.poles.row(i).allFinite()) {
      return curve_error("pole " + std::to_string(i) + " is not finite");
    }
  }
  if (curve.weights.size() != 0 && curve.weights.size() != curve.poles.rows()) {
    return curve_error("has " + std::to_string(curve.weights.size()) + " weights for " +
                       std::to_string(curve.poles.rows()) + " poles");
  }
  for (Eigen::Index i = 0; i < curve.weights.size(); ++i) {
    if (!std::isfinite(curve.weights[i]) || !(curve.weights[i] > 0.0)) {
      return curve_error("weight must be positive and finite: " +
                         at("weights", i, curve.weights[i]));
    }
  }
  return Status::success();
}

Eigen::Vector2d evaluate_trim_curve(const TrimCurve& curve, double t) {
  const int n = curve.count();
  const double t_clamped =
      std::clamp(t, curve.knots[curve.degree], curve.knots[static_cast<Eigen::Index>(n)]);
  const int span = find_span(curve.degree, curve.knots, n, t_clamped);
  const Eigen::MatrixXd basis = basis_derivatives(curve.degree, curve.knots, span, t_clamped, 0);
  Eigen::Vector2d sum = Eigen::Vector2d::Zero();
  double weight_sum = 0.0;
  for (int r = 0; r <= curve.degree; ++r) {
    const Eigen::Index i = span - curve.degree + r;
    const double w = curve.is_rational() ? curve.weights[i] : 1.0;
    sum += basis(0, r) * w * curve.poles.row(i).transpose();
    weight_sum += basis(0, r) * w;
  }
  return sum / weight_sum;
}

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

Status validate_face(const FaceRecord& face, std::size_t face_index) {
  const std::string where = "face " + std::to_string(face_index);
  const Status check = validate(face.surface);
  if (!check.ok()) {
    return Status::error(StatusCode::invalid_surface, where + " surface: " + check.message);
  }
  for (std::size_t l = 0; l < face.loops.size(); ++l) {
    if (face.loops[l].curves.empty()) {
      return Status::error(StatusCode::invalid_surface,
                           where + " loop " + std::to_string(l) + " has no curves");
    }
    for (std::size_t c = 0; c < face.loops[l].curves.size(); ++c) {
      const Status status = validate_trim_curve(face.loops[l].curves[c]);
      if (!status.ok()) {
        return Status::error(status.code, where + " loop " + std::to_string(l) + " curve " +
                                              std::to_string(c) + ": " + status.message);
      }
    }
  }
  return Status::success();
}

}  // namespace argil::io
