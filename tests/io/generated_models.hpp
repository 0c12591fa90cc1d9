#pragma once
// Models for the round-trip tests: many generated surfaces, and a trimmed face
// with an outer loop of lines and a hole of rational arcs.

#include <algorithm>
#include <cmath>
#include <random>
#include <string>

#include "argil/io/model/model.hpp"
#include "support/random_surface.hpp"

namespace argil::test {

// 50 surfaces over degrees 1..9 in both directions, every other one rational,
// with repeated interior knots.
inline io::Model generated_model() {
  std::mt19937_64 rng(20240611);
  io::Model model;
  for (int k = 0; k < 50; ++k) {
    RandomSurfaceOptions options;
    options.min_degree = 1;
    options.max_degree = 9;
    options.rational = k % 2 == 1;
    options.repeated_knots = true;
    io::FaceRecord face;
    face.surface = random_surface(rng, options);
    face.source_id = "generated " + std::to_string(k);
    model.faces.push_back(std::move(face));
  }
  return model;
}

inline io::TrimCurve line(Eigen::Vector2d a, Eigen::Vector2d b) {
  io::TrimCurve c;
  c.degree = 1;
  c.knots = Eigen::Vector4d(0.0, 0.0, 1.0, 1.0);
  c.points.resize(2, 2);
  c.points.row(0) = a;
  c.points.row(1) = b;
  return c;
}

// A full circle as four rational quadratic arcs, clockwise when `clockwise`.
inline io::TrimLoop circle(Eigen::Vector2d centre, Eigen::Vector2d radii, bool clockwise) {
  io::TrimLoop loop;
  loop.outer = !clockwise;
  const double w = std::sqrt(0.5);
  for (int q = 0; q < 4; ++q) {
    const double a0 = q * M_PI / 2, a1 = (q + 1) * M_PI / 2;
    const auto at = [&](double a, double scale) {
      return Eigen::Vector2d(centre.x() + scale * radii.x() * std::cos(a),
                             centre.y() + scale * radii.y() * std::sin(a));
    };
    io::TrimCurve c;
    c.degree = 2;
    c.knots.resize(6);
    c.knots << 0, 0, 0, 1, 1, 1;
    c.points.resize(3, 2);
    c.points.row(0) = at(a0, 1.0);
    c.points.row(1) = at(0.5 * (a0 + a1), 1.0 / w);
    c.points.row(2) = at(a1, 1.0);
    c.weights = Eigen::Vector3d(1.0, w, 1.0);
    loop.curves.push_back(c);
  }
  if (clockwise) {
    std::reverse(loop.curves.begin(), loop.curves.end());
    for (io::TrimCurve& c : loop.curves) c.points = c.points.colwise().reverse().eval();
  }
  return loop;
}

// The asymmetric test surface (docs/conventions.md), trimmed by an inset rectangle with a round
// hole.
inline io::FaceRecord trimmed_face() {
  io::FaceRecord face;
  face.surface = asymmetric_surface(true);
  const BSplineSurface& s = face.surface;
  const Eigen::Vector2d lo(s.domain_start(Direction::u), s.domain_start(Direction::v));
  const Eigen::Vector2d hi(s.domain_end(Direction::u), s.domain_end(Direction::v));
  const Eigen::Vector2d size = hi - lo;
  const Eigen::Vector2d a = lo + 0.1 * size, c = lo + 0.9 * size;
  const Eigen::Vector2d b(c.x(), a.y()), d(a.x(), c.y());
  io::TrimLoop outer;
  outer.curves = {line(a, b), line(b, c), line(c, d), line(d, a)};
  face.loops.push_back(outer);
  face.loops.push_back(circle(lo + 0.5 * size, 0.15 * size, true));
  face.name = "asymmetric, trimmed";
  face.source_id = "test";
  return face;
}

}  // namespace argil::test
