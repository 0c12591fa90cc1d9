#include "argil/core/deform/deformable_body.hpp"

#include <cmath>
#include <string>

#include "argil/core/base/number_text.hpp"

namespace argil {

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
  body.springs_ = grid_springs(nu, nv);
  body.fixed_ = fixed_nodes(nu, nv, conditions);
  body.masses_ = node_masses(surface, body.operators(), material.density);
  const MaterialRange& r = kMaterialRange;
  for (Eigen::Index i = 0; i < body.masses_.size(); ++i) {
    const double m = body.masses_[i];
    if (!r.node_mass.contains(m)) {
      // The derived mass rounds away from the range, so the printed value
      // still lies outside it.
      const LimitSide away = m > r.node_mass.high ? LimitSide::lower : LimitSide::upper;
      return Status::error(StatusCode::invalid_argument,
                           "material.density " + number_text(material.density) +
                               " kg/mm^2 gives node " + std::to_string(i) + " a mass of " +
                               limit_text(m, away) + " kg; node masses must be in " +
                               interval_text(r.node_mass, "kg"));
    }
  }
  body.rest_ = evaluate_nodes(surface, body.operators());
  body.nodes_ = body.rest_;
  body.velocities_ = ControlNet::Zero(body.rest_.rows(), 3);
  return body;
}

double DeformableBody::kinetic_energy() const {
  double e = 0.0;
  for (Eigen::Index i = 0; i < velocities_.rows(); ++i)
    e += 0.5 * kMassToNewtonSecond2PerMm * masses_[i] * velocities_.row(i).squaredNorm();
  return e;
}

double DeformableBody::potential_energy() const {
  return elastic_energy(springs_, {material_.stiffness, material_.anchor_stiffness},
                        nodes_ - rest_);
}

Status DeformableBody::factorize(double dt) {
  if (solver_ && solver_dt_ == dt) return Status::success();
  const SurfaceOperators& ops = operators();
  const ImplicitStepRequest request{
      .count_u = ops.u->count(), .count_v = ops.v->count(), .material = material_, .dt = dt};
  Result<BandedCholesky> f =
      BandedCholesky::factorize(implicit_step_matrix(springs_, masses_, fixed_, request));
  if (!f.ok()) return f.status();
  solver_ = std::move(f).value();
  solver_dt_ = dt;
  return Status::success();
}

Status DeformableBody::step(double dt, const ControlNet& node_forces) {
  Result<LoadPreview> preview = begin_step(dt, node_forces, {});
  if (!preview.ok()) return preview.status();
  finish_step(Eigen::Vector3d::Zero());
  return Status::success();
}

Result<LoadPreview> DeformableBody::begin_step(double dt, const ControlNet& node_forces,
                                               const Eigen::VectorXd& pattern) {
  if (const Interval range{0.0, kMaxTimeStep, IntervalEnds::open_low}; !range.contains(dt)) {
    return Status::error(StatusCode::invalid_argument,
                         "time step dt " + out_of_interval_text(dt, range, "s"));
  }
  if (Status s = factorize(dt); !s.ok()) return s;
  const Eigen::Index n = nodes_.rows();
  assert(node_forces.rows() == 0 || node_forces.rows() == n);
  assert(pattern.size() == 0 || pattern.size() == n);
  has_pattern_ = pattern.size() > 0;
  step_dt_ = dt;
  ControlNet force = elastic_forces(springs_, {material_.stiffness, material_.anchor_stiffness},
                                    nodes_ - rest_, fixed_);
  if (node_forces.rows() > 0) force += node_forces;
  work_.resize(n, has_pattern_ ? 4 : 3);
  for (Eigen::Index i = 0; i < n; ++i) {
    if (fixed_[static_cast<std::size_t>(i)]) {
      work_.row(i).setZero();
      continue;
    }
    const double m = kMassToNewtonSecond2PerMm * masses_[i];
    for (int c = 0; c < 3; ++c) work_(i, c) = m * velocities_(i, c) + dt * force(i, c);
    if (has_pattern_) work_(i, 3) = pattern[i];
  }
  solver_->solve_in_place(work_);
  LoadPreview preview;
  if (has_pattern_) {
    for (Eigen::Index i = 0; i < n; ++i) {
      if (fixed_[static_cast<std::size_t>(i)]) continue;
      preview.free_motion += dt * pattern[i] * work_.row(i).head<3>().transpose();
      preview.compliance += dt * dt * pattern[i] * work_(i, 3);
    }
  }
  return preview;
}

void DeformableBody::finish_step(const Eigen::Vector3d& pattern_force) {
  const Eigen::Index n = nodes_.rows();
  const double h = step_dt_;
  for (Eigen::Index i = 0; i < n; ++i) {
    if (fixed_[static_cast<std::size_t>(i)]) continue;  // x = x_rest, v = 0 throughout
    Eigen::RowVector3d v = work_.row(i).head<3>();
    if (has_pattern_) v += h * work_(i, 3) * pattern_force.transpose();
    velocities_.row(i) = v;
    nodes_.row(i) += h * v;
  }
  if (std::isfinite(material_.yield)) {
    // Plastic flow: the rest position follows so the anchor stretch is the yield.
    for (Eigen::Index i = 0; i < n; ++i) {
      const Eigen::RowVector3d stretch = nodes_.row(i) - rest_.row(i);
      const double length = stretch.norm();
      if (length > material_.yield) rest_.row(i) += (1.0 - material_.yield / length) * stretch;
    }
  }
  hierarchy_.set_control_points(fit_control_points(surface(), operators(), nodes_));
}

}  // namespace argil
