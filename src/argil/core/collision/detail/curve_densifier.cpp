#include "argil/core/collision/detail/curve_densifier.hpp"

#include <algorithm>
#include <cmath>

namespace argil {

/// The cubic Hermite arc between two curve points with the curve's tangents
/// there, in space and in both parameter planes, over s in [0, 1]. Its error
/// against the curve is of fourth order in the arc's length and largest near
/// s = 1/2, where the densifier measures it.
struct HermiteArc {
  const PairPoint& lo;
  const PairPoint& hi;
  const CurveTangent& t_lo;
  const CurveTangent& t_hi;
  double scale;  // signed chord length: the tangents' scale along lo -> hi [mm]

  /// Weights of (lo, t_lo, hi, t_hi) in the arc's derivative of `order` at s.
  static Eigen::Vector4d weights(double s, int order) {
    switch (order) {
      case 0:
        return {(1 + 2 * s) * (1 - s) * (1 - s), s * (1 - s) * (1 - s), s * s * (3 - 2 * s),
                s * s * (s - 1)};
      case 1:
        return {6 * s * s - 6 * s, 3 * s * s - 4 * s + 1, 6 * s - 6 * s * s, 3 * s * s - 2 * s};
      default:
        return {12 * s - 6, 6 * s - 4, 6 - 12 * s, 6 * s - 2};
    }
  }

  Eigen::Vector3d point(double s, int order = 0) const {
    const Eigen::Vector4d w = weights(s, order);
    return w[0] * lo.point + w[1] * scale * t_lo.unit + w[2] * hi.point + w[3] * scale * t_hi.unit;
  }

  /// The arc's point at s with parameters; a parameter both ends share
  /// exactly (a curve along a domain edge or an iso-line) keeps that value,
  /// so refinement holds it on the edge as it does at the ends.
  PairPoint at(double s) const {
    const Eigen::Vector4d w = weights(s, 0);
    const auto blend = [&](const Eigen::Vector2d& p0, const Eigen::Vector2d& t0,
                           const Eigen::Vector2d& p1, const Eigen::Vector2d& t1) {
      Eigen::Vector2d x = w[0] * p0 + w[1] * scale * t0 + w[2] * p1 + w[3] * scale * t1;
      for (int k = 0; k < 2; ++k)
        if (p0[k] == p1[k]) x[k] = p0[k];
      return x;
    };
    return {point(s), blend(lo.uv_a, t_lo.uv_a, hi.uv_a, t_hi.uv_a),
            blend(lo.uv_b, t_lo.uv_b, hi.uv_b, t_hi.uv_b)};
  }

  /// The distance from q to the arc near its middle (Newton on the foot's s
  /// from s = 1/2, kept inside the arc).
  double distance_near_middle(const Eigen::Vector3d& q) const {
    double s = 0.5;
    for (int it = 0; it < 4; ++it) {
      const Eigen::Vector3d d = point(s) - q, d1 = point(s, 1), d2 = point(s, 2);
      const double slope = d1.squaredNorm() + d.dot(d2);
      if (!(slope > 0.0)) break;
      s = std::clamp(s - d.dot(d1) / slope, 0.0, 1.0);
    }
    return (point(s) - q).norm();
  }

  /// The largest |P''(s)| over the arc: P'' is linear in s, so at an end.
  double max_second_derivative() const {
    return std::max(point(0.0, 2).norm(), point(1.0, 2).norm());
  }
};

namespace {

/// The arc when both ends have a tangent within 60 degrees of the chord, in
/// the same sense; otherwise the curve turns too much for one cubic.
std::optional<HermiteArc> hermite_arc(const PairPoint& lo, const CurveTangent& t_lo,
                                      const PairPoint& hi, const CurveTangent& t_hi) {
  const Eigen::Vector3d chord = hi.point - lo.point;
  const double length = chord.norm();
  if (t_lo.unit.isZero(0.0) || t_hi.unit.isZero(0.0) || !(length > 0.0)) return std::nullopt;
  const double sign = t_lo.unit.dot(chord) >= 0.0 ? 1.0 : -1.0;
  if (!(sign * t_lo.unit.dot(chord) >= 0.5 * length && sign * t_hi.unit.dot(chord) >= 0.5 * length))
    return std::nullopt;
  return HermiteArc{lo, hi, t_lo, t_hi, sign * length};
}

/// At most this many pieces from one measured arc (a longer run of chords
/// is split by halving first).
constexpr int kMaxPieces = 256;

}  // namespace

IntersectionCurve CurveDensifier::run(const IntersectionCurve& c, const std::vector<bool>& refined,
                                      const std::vector<std::optional<CurveTangent>>& tangents) {
  out_ = {};
  const auto node = [&](std::size_t k) {
    return Node{{c.points[k], c.uv_a[k], c.uv_b[k]},
                k < tangents.size() ? tangents[k] : std::optional<CurveTangent>{}};
  };
  Node lo, hi;
  for (std::size_t k = 0; k < c.points.size(); ++k) {
    push({c.points[k], c.uv_a[k], c.uv_b[k]});
    if (k + 1 < c.points.size() && refined[k] && refined[k + 1]) {
      // The last segment's end starts this one, with its tangent if found.
      lo = k > 0 && refined[k - 1] ? std::move(hi) : node(k);
      hi = node(k + 1);
      fill(lo, hi, 0);
    }
  }
  return std::move(out_);
}

std::optional<IntersectionCurve> CurveDensifier::between(const PairPoint& lo, const PairPoint& hi) {
  out_ = {};
  Node a{lo, {}}, b{hi, {}};
  if (!fill(a, b, 0)) return std::nullopt;
  return std::move(out_);
}

const CurveTangent& CurveDensifier::tangent(Node& n) const {
  if (!n.tangent) n.tangent = curve_tangent(pair_.eval_a, pair_.eval_b, n.at.uv_a, n.at.uv_b);
  return *n.tangent;
}

void CurveDensifier::push(const PairPoint& p) {
  out_.points.push_back(p.point);
  out_.uv_a.push_back(p.uv_a);
  out_.uv_b.push_back(p.uv_b);
}

/// Fills the open interval between two refined points; false when it stopped
/// short (a failed refinement or the depth limit). The curve point across the
/// middle of the chord decides: within the tolerance of the chord, the chord
/// stays; else, where the Hermite arc through both ends passes within an
/// eighth of the tolerance of that point, the arc is trusted and cut into
/// chords it keeps within half the tolerance, each new point refined from the
/// arc; else the interval is halved at that point.
bool CurveDensifier::fill(Node& lo, Node& hi, int depth) {
  if (depth >= kMaxDepth) return false;
  const PairPoint chord{0.5 * (lo.at.point + hi.at.point), 0.5 * (lo.at.uv_a + hi.at.uv_a),
                        0.5 * (lo.at.uv_b + hi.at.uv_b)};
  // With both tangents at hand the arc's middle is a closer start than the
  // chord's (a Newton step fewer); finding them just for that costs more.
  const std::optional<HermiteArc> known =
      lo.tangent && hi.tangent ? hermite_arc(lo.at, *lo.tangent, hi.at, *hi.tangent) : std::nullopt;
  // (Near a domain edge the arc can bend out of the domain: the chord cannot.)
  std::optional<PairPoint> arc_middle;
  if (known) arc_middle = known->at(0.5);
  const bool from_arc = arc_middle && in_domains(*arc_middle);
  const double length = (hi.at.point - lo.at.point).norm();
  const std::optional<RefinedPair> r =
      refine_near(pair_, from_arc ? *arc_middle : chord, true, length + tolerance_);
  if (!r) return false;
  if ((r->point - chord.point).norm() <= tolerance_) return true;
  Node mid{{r->point, r->uv_a, r->uv_b}, r->tangent};
  const std::optional<HermiteArc> arc =
      known ? known : hermite_arc(lo.at, tangent(lo), hi.at, tangent(hi));
  if (arc && arc->distance_near_middle(r->point) <= tolerance_ / 8) {
    // A chord over ds of the arc strays at most max|P''| ds^2 / 8 from it.
    const double pieces = std::ceil(std::sqrt(arc->max_second_derivative() / (4 * tolerance_)));
    if (pieces <= kMaxPieces) {
      // From the arc's middle, the curve point found is the arc's middle
      // point refined: an even count keeps it.
      const int count = from_arc ? 2 * std::max(1, static_cast<int>(pieces + 1) / 2)
                                 : std::max(2, static_cast<int>(pieces));
      if (fill_along(*arc, from_arc ? &mid : nullptr, count)) return true;
    }
  }
  const bool first = fill(lo, mid, depth + 1);
  push(mid.at);
  return fill(mid, hi, depth + 1) && first;
}

/// The arc's points at s = k / pieces strictly inside it, each refined onto
/// the curve from the arc (the middle one is `mid` when given), pushed in
/// order; false, pushing nothing, when one starts outside a domain, lands
/// farther than an eighth of the tolerance from the arc (the arc is not as
/// good there as at its middle) or the points do not advance along the chord.
bool CurveDensifier::fill_along(const HermiteArc& arc, const Node* mid, int pieces) {
  const Eigen::Vector3d chord = arc.hi.point - arc.lo.point;
  // Pushed straight onto the output (no buffer to allocate) and taken back
  // when the arc fails.
  const std::size_t kept = out_.points.size();
  const auto fail = [&] {
    out_.points.resize(kept);
    out_.uv_a.resize(kept);
    out_.uv_b.resize(kept);
    return false;
  };
  Eigen::Vector3d previous = arc.lo.point;
  for (int k = 1; k < pieces; ++k) {
    PairPoint p;
    if (mid && 2 * k == pieces) {
      p = mid->at;
    } else {
      const PairPoint start = arc.at(static_cast<double>(k) / pieces);
      if (!in_domains(start)) return fail();
      const std::optional<RefinedPair> r = refine_near(pair_, start, true, tolerance_ / 8);
      if (!r) return fail();
      p = {r->point, r->uv_a, r->uv_b};
    }
    if (!((p.point - previous).dot(chord) > 0.0)) return fail();
    previous = p.point;
    push(p);
  }
  if (!((arc.hi.point - previous).dot(chord) > 0.0)) return fail();
  return true;
}

bool CurveDensifier::in_domains(const PairPoint& p) const {
  const auto inside = [](const BSplineSurface& s, const Eigen::Vector2d& uv) {
    return uv[0] >= s.domain_start(Direction::u) && uv[0] <= s.domain_end(Direction::u) &&
           uv[1] >= s.domain_start(Direction::v) && uv[1] <= s.domain_end(Direction::v);
  };
  return inside(pair_.a(), p.uv_a) && inside(pair_.b(), p.uv_b);
}

}  // namespace argil
