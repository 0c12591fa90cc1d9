#include "intersection_oracle.hpp"

#include <GeomAPI_ProjectPointOnSurf.hxx>
#include <GeomInt_IntSS.hxx>
#include <Geom_Curve.hxx>
#include <Precision.hxx>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>

#include "bench_surfaces.hpp"

namespace argil::bench {

GraphSurface::GraphSurface(const BSplineSurface& surface) : s(to_occt(surface)) {
  s->Bounds(u0, u1, v0, v1);
}

double GraphSurface::invert(int axis, double value) const {
  double lo = axis == 0 ? u0 : v0, hi = axis == 0 ? u1 : v1;
  const auto coordinate = [&](double t) {
    const gp_Pnt p = axis == 0 ? s->Value(t, v0) : s->Value(u0, t);
    return axis == 0 ? p.X() : p.Y();
  };
  const bool rising = coordinate(hi) > coordinate(lo);
  for (int k = 0; k < 64 && hi - lo > 0.0; ++k) {
    const double mid = 0.5 * (lo + hi);
    if ((coordinate(mid) < value) == rising)
      lo = mid;
    else
      hi = mid;
  }
  return 0.5 * (lo + hi);
}

SurfaceDistance::SurfaceDistance(const BSplineSurface& a, const BSplineSurface& b, bool graphs) {
  const BSplineSurface* sides[2] = {&a, &b};
  for (int k = 0; k < 2; ++k) {
    const Handle(Geom_BSplineSurface) o = to_occt(*sides[k]);
    double u0, u1, v0, v1;
    o->Bounds(u0, u1, v0, v1);
    project_[k].Init(o, u0, u1, v0, v1, Precision::Confusion());
    if (graphs) graphs_.emplace_back(*sides[k]);
  }
}

double SurfaceDistance::to(int side, const Eigen::Vector3d& p) {
  GeomAPI_ProjectPointOnSurf& projection = project_[side];
  projection.Perform(gp_Pnt(p.x(), p.y(), p.z()));
  double d = projection.NbPoints() > 0 ? projection.LowerDistance() : HUGE_VAL;
  if (!graphs_.empty()) {
    const GraphSurface& g = graphs_[static_cast<std::size_t>(side)];
    const gp_Pnt lo = g.s->Value(g.u0, g.v0), hi = g.s->Value(g.u1, g.v1);
    const bool inside = p.x() >= std::min(lo.X(), hi.X()) && p.x() <= std::max(lo.X(), hi.X()) &&
                        p.y() >= std::min(lo.Y(), hi.Y()) && p.y() <= std::max(lo.Y(), hi.Y());
    if (inside) {
      const gp_Pnt q = g.s->Value(g.invert(0, p.x()), g.invert(1, p.y()));
      d = std::min(d, std::abs(p.z() - q.Z()));
    }
  }
  return d;
}

double SurfaceDistance::worst(const std::vector<Polyline>& lines) {
  std::size_t total = 0;
  for (const Polyline& l : lines) total += l.size();
  const std::size_t stride = std::max<std::size_t>(1, total / 2000);
  double worst = 0.0;
  std::size_t k = 0;
  for (const Polyline& l : lines)
    for (const Eigen::Vector3d& q : l)
      if (k++ % stride == 0) worst = std::max({worst, to(0, q), to(1, q)});
  return worst;
}

namespace {

struct UnionFind {
  std::vector<int> parent;
  explicit UnionFind(std::size_t n) : parent(n) { std::iota(parent.begin(), parent.end(), 0); }
  int find(int i) {
    while (parent[static_cast<std::size_t>(i)] != i)
      i = parent[static_cast<std::size_t>(i)] =
          parent[static_cast<std::size_t>(parent[static_cast<std::size_t>(i)])];
    return i;
  }
  void join(int i, int j) { parent[static_cast<std::size_t>(find(i))] = find(j); }
};

}  // namespace

OracleCurves graph_oracle(const BSplineSurface& a, const BSplineSurface& b, int grid,
                          bool samples) {
  const GraphSurface ga(a), gb(b);
  // The common square: where both graphs are defined.
  const double x0 = std::max(ga.s->Value(ga.u0, ga.v0).X(), gb.s->Value(gb.u0, gb.v0).X());
  const double x1 = std::min(ga.s->Value(ga.u1, ga.v0).X(), gb.s->Value(gb.u1, gb.v0).X());
  const double y0 = std::max(ga.s->Value(ga.u0, ga.v0).Y(), gb.s->Value(gb.u0, gb.v0).Y());
  const double y1 = std::min(ga.s->Value(ga.u0, ga.v1).Y(), gb.s->Value(gb.u0, gb.v1).Y());
  if (!(x1 > x0 && y1 > y0)) throw std::runtime_error("graph oracle: the graphs do not overlap");
  const int n = grid + 1;
  const auto at = [](double lo, double hi, int i, int count) {
    return lo + (hi - lo) * i / (count - 1);
  };
  // Parameters of each grid line on each surface.
  std::vector<double> ua(n), va(n), ub(n), vb(n);
  for (int i = 0; i < n; ++i) {
    ua[static_cast<std::size_t>(i)] = ga.invert(0, at(x0, x1, i, n));
    ub[static_cast<std::size_t>(i)] = gb.invert(0, at(x0, x1, i, n));
    va[static_cast<std::size_t>(i)] = ga.invert(1, at(y0, y1, i, n));
    vb[static_cast<std::size_t>(i)] = gb.invert(1, at(y0, y1, i, n));
  }
  const auto z_gap = [&](double ua_, double va_, double ub_, double vb_) {
    return ga.s->Value(ua_, va_).Z() - gb.s->Value(ub_, vb_).Z();
  };
  std::vector<double> f(static_cast<std::size_t>(n) * static_cast<std::size_t>(n));
  const auto node = [n](int i, int j) {
    return static_cast<std::size_t>(i) * static_cast<std::size_t>(n) + static_cast<std::size_t>(j);
  };
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      f[node(i, j)] = z_gap(ua[static_cast<std::size_t>(i)], va[static_cast<std::size_t>(j)],
                            ub[static_cast<std::size_t>(i)], vb[static_cast<std::size_t>(j)]);

  OracleCurves out;
  out.method = "brute force, " + std::to_string(grid) + "^2 grid";
  const int cells = grid * grid;
  UnionFind components(static_cast<std::size_t>(cells));
  std::vector<bool> crossed(static_cast<std::size_t>(cells), false);
  const auto cell = [grid](int i, int j) { return i * grid + j; };
  const auto positive = [](double v) { return v >= 0.0; };
  // Edge (i, j) -> (i + di, j + dj) crosses: solve where (regula falsi,
  // Illinois) and keep the point as a sample.
  const auto solve = [&](int i, int j, int di, int dj) {
    const bool along_x = di == 1;
    const double fixed = along_x ? at(y0, y1, j, n) : at(x0, x1, i, n);
    double lo = along_x ? at(x0, x1, i, n) : at(y0, y1, j, n);
    double hi = along_x ? at(x0, x1, i + 1, n) : at(y0, y1, j + 1, n);
    const auto gap = [&](double t) {
      return along_x ? z_gap(ga.invert(0, t), va[static_cast<std::size_t>(j)], gb.invert(0, t),
                             vb[static_cast<std::size_t>(j)])
                     : z_gap(ua[static_cast<std::size_t>(i)], ga.invert(1, t),
                             ub[static_cast<std::size_t>(i)], gb.invert(1, t));
    };
    double flo = f[node(i, j)], fhi = f[node(i + di, j + dj)];
    double t = lo;
    for (int k = 0; k < 40 && hi - lo > 1e-15 * (std::abs(hi) + 1.0); ++k) {
      t = std::clamp(hi - fhi * (hi - lo) / (fhi - flo), lo, hi);
      const double ft = gap(t);
      if (ft == 0.0) break;
      if (positive(ft) == positive(fhi)) {
        hi = t;
        fhi = ft;
        flo *= 0.5;
      } else {
        lo = t;
        flo = ft;
        fhi *= 0.5;
      }
    }
    const double x = along_x ? t : fixed, y = along_x ? fixed : t;
    const gp_Pnt p = ga.s->Value(ga.invert(0, x), ga.invert(1, y));
    out.samples.emplace_back(p.X(), p.Y(), p.Z());
  };
  // Edge (i, j) -> (i + di, j + dj): where it crosses, join the cells on
  // both sides.
  const auto edge = [&](int i, int j, int di, int dj) {
    if (positive(f[node(i, j)]) == positive(f[node(i + di, j + dj)])) return;
    const bool along_x = di == 1;
    if (samples) solve(i, j, di, dj);
    // The cells on either side of the edge (one at the square's border).
    std::vector<int> sides;
    if (along_x) {
      if (j > 0) sides.push_back(cell(i, j - 1));
      if (j < grid) sides.push_back(cell(i, j));
    } else {
      if (i > 0) sides.push_back(cell(i - 1, j));
      if (i < grid) sides.push_back(cell(i, j));
    }
    for (int s : sides) crossed[static_cast<std::size_t>(s)] = true;
    if (sides.size() == 2) components.join(sides[0], sides[1]);
  };
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      if (i + 1 < n) edge(i, j, 1, 0);
      if (j + 1 < n) edge(i, j, 0, 1);
    }
  std::vector<int> roots;
  for (int c = 0; c < cells; ++c)
    if (crossed[static_cast<std::size_t>(c)]) roots.push_back(components.find(c));
  std::sort(roots.begin(), roots.end());
  out.components = static_cast<int>(std::unique(roots.begin(), roots.end()) - roots.begin());
  if (samples) out.residual = SurfaceDistance(a, b, true).worst({out.samples});
  return out;
}

OracleCurves occt_oracle(const BSplineSurface& a, const BSplineSurface& b, double size) {
  OracleCurves out;
  out.method = "OpenCASCADE GeomInt_IntSS at 1e-10 of the size";
  GeomInt_IntSS x(to_occt(a), to_occt(b), 1e-10 * size);
  if (!x.IsDone()) throw std::runtime_error("OCCT oracle: GeomInt_IntSS failed");
  std::vector<std::pair<Eigen::Vector3d, Eigen::Vector3d>> ends;
  for (int i = 1; i <= x.NbLines(); ++i) {
    const Handle(Geom_Curve)& line = x.Line(i);
    const double t0 = line->FirstParameter(), t1 = line->LastParameter();
    if (Precision::IsInfinite(t0) || Precision::IsInfinite(t1)) continue;
    constexpr int kSamples = 4000;
    for (int k = 0; k <= kSamples; ++k) {
      const gp_Pnt p = line->Value(t0 + (t1 - t0) * k / kSamples);
      out.samples.emplace_back(p.X(), p.Y(), p.Z());
    }
    ends.emplace_back(out.samples[out.samples.size() - kSamples - 1], out.samples.back());
  }
  // Lines whose ends meet (within 1e-6 of the size) are pieces of one curve.
  UnionFind components(ends.size());
  const double join = 1e-6 * size;
  for (std::size_t i = 0; i < ends.size(); ++i)
    for (std::size_t j = i + 1; j < ends.size(); ++j)
      for (const Eigen::Vector3d& p : {ends[i].first, ends[i].second})
        for (const Eigen::Vector3d& q : {ends[j].first, ends[j].second})
          if ((p - q).norm() <= join) components.join(static_cast<int>(i), static_cast<int>(j));
  std::vector<int> roots;
  for (std::size_t i = 0; i < ends.size(); ++i)
    roots.push_back(components.find(static_cast<int>(i)));
  std::sort(roots.begin(), roots.end());
  out.components = static_cast<int>(std::unique(roots.begin(), roots.end()) - roots.begin());
  out.residual = SurfaceDistance(a, b, false).worst({out.samples});
  return out;
}

}  // namespace argil::bench
