#include "argil/core/operators/surface_operators.hpp"

#include <cassert>
#include <utility>

#include "argil/core/geometry/detail/homogeneous_derivatives.hpp"

namespace argil {

Result<SurfaceOperators> surface_operators(const BSplineSurface& surface, OperatorCache& cache) {
  if (Status check = validate(surface); !check.ok()) return check;
  SurfaceOperators ops;
  for (Direction d : kDirections) {
    Result<std::shared_ptr<const CurveOperators>> built =
        cache.get(surface.degree_in(d), surface.knots_in(d));
    if (!built.ok()) {
      Status s = built.status();
      s.message = std::string("direction ") + to_string(d) + ": " + s.message;
      return s;
    }
    (d == Direction::u ? ops.u : ops.v) = built.value();
  }
  return ops;
}

namespace {

void resize(ControlNet& m, Eigen::Index rows) {
  if (m.rows() != rows) m.resize(rows, 3);
}

/// Sizes the grid's arrays for `total` samples up to `order`.
void prepare_grid(SurfaceGrid& out, Eigen::Index count_u, Eigen::Index count_v, int order) {
  out.count_u = static_cast<int>(count_u);
  out.count_v = static_cast<int>(count_v);
  const Eigen::Index total = count_u * count_v;
  resize(out.points, total);
  if (order >= 1) {
    resize(out.du, total);
    resize(out.dv, total);
    resize(out.normals, total);
  }
  if (order >= 2) {
    resize(out.duu, total);
    resize(out.duv, total);
    resize(out.dvv, total);
  }
}

/// The homogeneous net contracted over u at one u sample: c[k].row(j) =
/// sum_r N^(k)_r(u) (w P, w)_(first + r, j) for k = 0 .. order.
struct ContractedRow {
  Eigen::MatrixX4d c0, c1, c2;
};

/// Contracts the net row by row into one set of buffers, reused across the
/// rows of a grid (grids are evaluated every tick).
class RowContractor {
 public:
  RowContractor(const BSplineSurface& s, const SamplingRows& u_rows, int order)
      : s_(s), u_rows_(u_rows), order_(order) {
    const int nv = s.count(Direction::v);
    row_ = {Eigen::MatrixX4d(nv, 4), Eigen::MatrixX4d(nv, 4), Eigen::MatrixX4d(nv, 4)};
  }

  /// Row at u sample a; valid until the next call.
  const ContractedRow& at(Eigen::Index a) {
    const int fu = u_rows_.first_pole[static_cast<std::size_t>(a)];
    const bool rational = s_.is_rational();
    row_.c0.setZero();
    if (order_ >= 1) row_.c1.setZero();
    if (order_ >= 2) row_.c2.setZero();
    for (int r = 0; r <= s_.degree[0]; ++r) {
      const double n0 = u_rows_.values(a, r);
      const double n1 = u_rows_.d1(a, r);
      const double n2 = u_rows_.d2(a, r);
      for (int j = 0; j < row_.c0.rows(); ++j) {
        const Eigen::Index k = s_.pole_index(fu + r, j);
        const double w = rational ? s_.weights[k] : 1.0;
        const Eigen::Vector4d pw(w * s_.control_points(k, 0), w * s_.control_points(k, 1),
                                 w * s_.control_points(k, 2), w);
        row_.c0.row(j) += n0 * pw.transpose();
        if (order_ >= 1) row_.c1.row(j) += n1 * pw.transpose();
        if (order_ >= 2) row_.c2.row(j) += n2 * pw.transpose();
      }
    }
    return row_;
  }

 private:
  const BSplineSurface& s_;
  const SamplingRows& u_rows_;
  int order_;
  ContractedRow row_;
};

/// Derivatives at v sample b from a contracted row: a short (q+1)-term sum.
SurfaceDerivatives sample_along_v(const ContractedRow& c, const SamplingRows& v_rows,
                                  Eigen::Index b, int q, int order) {
  const int fv = v_rows.first_pole[static_cast<std::size_t>(b)];
  detail::HomogeneousDerivatives h;
  for (int l = 0; l <= q; ++l) {
    const double m0 = v_rows.values(b, l);
    h.a00 += m0 * c.c0.row(fv + l).transpose();
    if (order >= 1) {
      const double m1 = v_rows.d1(b, l);
      h.a10 += m0 * c.c1.row(fv + l).transpose();
      h.a01 += m1 * c.c0.row(fv + l).transpose();
    }
    if (order >= 2) {
      h.a20 += m0 * c.c2.row(fv + l).transpose();
      h.a11 += v_rows.d1(b, l) * c.c1.row(fv + l).transpose();
      h.a02 += v_rows.d2(b, l) * c.c0.row(fv + l).transpose();
    }
  }
  return detail::cartesian(h, order);
}

void store(SurfaceGrid& out, Eigen::Index row, const SurfaceDerivatives& d, int order) {
  out.points.row(row) = d.point;
  if (order >= 1) {
    out.du.row(row) = d.du;
    out.dv.row(row) = d.dv;
    out.normals.row(row) = unit_normal(d);
  }
  if (order >= 2) {
    out.duu.row(row) = d.duu;
    out.duv.row(row) = d.duv;
    out.dvv.row(row) = d.dvv;
  }
}

}  // namespace

void evaluate_grid(const BSplineSurface& s, const SamplingRows& u_rows, const SamplingRows& v_rows,
                   int order, SurfaceGrid& out) {
  assert(order >= 0 && order <= 2);
  prepare_grid(out, u_rows.size(), v_rows.size(), order);
  // Row a of the grid: contract the net over u once, then sample along v.
  RowContractor contract(s, u_rows, order);
  for (Eigen::Index a = 0; a < u_rows.size(); ++a) {
    const ContractedRow& c = contract.at(a);
    for (Eigen::Index b = 0; b < v_rows.size(); ++b)
      store(out, a * v_rows.size() + b, sample_along_v(c, v_rows, b, s.degree[1], order), order);
  }
}

BezierPatch bezier_patch(const BSplineSurface& s, const SurfaceOperators& ops, int element_u,
                         int element_v) {
  const int p = s.degree[0];
  const int q = s.degree[1];
  const BezierExtraction& xu = ops.u->extraction();
  const BezierExtraction& xv = ops.v->extraction();
  const int fu = xu.spans[static_cast<std::size_t>(element_u)] - p;
  const int fv = xv.spans[static_cast<std::size_t>(element_v)] - q;
  const Eigen::MatrixXd& eu = xu.operators[static_cast<std::size_t>(element_u)];
  const Eigen::MatrixXd& ev = xv.operators[static_cast<std::size_t>(element_v)];
  const bool rational = s.is_rational();

  // B = E_u * P_local * E_v^T on the span's homogeneous poles.
  PatchNet local((p + 1) * (q + 1), 4);
  for (int a = 0; a <= p; ++a) {
    for (int b = 0; b <= q; ++b) {
      const Eigen::Index k = s.pole_index(fu + a, fv + b);
      const double w = rational ? s.weights[k] : 1.0;
      local.row(a * (q + 1) + b) << w * s.control_points(k, 0), w * s.control_points(k, 1),
          w * s.control_points(k, 2), w;
    }
  }
  return map_along(map_along(BezierPatch{p, q, std::move(local)}, Direction::u, eu), Direction::v,
                   ev);
}

ControlNet evaluate_nodes(const BSplineSurface& s, const SurfaceOperators& ops) {
  SurfaceGrid grid;
  evaluate_grid(s, ops.u->greville_rows(), ops.v->greville_rows(), 0, grid);
  return grid.points;
}

Eigen::VectorXd weights_at_nodes(const BSplineSurface& s, const SurfaceOperators& ops) {
  const int nu = s.count(Direction::u);
  const int nv = s.count(Direction::v);
  Eigen::VectorXd w = Eigen::VectorXd::Ones(static_cast<Eigen::Index>(nu) * nv);
  if (!s.is_rational()) return w;
  const SamplingRows& ru = ops.u->greville_rows();
  const SamplingRows& rv = ops.v->greville_rows();
  const int p = s.degree[0];
  const int q = s.degree[1];
  for (int i = 0; i < nu; ++i) {
    for (int j = 0; j < nv; ++j) {
      double sum = 0.0;
      for (int a = 0; a <= p; ++a) {
        for (int b = 0; b <= q; ++b) {
          sum += ru.values(i, a) * rv.values(j, b) *
                 s.weights[s.pole_index(ru.first_pole[static_cast<std::size_t>(i)] + a,
                                        rv.first_pole[static_cast<std::size_t>(j)] + b)];
        }
      }
      w[s.pole_index(i, j)] = sum;
    }
  }
  return w;
}

ControlNet fit_control_points(const BSplineSurface& s, const SurfaceOperators& ops,
                              const ControlNet& nodes) {
  const int nu = s.count(Direction::u);
  const int nv = s.count(Direction::v);
  assert(nodes.rows() == static_cast<Eigen::Index>(nu) * nv);
  const Eigen::VectorXd w = weights_at_nodes(s, ops);

  // Solve A_u X A_v^T = H for the homogeneous coordinates H = w * node.
  // Along u: rows are i, columns (j, coordinate).
  Eigen::MatrixXd by_u(nu, 3 * nv);
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j < nv; ++j)
      for (int c = 0; c < 3; ++c)
        by_u(i, 3 * j + c) = w[s.pole_index(i, j)] * nodes(s.pole_index(i, j), c);
  ops.u->collocation().solve_in_place(by_u);
  // Along v: rows are j, columns (i, coordinate).
  Eigen::MatrixXd by_v(nv, 3 * nu);
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j < nv; ++j)
      for (int c = 0; c < 3; ++c) by_v(j, 3 * i + c) = by_u(i, 3 * j + c);
  ops.v->collocation().solve_in_place(by_v);

  ControlNet control(static_cast<Eigen::Index>(nu) * nv, 3);
  for (int i = 0; i < nu; ++i) {
    for (int j = 0; j < nv; ++j) {
      const Eigen::Index k = s.pole_index(i, j);
      const double weight = s.is_rational() ? s.weights[k] : 1.0;
      for (int c = 0; c < 3; ++c) control(k, c) = by_v(j, 3 * i + c) / weight;
    }
  }
  return control;
}

Eigen::MatrixXd fit_adjoint(const BSplineSurface& s, const SurfaceOperators& ops,
                            const Eigen::MatrixXd& control_forces) {
  const int nu = s.count(Direction::u);
  const int nv = s.count(Direction::v);
  const Eigen::Index columns = control_forces.cols();
  assert(control_forces.rows() == static_cast<Eigen::Index>(nu) * nv);
  // Fit = diag(1/w) (A_u^-1 (x) A_v^-1) diag(W) with W the weight function at
  // the nodes, so Fit^T = diag(W) (A_u^-T (x) A_v^-T) diag(1/w).
  const Eigen::VectorXd w_nodes = weights_at_nodes(s, ops);
  Eigen::MatrixXd by_u(nu, nv * columns);
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j < nv; ++j) {
      const Eigen::Index k = s.pole_index(i, j);
      const double weight = s.is_rational() ? s.weights[k] : 1.0;
      for (Eigen::Index c = 0; c < columns; ++c)
        by_u(i, columns * j + c) = control_forces(k, c) / weight;
    }
  ops.u->collocation().solve_transpose_in_place(by_u);
  Eigen::MatrixXd by_v(nv, nu * columns);
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j < nv; ++j)
      for (Eigen::Index c = 0; c < columns; ++c)
        by_v(j, columns * i + c) = by_u(i, columns * j + c);
  ops.v->collocation().solve_transpose_in_place(by_v);
  Eigen::MatrixXd out(static_cast<Eigen::Index>(nu) * nv, columns);
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j < nv; ++j) {
      const Eigen::Index k = s.pole_index(i, j);
      for (Eigen::Index c = 0; c < columns; ++c) out(k, c) = w_nodes[k] * by_v(j, columns * i + c);
    }
  return out;
}

}  // namespace argil
