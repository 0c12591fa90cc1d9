#include "support/test_plates.hpp"

namespace argil::test {

Eigen::VectorXd piece_knots(int degree, int pieces, int join) {
  Eigen::VectorXd k(2 * (degree + 1) + (pieces - 1) * join);
  Eigen::Index at = 0;
  for (int c = 0; c <= degree; ++c) k[at++] = 0.0;
  for (int piece = 1; piece < pieces; ++piece)
    for (int c = 0; c < join; ++c) k[at++] = static_cast<double>(piece) / pieces;
  for (int c = 0; c <= degree; ++c) k[at++] = 1.0;
  return k;
}

BSplineSurface flat_plate(const PlateShape& shape) {
  BSplineSurface s;
  s.degree = {1, shape.degree_v};
  s.knots = {piece_knots(1, shape.spans_u, 1),
             piece_knots(shape.degree_v, shape.pieces_v, shape.join_v)};
  const Eigen::VectorXd gu = greville_abscissae(1, s.knots[0]);
  const Eigen::VectorXd gv = greville_abscissae(shape.degree_v, s.knots[1]);
  s.control_points.resize(gu.size() * gv.size(), 3);
  for (Eigen::Index i = 0; i < gu.size(); ++i)
    for (Eigen::Index j = 0; j < gv.size(); ++j)
      s.control_points.row(s.pole_index(static_cast<int>(i), static_cast<int>(j)))
          << shape.width * gu[i],
          shape.height * gv[j], 0.0;
  return s;
}

BSplineSurface flat_bicubic_panel(double size, int spans) {
  BSplineSurface s;
  s.degree = {3, 3};
  s.knots = {piece_knots(3, spans, 1), piece_knots(3, spans, 1)};
  const Eigen::VectorXd g = greville_abscissae(3, s.knots[0]);
  s.control_points.resize(g.size() * g.size(), 3);
  for (Eigen::Index i = 0; i < g.size(); ++i)
    for (Eigen::Index j = 0; j < g.size(); ++j)
      s.control_points.row(s.pole_index(static_cast<int>(i), static_cast<int>(j))) << size * g[i],
          size * g[j], 0.0;
  return s;
}

}  // namespace argil::test
