#include "argil/core/deform/deformable_body.hpp"

#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>
#include <string>
#include <utility>

#include "argil/core/base/number_text.hpp"
#include "argil/core/deform/contact_response.hpp"
#include "argil/core/operators/surface_operators.hpp"

namespace argil {

namespace {

/// Which control points the boundary conditions hold (one flag per pole).
std::vector<char> held_poles(int nu, int nv, const BoundaryConditions& c) {
  std::vector<char> fixed(static_cast<std::size_t>(nu) * static_cast<std::size_t>(nv), 0);
  for (int i = 0; i < nu; ++i) {
    for (int j = 0; j < nv; ++j) {
      const bool corner = (i == 0 || i == nu - 1) && (j == 0 || j == nv - 1);
      const bool held = (c.fixed_u0 && i == 0) || (c.fixed_u1 && i == nu - 1) ||
                        (c.fixed_v0 && j == 0) || (c.fixed_v1 && j == nv - 1) ||
                        (c.fixed_corners && corner);
      fixed[static_cast<std::size_t>(i * nv + j)] = held ? 1 : 0;
    }
  }
  return fixed;
}

}  // namespace

void DeformableBody::plastic_flow(const ControlNet& points) {
  // The surface yields where it stretched past the yield: measured over each
  // control point's cell around its Greville point (3 x 3 samples, each a
  // positive average of the poles' stretches: nothing inverted), so the flow
  // follows the surface wherever the tool is, not the net's spacing. The
  // surface stretches no more than its poles (convex hull), so cells whose
  // poles all stay within the yield are skipped.
  const ControlNet stretch = points - rest_;
  const Eigen::VectorXd pole_stretch = stretch.rowwise().norm();
  ControlNet flow = ControlNet::Zero(rest_.rows(), 3);
  bool flows = false;
  for (Eigen::Index i = 0; i < rest_.rows(); ++i) {
    const YieldCell& cell = yield_cells_[static_cast<std::size_t>(i)];
    double bound = 0.0;
    for (const int j : cell.poles) bound = std::max(bound, pole_stretch[j]);
    if (!(bound > material_.yield)) continue;
    double largest = 0.0;
    for (const auto& sample : cell.samples) {
      Eigen::RowVector3d surface = Eigen::RowVector3d::Zero();
      for (const auto& [j, w] : sample) surface += w * stretch.row(j);
      largest = std::max(largest, surface.norm());
    }
    if (!(largest > material_.yield)) continue;
    flow.row(i) = (1.0 - material_.yield / largest) * stretch.row(i);
    flows = true;
  }
  if (flows) {
    // Across a C0 join the three poles of a row move so the join keeps its
    // angle: the smallest change to their flows with (after - on) = ratio (on
    // - before), the same condition the joint term holds the displacement to.
    for (const JoinRow& r : join_rows_) {
      const Eigen::RowVector3d miss =
          (flow.row(r.after) - flow.row(r.on)) - r.ratio * (flow.row(r.on) - flow.row(r.before));
      const double c2 = r.ratio * r.ratio + (1.0 + r.ratio) * (1.0 + r.ratio) + 1.0;
      flow.row(r.before) -= (r.ratio / c2) * miss;
      flow.row(r.on) += ((1.0 + r.ratio) / c2) * miss;
      flow.row(r.after) -= (1.0 / c2) * miss;
    }
    // Flow dissipates: it may not raise the stored energy 1/2 U^T K U, U = P
    // - P_rest (moving rest points one by one can, where a neighbour
    // stretched more). Along the flow the energy is a parabola in its
    // fraction alpha, E0 - alpha flow.K U + alpha^2 / 2 flow.K flow; take the
    // largest alpha up to 1 that does not raise it.
    const ControlNet k_flow = stiffness_.multiply(flow);
    const double along = (k_flow.array() * stretch.array()).sum();
    const double curve = (k_flow.array() * flow.array()).sum();
    const double fraction = curve > 0.0 ? std::clamp(2.0 * along / curve, 0.0, 1.0) : 1.0;
    rest_ += fraction * flow;
  }
  // Every control point's own stretch stays within kPlasticStretchCap yields,
  // so a high-degree net cannot drift in patterns the surface barely shows.
  const double cap = kPlasticStretchCap * material_.yield;
  for (Eigen::Index i = 0; i < rest_.rows(); ++i) {
    const Eigen::RowVector3d own = points.row(i) - rest_.row(i);
    const double length = own.norm();
    if (length > cap) rest_.row(i) += (1.0 - cap / length) * own;
  }
  // The cap acts pole by pole; a tied join's `on` pole keeps its row's
  // proportions (its stretch the tie's blend of its neighbours').
  for (const JoinRow& r : join_rows_) {
    if (!r.tied) continue;
    const double l = r.lambda();
    rest_.row(r.on) = points.row(r.on) - l * (points.row(r.before) - rest_.row(r.before)) -
                      (1.0 - l) * (points.row(r.after) - rest_.row(r.after));
  }
}

DeformableBody::DeformableBody(SurfaceHierarchy hierarchy, const Material& material)
    : hierarchy_(std::move(hierarchy)), material_(material) {}

Result<DeformableBody> DeformableBody::create(const BSplineSurface& surface,
                                              const Material& material,
                                              const BoundaryConditions& conditions,
                                              OperatorCache& cache) {
  if (Status s = validate(material); !s.ok()) return s;
  Result<SurfaceHierarchy> h = SurfaceHierarchy::build(surface, cache);
  if (!h.ok()) return h.status();
  DeformableBody body(std::move(h).value(), material);
  const int nu = surface.count(Direction::u);
  const int nv = surface.count(Direction::v);
  body.shell_ = shell_matrices(surface);
  const ShellStiffness k = shell_stiffness(material);
  // A control point with (almost) no area, on a collapsed edge or a row of
  // coincident poles, gets 1e-3 of the mean mass so the step can move it.
  body.masses_ = k.mass_per_area * body.shell_.area.cwiseMax(1e-3 * body.shell_.area.mean());
  body.fixed_ = held_poles(nu, nv, conditions);
  // Elastic terms: A Membrane + D Bending + D Joints.
  const int ru0 = body.shell_.foundation.reach_u(), rv0 = body.shell_.foundation.reach_v();
  PoleStencilMatrix elastic(nu, nv, ru0, rv0);
  elastic.add_scaled(body.shell_.membrane, k.membrane);
  elastic.add_scaled(body.shell_.bending, k.bending);
  elastic.add_scaled(body.shell_.joints, k.bending);

  // Conditioning at the haptic step: a material far too stiff for its mass on
  // this face (a tiny face, or steel's bending over a few micrometres) gets its
  // elastic stiffness scaled down until every control point reaches
  // min_inertia_ratio; such modes are frozen at 1 kHz either way.
  const double h2 = kHapticStep * kHapticStep;
  const double r_min = kMaterialRange.min_inertia_ratio;
  for (Eigen::Index i = 0; i < body.masses_.size(); ++i) {
    const double inertia =
        kMassToNewtonSecond2PerMm * body.masses_[i] + h2 * k.foundation * body.shell_.area[i];
    const double foundation = h2 * k.foundation * body.shell_.foundation.diagonal(i);
    const double bend = h2 * elastic.diagonal(i);
    if (bend > 0.0 && inertia < r_min * (foundation + body.elastic_scale_ * bend))
      body.elastic_scale_ = std::max(0.0, (inertia / r_min - foundation) / bend);
  }
  body.stiffness_ = PoleStencilMatrix(nu, nv, ru0, rv0);
  body.stiffness_.add_scaled(body.shell_.foundation, k.foundation);
  body.stiffness_.add_scaled(elastic, body.elastic_scale_);

  // Solve order: the narrower band of the two row-major orders.
  // A tie couples a join's neighbours to everything its `on` pole touches.
  body.join_rows_ = join_rows(surface, body.fixed_);
  const std::array<int, 2> tied = tie_reach(body.join_rows_);
  const int ru = body.stiffness_.reach_u() + tied[0], rv = body.stiffness_.reach_v() + tied[1];
  // Ties go to the direction with more poles (then the higher degree) as the
  // slow index, so a transposed net is solved in the same physical order and
  // gives the same result to the last bit.
  const long long band_u = static_cast<long long>(ru) * nv + rv;
  const long long band_v = static_cast<long long>(rv) * nu + ru;
  const bool by_u = band_u != band_v
                        ? band_u < band_v
                        : std::pair(nu, surface.degree[0]) >= std::pair(nv, surface.degree[1]);
  body.bandwidth_ = by_u ? ru * nv + rv : rv * nu + ru;
  const Eigen::Index n = static_cast<Eigen::Index>(nu) * nv;
  body.order_.resize(static_cast<std::size_t>(n));
  body.rank_.resize(static_cast<std::size_t>(n));
  for (int i = 0; i < nu; ++i) {
    for (int j = 0; j < nv; ++j) {
      const int r = by_u ? i * nv + j : j * nu + i;
      body.order_[static_cast<std::size_t>(r)] = surface.pole_index(i, j);
      body.rank_[static_cast<std::size_t>(surface.pole_index(i, j))] = r;
    }
  }
  body.bandwidth_ = std::min<int>(body.bandwidth_, static_cast<int>(n) - 1);
  body.bandwidth_ = std::max(body.bandwidth_, 0);
  body.rest_ = surface.control_points;
  {
    const Eigen::VectorXd gu = greville_abscissae(surface.degree[0], surface.knots[0]);
    const Eigen::VectorXd gv = greville_abscissae(surface.degree[1], surface.knots[1]);
    // The three abscissae of pole i's cell along one direction.
    const auto cell = [](const Eigen::VectorXd& g, int i) {
      const Eigen::Index last = g.size() - 1;
      const double lo = i > 0 ? 0.5 * (g[i - 1] + g[i]) : g[0];
      const double hi = i < last ? 0.5 * (g[i] + g[i + 1]) : g[last];
      return std::array<double, 3>{lo, g[i], hi};
    };
    body.yield_cells_.resize(static_cast<std::size_t>(n));
    for (int i = 0; i < nu; ++i)
      for (int j = 0; j < nv; ++j) {
        YieldCell& c = body.yield_cells_[static_cast<std::size_t>(surface.pole_index(i, j))];
        for (const double u : cell(gu, i))
          for (const double v : cell(gv, j)) {
            c.samples.push_back(basis_at(surface, {u, v}));
            for (const auto& [pole, w] : c.samples.back()) c.poles.push_back(pole);
          }
        std::sort(c.poles.begin(), c.poles.end());
        c.poles.erase(std::unique(c.poles.begin(), c.poles.end()), c.poles.end());
      }
  }
  body.velocities_ = ControlNet::Zero(n, 3);
  // Factorised now, at the haptic step, so the first tick does not pay for it
  // (28 ms on a 64 x 64 net); another dt refactorises at its first step.
  if (Status f = body.factorize(kHapticStep); !f.ok()) return f;
  return body;
}

double DeformableBody::kinetic_energy() const {
  double e = 0.0;
  for (Eigen::Index i = 0; i < velocities_.rows(); ++i)
    e += 0.5 * kMassToNewtonSecond2PerMm * masses_[i] * velocities_.row(i).squaredNorm();
  return e;
}

double DeformableBody::potential_energy() const {
  return 0.5 * stiffness_.quadratic_form(control_points() - rest_);
}

double DeformableBody::last_step_motion() const {
  return velocities_.rows() > 0 ? step_dt_ * velocities_.rowwise().norm().maxCoeff() : 0.0;
}

bool DeformableBody::settled(double distance) const {
  if (!(last_step_motion() < distance)) return false;
  const ControlNet stretch = control_points() - rest_;
  return stretch.rows() == 0 || stretch.rowwise().norm().maxCoeff() < distance;
}

SymmetricBandMatrix DeformableBody::step_matrix(double dt) const {
  const Eigen::Index n = masses_.size();
  SymmetricBandMatrix a(static_cast<int>(n), bandwidth_);
  const double scale = dt * material_.damping + dt * dt;  // multiplies K (springs and dashpots)
  const auto is_fixed = [&](Eigen::Index pole) {
    return fixed_[static_cast<std::size_t>(pole)] != 0;
  };
  const int nu = stiffness_.count_u(), nv = stiffness_.count_v();
  const int ru = stiffness_.reach_u(), rv = stiffness_.reach_v();
  for (int i = 0; i < nu; ++i) {
    for (int j = 0; j < nv; ++j) {
      const Eigen::Index pa = static_cast<Eigen::Index>(i) * nv + j;
      const int ra = rank_[static_cast<std::size_t>(pa)];
      if (is_fixed(pa)) {
        a.at(ra, ra) = 1.0;  // a held point's velocity is zero: no coupling
        continue;
      }
      a.at(ra, ra) += kMassToNewtonSecond2PerMm * masses_[pa];
      for (int di = std::max(-ru, -i); di <= std::min(ru, nu - 1 - i); ++di) {
        for (int dj = std::max(-rv, -j); dj <= std::min(rv, nv - 1 - j); ++dj) {
          const Eigen::Index pb = static_cast<Eigen::Index>(i + di) * nv + (j + dj);
          const int rb = rank_[static_cast<std::size_t>(pb)];
          if (rb > ra || is_fixed(pb)) continue;  // lower half only
          a.at(ra, rb) += scale * stiffness_.at(i, j, di, dj);
        }
      }
    }
  }
  tie_matrix(a, join_rows_, rank_);
  return a;
}

Status DeformableBody::factorize(double dt) {
  if (solver_ && solver_dt_ == dt) return Status::success();
  Result<BandedCholesky> f = BandedCholesky::factorize(step_matrix(dt));
  if (!f.ok()) return f.status();
  solver_ = std::move(f).value();
  solver_dt_ = dt;
  return Status::success();
}

Status DeformableBody::step(double dt, const ControlNet& forces) {
  Result<LoadPreview> preview = begin_step(dt, forces, {});
  if (!preview.ok()) return preview.status();
  finish_step(Eigen::Vector3d::Zero());
  return Status::success();
}

Result<LoadPreview> DeformableBody::begin_step(double dt, const ControlNet& forces,
                                               const Eigen::VectorXd& pattern) {
  if (const Interval range{0.0, kMaxTimeStep, IntervalEnds::open_low}; !range.contains(dt)) {
    return Status::error(StatusCode::invalid_argument,
                         "time step dt " + out_of_interval_text(dt, range, "s"));
  }
  if (Status s = factorize(dt); !s.ok()) return s;
  const Eigen::Index n = masses_.size();
  assert(forces.rows() == 0 || forces.rows() == n);
  assert(pattern.size() == 0 || pattern.size() == n);
  has_pattern_ = pattern.size() > 0;
  step_dt_ = dt;
  Eigen::MatrixXd force = -stiffness_.multiply(control_points() - rest_);
  if (forces.rows() > 0) force += forces;
  work_.resize(n, has_pattern_ ? 4 : 3);
  for (Eigen::Index r = 0; r < n; ++r) {
    const Eigen::Index i = order_[static_cast<std::size_t>(r)];
    if (fixed_[static_cast<std::size_t>(i)]) {
      work_.row(r).setZero();
      continue;
    }
    const double m = kMassToNewtonSecond2PerMm * masses_[i];
    for (int c = 0; c < 3; ++c) work_(r, c) = m * velocities_(i, c) + dt * force(i, c);
    if (has_pattern_) work_(r, 3) = pattern[i];
  }
  tie_load(work_, join_rows_, rank_);
  solver_->solve_in_place(work_);
  untie_solution(work_, join_rows_, rank_);
  LoadPreview preview;
  if (has_pattern_) {
    for (Eigen::Index r = 0; r < n; ++r) {
      const Eigen::Index i = order_[static_cast<std::size_t>(r)];
      if (fixed_[static_cast<std::size_t>(i)]) continue;
      preview.free_motion += dt * pattern[i] * work_.row(r).head<3>().transpose();
      preview.compliance += dt * dt * pattern[i] * work_(r, 3);
    }
  }
  return preview;
}

void DeformableBody::finish_step(const Eigen::Vector3d& pattern_force) {
  const Eigen::Index n = masses_.size();
  const double h = step_dt_;
  ControlNet points = control_points();
  for (Eigen::Index r = 0; r < n; ++r) {
    const Eigen::Index i = order_[static_cast<std::size_t>(r)];
    if (fixed_[static_cast<std::size_t>(i)]) continue;  // P = P_rest, V = 0 throughout
    Eigen::RowVector3d v = work_.row(r).head<3>();
    if (has_pattern_) v += h * work_(r, 3) * pattern_force.transpose();
    velocities_.row(i) = v;
    points.row(i) += h * v;
  }
  if (std::isfinite(material_.yield)) plastic_flow(points);
  hierarchy_.set_control_points(points);
}

}  // namespace argil
