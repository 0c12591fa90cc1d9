#include "argil/core/deform/shell_matrices.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cassert>
#include <cmath>
#include <vector>

#include "argil/core/deform/detail/gauss_legendre.hpp"
#include "argil/core/geometry/basis.hpp"

namespace argil {

namespace {

/// The rational basis functions non-zero on one knot span (su, sv) and their
/// derivatives up to order 2 at (u, v); local index a * (q + 1) + b for pole
/// (first_u + a, first_v + b).
struct LocalBasis {
  int first_u = 0;
  int first_v = 0;
  Eigen::VectorXd r, ru, rv, ruu, ruv, rvv;
};

LocalBasis local_basis(const BSplineSurface& s, int su, int sv, double u, double v) {
  const int p = s.degree[0];
  const int q = s.degree[1];
  Eigen::MatrixXd bu(3, p + 1), bv(3, q + 1);
  basis_derivatives(p, s.knots[0], su, u, 2, bu);
  basis_derivatives(q, s.knots[1], sv, v, 2, bv);
  const int n = (p + 1) * (q + 1);
  LocalBasis out;
  out.first_u = su - p;
  out.first_v = sv - q;
  // Weighted B-spline products N w and the weight function W = sum N w.
  Eigen::VectorXd n0(n), nu(n), nv(n), nuu(n), nuv(n), nvv(n);
  for (int a = 0; a <= p; ++a) {
    for (int b = 0; b <= q; ++b) {
      const int k = a * (q + 1) + b;
      const double w =
          s.is_rational() ? s.weights[s.pole_index(out.first_u + a, out.first_v + b)] : 1.0;
      n0[k] = bu(0, a) * bv(0, b) * w;
      nu[k] = bu(1, a) * bv(0, b) * w;
      nv[k] = bu(0, a) * bv(1, b) * w;
      nuu[k] = bu(2, a) * bv(0, b) * w;
      nuv[k] = bu(1, a) * bv(1, b) * w;
      nvv[k] = bu(0, a) * bv(2, b) * w;
    }
  }
  const double w0 = n0.sum(), wu = nu.sum(), wv = nv.sum();
  const double wuu = nuu.sum(), wuv = nuv.sum(), wvv = nvv.sum();
  // Quotient rule for R = N w / W, term by term.
  out.r = n0 / w0;
  out.ru = (nu - out.r * wu) / w0;
  out.rv = (nv - out.r * wv) / w0;
  out.ruu = (nuu - 2.0 * out.ru * wu - out.r * wuu) / w0;
  out.ruv = (nuv - out.ru * wv - out.rv * wu - out.r * wuv) / w0;
  out.rvv = (nvv - 2.0 * out.rv * wv - out.r * wvv) / w0;
  return out;
}

/// sum_k coefficient_k P_k over the local poles of `basis`.
Eigen::Vector3d combine(const BSplineSurface& s, const LocalBasis& basis,
                        const Eigen::VectorXd& coefficient) {
  const int q = s.degree[1];
  Eigen::Vector3d out = Eigen::Vector3d::Zero();
  for (Eigen::Index k = 0; k < coefficient.size(); ++k) {
    const int a = static_cast<int>(k) / (q + 1);
    const int b = static_cast<int>(k) % (q + 1);
    out += coefficient[k] *
           s.control_points.row(s.pole_index(basis.first_u + a, basis.first_v + b)).transpose();
  }
  return out;
}

/// Non-empty knot spans of one direction.
std::vector<int> spans(const BSplineSurface& s, int direction) {
  const int p = s.degree[static_cast<std::size_t>(direction)];
  const Eigen::VectorXd& t = s.knots[static_cast<std::size_t>(direction)];
  const int n = static_cast<int>(t.size()) - p - 1;
  std::vector<int> out;
  for (int k = p; k < n; ++k)
    if (t[k] < t[k + 1]) out.push_back(k);
  return out;
}

/// The stencil reach in one direction: the basis overlap p, and 2 so the
/// joint terms of degree-1 faces (which couple poles two apart) fit.
int reach(int degree) { return std::max(degree, 2); }

/// Gauss points per knot span in one direction: degree + 1 integrates a
/// polynomial face's mass exactly; a rational face's integrands are quotients,
/// so it gets twice as many (capped).
int quadrature_points(const BSplineSurface& s, int direction) {
  const int p = s.degree[static_cast<std::size_t>(direction)];
  return s.is_rational() ? std::min(2 * p + 2, 32) : p + 1;
}

/// A pole and a coefficient of a linear functional of the displacement.
struct Term {
  int i = 0;
  int j = 0;
  double c = 0.0;
};

/// Adds weight * (sum_a c_a dp_a)^2 to `m`. Coefficients below 1e-12 of the
/// largest are rounding (the cross derivative at a C0 line involves only the
/// two poles either side), so they are dropped and every pair fits the stencil.
void add_square(PoleStencilMatrix& m, std::vector<Term> terms, double weight) {
  double largest = 0.0;
  for (const Term& a : terms) largest = std::max(largest, std::abs(a.c));
  std::erase_if(terms, [&](const Term& a) { return std::abs(a.c) <= 1e-12 * largest; });
  for (const Term& a : terms) {
    for (const Term& b : terms) {
      const int di = b.i - a.i, dj = b.j - a.j;
      assert(std::abs(di) <= m.reach_u() && std::abs(dj) <= m.reach_v());
      if (std::abs(di) > m.reach_u() || std::abs(dj) > m.reach_v()) continue;
      m.add(a.i, a.j, di, dj, weight * a.c * b.c);
    }
  }
}

void integrate_area(const BSplineSurface& s, ShellMatrices& out) {
  const int p = s.degree[0];
  const int q = s.degree[1];
  const detail::QuadratureRule ru = detail::gauss_legendre(quadrature_points(s, 0));
  const detail::QuadratureRule rv = detail::gauss_legendre(quadrature_points(s, 1));
  const int n = (p + 1) * (q + 1);
  Eigen::Matrix2Xd grad(2, n), flux(2, n);                          // gradient, and g^-1 times it
  std::vector<Eigen::Matrix2d> shape(static_cast<std::size_t>(n));  // g^-1 H
  for (const int su : spans(s, 0)) {
    const double u0 = s.knots[0][su], du = s.knots[0][su + 1] - u0;
    for (const int sv : spans(s, 1)) {
      const double v0 = s.knots[1][sv], dv = s.knots[1][sv + 1] - v0;
      for (Eigen::Index gu = 0; gu < ru.points.size(); ++gu) {
        for (Eigen::Index gv = 0; gv < rv.points.size(); ++gv) {
          const LocalBasis b =
              local_basis(s, su, sv, u0 + du * ru.points[gu], v0 + dv * rv.points[gv]);
          const Eigen::Vector3d su3 = combine(s, b, b.ru), sv3 = combine(s, b, b.rv);
          Eigen::Matrix2d g;
          g << su3.dot(su3), su3.dot(sv3), su3.dot(sv3), sv3.dot(sv3);
          const double det = g.determinant();
          // A degenerate point (collapsed edge) has no area to integrate.
          if (!(det > 1e-20 * g.trace() * g.trace())) continue;
          const Eigen::Matrix2d ginv = g.inverse();
          const double da = std::sqrt(det) * du * dv * ru.weights[gu] * rv.weights[gv];
          // Christoffel symbols Gamma^c_ab = g^cd (S_ab . S_d), for ab = uu, uv, vv.
          const Eigen::Vector3d s_uu = combine(s, b, b.ruu), s_uv = combine(s, b, b.ruv),
                                s_vv = combine(s, b, b.rvv);
          const Eigen::Vector2d g_uu = ginv * Eigen::Vector2d(s_uu.dot(su3), s_uu.dot(sv3));
          const Eigen::Vector2d g_uv = ginv * Eigen::Vector2d(s_uv.dot(su3), s_uv.dot(sv3));
          const Eigen::Vector2d g_vv = ginv * Eigen::Vector2d(s_vv.dot(su3), s_vv.dot(sv3));
          for (int k = 0; k < n; ++k) {
            grad.col(k) << b.ru[k], b.rv[k];
            flux.col(k) = ginv * grad.col(k);
            Eigen::Matrix2d h;
            h(0, 0) = b.ruu[k] - g_uu.dot(grad.col(k));
            h(0, 1) = h(1, 0) = b.ruv[k] - g_uv.dot(grad.col(k));
            h(1, 1) = b.rvv[k] - g_vv.dot(grad.col(k));
            shape[static_cast<std::size_t>(k)] = ginv * h;
          }
          for (int k = 0; k < n; ++k) {
            const int ik = b.first_u + k / (q + 1), jk = b.first_v + k % (q + 1);
            out.area[s.pole_index(ik, jk)] += b.r[k] * da;
            for (int l = 0; l < n; ++l) {
              const int di = l / (q + 1) - k / (q + 1), dj = l % (q + 1) - k % (q + 1);
              const std::size_t ks = static_cast<std::size_t>(k), ls = static_cast<std::size_t>(l);
              out.foundation.add(ik, jk, di, dj, b.r[k] * b.r[l] * da);
              out.membrane.add(ik, jk, di, dj, grad.col(k).dot(flux.col(l)) * da);
              // tr(g^-1 H_k g^-1 H_l) = g^ac g^bd H_k,ab H_l,cd
              out.bending.add(ik, jk, di, dj, (shape[ks] * shape[ls]).trace() * da);
            }
          }
        }
      }
    }
  }
}

/// Joint terms along the C0 knot lines of one direction (0: lines u = const).
void integrate_joints(const BSplineSurface& s, int direction, ShellMatrices& out) {
  const std::size_t d = static_cast<std::size_t>(direction);
  const std::size_t e = 1 - d;  // along the line
  const int p = s.degree[d];
  const Eigen::VectorXd& t = s.knots[d];
  const int count = static_cast<int>(t.size()) - p - 1;
  const detail::QuadratureRule rule =
      detail::gauss_legendre(quadrature_points(s, static_cast<int>(e)));
  // A degree-1 direction is all C0 lines (a faceted face): its joints are its
  // only bending, so they take the material's stiffness, not a stiff joint's.
  const double joint_stiffness = p == 1 ? 1.0 : kJointStiffness;
  for (int k = p + 1; k < count;) {
    int m = 1;
    while (k + m < count && t[k + m] == t[k]) ++m;
    const int left = k - 1;       // span ending at t[k]
    const int right = k + m - 1;  // span starting at t[k]
    const bool c0 = m == p && t[left] < t[k] && t[k] < t[right + 1];
    if (c0) {
      const double at = t[k];
      const double width_left = at - t[left], width_right = t[right + 1] - at;
      for (const int se : spans(s, static_cast<int>(e))) {
        const double e0 = s.knots[e][se], de = s.knots[e][se + 1] - e0;
        for (Eigen::Index g = 0; g < rule.points.size(); ++g) {
          const double along = e0 + de * rule.points[g];
          const auto basis_on = [&](int span) {
            return d == 0 ? local_basis(s, span, se, at, along)
                          : local_basis(s, se, span, along, at);
          };
          const LocalBasis lb = basis_on(left), rb = basis_on(right);
          const Eigen::VectorXd& lc = d == 0 ? lb.ru : lb.rv;  // across the line
          const Eigen::VectorXd& rc = d == 0 ? rb.ru : rb.rv;
          const double speed_l = combine(s, lb, lc).norm(), speed_r = combine(s, rb, rc).norm();
          const double ds = combine(s, lb, d == 0 ? lb.rv : lb.ru).norm() * de * rule.weights[g];
          if (!(speed_l > 0.0 && speed_r > 0.0 && ds > 0.0)) continue;
          const double h = 0.5 * (speed_l * width_left + speed_r * width_right);
          std::vector<Term> terms;
          const int q = s.degree[1];
          const auto add_side = [&](const LocalBasis& b, const Eigen::VectorXd& c, double scale) {
            for (Eigen::Index k2 = 0; k2 < c.size(); ++k2) {
              if (c[k2] == 0.0) continue;
              const int i = b.first_u + static_cast<int>(k2) / (q + 1);
              const int j = b.first_v + static_cast<int>(k2) % (q + 1);
              terms.push_back({i, j, scale * c[k2]});
            }
          };
          add_side(lb, lc, -1.0 / speed_l);
          add_side(rb, rc, 1.0 / speed_r);
          add_square(out.joints, terms, joint_stiffness * ds / h);
        }
      }
    }
    k += m;
  }
}

}  // namespace

ShellMatrices shell_matrices(const BSplineSurface& s) {
  const int nu = s.count(Direction::u);
  const int nv = s.count(Direction::v);
  const int reach_u = reach(s.degree[0]), reach_v = reach(s.degree[1]);
  ShellMatrices out;
  out.area = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(nu) * nv);
  out.foundation = PoleStencilMatrix(nu, nv, reach_u, reach_v);
  out.membrane = out.foundation;
  out.bending = out.foundation;
  out.joints = out.foundation;
  integrate_area(s, out);
  integrate_joints(s, 0, out);
  integrate_joints(s, 1, out);
  out.total_area = out.area.sum();
  return out;
}

}  // namespace argil
