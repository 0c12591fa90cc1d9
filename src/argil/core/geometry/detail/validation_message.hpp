#pragma once
// Validation results whose messages name the field, index and value, and the
// weight rules surfaces and curves share.

#include <Eigen/Core>
#include <cmath>
#include <sstream>
#include <type_traits>

#include "argil/core/base/number_text.hpp"
#include "argil/core/geometry/bspline_surface.hpp"

namespace argil::detail {

/// A part of a defect's text; numbers print as number_text, exact and short.
template <class Part>
void append_part(std::ostringstream& text, const Part& part) {
  if constexpr (std::is_floating_point_v<Part>) {
    text << number_text(static_cast<double>(part));
  } else {
    text << part;
  }
}

/// The defect with its message: the parts streamed in order, numbers in their
/// shortest exact form so the message reproduces the input.
template <class... Parts>
Status defect(const Parts&... parts) {
  std::ostringstream text;
  (append_part(text, parts), ...);
  return Status::error(StatusCode::invalid_surface, text.str());
}

/// Weights of n control points: empty (polynomial) or n values, each finite,
/// positive and in [1 / kMaxWeight, kMaxWeight], the largest at most
/// kMaxWeightRatio times the smallest. The same rules for surfaces and curves.
inline Status validate_weights(const Eigen::VectorXd& w, Eigen::Index n) {
  if (w.size() != 0 && w.size() != n) {
    return defect("weights has ", w.size(), " values, expected 0 or ", n);
  }
  for (Eigen::Index r = 0; r < w.size(); ++r) {
    if (!std::isfinite(w[r])) {
      return defect("weights[", r, "] is ", w[r]);
    }
    if (!(w[r] > 0.0)) {
      return defect("weights[", r, "] is ", w[r], ", weights must be positive");
    }
    if (w[r] > kMaxWeight || w[r] < 1.0 / kMaxWeight) {
      return defect("weights[", r, "] is ", w[r], ", outside the supported [", 1.0 / kMaxWeight,
                    ", ", kMaxWeight, "]");
    }
  }
  if (w.size() > 0 && w.maxCoeff() > kMaxWeightRatio * w.minCoeff()) {
    return defect("weights range from ", w.minCoeff(), " to ", w.maxCoeff(),
                  ", a ratio above the supported ", kMaxWeightRatio);
  }
  return Status::success();
}

}  // namespace argil::detail
