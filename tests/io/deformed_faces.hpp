#pragma once
// Faces deformed the way a runaway sculpt leaves them: every control point,
// interior and boundary, moved by a few percent of the face's size, while the
// trims stay where they were in (u, v).

#include <cstdint>
#include <random>
#include <vector>

#include "argil/io/model/model.hpp"

namespace argil::test {

/// `face` with every control point moved by a random vector whose coordinates are
/// uniform in [-fraction, fraction] times the diagonal of the face's control-point
/// box. Knots, weights, trims and orientation are kept; the same seed gives the
/// same net.
inline io::FaceRecord deformed(const io::FaceRecord& face, double fraction, std::uint64_t seed) {
  io::FaceRecord out = face;
  const double size = control_point_box(face.surface).diagonal();
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> offset(-fraction * size, fraction * size);
  for (Eigen::Index k = 0; k < out.surface.control_points.rows(); ++k) {
    for (Eigen::Index c = 0; c < 3; ++c) out.surface.control_points(k, c) += offset(rng);
  }
  return out;
}

/// `face` with its first row of control points (the side u = u_min) pulled
/// together to within `fraction` of the face's size of one point, the way a
/// cone's apex comes out of a deformation that moved its coincident poles
/// slightly apart; random offsets per coordinate as in deformed().
inline io::FaceRecord side_collapsed(const io::FaceRecord& face, double fraction,
                                     std::uint64_t seed) {
  io::FaceRecord out = face;
  BSplineSurface& s = out.surface;
  const double size = control_point_box(face.surface).diagonal();
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> offset(-fraction * size, fraction * size);
  const Eigen::RowVector3d apex = s.control_points.row(s.pole_index(0, 0));
  for (int j = 0; j < s.count(Direction::v); ++j) {
    for (Eigen::Index c = 0; c < 3; ++c) {
      s.control_points(s.pole_index(0, j), c) = apex[c] + offset(rng);
    }
  }
  return out;
}

/// `face` with the poles of every side that collapses to one point (a cone's
/// apex: all its poles equal) moved apart by random offsets, each coordinate
/// uniform in [-fraction, fraction] times the face's size: what a deformation
/// that moves coincident poles slightly differently leaves. Faces without such a
/// side are returned as they are.
inline io::FaceRecord apex_split(const io::FaceRecord& face, double fraction, std::uint64_t seed) {
  io::FaceRecord out = face;
  BSplineSurface& s = out.surface;
  const int nu = s.count(Direction::u), nv = s.count(Direction::v);
  const double size = control_point_box(face.surface).diagonal();
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> offset(-fraction * size, fraction * size);
  const auto split = [&](std::vector<Eigen::Index> rows) {
    for (const Eigen::Index row : rows) {
      if (face.surface.control_points.row(row) != face.surface.control_points.row(rows[0])) return;
    }
    for (const Eigen::Index row : rows) {
      for (Eigen::Index c = 0; c < 3; ++c) s.control_points(row, c) += offset(rng);
    }
  };
  std::vector<Eigen::Index> u0, u1, v0, v1;
  for (int j = 0; j < nv; ++j) {
    u0.push_back(s.pole_index(0, j));
    u1.push_back(s.pole_index(nu - 1, j));
  }
  for (int i = 0; i < nu; ++i) {
    v0.push_back(s.pole_index(i, 0));
    v1.push_back(s.pole_index(i, nv - 1));
  }
  for (const auto& side : {u0, u1, v0, v1}) split(side);
  return out;
}

/// Every face of `model` deformed (face f with seed `seed + f`).
inline io::Model deformed(const io::Model& model, double fraction, std::uint64_t seed) {
  io::Model out = model;
  for (std::size_t f = 0; f < out.faces.size(); ++f) {
    out.faces[f] = deformed(model.faces[f], fraction, seed + f);
  }
  return out;
}

}  // namespace argil::test
