// TrimRegion's edge query on one piece: the point of S(c(t)) closest to a
// point in space.
#include <algorithm>
#include <array>
#include <cmath>

#include "argil/core/geometry/basis.hpp"
#include "argil/core/geometry/evaluate.hpp"
#include "argil/core/geometry/param_rect.hpp"
#include "argil/core/geometry/trim_region.hpp"

namespace argil {

namespace {

/// Samples before Gauss-Newton: this many intervals per knot span of the
/// surface the piece's box covers (within a span S is one rational
/// polynomial), at most kMaxSamples in all.
constexpr int kSamplesPerSpan = 8;
constexpr int kMaxSamples = 128;
constexpr int kNewtonSteps = 12;

/// A point of a Bezier piece and its derivative by the local parameter s.
struct CurveSample {
  Eigen::Vector2d c = Eigen::Vector2d::Zero();
  Eigen::Vector2d dc = Eigen::Vector2d::Zero();
};

CurveSample bezier_sample(const Eigen::Vector3d* pw, int degree, double s) {
  std::array<Eigen::Vector3d, kMaxDegree + 1> work;
  std::copy(pw, pw + degree + 1, work.begin());
  for (int r = 1; r < degree; ++r) {
    for (int i = 0; i <= degree - r; ++i) {
      const auto k = static_cast<std::size_t>(i);
      work[k] = (1.0 - s) * work[k] + s * work[k + 1];
    }
  }
  const Eigen::Vector3d h = (1.0 - s) * work[0] + s * work[1];
  const Eigen::Vector3d dh = degree * (work[1] - work[0]);
  CurveSample out;
  out.c = h.head<2>() / h.z();
  out.dc = (dh.head<2>() - out.c * dh.z()) / h.z();
  return out;
}

Eigen::Vector2d clamped(const ParamRect& domain, const Eigen::Vector2d& uv) {
  return {std::clamp(uv.x(), domain.u0, domain.u1), std::clamp(uv.y(), domain.v0, domain.v1)};
}

/// Knot spans of the surface that [lo, hi] (clamped to the domain) reaches into, in u and v
/// together.
int spans_covered(const BSplineSurface& s, const Eigen::Vector2d& lo, const Eigen::Vector2d& hi) {
  int spans = 0;
  for (const Direction d : kDirections) {
    const int p = s.degree_in(d), n = s.count(d);
    const Eigen::VectorXd& knots = s.knots_in(d);
    spans += find_span(p, knots, n, hi[index_of(d)]) - find_span(p, knots, n, lo[index_of(d)]);
  }
  return spans + 1;
}

}  // namespace

TrimEdgePoint TrimRegion::closest_on_piece(int index, const BSplineSurface& surface,
                                           const Eigen::Vector3d& p_W) const {
  const Piece& piece = pieces_[static_cast<std::size_t>(index)];
  const Eigen::Vector3d* pw = &points_[static_cast<std::size_t>(piece.first)];
  const ParamRect domain = domain_of(surface);
  double best_s = 0.0;
  double best_d2 = std::numeric_limits<double>::infinity();
  const int intervals = std::min(kSamplesPerSpan * spans_covered(surface, clamped(domain, piece.lo),
                                                                 clamped(domain, piece.hi)),
                                 kMaxSamples);
  for (int k = 0; k <= intervals; ++k) {
    const double s = static_cast<double>(k) / intervals;
    const Eigen::Vector2d uv = clamped(domain, bezier_sample(pw, piece.degree, s).c);
    const double d2 = (evaluate(surface, uv.x(), uv.y()) - p_W).squaredNorm();
    if (d2 < best_d2) {
      best_d2 = d2;
      best_s = s;
    }
  }
  // Gauss-Newton on |S(c(s)) - p|^2 from the best sample, halving a step
  // that does not improve; each point is evaluated once, with its derivatives.
  CurveSample c = bezier_sample(pw, piece.degree, best_s);
  Eigen::Vector2d uv = clamped(domain, c.c);
  SurfaceDerivatives d = evaluate_derivatives(surface, uv.x(), uv.y(), 1);
  for (int step = 0; step < kNewtonSteps; ++step) {
    const Eigen::Vector3d g = d.du * c.dc.x() + d.dv * c.dc.y();
    const double gg = g.squaredNorm();
    if (!(gg > 0.0)) break;
    double ds = -(d.point - p_W).dot(g) / gg;
    bool improved = false;
    for (int halving = 0; halving < 4 && !improved; ++halving, ds *= 0.5) {
      const double s = std::clamp(best_s + ds, 0.0, 1.0);
      if (s == best_s) break;
      const CurveSample next = bezier_sample(pw, piece.degree, s);
      const Eigen::Vector2d next_uv = clamped(domain, next.c);
      const SurfaceDerivatives next_d = evaluate_derivatives(surface, next_uv.x(), next_uv.y(), 1);
      const double d2 = (next_d.point - p_W).squaredNorm();
      if (d2 < best_d2) {
        improved = true;
        best_d2 = d2;
        best_s = s;
        c = next;
        uv = next_uv;
        d = next_d;
      }
    }
    if (!improved || std::abs(ds) < 1e-14) break;
  }
  TrimEdgePoint out;
  out.uv = uv;
  out.point = d.point;
  out.distance = std::sqrt(best_d2);
  out.loop = piece.loop;
  out.curve = piece.curve;
  out.t = piece.t0 + best_s * (piece.t1 - piece.t0);
  return out;
}

}  // namespace argil
