#include "intersection_peers.hpp"

#include <sisl.h>
#include <GeomAPI_IntSS.hxx>
#include <Geom_Curve.hxx>
#include <Precision.hxx>

#include <algorithm>
#include <cstdlib>
#include <ctime>

#include "argil/core.hpp"
#include "bench_surfaces.hpp"
#include "bench_timing.hpp"
#include "support/polyline_distance.hpp"

namespace argil::bench {
namespace {

// Peers that return parametric curves are sampled until every chord lies
// within kChordShare * eps of the curve (at its midpoint and quarter points),
// so the sampling adds nothing visible to the error measured.
constexpr double kChordShare = 1e-3;
constexpr int kFirstIntervals = 64;
constexpr int kMaxDepth = 24;
constexpr int kMaxRuns = 7;
constexpr double kCpuBudgetMs = 1000.0;
// SISL's computational resolution: the relative rounding of doubles.
constexpr double kSislResolution = 1e-15;

// Thread CPU time: the peers run single-threaded, and the process clock
// advances only at scheduler ticks (4 ms) once RLIMIT_CPU arms the process's
// CPU timer (guarded_run), which made sub-tick runs read 0.
double cpu_ms() { return 1e-3 * thread_cpu_us(); }

/// A polynomial surface as SISL wants it: order = degree + 1, vertices with
/// the first parameter running fastest, copied (icopy = 1).
SISLSurf* to_sisl(const BSplineSurface& s) {
  const int nu = s.count(Direction::u), nv = s.count(Direction::v);
  std::vector<double> ku(s.knots[0].data(), s.knots[0].data() + s.knots[0].size());
  std::vector<double> kv(s.knots[1].data(), s.knots[1].data() + s.knots[1].size());
  std::vector<double> coef;
  coef.reserve(static_cast<std::size_t>(nu) * static_cast<std::size_t>(nv) * 3);
  for (int j = 0; j < nv; ++j)
    for (int i = 0; i < nu; ++i)
      for (int d = 0; d < 3; ++d) coef.push_back(s.control_points(s.pole_index(i, j), d));
  return newSurf(nu, nv, s.degree[0] + 1, s.degree[1] + 1, ku.data(), kv.data(), coef.data(), 1, 3,
                 1);
}

/// Adds the points of curve(t) over (t0, t1] to `line`, splitting intervals
/// whose chord is farther than `tol` from the curve.
template <class Curve>
void sample_interval(const Curve& curve, double t0, const Eigen::Vector3d& p0, double t1,
                     const Eigen::Vector3d& p1, double tol, int depth, Polyline& line) {
  const double tm = 0.5 * (t0 + t1);
  const Eigen::Vector3d pm = curve(tm);
  const bool straight = test::distance_to_segment(pm, p0, p1) <= tol &&
                        test::distance_to_segment(curve(0.5 * (t0 + tm)), p0, p1) <= tol &&
                        test::distance_to_segment(curve(0.5 * (tm + t1)), p0, p1) <= tol;
  if (straight || depth >= kMaxDepth) {
    line.push_back(p1);
    return;
  }
  sample_interval(curve, t0, p0, tm, pm, tol, depth + 1, line);
  sample_interval(curve, tm, pm, t1, p1, tol, depth + 1, line);
}

template <class Curve>
Polyline sample_curve(const Curve& curve, double t0, double t1, double tol) {
  Polyline line{curve(t0)};
  for (int k = 0; k < kFirstIntervals; ++k) {
    const double a = t0 + (t1 - t0) * k / kFirstIntervals;
    const double b = t0 + (t1 - t0) * (k + 1) / kFirstIntervals;
    sample_interval(curve, a, line.back(), b, curve(b), tol, 0, line);
  }
  return line;
}

Polyline sample_sisl_curve(SISLCurve* c, double tol) {
  const auto at = [c](double t) {
    int left = 0, status = 0;
    double p[3];
    s1221(c, 0, t, &left, p, &status);
    return Eigen::Vector3d(p[0], p[1], p[2]);
  };
  return sample_curve(at, c->et[c->ik - 1], c->et[c->in], tol);
}

/// One SISL run: s1859 then s1310 on every curve; curves whose marching
/// failed keep their guide points' parameters evaluated on a.
PeerOutput sisl_once(SISLSurf* a, SISLSurf* b, double eps, bool keep) {
  PeerOutput out;
  int points = 0, curves = 0, status = 0;
  double *par_a = nullptr, *par_b = nullptr;
  SISLIntcurve** list = nullptr;
  s1859(a, b, kSislResolution, eps, &points, &par_a, &par_b, &curves, &list, &status);
  out.curves = status < 0 ? -1 : curves;
  for (int k = 0; k < curves; ++k) {
    int march = 0;
    // icur = 1: make the 3D curve; amax = 0: no extra step limit; igraph = 0.
    s1310(a, b, list[k], eps, 0.0, 1, 0, &march);
    if (!keep) continue;
    if (march >= 0 && list[k]->pgeom) {
      out.polylines.push_back(sample_sisl_curve(list[k]->pgeom, kChordShare * eps));
    } else {
      Polyline guide;
      for (int g = 0; g < list[k]->ipoint; ++g) {
        int left_u = 0, left_v = 0, st = 0;
        double p[3];
        s1424(a, 0, 0, &list[k]->epar1[2 * g], &left_u, &left_v, p, &st);
        guide.emplace_back(p[0], p[1], p[2]);
      }
      out.polylines.push_back(guide);
    }
  }
  std::free(par_a);
  std::free(par_b);
  if (list) freeIntcrvlist(list, curves);
  return out;
}

PeerOutput occt_once(const Handle(Geom_BSplineSurface) & a, const Handle(Geom_BSplineSurface) & b,
                     double eps, bool keep) {
  PeerOutput out;
  GeomAPI_IntSS x(a, b, eps);
  out.curves = x.IsDone() ? x.NbLines() : -1;
  if (!keep || !x.IsDone()) return out;
  for (int i = 1; i <= x.NbLines(); ++i) {
    const Handle(Geom_Curve) line = x.Line(i);
    const double t0 = line->FirstParameter(), t1 = line->LastParameter();
    if (Precision::IsInfinite(t0) || Precision::IsInfinite(t1)) continue;
    const auto at = [&line](double t) {
      const gp_Pnt p = line->Value(t);
      return Eigen::Vector3d(p.X(), p.Y(), p.Z());
    };
    out.polylines.push_back(sample_curve(at, t0, t1, kChordShare * eps));
  }
  return out;
}

PeerOutput argil_result(const CollisionResult& r) {
  PeerOutput out;
  out.curves = r.status.ok() ? static_cast<int>(r.curves.size()) : -1;
  for (const IntersectionCurve& c : r.curves) out.polylines.push_back(c.points);
  return out;
}

/// Runs `once(keep)` until kMaxRuns or the CPU budget, timing each run;
/// only the last run converts its curves (keep = true).
template <class Once>
PeerOutput timed(Once once) {
  std::vector<double> times;
  PeerOutput out;
  double spent = 0.0;
  while (static_cast<int>(times.size()) < kMaxRuns && spent < kCpuBudgetMs) {
    const bool last = static_cast<int>(times.size()) + 1 == kMaxRuns;
    const double t0 = cpu_ms();
    PeerOutput run = once(last);
    const double dt = cpu_ms() - t0;
    times.push_back(dt);
    spent += dt;
    if (last || spent >= kCpuBudgetMs) {
      if (!last) run = once(true);  // the curves of one more run, untimed
      out = std::move(run);
    }
  }
  out.cpu_ms = median(times);
  out.runs = static_cast<int>(times.size());
  return out;
}

}  // namespace

std::string peer_name(Peer peer) {
  switch (peer) {
    case Peer::argil_cold:
      return "argil";
    case Peer::argil_warm:
      return "argil-warm";
    case Peer::occt:
      return "occt";
    case Peer::sisl:
      return "sisl";
  }
  return "?";
}

std::vector<double> PeerOutput::to_payload() const {
  std::vector<double> p{cpu_ms, static_cast<double>(runs), static_cast<double>(curves),
                        static_cast<double>(polylines.size())};
  for (const Polyline& line : polylines) {
    p.push_back(static_cast<double>(line.size()));
    for (const Eigen::Vector3d& q : line) p.insert(p.end(), {q.x(), q.y(), q.z()});
  }
  return p;
}

PeerOutput PeerOutput::from_payload(const std::vector<double>& p) {
  PeerOutput out;
  if (p.size() < 4) return out;
  out.cpu_ms = p[0];
  out.runs = static_cast<int>(p[1]);
  out.curves = static_cast<int>(p[2]);
  std::size_t at = 4;
  for (int k = 0; k < static_cast<int>(p[3]) && at < p.size(); ++k) {
    const auto n = static_cast<std::size_t>(p[at++]);
    Polyline line;
    for (std::size_t i = 0; i < n && at + 2 < p.size(); ++i, at += 3)
      line.emplace_back(p[at], p[at + 1], p[at + 2]);
    out.polylines.push_back(std::move(line));
  }
  return out;
}

PeerOutput run_peer(Peer peer, const BSplineSurface& a, const BSplineSurface& b, double eps) {
  const CollisionRequest request{.tolerance = eps, .refine = true};
  switch (peer) {
    case Peer::argil_cold:
      return timed([&](bool) {
        OperatorCache cache;
        const SurfaceHierarchy ha = SurfaceHierarchy::build(a, cache).value();
        const SurfaceHierarchy hb = SurfaceHierarchy::build(b, cache).value();
        return argil_result(collide(ha, hb, request));
      });
    case Peer::argil_warm: {
      // Every run moves every pole (the pair and the pair shifted together
      // by 1e-3 of a's size, in turn: the same intersection), so each node
      // reached recomputes its Bezier net and bounds; the topology stays.
      OperatorCache cache;
      SurfaceHierarchy ha = SurfaceHierarchy::build(a, cache).value();
      SurfaceHierarchy hb = SurfaceHierarchy::build(b, cache).value();
      const Eigen::RowVector3d shift(1e-3 * control_point_box(a).diagonal(), 0.0, 0.0);
      const ControlNet na[2] = {a.control_points.rowwise() + shift, a.control_points};
      const ControlNet nb[2] = {b.control_points.rowwise() + shift, b.control_points};
      (void)collide(ha, hb, request);  // the first query builds the levels it needs
      int turn = 0;
      return timed([&](bool) {
        turn = 1 - turn;
        ha.set_control_points(na[turn]);
        hb.set_control_points(nb[turn]);
        PeerOutput out = argil_result(collide(ha, hb, request));
        // The last kept run may be the shifted pair: report it in place.
        if (turn == 0)
          for (Polyline& line : out.polylines)
            for (Eigen::Vector3d& q : line) q -= shift.transpose();
        return out;
      });
    }
    case Peer::occt: {
      const Handle(Geom_BSplineSurface) oa = to_occt(a);
      const Handle(Geom_BSplineSurface) ob = to_occt(b);
      return timed([&](bool keep) { return occt_once(oa, ob, eps, keep); });
    }
    case Peer::sisl: {
      SISLSurf* sa = to_sisl(a);
      SISLSurf* sb = to_sisl(b);
      PeerOutput out = timed([&](bool keep) { return sisl_once(sa, sb, eps, keep); });
      freeSurf(sa);
      freeSurf(sb);
      return out;
    }
  }
  return {};
}

}  // namespace argil::bench
