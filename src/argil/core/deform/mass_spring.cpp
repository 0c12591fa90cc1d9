#include "argil/core/deform/mass_spring.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

namespace argil {

std::vector<Spring> grid_springs(int nu, int nv) {
  std::vector<Spring> springs;
  const auto id = [nv](int i, int j) { return i * nv + j; };
  const auto add = [&](int i0, int j0, int i1, int j1, SpringKind kind) {
    if (i0 < 0 || j0 < 0 || i1 < 0 || j1 < 0 || i0 >= nu || i1 >= nu || j0 >= nv || j1 >= nv)
      return;
    springs.push_back({std::min(id(i0, j0), id(i1, j1)), std::max(id(i0, j0), id(i1, j1)), kind});
  };
  for (int i = 0; i < nu; ++i) {
    for (int j = 0; j < nv; ++j) {
      add(i, j, i + 1, j, SpringKind::structural);
      add(i, j, i, j + 1, SpringKind::structural);
      add(i, j, i + 1, j + 1, SpringKind::shear);
      add(i + 1, j, i, j + 1, SpringKind::shear);
      add(i, j, i + 2, j, SpringKind::bending);
      add(i, j, i, j + 2, SpringKind::bending);
    }
  }
  std::sort(springs.begin(), springs.end(),
            [](const Spring& x, const Spring& y) { return x.a != y.a ? x.a < y.a : x.b < y.b; });
  return springs;
}

int grid_bandwidth(int nu, int nv) {
  int width = 0;
  for (const Spring& s : grid_springs(std::min(nu, 3), nv)) width = std::max(width, s.b - s.a);
  return width;
}

Eigen::VectorXd node_masses(const BSplineSurface& s, const SurfaceOperators& ops, double density) {
  SurfaceGrid grid;
  evaluate_grid(s, ops.u->greville_rows(), ops.v->greville_rows(), 1, grid);
  // Half the parameter distance to the neighbouring nodes in one direction.
  const auto cell = [](const Eigen::VectorXd& xi) {
    const Eigen::Index n = xi.size();
    Eigen::VectorXd w(n);
    for (Eigen::Index i = 0; i < n; ++i)
      w[i] = 0.5 * (xi[std::min(i + 1, n - 1)] - xi[std::max<Eigen::Index>(i - 1, 0)]);
    return w;
  };
  const Eigen::VectorXd wu = cell(ops.u->greville());
  const Eigen::VectorXd wv = cell(ops.v->greville());
  const int nu = s.count(Direction::u);
  const int nv = s.count(Direction::v);
  Eigen::VectorXd area(static_cast<Eigen::Index>(nu) * nv);
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j < nv; ++j) {
      const Eigen::Index k = s.pole_index(i, j);
      const Eigen::Vector3d su = grid.du.row(k).transpose();
      const Eigen::Vector3d sv = grid.dv.row(k).transpose();
      area[k] = su.cross(sv).norm() * wu[i] * wv[j];
    }
  const double floor = 1e-3 * area.mean();
  return density * area.cwiseMax(floor);
}

std::vector<char> fixed_nodes(int nu, int nv, const BoundaryConditions& c) {
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

ControlNet elastic_forces(const std::vector<Spring>& springs, const SpringConstants& constants,
                          const ControlNet& u, const std::vector<char>& fixed) {
  const double k = constants.stiffness;
  const double k_anchor = constants.anchor_stiffness;
  ControlNet f = -k_anchor * u;
  if (k != 0.0) {
    for (const Spring& s : springs) {
      const Eigen::RowVector3d pull = k * (u.row(s.b) - u.row(s.a));
      f.row(s.a) += pull;
      f.row(s.b) -= pull;
    }
  }
  for (Eigen::Index i = 0; i < f.rows(); ++i)
    if (fixed[static_cast<std::size_t>(i)]) f.row(i).setZero();
  return f;
}

double elastic_energy(const std::vector<Spring>& springs, const SpringConstants& constants,
                      const ControlNet& u) {
  const double k = constants.stiffness;
  const double k_anchor = constants.anchor_stiffness;
  double energy = 0.5 * k_anchor * u.squaredNorm();
  for (const Spring& s : springs) energy += 0.5 * k * (u.row(s.b) - u.row(s.a)).squaredNorm();
  return energy;
}

SymmetricBandMatrix implicit_step_matrix(const std::vector<Spring>& springs,
                                         const Eigen::VectorXd& masses,
                                         const std::vector<char>& fixed,
                                         const ImplicitStepRequest& request) {
  const int nu = request.count_u;
  const int nv = request.count_v;
  const Material& m = request.material;
  const double dt = request.dt;
  const int n = nu * nv;
  SymmetricBandMatrix a(n, grid_bandwidth(nu, nv));
  const double scale = dt * m.damping + dt * dt;  // multiplies K (stiffness and dashpots)
  const auto is_fixed = [&](int i) { return fixed[static_cast<std::size_t>(i)] != 0; };
  for (int i = 0; i < n; ++i) {
    a.at(i, i) =
        is_fixed(i) ? 1.0 : kMassToNewtonSecond2PerMm * masses[i] + scale * m.anchor_stiffness;
  }
  if (m.stiffness == 0.0) return a;
  const double k = scale * m.stiffness;
  for (const Spring& s : springs) {
    // A fixed node's velocity is zero: its coupling moves to no right-hand side.
    if (!is_fixed(s.a)) a.at(s.a, s.a) += k;
    if (!is_fixed(s.b)) a.at(s.b, s.b) += k;
    if (!is_fixed(s.a) && !is_fixed(s.b)) a.at(s.b, s.a) -= k;
  }
  return a;
}

}  // namespace argil
