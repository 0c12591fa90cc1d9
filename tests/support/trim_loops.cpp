#include "support/trim_loops.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "argil/core/geometry/param_rect.hpp"

namespace argil::test {

namespace {

/// Row k of a curve's points (element-wise: GCC 12 misreads row assignment
/// from a 2-vector temporary as an overread).
void set_point(BSplineCurve& c, Eigen::Index k, const Eigen::Vector2d& p) {
  c.points(k, 0) = p.x();
  c.points(k, 1) = p.y();
}

Eigen::Vector2d point(const BSplineCurve& c, Eigen::Index k) {
  return {c.points(k, 0), c.points(k, 1)};
}

}  // namespace

BSplineCurve trim_line(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  BSplineCurve c;
  c.degree = 1;
  c.knots = Eigen::Vector4d(0, 0, 1, 1);
  c.points.resize(2, 2);
  set_point(c, 0, a);
  set_point(c, 1, b);
  return c;
}

BSplineCurve trim_arc(const Eigen::Vector2d& centre, double rx, double ry, double a0, double a1) {
  const double half = 0.5 * (a1 - a0);
  const double w = std::cos(half);
  const auto at = [&](double a, double scale) {
    return Eigen::Vector2d(centre.x() + scale * rx * std::cos(a),
                           centre.y() + scale * ry * std::sin(a));
  };
  BSplineCurve c;
  c.degree = 2;
  c.knots.resize(6);
  c.knots << 0, 0, 0, 1, 1, 1;
  c.points.resize(3, 2);
  set_point(c, 0, at(a0, 1.0));
  set_point(c, 1, at(a0 + half, 1.0 / w));
  set_point(c, 2, at(a1, 1.0));
  c.weights = Eigen::Vector3d(1.0, w, 1.0);
  return c;
}

namespace {

void reverse_curve(BSplineCurve& c) {
  const double a = c.knots[0], b = c.knots[c.knots.size() - 1];
  c.knots = (a + b - c.knots.reverse().array()).matrix().eval();  // eval(): aliasing
  c.points = c.points.colwise().reverse().eval();
  if (c.is_rational()) c.weights = c.weights.reverse().eval();
}

TrimLoop oriented(TrimLoop loop, bool outer) {
  loop.outer = outer;
  if (!outer) {
    std::reverse(loop.curves.begin(), loop.curves.end());
    for (BSplineCurve& c : loop.curves) reverse_curve(c);
  }
  return loop;
}

}  // namespace

TrimLoop ellipse_loop(const Eigen::Vector2d& centre, double rx, double ry, bool outer) {
  TrimLoop loop;
  const double q = 0.5 * std::numbers::pi;
  for (int k = 0; k < 4; ++k) loop.curves.push_back(trim_arc(centre, rx, ry, k * q, (k + 1) * q));
  // The arcs meet where the previous one ends, bit for bit.
  for (std::size_t k = 0; k < 4; ++k)
    set_point(loop.curves[k], 2, point(loop.curves[(k + 1) % 4], 0));
  return oriented(loop, outer);
}

TrimLoop rectangle_loop(const Eigen::Vector2d& lo, const Eigen::Vector2d& hi, bool outer) {
  const Eigen::Vector2d b(hi.x(), lo.y()), d(lo.x(), hi.y());
  TrimLoop loop;
  loop.curves = {trim_line(lo, b), trim_line(b, hi), trim_line(hi, d), trim_line(d, lo)};
  return oriented(loop, outer);
}

std::vector<TrimLoop> asymmetric_trims(const ParamRect& domain) {
  const auto at = [&](double s, double t) {
    return Eigen::Vector2d(domain.u0 + s * domain.width(), domain.v0 + t * domain.height());
  };
  TrimLoop outer;
  // Bottom: a wavy cubic, non-uniform knots with a double knot, left to right.
  BSplineCurve bottom;
  bottom.degree = 3;
  bottom.knots.resize(11);
  bottom.knots << 0, 0, 0, 0, 0.2, 0.45, 0.45, 1, 1, 1, 1;
  bottom.points.resize(7, 2);
  const double wave[7] = {0.0, 0.06, -0.02, 0.08, 0.01, 0.07, 0.0};
  for (int i = 0; i < 7; ++i) set_point(bottom, i, at(0.08 + 0.8 * i / 6.0, 0.1 + wave[i]));
  outer.curves.push_back(bottom);
  // Right: an exact elliptic arc bulging out, from the bottom's end upwards.
  const Eigen::Vector2d b_end = point(bottom, 6);
  const Eigen::Vector2d r_end = at(0.88, 0.85);
  const Eigen::Vector2d centre(b_end.x(), 0.5 * (b_end.y() + r_end.y()));
  const double ry = 0.5 * (r_end.y() - b_end.y());
  outer.curves.push_back(trim_arc(centre, 0.07 * domain.width(), ry, -0.5 * std::numbers::pi, 0.0));
  outer.curves.push_back(trim_arc(centre, 0.07 * domain.width(), ry, 0.0, 0.5 * std::numbers::pi));
  set_point(outer.curves[1], 0, b_end);
  set_point(outer.curves[2], 0, point(outer.curves[1], 2));
  // Top: a line to the left, starting a hair (1e-5 of the domain) further
  // left than the arc's end: a gap the region closes with a segment.
  const Eigen::Vector2d top_start =
      point(outer.curves[2], 2) - Eigen::Vector2d(1e-5 * domain.width(), 0.0);
  const Eigen::Vector2d top_end = at(0.12, 0.92);
  outer.curves.push_back(trim_line(top_start, top_end));
  // Left: a wavy rational quartic back down to the bottom's start.
  BSplineCurve left;
  left.degree = 4;
  left.knots.resize(11);
  left.knots << 0, 0, 0, 0, 0, 0.6, 1, 1, 1, 1, 1;
  left.points.resize(6, 2);
  const Eigen::Vector2d l_end = point(bottom, 0);
  const double sway[6] = {0.0, -0.05, 0.03, -0.04, 0.02, 0.0};
  for (int i = 0; i < 6; ++i) {
    const double s = i / 5.0;
    set_point(left, i,
              (1 - s) * top_end + s * l_end + Eigen::Vector2d(sway[i] * domain.width(), 0.0));
  }
  left.weights.resize(6);
  left.weights << 1.0, 0.7, 1.6, 0.9, 1.3, 1.0;
  outer.curves.push_back(left);
  std::vector<TrimLoop> loops{outer};
  loops.push_back(
      ellipse_loop(at(0.35, 0.45), 0.12 * domain.width(), 0.09 * domain.height(), false));
  loops.push_back(rectangle_loop(at(0.6, 0.5), at(0.72, 0.7), false));
  return loops;
}

std::vector<Eigen::Vector2d> dense_polygon(const TrimLoop& loop, int per_curve) {
  std::vector<Eigen::Vector2d> polygon;
  for (const BSplineCurve& c : loop.curves) {
    for (int k = 0; k < per_curve; ++k) {
      const double t = c.domain_start() +
                       (c.domain_end() - c.domain_start()) * k / static_cast<double>(per_curve);
      polygon.push_back(evaluate(c, t));
    }
    polygon.push_back(evaluate(c, c.domain_end()));
  }
  return polygon;
}

bool inside_polygons(const std::vector<std::vector<Eigen::Vector2d>>& polygons,
                     const Eigen::Vector2d& uv) {
  bool inside = false;
  for (const auto& polygon : polygons) {
    for (std::size_t i = 0, j = polygon.size() - 1; i < polygon.size(); j = i++) {
      const Eigen::Vector2d& a = polygon[i];
      const Eigen::Vector2d& b = polygon[j];
      if ((a.y() > uv.y()) != (b.y() > uv.y())) {
        const double x = a.x() + (uv.y() - a.y()) * (b.x() - a.x()) / (b.y() - a.y());
        if (uv.x() < x) inside = !inside;
      }
    }
  }
  return inside;
}

double polygon_distance(const std::vector<std::vector<Eigen::Vector2d>>& polygons,
                        const Eigen::Vector2d& uv) {
  double best = std::numeric_limits<double>::infinity();
  for (const auto& polygon : polygons) {
    for (std::size_t i = 0, j = polygon.size() - 1; i < polygon.size(); j = i++) {
      const Eigen::Vector2d ab = polygon[i] - polygon[j];
      const double s =
          std::clamp((uv - polygon[j]).dot(ab) / std::max(ab.squaredNorm(), 1e-300), 0.0, 1.0);
      best = std::min(best, (uv - (polygon[j] + s * ab)).norm());
    }
  }
  return best;
}

BSplineSurface asymmetric_plate(double size, double height) {
  BSplineSurface s;
  s.degree = {3, 2};
  s.knots[0].resize(11);
  s.knots[0] << 0, 0, 0, 0, 0.3, 0.3, 0.75, 1, 1, 1, 1;
  s.knots[1].resize(8);
  s.knots[1] << 0, 0, 0, 0.1, 0.65, 1, 1, 1;
  const Eigen::VectorXd gu = greville_abscissae(3, s.knots[0]);
  const Eigen::VectorXd gv = greville_abscissae(2, s.knots[1]);
  s.control_points.resize(7 * 5, 3);
  for (int i = 0; i < 7; ++i)
    for (int j = 0; j < 5; ++j)
      s.control_points.row(s.pole_index(i, j)) << size * gu[i], size * gv[j], height;
  return s;
}

}  // namespace argil::test
