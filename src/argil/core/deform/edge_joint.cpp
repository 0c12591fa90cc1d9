#include "argil/core/deform/edge_joint.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <utility>

#include "argil/core/geometry/basis.hpp"
#include "argil/core/geometry/evaluate.hpp"
#include "argil/core/linalg/psd_pseudo_inverse.hpp"

namespace argil {
namespace {

/// The displacement field's basis at one point: R_i and its u and v
/// derivatives for every pole non-zero there (rational faces: fixed weights).
struct BasisRow {
  std::vector<Eigen::Index> poles;
  std::vector<double> value, du, dv;
};

Eigen::Vector2d clamped(const BSplineSurface& s, const Eigen::Vector2d& uv) {
  return {std::clamp(uv.x(), s.domain_start(Direction::u), s.domain_end(Direction::u)),
          std::clamp(uv.y(), s.domain_start(Direction::v), s.domain_end(Direction::v))};
}

BasisRow basis_row(const BSplineSurface& s, const Eigen::Vector2d& at) {
  const Eigen::Vector2d uv = clamped(s, at);
  const int p = s.degree[0], q = s.degree[1];
  const int su = find_span(p, s.knots[0], s.count(Direction::u), uv.x());
  const int sv = find_span(q, s.knots[1], s.count(Direction::v), uv.y());
  const Eigen::MatrixXd nu = basis_derivatives(p, s.knots[0], su, uv.x(), 1);
  const Eigen::MatrixXd nv = basis_derivatives(q, s.knots[1], sv, uv.y(), 1);
  BasisRow row;
  for (int a = 0; a <= p; ++a)
    for (int b = 0; b <= q; ++b) {
      const Eigen::Index pole = s.pole_index(su - p + a, sv - q + b);
      const double w = s.is_rational() ? s.weights[pole] : 1.0;
      row.poles.push_back(pole);
      row.value.push_back(w * nu(0, a) * nv(0, b));
      row.du.push_back(w * nu(1, a) * nv(0, b));
      row.dv.push_back(w * nu(0, a) * nv(1, b));
    }
  if (s.is_rational()) {
    double w = 0.0, wu = 0.0, wv = 0.0;
    for (std::size_t k = 0; k < row.poles.size(); ++k) {
      w += row.value[k];
      wu += row.du[k];
      wv += row.dv[k];
    }
    for (std::size_t k = 0; k < row.poles.size(); ++k) {
      const double r = row.value[k] / w;
      row.du[k] = (row.du[k] - r * wu) / w;
      row.dv[k] = (row.dv[k] - r * wv) / w;
      row.value[k] = r;
    }
  }
  return row;
}

Eigen::Vector2d curve_uv(const BSplineCurve& c, double t) {
  const Eigen::VectorXd x = evaluate(c, t);
  return {x[0], x[1]};
}

Eigen::Vector3d point_on(const BSplineSurface& s, const Eigen::Vector2d& uv) {
  const Eigen::Vector2d c = clamped(s, uv);
  return evaluate(s, c.x(), c.y());
}

/// How many knot spans of `s` a curve in its (u, v) crosses (a dense walk).
int spans_along(const BSplineSurface& s, const BSplineCurve& c) {
  constexpr int kWalk = 256;
  std::set<std::pair<int, int>> spans;
  for (int k = 0; k <= kWalk; ++k) {
    const double t = c.domain_start() + (c.domain_end() - c.domain_start()) * k / kWalk;
    const Eigen::Vector2d uv = clamped(s, curve_uv(c, t));
    spans.emplace(find_span(s.degree[0], s.knots[0], s.count(Direction::u), uv.x()),
                  find_span(s.degree[1], s.knots[1], s.count(Direction::v), uv.y()));
  }
  return static_cast<int>(spans.size());
}

/// The unit 3D direction `c` in the tangent plane at `uv` as a (u, v)
/// direction w: S_u w_u + S_v w_v = c (least squares).
Eigen::Vector2d parameter_direction(const BSplineSurface& s, const Eigen::Vector2d& uv,
                                    const Eigen::Vector3d& c) {
  const Eigen::Vector2d at = clamped(s, uv);
  const SurfaceDerivatives d = evaluate_derivatives(s, at.x(), at.y(), 1);
  Eigen::Matrix<double, 3, 2> j;
  j << d.du, d.dv;
  return (j.transpose() * j).ldlt().solve(j.transpose() * c);
}

double line_angle(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return std::atan2(a.cross(b).norm(), std::abs(a.dot(b)));
}

}  // namespace

std::vector<EdgeSample> sample_shared_edge(const BSplineSurface& a, const BSplineCurve& pcurve_a,
                                           const BSplineSurface& b, const BSplineCurve& pcurve_b) {
  const int spans = spans_along(a, pcurve_a) + spans_along(b, pcurve_b);
  const int count = std::clamp(3 * spans, 16, 96);
  // b's curve walked densely; each sample starts from the nearest walk point.
  constexpr int kWalk = 512;
  const double b0 = pcurve_b.domain_start(), b1 = pcurve_b.domain_end();
  std::vector<Eigen::Vector3d> walk;
  for (int k = 0; k <= kWalk; ++k)
    walk.push_back(point_on(b, curve_uv(pcurve_b, b0 + (b1 - b0) * k / kWalk)));
  std::vector<EdgeSample> out;
  const double a0 = pcurve_a.domain_start(), a1 = pcurve_a.domain_end();
  for (int k = 0; k < count; ++k) {
    const double ta = k + 1 == count ? a1 : a0 + (a1 - a0) * k / (count - 1);
    EdgeSample s;
    s.uv_a = curve_uv(pcurve_a, ta);
    double tb = k == 0 ? b0 : b1;
    if (k > 0 && k + 1 < count) {
      const Eigen::Vector3d p = point_on(a, s.uv_a);
      int nearest = 0;
      for (int j = 1; j <= kWalk; ++j)
        if ((walk[j] - p).squaredNorm() < (walk[nearest] - p).squaredNorm()) nearest = j;
      // Golden-section search between the walk points either side.
      double lo = b0 + (b1 - b0) * std::max(0, nearest - 1) / kWalk;
      double hi = b0 + (b1 - b0) * std::min(kWalk, nearest + 1) / kWalk;
      const auto distance = [&](double t) {
        return (point_on(b, curve_uv(pcurve_b, t)) - p).squaredNorm();
      };
      const double g = 0.5 * (std::sqrt(5.0) - 1.0);
      for (int it = 0; it < 60 && hi - lo > 1e-15 * (b1 - b0); ++it) {
        const double x1 = hi - g * (hi - lo), x2 = lo + g * (hi - lo);
        if (distance(x1) < distance(x2)) {
          hi = x2;
        } else {
          lo = x1;
        }
      }
      tb = 0.5 * (lo + hi);
    }
    s.uv_b = curve_uv(pcurve_b, tb);
    out.push_back(s);
  }
  return out;
}

Result<EdgeJoint> EdgeJoint::create(const JointFace& a, const JointFace& b,
                                    const std::vector<EdgeSample>& samples, bool seam) {
  if (samples.size() < 2) {
    return Status::error(
        StatusCode::invalid_argument,
        "edge joint: " + std::to_string(samples.size()) + " samples; at least 2 are needed");
  }
  const std::array<const JointFace*, 2> face{&a, &b};
  for (int f = 0; f < 2; ++f) {
    const std::size_t n = static_cast<std::size_t>(face[f]->surface->control_points.rows());
    if (!(face[f]->held.empty() || face[f]->held.size() == n)) {
      return Status::error(StatusCode::invalid_argument,
                           std::string("edge joint: face ") + (f == 0 ? "a" : "b") +
                               ": held flags do not match its " + std::to_string(n) + " poles");
    }
  }
  EdgeJoint j;
  j.seam_ = seam;
  const BSplineSurface& sa = *a.surface;
  const BSplineSurface& sb = *b.surface;
  // The unknowns: every free pole a sample reaches (a seam's two sides share them).
  std::map<std::pair<int, Eigen::Index>, int> unknown;
  const auto column = [&](int side, Eigen::Index pole) -> int {
    const JointFace& f = *face[side];
    if (!f.held.empty() && f.held[static_cast<std::size_t>(pole)]) return -1;
    const std::pair<int, Eigen::Index> key{seam ? 0 : side, pole};
    const auto [it, added] = unknown.emplace(key, static_cast<int>(j.pole_.size()));
    if (added) {
      j.side_.push_back(key.first);
      j.pole_.push_back(pole);
    }
    return it->second;
  };
  const std::size_t count = samples.size();
  std::vector<std::array<BasisRow, 2>> basis(count);
  std::vector<std::array<Eigen::Vector3d, 2>> normal(count);
  std::vector<Eigen::Vector3d> point(count);
  double length = 0.0;
  for (std::size_t k = 0; k < count; ++k) {
    basis[k] = {basis_row(sa, samples[k].uv_a), basis_row(sb, samples[k].uv_b)};
    for (int side = 0; side < 2; ++side)
      for (const Eigen::Index pole : basis[k][static_cast<std::size_t>(side)].poles)
        column(side, pole);
    const Eigen::Vector2d ua = clamped(sa, samples[k].uv_a), ub = clamped(sb, samples[k].uv_b);
    point[k] = evaluate(sa, ua.x(), ua.y());
    normal[k] = {unit_normal(sa, ua.x(), ua.y()), unit_normal(sb, ub.x(), ub.y())};
    j.tangent_.push_back(line_angle(normal[k][0], normal[k][1]) <= kTangentJoinAngle);
    if (k > 0) length += (point[k] - point[k - 1]).norm();
  }
  // Turn rows are scaled by the sample spacing: an angle times a length, like the G0 rows.
  const double spacing = length / static_cast<double>(count - 1);
  // Each face's direction across the edge, c = n x e, in its own tangent plane.
  std::vector<std::array<Eigen::Vector3d, 2>> across(count);
  std::vector<char> turns(count, 0);
  Eigen::Index turn_rows = 0;
  for (std::size_t k = 0; k < count; ++k) {
    const Eigen::Vector3d e = point[std::min(k + 1, count - 1)] - point[k > 0 ? k - 1 : 0];
    bool ok = true;
    for (int side = 0; side < 2; ++side) {
      const Eigen::Vector3d c = normal[k][static_cast<std::size_t>(side)].cross(e);
      ok = ok && c.norm() > 1e-9 * e.norm() && e.norm() > 0.0;
      if (ok) across[k][static_cast<std::size_t>(side)] = c.normalized();
    }
    turns[k] = ok ? 1 : 0;
    turn_rows += ok ? 1 : 0;
    if (!ok) j.tangent_[k] = 0;
    if (j.tangent_[k]) ++j.tangent_count_;
  }
  const Eigen::Index n = static_cast<Eigen::Index>(j.pole_.size());
  const Eigen::Index m = 3 * static_cast<Eigen::Index>(count) + turn_rows;
  j.scalar_.resize(count);
  Eigen::MatrixXd rows = Eigen::MatrixXd::Zero(m, 3 * n);
  Eigen::Index row = 0;
  for (std::size_t k = 0; k < count; ++k) {
    for (int side = 0; side < 2; ++side) {
      const double sign = side == 0 ? 1.0 : -1.0;
      const BasisRow& r = basis[k][static_cast<std::size_t>(side)];
      for (std::size_t t = 0; t < r.poles.size(); ++t) {
        const int c = column(side, r.poles[t]);
        if (c < 0) continue;
        for (int x = 0; x < 3; ++x) rows(row + x, 3 * c + x) += sign * r.value[t];
        j.scalar_[k].value.emplace_back(c, sign * r.value[t]);
      }
    }
    j.scalar_[k].g0_row = row;
    row += 3;
    if (!turns[k]) continue;
    j.scalar_[k].turn_row = row;
    j.scalar_[k].normal = normal[k];
    // Both faces turn alike about the edge: n_a . D_ca d_a = n_b . D_cb d_b
    // (a rigid turn by w gives w on either side, whatever the faces'
    // orientations), so the angle between them is kept: G1 stays G1 and a
    // crease keeps its angle.
    for (int side = 0; side < 2; ++side) {
      const std::size_t f = static_cast<std::size_t>(side);
      const double sign = side == 0 ? 1.0 : -1.0;
      const BSplineSurface& s = side == 0 ? sa : sb;
      const Eigen::Vector2d& uv = side == 0 ? samples[k].uv_a : samples[k].uv_b;
      const Eigen::Vector2d w = parameter_direction(s, uv, across[k][f]);
      const BasisRow& r = basis[k][f];
      for (std::size_t t = 0; t < r.poles.size(); ++t) {
        const int c = column(side, r.poles[t]);
        if (c < 0) continue;
        const double slope = r.du[t] * w.x() + r.dv[t] * w.y();
        for (int x = 0; x < 3; ++x)
          rows(row, 3 * c + x) += sign * spacing * slope * normal[k][f][x];
        j.scalar_[k].turn[f].emplace_back(c, sign * spacing * slope);
      }
    }
    ++row;
  }
  j.rows_ = rows.sparseView();
  j.rest_ = j.gather(sa.control_points, sb.control_points);
  return j;
}

Eigen::VectorXd EdgeJoint::gather(const ControlNet& pa, const ControlNet& pb) const {
  Eigen::VectorXd x(3 * static_cast<Eigen::Index>(pole_.size()));
  for (std::size_t u = 0; u < pole_.size(); ++u) {
    const ControlNet& p = side_[u] == 0 ? pa : pb;
    x.segment<3>(3 * static_cast<Eigen::Index>(u)) = p.row(pole_[u]).transpose();
  }
  return x;
}

std::vector<Eigen::Index> EdgeJoint::loaded_poles(int side) const {
  std::vector<Eigen::Index> out;
  for (std::size_t u = 0; u < pole_.size(); ++u)
    if (side_[u] == side) out.push_back(pole_[u]);
  return out;
}

RowMajorMatrix EdgeJoint::unit_forces(int side) const {
  std::vector<Eigen::Index> row_of(pole_.size(), -1);
  Eigen::Index count = 0;
  for (std::size_t u = 0; u < pole_.size(); ++u)
    if (side_[u] == side) row_of[u] = count++;
  const Eigen::Index n = static_cast<Eigen::Index>(scalar_.size());
  RowMajorMatrix f = RowMajorMatrix::Zero(count, 3 * n);
  for (Eigen::Index k = 0; k < n; ++k) {
    const SampleRows& s = scalar_[static_cast<std::size_t>(k)];
    for (const auto& [u, w] : s.value)
      if (row_of[static_cast<std::size_t>(u)] >= 0) f(row_of[static_cast<std::size_t>(u)], k) += w;
    for (int t = 0; t < 2; ++t)
      for (const auto& [u, w] : s.turn[static_cast<std::size_t>(t)])
        if (row_of[static_cast<std::size_t>(u)] >= 0)
          f(row_of[static_cast<std::size_t>(u)], (1 + t) * n + k) += w;
  }
  return f;
}

Eigen::MatrixXd EdgeJoint::motion_of(const StepResponse& r, const Eigen::VectorXd& lambda) const {
  // Sample k's G0 multipliers move coordinate c by its scalar response; its
  // turn multiplier pushes along each face's normal.
  // The loads per coordinate, one row each, matching the response's columns:
  // [G0 | turn along n_a | turn along n_b].
  const Eigen::Index n = static_cast<Eigen::Index>(scalar_.size());
  RowMajorMatrix loads = RowMajorMatrix::Zero(3, 3 * n);
  for (Eigen::Index k = 0; k < n; ++k) {
    const SampleRows& s = scalar_[static_cast<std::size_t>(k)];
    loads.col(k) = lambda.segment<3>(s.g0_row);
    if (s.turn_row < 0) continue;
    loads.col(n + k) = lambda[s.turn_row] * s.normal[0];
    loads.col(2 * n + k) = lambda[s.turn_row] * s.normal[1];
  }
  // Row by row, three dot products: one pass over the response. A matrix
  // product with three columns would first copy (pack) the whole response.
  Eigen::MatrixXd out(r.motion.rows(), 3);
  for (Eigen::Index p = 0; p < r.motion.rows(); ++p) {
    for (Eigen::Index c = 0; c < 3; ++c) out(p, c) = r.motion.row(p).dot(loads.row(c));
  }
  return out;
}

void EdgeJoint::set_response(const StepResponse& a, const StepResponse& b, double dt) {
  response_ = {a, b};
  const Eigen::Index m = rows_.rows();
  // D: each unknown's motion per unit multiplier; G = A D (symmetric: A h^2 S^-1 A^T).
  Eigen::MatrixXd motion = Eigen::MatrixXd::Zero(rows_.cols(), m);
  const Eigen::Index n = static_cast<Eigen::Index>(scalar_.size());
  for (int side = 0; side < 2; ++side) {
    const StepResponse& r = response_[static_cast<std::size_t>(side)];
    if (r.poles.empty()) continue;
    std::map<Eigen::Index, Eigen::Index> row_of;
    for (std::size_t k = 0; k < r.poles.size(); ++k)
      row_of[r.poles[k]] = static_cast<Eigen::Index>(k);
    for (std::size_t u = 0; u < pole_.size(); ++u) {
      if (side_[u] != side) continue;
      const auto it = row_of.find(pole_[u]);
      if (it == row_of.end()) continue;
      const Eigen::Index p = it->second, x = 3 * static_cast<Eigen::Index>(u);
      for (Eigen::Index k = 0; k < n; ++k) {
        const SampleRows& s = scalar_[static_cast<std::size_t>(k)];
        for (Eigen::Index c = 0; c < 3; ++c) motion(x + c, s.g0_row + c) = r.motion(p, k);
        if (s.turn_row >= 0) {
          motion.block<3, 1>(x, s.turn_row) =
              r.motion(p, n + k) * s.normal[0] + r.motion(p, 2 * n + k) * s.normal[1];
        }
      }
    }
  }
  Eigen::MatrixXd g = rows_ * motion;
  g = 0.5 * (g + g.transpose()).eval();
  // Eigenpairs below 1e-10 of the largest are directions the conditions do
  // not fix independently (rounding): they get no multiplier.
  inverse_factor_ = psd_pseudo_inverse_factor(g, 1e-10);
  response_dt_ = dt;
}

Eigen::VectorXd EdgeJoint::pseudo_solve(const Eigen::VectorXd& b) const {
  return inverse_factor_ * (inverse_factor_.transpose() * b);
}

EdgeJoint::Correction EdgeJoint::correction(const ControlNet& pa, const ControlNet& pb,
                                            double slack) const {
  Correction out;
  const Eigen::VectorXd residual = rows_ * (gather(pa, pb) - rest_);
  out.residual = residual.size() > 0 ? residual.cwiseAbs().maxCoeff() : 0.0;
  if (!(out.residual > slack) || !ready()) return out;
  const Eigen::VectorXd lambda = -pseudo_solve(residual);
  const Eigen::VectorXd force = rows_.transpose() * lambda;
  for (int side = 0; side < 2; ++side) {
    PoleCorrection& c = side == 0 ? out.a : out.b;
    const StepResponse& r = response_[static_cast<std::size_t>(side)];
    if (r.poles.empty()) continue;
    const Eigen::MatrixXd d = motion_of(r, lambda);
    std::vector<Eigen::RowVector3d> moves;
    for (std::size_t k = 0; k < r.poles.size(); ++k) {
      // A pole moved by nothing is left alone (its hierarchy is not refreshed).
      if (!(d.row(static_cast<Eigen::Index>(k)).norm() >= 1e-2 * slack)) continue;
      c.poles.push_back(r.poles[k]);
      moves.push_back(d.row(static_cast<Eigen::Index>(k)));
    }
    c.points.resize(static_cast<Eigen::Index>(moves.size()), 3);
    for (std::size_t k = 0; k < moves.size(); ++k)
      c.points.row(static_cast<Eigen::Index>(k)) = moves[k];
    c.velocities = c.points / response_dt_;
    std::vector<Eigen::RowVector3d> pushes;
    for (std::size_t u = 0; u < pole_.size(); ++u) {
      if (side_[u] != side) continue;
      c.loaded.push_back(pole_[u]);
      pushes.push_back(force.segment<3>(3 * static_cast<Eigen::Index>(u)).transpose());
    }
    c.forces.resize(static_cast<Eigen::Index>(pushes.size()), 3);
    for (std::size_t k = 0; k < pushes.size(); ++k)
      c.forces.row(static_cast<Eigen::Index>(k)) = pushes[k];
  }
  return out;
}

}  // namespace argil
