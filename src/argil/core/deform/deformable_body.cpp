#include "argil/core/deform/deformable_body.hpp"

#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <string>
#include <utility>

#include "argil/core/base/number_text.hpp"
#include "argil/core/deform/contact_response.hpp"
#include "argil/core/geometry/basis.hpp"
#include "argil/core/operators/surface_operators.hpp"

namespace argil {

namespace {

/// One axis of the window that follows the loads [lo, hi) out of the current
/// window [cur_lo, cur_hi) (empty: cur_lo >= cur_hi), m the margin, s the
/// slack (0 for a first window), n the poles along the axis. A side the
/// loads' margin passed gets the slack (the way they travel) and the side
/// opposite it one pole of it (they travel away from it; the pole keeps a
/// load flickering between two knot spans from moving the window back and
/// forth); an axis they did not leave keeps the current sides, between
/// margin and margin + slack from the loads.
std::array<int, 2> follow_axis(int lo, int hi, int cur_lo, int cur_hi, int m, int s, int n) {
  const bool empty = cur_lo >= cur_hi;
  const bool past_lo = empty || std::max(0, lo - m) < cur_lo;
  const bool past_hi = empty || std::min(n, hi + m) > cur_hi;
  const int behind = std::min(s, 1);
  std::array<int, 2> out;
  if (past_lo || past_hi) {
    out = {lo - m - (past_lo ? s : behind), hi + m + (past_hi ? s : behind)};
  } else {
    out = {std::clamp(cur_lo, lo - m - s, lo - m), std::clamp(cur_hi, hi + m, hi + m + s)};
  }
  return {std::max(0, out[0]), std::min(n, out[1])};
}

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

/// The three abscissae of pole i's yield cell along one direction: halfway to
/// the previous Greville point, its own, halfway to the next.
std::array<double, 3> yield_cell_abscissae(const Eigen::VectorXd& greville, int i) {
  const Eigen::Index last = greville.size() - 1;
  const double lo = i > 0 ? 0.5 * (greville[i - 1] + greville[i]) : greville[0];
  const double hi = i < last ? 0.5 * (greville[i] + greville[i + 1]) : greville[last];
  return {lo, greville[i], hi};
}

/// Pole p's (i, j) on a net nv poles wide along v.
std::pair<int, int> pole_ij(Eigen::Index p, int nv) {
  return {static_cast<int>(p / nv), static_cast<int>(p % nv)};
}

}  // namespace

void DeformableBody::plastic_flow(const ControlNet& points, const PoleWindow& moved) {
  // The surface yields where it stretched past the yield: measured over each
  // control point's cell around its Greville point (3 x 3 samples, each a
  // positive average of the poles' stretches: nothing inverted), so the flow
  // follows the surface wherever the tool is, not the net's spacing. The
  // surface stretches no more than its poles (convex hull), so cells whose
  // poles all stay within the yield are skipped. Only poles in `moved` moved
  // this step: only cells that see one can newly yield.
  const int nu = stiffness_.count_u(), nv = stiffness_.count_v();
  const int ku = stiffness_.reach_u(), kv = stiffness_.reach_v();
  const PoleWindow cells = moved.grown(yield_reach_[0], yield_reach_[1], nu, nv);
  // A C0 join's rows spread the flow one more pole each way of their `on` pole.
  const PoleWindow flowing = cells.grown(2, 2, nu, nv);
  const PoleWindow k_rows = flowing.grown(ku, kv, nu, nv);  // K flow's stencils read these
  const PoleWindow seen = cells.grown(yield_reach_[0], yield_reach_[1], nu, nv).united(k_rows);
  const auto each = [](const PoleWindow& box, int width, const auto& f) {
    for (int i = box.i0; i < box.i1; ++i)
      for (int j = box.j0; j < box.j1; ++j) f(static_cast<Eigen::Index>(i) * width + j);
  };
  Eigen::VectorXd& pole_stretch = stretch_norm_;
  each(seen, nv, [&](Eigen::Index r) {
    stretch_.row(r) = points.row(r) - rest_.row(r);
    pole_stretch[r] = stretch_.row(r).norm();
  });
  std::vector<Eigen::Index>& flowing_poles = flowing_poles_;
  flowing_poles.clear();
  each(cells, nv, [&](Eigen::Index i) {
    const auto [ci, cj] = pole_ij(i, nv);
    const YieldBasis& bu = yield_basis_[0];
    const YieldBasis& bv = yield_basis_[1];
    double bound = 0.0;
    for (const int a : bu.poles[static_cast<std::size_t>(ci)])
      for (const int b : bv.poles[static_cast<std::size_t>(cj)])
        bound = std::max(bound, pole_stretch[static_cast<Eigen::Index>(a) * nv + b]);
    if (!(bound > material_.yield)) return;
    const double largest = largest_cell_stretch(ci, cj);
    if (!(largest > material_.yield)) return;
    flow_.row(i) = (1.0 - material_.yield / largest) * stretch_.row(i);
    flowing_poles.push_back(i);
  });
  if (!flowing_poles.empty()) {
    // Across a C0 join the three poles of a row move so the join keeps its
    // angle: the smallest change to their flows with (after - on) = ratio (on
    // - before), the same condition the joint term holds the displacement to.
    // (Rows outside `cells` have no flow and are unchanged.)
    for (const JoinRow& r : join_rows_) {
      const Eigen::RowVector3d miss = (flow_.row(r.after) - flow_.row(r.on)) -
                                      r.ratio * (flow_.row(r.on) - flow_.row(r.before));
      if (miss.isZero(0.0)) continue;
      const double c2 = r.ratio * r.ratio + (1.0 + r.ratio) * (1.0 + r.ratio) + 1.0;
      flow_.row(r.before) -= (r.ratio / c2) * miss;
      flow_.row(r.on) += ((1.0 + r.ratio) / c2) * miss;
      flow_.row(r.after) -= (1.0 / c2) * miss;
      flowing_poles.insert(flowing_poles.end(), {r.before, r.on, r.after});
    }
    std::sort(flowing_poles.begin(), flowing_poles.end());
    flowing_poles.erase(std::unique(flowing_poles.begin(), flowing_poles.end()),
                        flowing_poles.end());
    // Flow dissipates: it may not raise the stored energy 1/2 U^T K U, U = P
    // - P_rest (moving rest points one by one can, where a neighbour
    // stretched more). Along the flow the energy is a parabola in its
    // fraction alpha, E0 - alpha flow.K U + alpha^2 / 2 flow.K flow; take the
    // largest alpha up to 1 that does not raise it. K is symmetric, so both
    // products need K's rows at the flowing poles only (flow is zero elsewhere).
    double along = 0.0, curve = 0.0;
    for (const Eigen::Index p : flowing_poles) {
      const auto [i, j] = pole_ij(p, nv);
      along += flow_.row(p).dot(stiffness_.row_product(stretch_, i, j));
      curve += flow_.row(p).dot(stiffness_.row_product(flow_, i, j));
    }
    const double fraction = curve > 0.0 ? std::clamp(2.0 * along / curve, 0.0, 1.0) : 1.0;
    // flow_ is zero between steps (row products read around the rows they use).
    for (const Eigen::Index p : flowing_poles) {
      rest_.row(p) += fraction * flow_.row(p);
      flow_.row(p).setZero();
    }
  }
  // Every control point's own stretch stays within kPlasticStretchCap yields,
  // so a high-degree net cannot drift in patterns the surface barely shows.
  const double cap = kPlasticStretchCap * material_.yield;
  each(flowing, nv, [&](Eigen::Index i) {
    const Eigen::RowVector3d own = points.row(i) - rest_.row(i);
    const double length = own.norm();
    if (length > cap) rest_.row(i) += (1.0 - cap / length) * own;
  });
  // The cap acts pole by pole; a tied join's `on` pole keeps its row's
  // proportions (its stretch the tie's blend of its neighbours').
  for (const JoinRow& r : join_rows_) {
    const auto [i, j] = pole_ij(r.on, nv);
    if (!r.tied || !flowing.contains(i, j)) continue;
    const double l = r.lambda();
    rest_.row(r.on) = points.row(r.on) - l * (points.row(r.before) - rest_.row(r.before)) -
                      (1.0 - l) * (points.row(r.after) - rest_.row(r.after));
  }
}

double DeformableBody::largest_cell_stretch(int ci, int cj) {
  double largest = 0.0;
  if (surface().is_rational()) {
    for (int su = 3 * ci; su < 3 * ci + 3; ++su)
      for (int sv = 3 * cj; sv < 3 * cj + 3; ++sv)
        largest = std::max(largest, sample_stretch(su, sv).norm());
    return largest;
  }
  // A polynomial basis is a tensor product that sums to one: each of the
  // cell's three v samples is summed along v once per row of poles the cell
  // reads, then along u for each u sample (84 to 108 vector products for a
  // bicubic cell instead of 144, and no weights or their sum).
  const YieldBasis& bu = yield_basis_[0];
  const YieldBasis& bv = yield_basis_[1];
  const int p = bu.degree, q = bv.degree, nv = stiffness_.count_v();
  const auto at = [](const std::vector<int>& v, int k) { return v[static_cast<std::size_t>(k)]; };
  const int row0 = at(bu.first, 3 * ci), rows = at(bu.first, 3 * ci + 2) + p + 1 - row0;
  cell_rows_.resize(static_cast<std::size_t>(3 * rows));
  for (int k = 0; k < 3; ++k) {
    const int sv = 3 * cj + k, fv = at(bv.first, sv);
    const double* vv = &bv.values[static_cast<std::size_t>(sv) * static_cast<std::size_t>(q + 1)];
    for (int r = 0; r < rows; ++r) {
      Eigen::RowVector3d sum = Eigen::RowVector3d::Zero();
      const Eigen::Index first = static_cast<Eigen::Index>(row0 + r) * nv + fv;
      for (int b = 0; b <= q; ++b) sum += vv[b] * stretch_.row(first + b);
      cell_rows_[static_cast<std::size_t>(3 * r + k)] = sum;
    }
  }
  for (int su = 3 * ci; su < 3 * ci + 3; ++su) {
    const int fu = at(bu.first, su) - row0;
    const double* vu = &bu.values[static_cast<std::size_t>(su) * static_cast<std::size_t>(p + 1)];
    for (int k = 0; k < 3; ++k) {
      Eigen::RowVector3d sample = Eigen::RowVector3d::Zero();
      for (int a = 0; a <= p; ++a)
        sample += vu[a] * cell_rows_[static_cast<std::size_t>(3 * (fu + a) + k)];
      largest = std::max(largest, sample.norm());
    }
  }
  return largest;
}

Eigen::RowVector3d DeformableBody::sample_stretch(int su, int sv) const {
  // The rational basis at the sample as pole_weights_at computes it (the
  // products, zeros skipped, over their sum), applied to the stretch.
  const YieldBasis& bu = yield_basis_[0];
  const YieldBasis& bv = yield_basis_[1];
  const int p = bu.degree, q = bv.degree, nv = stiffness_.count_v();
  const int fu = bu.first[static_cast<std::size_t>(su)],
            fv = bv.first[static_cast<std::size_t>(sv)];
  const double* vu = &bu.values[static_cast<std::size_t>(su) * static_cast<std::size_t>(p + 1)];
  const double* vv = &bv.values[static_cast<std::size_t>(sv) * static_cast<std::size_t>(q + 1)];
  const BSplineSurface& s = surface();
  const auto weight = [&](int a, int b) {
    const Eigen::Index pole = static_cast<Eigen::Index>(fu + a) * nv + fv + b;
    return vu[a] * vv[b] * (s.is_rational() ? s.weights[pole] : 1.0);
  };
  double sum = 0.0;
  for (int a = 0; a <= p; ++a)
    for (int b = 0; b <= q; ++b) sum += weight(a, b);
  Eigen::RowVector3d out = Eigen::RowVector3d::Zero();
  for (int a = 0; a <= p; ++a)
    for (int b = 0; b <= q; ++b) {
      const double w = weight(a, b);
      if (w == 0.0) continue;
      out += (w / sum) * stretch_.row(static_cast<Eigen::Index>(fu + a) * nv + fv + b);
    }
  return out;
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

  body.join_rows_ = join_rows(surface, body.fixed_);
  body.full_ = body.region({0, nu, 0, nv});
  const Eigen::Index n = static_cast<Eigen::Index>(nu) * nv;
  body.rest_ = surface.control_points;
  // The yield cells' samples are tensor products of 1D bases: kept per
  // direction (memory along the net's sides, not its area).
  for (const Direction d : {Direction::u, Direction::v}) {
    const auto at = static_cast<std::size_t>(d);
    YieldBasis& yb = body.yield_basis_[at];
    const int degree = surface.degree[at];
    const Eigen::VectorXd& knots = surface.knots[at];
    const int count = surface.count(d);
    const Eigen::VectorXd greville = greville_abscissae(degree, knots);
    yb.degree = degree;
    yb.poles.resize(static_cast<std::size_t>(count));
    Eigen::MatrixXd basis(1, degree + 1);
    for (int i = 0; i < count; ++i) {
      std::vector<int>& poles = yb.poles[static_cast<std::size_t>(i)];
      for (const double t : yield_cell_abscissae(greville, i)) {
        const int span = find_span(degree, knots, count, t);
        basis_derivatives(degree, knots, span, t, 0, basis);
        yb.first.push_back(span - degree);
        for (int a = 0; a <= degree; ++a) {
          yb.values.push_back(basis(0, a));
          if (basis(0, a) != 0.0) poles.push_back(span - degree + a);
        }
      }
      std::sort(poles.begin(), poles.end());
      poles.erase(std::unique(poles.begin(), poles.end()), poles.end());
      for (const int pole : poles)
        body.yield_reach_[at] = std::max(body.yield_reach_[at], std::abs(pole - i));
    }
  }
  body.velocities_ = ControlNet::Zero(n, 3);
  body.stretch_ = body.force_ = body.flow_ = Eigen::MatrixXd::Zero(n, 3);
  body.stretch_norm_ = Eigen::VectorXd::Zero(n);
  // A local window reaches a few influence lengths of the loads: the bending
  // length (D / k_a)^(1/4) and the membrane's sqrt(A / k_a), in poles at the
  // net's mean pitch, plus the basis' reach. Without a foundation the whole
  // face carries the load: the window is the net.
  {
    const double a = k.membrane * body.elastic_scale_, d = k.bending * body.elastic_scale_;
    body.influence_length_ =
        k.foundation > 0.0 ? std::max(std::pow(d / k.foundation, 0.25), std::sqrt(a / k.foundation))
                           : std::numeric_limits<double>::infinity();
    const double length = 3.0 * body.influence_length_;
    const ControlNet& p = surface.control_points;
    double pitch_u = 0.0, pitch_v = 0.0;
    for (int i = 0; i < nu; ++i)
      for (int j = 0; j < nv; ++j) {
        const Eigen::Index r = surface.pole_index(i, j);
        if (i + 1 < nu) pitch_u += (p.row(surface.pole_index(i + 1, j)) - p.row(r)).norm();
        if (j + 1 < nv) pitch_v += (p.row(surface.pole_index(i, j + 1)) - p.row(r)).norm();
      }
    pitch_u /= std::max(1, (nu - 1) * nv);
    pitch_v /= std::max(1, nu * (nv - 1));
    const auto poles = [&](double pitch, int degree, int count) {
      const double spans = pitch > 0.0 ? std::ceil(length / pitch) : count;
      return static_cast<int>(std::min<double>(count, degree + spans));
    };
    body.margin_ = {poles(pitch_u, surface.degree[0], nu), poles(pitch_v, surface.degree[1], nv)};
    body.slack_ = {std::max(4, body.margin_[0] / 3), std::max(4, body.margin_[1] / 3)};
  }
  body.points_ = surface.control_points;
  body.pattern_ = Eigen::VectorXd::Zero(n);
  // Factorised now, at the haptic step, so the first tick does not pay for it
  // (28 ms on a 64 x 64 net); another dt refactorises at its first step. A
  // net too large for that is solved in local windows only (the whole net is
  // factorised when a window reaches it, or without local solves).
  const double full_work =
      0.5 * static_cast<double>(n) * body.full_.bandwidth * body.full_.bandwidth;
  if (full_work <= kCreateFactorWork) {
    if (Status f = body.factorize(kHapticStep); !f.ok()) return f;
  }
  return body;
}

double DeformableBody::kinetic_energy() const {
  double e = 0.0;
  for (Eigen::Index i = 0; i < velocities_.rows(); ++i)
    e += 0.5 * kMassToNewtonSecond2PerMm * masses_[i] * velocities_.row(i).squaredNorm();
  return e;
}

double DeformableBody::potential_energy() const {
  return 0.5 * stiffness_.quadratic_form(points_ - rest_);
}

double DeformableBody::step_pole_motion() const {
  // Poles outside the window a step solved do not move (held, V = 0).
  const int nv = stiffness_.count_v();
  const PoleWindow& w = stepped_window_;
  double largest = 0.0;
  for (int i = w.i0; i < w.i1; ++i)
    for (int j = w.j0; j < w.j1; ++j)
      largest = std::max(largest, velocities_.row(static_cast<Eigen::Index>(i) * nv + j).norm());
  return step_dt_ * largest;
}

bool DeformableBody::rests_outside(const PoleWindow& kept) const {
  const int nu = stiffness_.count_u(), nv = stiffness_.count_v();
  const int ru = stiffness_.reach_u(), rv = stiffness_.reach_v();
  const PoleWindow& w = stepped_window_;
  for (int i = w.i0; i < w.i1; ++i) {
    for (int j = w.j0; j < w.j1; ++j) {
      const Eigen::Index pole = static_cast<Eigen::Index>(i) * nv + j;
      if (kept.contains(i, j) || fixed_[static_cast<std::size_t>(pole)]) continue;
      if (!(step_dt_ * velocities_.row(pole).norm() < kWindowRestMotion)) return false;
      // At rest is no velocity and no force: a pole at an oscillation's
      // turning point has the one without the other. The force, over the
      // pole's own stiffness, is how far it would move if let go alone.
      Eigen::RowVector3d force = Eigen::RowVector3d::Zero();
      for (int di = std::max(-ru, -i); di <= std::min(ru, nu - 1 - i); ++di)
        for (int dj = std::max(-rv, -j); dj <= std::min(rv, nv - 1 - j); ++dj) {
          const Eigen::Index q = static_cast<Eigen::Index>(i + di) * nv + (j + dj);
          force += stiffness_.at(i, j, di, dj) * (points_.row(q) - rest_.row(q));
        }
      const double own = stiffness_.at(i, j, 0, 0);
      if (!(own > 0.0) || !(force.norm() < kWindowRestMotion * own)) return false;
    }
  }
  return true;
}

double DeformableBody::last_step_motion() const {
  return std::max(step_pole_motion(), displaced_motion_);
}

double DeformableBody::last_step_travel() const { return step_pole_motion() + displaced_travel_; }

void DeformableBody::displace(const std::vector<Eigen::Index>& poles, const ControlNet& dp,
                              const ControlNet& dv) {
  const int nv = stiffness_.count_v();
  PoleWindow moved;
  for (std::size_t k = 0; k < poles.size(); ++k) {
    const Eigen::Index p = poles[k];
    if (fixed_[static_cast<std::size_t>(p)]) continue;
    const Eigen::Index r = static_cast<Eigen::Index>(k);
    points_.row(p) += dp.row(r);
    velocities_.row(p) += dv.row(r);
    displaced_motion_ = std::max(displaced_motion_, dp.row(r).norm());
    if (displaced_sum_.empty())
      displaced_sum_.assign(static_cast<std::size_t>(points_.rows()), 0.0);
    double& sum = displaced_sum_[static_cast<std::size_t>(p)];
    sum += dp.row(r).norm();
    displaced_travel_ = std::max(displaced_travel_, sum);
    const auto [i, j] = pole_ij(p, nv);
    moved = moved.united({i, i + 1, j, j + 1});
  }
  if (moved.empty()) return;
  displaced_ = displaced_.united(moved);
  resting_ = false;
  hierarchy_.set_control_points_in(points_, moved.i0, moved.i1, moved.j0, moved.j1);
}

bool DeformableBody::weld(const std::vector<std::pair<Eigen::Index, Eigen::Index>>& pairs) {
  const int nv = stiffness_.count_v();
  PoleWindow moved;
  for (const auto& [first, second] : pairs) {
    if (points_.row(first) == points_.row(second) &&
        velocities_.row(first) == velocities_.row(second))
      continue;
    const bool hold_first = fixed_[static_cast<std::size_t>(first)] != 0;
    const bool hold_second = fixed_[static_cast<std::size_t>(second)] != 0;
    if (hold_first && hold_second) continue;  // both held: neither moves
    const double w = hold_first ? 1.0 : hold_second ? 0.0 : 0.5;
    const Eigen::RowVector3d point = w * points_.row(first) + (1.0 - w) * points_.row(second);
    const Eigen::RowVector3d velocity =
        w * velocities_.row(first) + (1.0 - w) * velocities_.row(second);
    // Not counted in displaced_motion_: a weld closes what its seam joint
    // already holds within its slack, and counting it could keep a body whose
    // steps pull the seam apart by rounding from ever settling.
    for (const Eigen::Index p : {first, second}) {
      points_.row(p) = point;
      velocities_.row(p) = velocity;
      const auto [i, j] = pole_ij(p, nv);
      moved = moved.united({i, i + 1, j, j + 1});
    }
  }
  if (moved.empty()) return false;
  displaced_ = displaced_.united(moved);
  resting_ = false;
  hierarchy_.set_control_points_in(points_, moved.i0, moved.i1, moved.j0, moved.j1);
  return true;
}

bool DeformableBody::settled(double distance) const {
  if (!(last_step_motion() < distance)) return false;
  // A window opened on a body at rest holds the poles outside it at rest.
  const int nu = stiffness_.count_u(), nv = stiffness_.count_v();
  const PoleWindow w =
      step_local_ && local_->outside_at_rest ? local_->window : PoleWindow{0, nu, 0, nv};
  for (int i = w.i0; i < w.i1; ++i)
    for (int j = w.j0; j < w.j1; ++j) {
      const Eigen::Index r = static_cast<Eigen::Index>(i) * nv + j;
      if (!((points_.row(r) - rest_.row(r)).norm() < distance)) return false;
    }
  return true;
}

Box3 DeformableBody::solved_box() const {
  const int nv = stiffness_.count_v();
  const PoleWindow& w = stepped_window_;
  Box3 box{Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity()),
           Eigen::Vector3d::Constant(-std::numeric_limits<double>::infinity())};
  for (int i = w.i0; i < w.i1; ++i)
    for (int j = w.j0; j < w.j1; ++j) {
      const Eigen::Vector3d x = points_.row(static_cast<Eigen::Index>(i) * nv + j).transpose();
      box.min = box.min.cwiseMin(x);
      box.max = box.max.cwiseMax(x);
    }
  return box;
}

void DeformableBody::halt() {
  velocities_.setZero();
  // After a load the next one opens a window where it lands (or takes up the
  // dropped one, kept, when it lands inside it); a window anticipated on a
  // body still resting stays active (as in a world without sleep).
  if (!resting_) {
    keep_local();
    pending_.reset();
  }
  resting_ = true;
}

PoleWindow DeformableBody::tie_closed(PoleWindow window) const {
  const int nv = stiffness_.count_v();
  for (bool grew = true; grew;) {
    grew = false;
    for (const JoinRow& r : join_rows_) {
      if (!r.tied) continue;
      PoleWindow row;
      int inside = 0;
      for (const int pole : {r.before, r.on, r.after}) {
        const auto [i, j] = pole_ij(pole, nv);
        row = row.united({i, i + 1, j, j + 1});
        inside += window.contains(i, j) ? 1 : 0;
      }
      if (inside == 0 || inside == 3) continue;
      window = window.united(row);
      grew = true;
    }
  }
  return window;
}

DeformableBody::SolveRegion DeformableBody::region(const PoleWindow& window) const {
  const int nu = stiffness_.count_u(), nv = stiffness_.count_v();
  const int wu = window.count_u(), wv = window.count_v();
  SolveRegion out;
  out.window = window;
  for (const JoinRow& r : join_rows_) {
    const auto [i, j] = pole_ij(r.on, nv);
    if (r.tied && window.contains(i, j)) out.ties.push_back(r);
  }
  // Solve order: the narrower band of the two row-major orders.
  // A tie couples a join's neighbours to everything its `on` pole touches.
  const std::array<int, 2> tied = tie_reach(out.ties);
  const int ru = stiffness_.reach_u() + tied[0], rv = stiffness_.reach_v() + tied[1];
  // Ties go to the direction with more poles (then the higher degree) as the
  // slow index, so a transposed net is solved in the same physical order and
  // gives the same result to the last bit.
  const long long band_u = static_cast<long long>(ru) * wv + rv;
  const long long band_v = static_cast<long long>(rv) * wu + ru;
  const std::array<int, 2>& degree = surface().degree;
  const bool by_u =
      band_u != band_v ? band_u < band_v : std::pair(wu, degree[0]) >= std::pair(wv, degree[1]);
  const int n = wu * wv;
  out.bandwidth = std::max(0, std::min(by_u ? ru * wv + rv : rv * wu + ru, n - 1));
  out.order.resize(static_cast<std::size_t>(n));
  out.rank.assign(static_cast<std::size_t>(nu) * static_cast<std::size_t>(nv), -1);
  for (int i = window.i0; i < window.i1; ++i) {
    for (int j = window.j0; j < window.j1; ++j) {
      const int r =
          by_u ? (i - window.i0) * wv + (j - window.j0) : (j - window.j0) * wu + (i - window.i0);
      const Eigen::Index pole = static_cast<Eigen::Index>(i) * nv + j;
      out.order[static_cast<std::size_t>(r)] = pole;
      out.rank[static_cast<std::size_t>(pole)] = r;
    }
  }
  return out;
}

SymmetricBandMatrix DeformableBody::step_matrix(const SolveRegion& region, double dt) const {
  const PoleWindow& w = region.window;
  SymmetricBandMatrix a =
      SymmetricBandMatrix::unfilled(w.count_u() * w.count_v(), region.bandwidth);
  fill_step_rows(region, dt, 0, a.size(), a);
  tie_matrix(a, region.ties, region.rank);
  return a;
}

void DeformableBody::fill_step_rows(const SolveRegion& region, double dt, int begin, int end,
                                    SymmetricBandMatrix& a) const {
  const double scale = dt * material_.damping + dt * dt;  // multiplies K (springs and dashpots)
  const auto is_fixed = [&](Eigen::Index pole) {
    return fixed_[static_cast<std::size_t>(pole)] != 0;
  };
  const int nu = stiffness_.count_u(), nv = stiffness_.count_v();
  const int ru = stiffness_.reach_u(), rv = stiffness_.reach_v();
  for (int ra = begin; ra < end; ++ra) {
    a.clear_row(ra);
    const Eigen::Index pa = region.order[static_cast<std::size_t>(ra)];
    const auto [i, j] = pole_ij(pa, nv);
    if (is_fixed(pa)) {
      a.at(ra, ra) = 1.0;  // a held point's velocity is zero: no coupling
      continue;
    }
    a.at(ra, ra) += kMassToNewtonSecond2PerMm * masses_[pa];
    for (int di = std::max(-ru, -i); di <= std::min(ru, nu - 1 - i); ++di) {
      for (int dj = std::max(-rv, -j); dj <= std::min(rv, nv - 1 - j); ++dj) {
        const Eigen::Index pb = static_cast<Eigen::Index>(i + di) * nv + (j + dj);
        const int rb = region.rank[static_cast<std::size_t>(pb)];
        // Lower half only; a pole outside the window is held (V = 0): its
        // coupling enters the load through -K (P - P_rest) alone.
        if (rb < 0 || rb > ra || is_fixed(pb)) continue;
        a.at(ra, rb) += scale * stiffness_.at(i, j, di, dj);
      }
    }
  }
}

Result<StepResponse> DeformableBody::step_response(const std::vector<Eigen::Index>& poles,
                                                   const RowMajorMatrix& forces, double dt) const {
  assert(forces.rows() == static_cast<Eigen::Index>(poles.size()));
  const int nu = stiffness_.count_u(), nv = stiffness_.count_v();
  PoleWindow loads;
  for (const Eigen::Index p : poles) {
    const auto [i, j] = pole_ij(p, nv);
    loads = loads.united({i, i + 1, j, j + 1});
  }
  StepResponse out;
  if (loads.empty()) return out;
  const SolveRegion r = region(tie_closed(loads.grown(margin_[0], margin_[1], nu, nv)));
  Result<BandedCholesky> factor = BandedCholesky::factorize(step_matrix(r, dt));
  if (!factor.ok()) return factor.status();
  RowMajorMatrix b = RowMajorMatrix::Zero(static_cast<Eigen::Index>(r.order.size()), forces.cols());
  for (std::size_t k = 0; k < poles.size(); ++k) {
    if (fixed_[static_cast<std::size_t>(poles[k])]) continue;
    b.row(r.rank[static_cast<std::size_t>(poles[k])]) += forces.row(static_cast<Eigen::Index>(k));
  }
  tie_load(b, r.ties, r.rank);
  factor.value().solve_in_place(b);
  untie_solution(b, r.ties, r.rank);
  for (std::size_t k = 0; k < r.order.size(); ++k)
    if (fixed_[static_cast<std::size_t>(r.order[k])]) b.row(static_cast<Eigen::Index>(k)).setZero();
  out.poles = r.order;
  out.motion = dt * dt * b;
  return out;
}

Status DeformableBody::factorize(double dt) {
  if (full_.solver && full_.dt == dt) return Status::success();
  Result<BandedCholesky> f = BandedCholesky::factorize(step_matrix(full_, dt));
  if (!f.ok()) return f.status();
  full_.solver = std::move(f).value();
  full_.dt = dt;
  return Status::success();
}

void DeformableBody::anticipate(const Eigen::Vector2d& uv, double dt) {
  if (!local_solves_ || local_ || pending_) return;
  const BSplineSurface& s = surface();
  const int nu = s.count(Direction::u), nv = s.count(Direction::v);
  const int p = s.degree[0], q = s.degree[1];
  const int su = find_span(p, s.knots[0], nu, uv.x()), sv = find_span(q, s.knots[1], nv, uv.y());
  // The poles a contact at uv would load, grown as a first window with slack
  // (the tool will have moved by the time it lands).
  const PoleWindow loads{su - p, su + 1, sv - q, sv + 1};
  const PoleWindow target =
      tie_closed(loads.grown(margin_[0] + slack_[0], margin_[1] + slack_[1], nu, nv));
  anticipated_whole_ = target == PoleWindow{0, nu, 0, nv};
  if (anticipated_whole_) return;       // nothing to prepare
  if (take_kept(target, target, dt)) {  // the window a load there last had
    local_->outside_at_rest = resting_;
    return;
  }
  pending_ = region(target);
  pending_->dt = dt;
  pending_->outside_at_rest = resting_;
}

bool DeformableBody::step_may_move_any(const std::vector<Eigen::Index>& poles) const {
  if (!local_solves_) return true;
  const std::optional<SolveRegion>& planned = pending_ ? pending_ : local_;
  // No window: a body that moves steps its whole net.
  if (!planned) return anticipated_whole_ || !resting_;
  const int nv = stiffness_.count_v();
  return std::any_of(poles.begin(), poles.end(), [&](Eigen::Index p) {
    const auto [i, j] = pole_ij(p, nv);
    return planned->window.contains(i, j);
  });
}

void DeformableBody::set_local_solves(bool on) {
  local_solves_ = on;
  if (!on) {
    local_.reset();
    pending_.reset();
    kept_.reset();
  }
}

void DeformableBody::keep_local() {
  if (local_ && local_->solver) kept_ = std::move(local_);
  local_.reset();
}

bool DeformableBody::take_kept(const PoleWindow& needed, const PoleWindow& target, double dt) {
  if (!kept_ || kept_->dt != dt || !kept_->window.contains(needed)) return false;
  // Replacing an active window, it must hold all the new one would: that
  // holds the poles the loads left behind that still move (held outside a
  // window, they would stop where they are).
  if (local_ && !kept_->window.contains(target)) return false;
  const auto size = [](const PoleWindow& w) {
    return static_cast<long long>(w.count_u()) * w.count_v();
  };
  // A window much larger than the loads need costs every step more than it saves.
  if (size(kept_->window) > 2 * size(target)) return false;
  // The active window it replaces (which the loads outgrew) is kept instead.
  std::swap(local_, kept_);
  if (kept_ && !kept_->solver) kept_.reset();
  return true;
}

Status DeformableBody::plan_region(double dt, const ControlNet& forces,
                                   const PoleWeights* pattern) {
  step_local_ = false;
  step_idle_ = false;
  if (!local_solves_) return Status::success();
  if (local_ && local_->dt != dt) local_.reset();
  if (kept_ && kept_->dt != dt) kept_.reset();  // its memory, for a window of no use
  if (pending_ && pending_->dt != dt) pending_.reset();
  const int nu = stiffness_.count_u(), nv = stiffness_.count_v();
  const PoleWindow net{0, nu, 0, nv};
  // The poles the loads act on.
  PoleWindow loads;
  const auto load_at = [&](Eigen::Index p) {
    const auto [i, j] = pole_ij(p, nv);
    loads = loads.united({i, i + 1, j, j + 1});
  };
  if (pattern)
    for (const auto& [p, w] : *pattern)
      if (w != 0.0) load_at(p);
  for (Eigen::Index p = 0; p < forces.rows(); ++p)
    if (!forces.row(p).isZero(0.0)) load_at(p);
  loads = loads.united(displaced_);  // a joint moved them: solved as loaded
  if (!loads.empty()) {
    // Move the window once the loads come within the influence margin of its
    // edge, with slack so the tool can travel before the next move. The first
    // window has no slack: it is factorised at once. The part the loads left
    // behind (a stroke's trail) is dropped when it has come to rest, so a long
    // stroke's tick costs what its first did; else the window grows.
    const PoleWindow needed = loads.grown(margin_[0], margin_[1], nu, nv);
    if (resting_ && !(local_ && local_->window.contains(needed)) &&
        !(pending_ && pending_->window.contains(needed))) {
      // An anticipated window the first load missed: open one where it landed.
      keep_local();
      pending_.reset();
    }
    const PoleWindow current = local_ ? local_->window : PoleWindow{};
    if (!current.contains(needed) && !(pending_ && pending_->window.contains(needed))) {
      const int su = local_ ? slack_[0] : 0, sv = local_ ? slack_[1] : 0;
      const std::array<int, 2> u =
          follow_axis(loads.i0, loads.i1, current.i0, current.i1, margin_[0], su, nu);
      const std::array<int, 2> v =
          follow_axis(loads.j0, loads.j1, current.j0, current.j1, margin_[1], sv, nv);
      PoleWindow target = tie_closed({u[0], u[1], v[0], v[1]});
      // Only an active window leaves a trail (a whole-net step has none to
      // drop, and scanning the net's forces would cost that step a pass).
      if (current.empty() || !rests_outside(target)) {
        target =
            tie_closed(target.united(current).united(pending_ ? pending_->window : PoleWindow{}));
      }
      // Poles outside a window opened on a resting body stay at rest.
      const bool outside_at_rest = local_ ? local_->outside_at_rest : resting_;
      pending_.reset();
      if (target == net) {
        local_.reset();  // the whole net
      } else if (take_kept(needed, target, dt)) {
        // A face a joint moves now and then comes back to the same window.
        local_->outside_at_rest = outside_at_rest;
      } else {
        pending_ = region(target);
        pending_->dt = dt;
        pending_->outside_at_rest = outside_at_rest;
      }
    }
  } else if (local_ && !pending_ && !local_->outside_at_rest) {
    // No load: once the window has come to rest the whole net relaxes again
    // (the held poles outside it may sit off their rest).
    double motion = 0.0;
    for (const Eigen::Index p : local_->order)
      motion = std::max(motion, step_dt_ * velocities_.row(p).norm());
    if (motion < kWindowRestMotion) keep_local();
  }
  if (Status f = advance_pending(dt, loads); !f.ok()) return f;
  step_local_ = local_.has_value() && local_->window.contains(loads);
  // (A window anticipated before the first load changes nothing at rest.)
  step_idle_ = loads.empty() && resting_;
  return Status::success();
}

Status DeformableBody::prepare_window(double dt) {
  if (!local_solves_ || !pending_) return Status::success();
  if (pending_->dt != dt) {
    pending_.reset();
    return Status::success();
  }
  return advance_pending(dt, {});
}

Status DeformableBody::advance_pending(double dt, const PoleWindow& loads) {
  if (pending_) {
    // This step's share of the pending factorisation: rows filled (a stencil
    // each) and factorised (about bandwidth^2 / 2 multiply-adds each).
    // A step that would otherwise solve the whole net may spend that solve's
    // work instead (two sweeps, four columns): it is never dearer than the
    // whole-net step it replaces.
    SolveRegion& r = *pending_;
    const int size = r.window.count_u() * r.window.count_v();
    const bool held = local_ && local_->window.contains(loads);
    double work = held && !loads.empty() ? kWindowGrowthWorkPerStep : kWindowFactorWorkPerStep;
    if (!loads.empty() && !held) {
      // (A net too large to factorise at create never solves the whole: its
      // first window is factorised at once.)
      work = full_.solver
                 ? std::max(work, 8.0 * static_cast<double>(masses_.size()) * full_.bandwidth)
                 : std::numeric_limits<double>::infinity();
    }
    const int stencil = (2 * stiffness_.reach_u() + 1) * (2 * stiffness_.reach_v() + 1);
    if (r.matrix.size() != size) {
      // Filled with the rows it factorises, so the matrix's memory is first
      // touched over the steps too. Ties mix rows across the band: a region
      // with ties (a C0 join's small nets) is filled at once.
      if (r.ties.empty()) {
        r.matrix = SymmetricBandMatrix::unfilled(size, r.bandwidth);
      } else {
        r.matrix = step_matrix(r, dt);
        work -= static_cast<double>(size) * stencil;
      }
    }
    // Without ties the rows filled are the rows factorised.
    const bool by_rows = r.ties.empty();
    const double fill = by_rows ? stencil + r.bandwidth + 1.0 : 0.0;
    const double per_row = 0.5 * r.bandwidth * r.bandwidth + r.bandwidth + 1.0 + fill;
    const int rows = std::max(1, static_cast<int>(std::min<double>(size, work / per_row)));
    const int last = std::min(size, r.factored_rows + rows);
    if (by_rows) fill_step_rows(r, dt, r.factored_rows, last, r.matrix);
    if (Status f = BandedCholesky::factorize_rows(r.matrix, r.factored_rows, last); !f.ok())
      return f;
    r.factored_rows = last;
    if (last == size) {
      r.solver = BandedCholesky::from_factor(std::move(r.matrix));
      local_ = std::move(pending_);
      pending_.reset();
    }
  }
  return Status::success();
}

Status DeformableBody::step(double dt, const ControlNet& forces) {
  Result<LoadPreview> preview = start_step(dt, forces, nullptr);
  if (!preview.ok()) return preview.status();
  finish_step(Eigen::Vector3d::Zero());
  return Status::success();
}

Result<LoadPreview> DeformableBody::begin_step(double dt, const ControlNet& forces,
                                               const Eigen::VectorXd& pattern) {
  if (pattern.size() == 0) return start_step(dt, forces, nullptr);
  assert(pattern.size() == masses_.size());
  PoleWeights weights;
  for (Eigen::Index p = 0; p < pattern.size(); ++p)
    if (pattern[p] != 0.0) weights.emplace_back(p, pattern[p]);
  return start_step(dt, forces, &weights);
}

Result<LoadPreview> DeformableBody::begin_step(double dt, const ControlNet& forces,
                                               const PoleWeights& pattern) {
  return start_step(dt, forces, &pattern);
}

Result<LoadPreview> DeformableBody::start_step(double dt, const ControlNet& forces,
                                               const PoleWeights* loads) {
  if (const Interval range{0.0, kMaxTimeStep, IntervalEnds::open_low}; !range.contains(dt)) {
    return Status::error(StatusCode::invalid_argument,
                         "time step dt " + out_of_interval_text(dt, range, "s"));
  }
  assert(forces.rows() == 0 || forces.rows() == masses_.size());
  if (Status s = plan_region(dt, forces, loads); !s.ok()) return s;
  if (!displaced_sum_.empty()) {
    const int nv = stiffness_.count_v();
    for (int i = displaced_.i0; i < displaced_.i1; ++i)
      for (int j = displaced_.j0; j < displaced_.j1; ++j)
        displaced_sum_[static_cast<std::size_t>(i) * static_cast<std::size_t>(nv) +
                       static_cast<std::size_t>(j)] = 0.0;
  }
  displaced_ = {};
  displaced_motion_ = 0.0;
  displaced_travel_ = 0.0;
  const bool loaded = (loads && !loads->empty()) || !forces.isZero(0.0);
  if (loaded) resting_ = false;
  if (step_idle_) {
    stepped_window_ = {};
    has_pattern_ = false;
    step_dt_ = dt;
    return LoadPreview{};
  }
  if (!step_local_) {
    if (Status s = factorize(dt); !s.ok()) return s;
  }
  const SolveRegion& region = step_local_ ? *local_ : full_;
  const PoleWindow& w = region.window;
  const int nu = stiffness_.count_u(), nv = stiffness_.count_v();
  // Poles outside a new window stop where they are: held for the stroke.
  // (Only the last solved window's poles can have a velocity.)
  if (step_local_ && !(stepped_window_ == w)) {
    const PoleWindow& last = stepped_window_;
    for (int i = last.i0; i < last.i1; ++i)
      for (int j = last.j0; j < last.j1; ++j)
        if (!w.contains(i, j)) velocities_.row(static_cast<Eigen::Index>(i) * nv + j).setZero();
  }
  stepped_window_ = w;
  has_pattern_ = loads != nullptr;
  if (has_pattern_) {
    // pattern_ is non-zero at the last pattern's poles only.
    for (const auto& entry : pattern_weights_) pattern_[entry.first] = 0.0;
    pattern_weights_ = *loads;
    for (const auto& [pole, weight] : pattern_weights_) pattern_[pole] = weight;
  }
  const Eigen::VectorXd& pattern = pattern_;
  step_dt_ = dt;
  // -K (P - P_rest) on the window's rows, which read the stencil around them.
  const PoleWindow around = w.grown(stiffness_.reach_u(), stiffness_.reach_v(), nu, nv);
  const ControlNet& points = control_points();
  for (int i = around.i0; i < around.i1; ++i) {
    const Eigen::Index r0 = static_cast<Eigen::Index>(i) * nv + around.j0;
    stretch_.middleRows(r0, around.count_v()) =
        points.middleRows(r0, around.count_v()) - rest_.middleRows(r0, around.count_v());
  }
  stiffness_.multiply_rows(stretch_, w.i0, w.i1, w.j0, w.j1, force_);
  const Eigen::Index n = static_cast<Eigen::Index>(region.order.size());
  work_.resize(n, has_pattern_ ? 4 : 3);
  for (Eigen::Index r = 0; r < n; ++r) {
    const Eigen::Index i = region.order[static_cast<std::size_t>(r)];
    if (fixed_[static_cast<std::size_t>(i)]) {
      work_.row(r).setZero();
      continue;
    }
    const double m = kMassToNewtonSecond2PerMm * masses_[i];
    for (int c = 0; c < 3; ++c) {
      double f = -force_(i, c);
      if (forces.rows() > 0) f += forces(i, c);
      work_(r, c) = m * velocities_(i, c) + dt * f;
    }
    if (has_pattern_) work_(r, 3) = pattern[i];
  }
  tie_load(work_, region.ties, region.rank);
  region.solver->solve_in_place(work_);
  untie_solution(work_, region.ties, region.rank);
  LoadPreview preview;
  if (has_pattern_) {
    for (Eigen::Index r = 0; r < n; ++r) {
      const Eigen::Index i = region.order[static_cast<std::size_t>(r)];
      if (fixed_[static_cast<std::size_t>(i)]) continue;
      preview.free_motion += dt * pattern[i] * work_.row(r).head<3>().transpose();
      preview.compliance += dt * dt * pattern[i] * work_(r, 3);
    }
  }
  return preview;
}

void DeformableBody::finish_step(const Eigen::Vector3d& pattern_force) {
  if (step_idle_) return;
  const SolveRegion& region = step_local_ ? *local_ : full_;
  const Eigen::Index n = static_cast<Eigen::Index>(region.order.size());
  const double h = step_dt_;
  ControlNet& points = points_;  // differs from the hierarchy's in the window only
  for (Eigen::Index r = 0; r < n; ++r) {
    const Eigen::Index i = region.order[static_cast<std::size_t>(r)];
    if (fixed_[static_cast<std::size_t>(i)]) continue;  // P = P_rest, V = 0 throughout
    Eigen::RowVector3d v = work_.row(r).head<3>();
    if (has_pattern_) v += h * work_(r, 3) * pattern_force.transpose();
    velocities_.row(i) = v;
    points.row(i) += h * v;
  }
  if (std::isfinite(material_.yield)) plastic_flow(points, region.window);
  const PoleWindow& w = region.window;
  hierarchy_.set_control_points_in(points, w.i0, w.i1, w.j0, w.j1);
}

}  // namespace argil
