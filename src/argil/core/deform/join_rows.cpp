#include "argil/core/deform/join_rows.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>

#include <Eigen/Geometry>

namespace argil {

namespace {

/// Entry (i, j) of a symmetric band matrix from its lower half; zero outside the band.
double entry(const SymmetricBandMatrix& a, int i, int j) {
  if (i < j) std::swap(i, j);
  return i - j <= a.bandwidth() ? a.at(i, j) : 0.0;
}

double& lower(SymmetricBandMatrix& a, int i, int j) {
  if (i < j) std::swap(i, j);
  assert(i - j <= a.bandwidth());
  return a.at(i, j);
}

}  // namespace

std::vector<JoinRow> join_rows(const BSplineSurface& rest, const std::vector<char>& held) {
  std::vector<JoinRow> rows;
  const int nu = rest.count(Direction::u), nv = rest.count(Direction::v);
  for (int d = 0; d < 2; ++d) {
    const int p = rest.degree[static_cast<std::size_t>(d)];
    if (p < 2) continue;
    const Eigen::VectorXd& t = rest.knots[static_cast<std::size_t>(d)];
    const int count = d == 0 ? nu : nv, across = d == 0 ? nv : nu;
    for (int line = p + 1; line < count;) {
      int m = 1;
      while (line + m < count && t[line + m] == t[line]) ++m;
      if (m == p) {  // a C0 join: pole line - 1 lies on it
        for (int e = 0; e < across; ++e) {
          const auto pole = [&](int i) {
            return static_cast<int>(d == 0 ? rest.pole_index(i, e) : rest.pole_index(e, i));
          };
          JoinRow r{.before = pole(line - 2), .on = pole(line - 1), .after = pole(line)};
          r.direction = d;
          const Eigen::Vector3d in =
              (rest.control_points.row(r.on) - rest.control_points.row(r.before)).transpose();
          const Eigen::Vector3d out =
              (rest.control_points.row(r.after) - rest.control_points.row(r.on)).transpose();
          const auto is_held = [&](int i) { return held[static_cast<std::size_t>(i)] != 0; };
          if (!(in.norm() > 0.0 && out.norm() > 0.0) || is_held(r.before) || is_held(r.on) ||
              is_held(r.after))
            continue;
          r.ratio = out.norm() / in.norm();
          r.tied = std::atan2(in.cross(out).norm(), in.dot(out)) < kG1JoinAngle;
          rows.push_back(r);
        }
      }
      line += m;
    }
  }
  // Ties apply one by one only where no tied row's `on` pole belongs to
  // another tied row: where a u and a v line cross (or a line lies next to
  // another), those rows stay on the joint term.
  std::vector<int> as_on(static_cast<std::size_t>(nu) * static_cast<std::size_t>(nv), 0);
  std::vector<int> as_side(as_on.size(), 0);
  for (const JoinRow& r : rows) {
    if (!r.tied) continue;
    ++as_on[static_cast<std::size_t>(r.on)];
    ++as_side[static_cast<std::size_t>(r.before)];
    ++as_side[static_cast<std::size_t>(r.after)];
  }
  for (JoinRow& r : rows) {
    const auto on = [&](int i) { return as_on[static_cast<std::size_t>(i)]; };
    if (r.tied && (on(r.on) > 1 || as_side[static_cast<std::size_t>(r.on)] > 0 ||
                   on(r.before) > 0 || on(r.after) > 0))
      r.tied = false;
  }
  return rows;
}

void tie_matrix(SymmetricBandMatrix& a, const std::vector<JoinRow>& rows,
                const std::vector<int>& rank) {
  // T = I + e_o (w - e_o)^T with w = lambda e_b + (1 - lambda) e_a:
  // T^T A T = A + (w - e_o) c^T + c (w - e_o)^T + c_o (w - e_o)(w - e_o)^T,
  // c = A e_o. No tied row's `on` is another's neighbour, so rows apply one
  // by one. Both unknowns of a coupling may have moved onto a neighbour along
  // the same direction, from either side: the band reaches 2 poles further.
  const int n = a.size(), band = a.bandwidth();
  std::vector<std::pair<int, double>> column;
  for (const JoinRow& r : rows) {
    if (!r.tied) continue;
    const int o = rank[static_cast<std::size_t>(r.on)];
    const int b = rank[static_cast<std::size_t>(r.before)];
    const int f = rank[static_cast<std::size_t>(r.after)];
    const double lb = r.lambda(), lf = 1.0 - lb;
    column.clear();
    // Only the couplings: the band's zeros beyond them may lie outside the
    // band of o's neighbours.
    for (int k = std::max(0, o - band); k <= std::min(n - 1, o + band); ++k)
      if (const double c = entry(a, k, o); k != o && c != 0.0) column.emplace_back(k, c);
    const double c_oo = entry(a, o, o);
    double c_b = 0.0, c_f = 0.0;
    for (const auto& [k, c] : column) {
      if (k == b) c_b = c;
      if (k == f) c_f = c;
    }
    // Rows and columns b and f gain lambda c (outside the 3 x 3 block of b, o, f).
    for (const auto& [k, c] : column) {
      if (k == b || k == f) continue;
      lower(a, b, k) += lb * c;
      lower(a, f, k) += lf * c;
    }
    lower(a, b, b) += 2.0 * lb * c_b + lb * lb * c_oo;
    lower(a, f, f) += 2.0 * lf * c_f + lf * lf * c_oo;
    lower(a, b, f) += lb * c_f + lf * c_b + lb * lf * c_oo;
    for (const auto& [k, c] : column) lower(a, o, k) = 0.0;
    lower(a, o, o) = 1.0;
  }
}

void tie_load(RowMajorMatrix& b, const std::vector<JoinRow>& rows, const std::vector<int>& rank) {
  for (const JoinRow& r : rows) {
    if (!r.tied) continue;
    const int o = rank[static_cast<std::size_t>(r.on)];
    b.row(rank[static_cast<std::size_t>(r.before)]) += r.lambda() * b.row(o);
    b.row(rank[static_cast<std::size_t>(r.after)]) += (1.0 - r.lambda()) * b.row(o);
    b.row(o).setZero();
  }
}

void untie_solution(RowMajorMatrix& x, const std::vector<JoinRow>& rows,
                    const std::vector<int>& rank) {
  for (const JoinRow& r : rows) {
    if (!r.tied) continue;
    x.row(rank[static_cast<std::size_t>(r.on)]) =
        r.lambda() * x.row(rank[static_cast<std::size_t>(r.before)]) +
        (1.0 - r.lambda()) * x.row(rank[static_cast<std::size_t>(r.after)]);
  }
}

std::array<int, 2> tie_reach(const std::vector<JoinRow>& rows) {
  std::array<int, 2> reach{0, 0};
  for (const JoinRow& r : rows)
    if (r.tied) reach[static_cast<std::size_t>(r.direction)] = 2;
  return reach;
}

}  // namespace argil
