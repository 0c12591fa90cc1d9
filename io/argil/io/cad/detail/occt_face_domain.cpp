#include "argil/io/cad/detail/occt_face_domain.hpp"

#include <BRepTools.hxx>
#include <BRep_Tool.hxx>
#include <Geom2d_Curve.hxx>
#include <TColStd_Array1OfReal.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Edge.hxx>

#include <cmath>
#include <optional>

namespace argil::io::detail {
namespace {

// Trims this close to the domain (relative to the period) are inside it:
// pcurves are computed to about 1e-9 of the domain.
constexpr double kInside = 1e-7;

double along(const gp_Pnt2d& p, bool u) { return u ? p.X() : p.Y(); }

bool closed(const Handle(Geom_BSplineSurface) & s, bool u) {
  return u ? s->IsUClosed() || s->IsUPeriodic() : s->IsVClosed() || s->IsVPeriodic();
}

// The face's seam along u (else v): the smaller parameter of a seam edge's two
// pcurves, each at one constant parameter a period apart from the other.
std::optional<double> seam_of(const TopoDS_Face& face, bool u, double period) {
  const double flat = kInside * period;
  for (TopExp_Explorer e(face, TopAbs_EDGE); e.More(); e.Next()) {
    const TopoDS_Edge& edge = TopoDS::Edge(e.Current());
    if (!BRep_Tool::IsClosed(edge, face)) continue;
    double f = 0.0, l = 0.0;
    const Handle(Geom2d_Curve) one = BRep_Tool::CurveOnSurface(edge, face, f, l);
    const Handle(Geom2d_Curve) other =
        BRep_Tool::CurveOnSurface(TopoDS::Edge(edge.Reversed()), face, f, l);
    if (one.IsNull() || other.IsNull()) continue;
    const double a = along(one->Value(f), u), b = along(other->Value(f), u);
    const bool constant = std::abs(a - along(one->Value(l), u)) <= flat &&
                          std::abs(b - along(other->Value(l), u)) <= flat;
    if (constant && std::abs(std::abs(a - b) - period) <= 1e-6 * period) return std::min(a, b);
  }
  return std::nullopt;
}

// `s` with its domain along u (else v) moved to [origin, origin + period]: made
// periodic, a knot of multiplicity degree inserted at the origin (the same
// surface, to rounding; an existing knot within kInside of a period is raised
// instead), the origin made the first knot, and the knots shifted to the face's
// parameters (by whole periods, and by at most that tolerance).
Handle(Geom_BSplineSurface)
    with_origin(const Handle(Geom_BSplineSurface) & s, bool u, double origin) {
  Handle(Geom_BSplineSurface) out = Handle(Geom_BSplineSurface)::DownCast(s->Copy());
  if (u && !out->IsUPeriodic()) out->SetUPeriodic();
  if (!u && !out->IsVPeriodic()) out->SetVPeriodic();
  double u0 = 0.0, u1 = 0.0, v0 = 0.0, v1 = 0.0;
  out->Bounds(u0, u1, v0, v1);
  const double first = u ? u0 : v0, period = u ? u1 - u0 : v1 - v0;
  double at = first + std::fmod(origin - first, period);  // inside the knot table
  if (at < first) at += period;
  const double tolerance = kInside * period;
  if (u) {
    out->InsertUKnot(at, out->UDegree(), tolerance, false);
  } else {
    out->InsertVKnot(at, out->VDegree(), tolerance, false);
  }
  const int count = u ? out->NbUKnots() : out->NbVKnots();
  int index = 1;
  for (int k = 1; k <= count; ++k) {
    const double knot = u ? out->UKnot(k) : out->VKnot(k);
    const double best = u ? out->UKnot(index) : out->VKnot(index);
    if (std::abs(knot - at) < std::abs(best - at)) index = k;
  }
  if (u) {
    out->SetUOrigin(index);
  } else {
    out->SetVOrigin(index);
  }
  TColStd_Array1OfReal knots(1, count);
  if (u) {
    out->UKnots(knots);
  } else {
    out->VKnots(knots);
  }
  const double shift = origin - knots(1);
  for (int k = 1; k <= count; ++k) knots(k) += shift;
  if (u) {
    out->SetUKnots(knots);
  } else {
    out->SetVKnots(knots);
  }
  return out;
}

}  // namespace

Handle(Geom_BSplineSurface)
    seated_on_face(const Handle(Geom_BSplineSurface) & surface, const TopoDS_Face& face) {
  Handle(Geom_BSplineSurface) seated = surface;
  double f[4] = {};  // the face's box: u0, u1, v0, v1
  BRepTools::UVBounds(face, f[0], f[1], f[2], f[3]);
  for (const bool u : {true, false}) {
    if (!closed(seated, u)) continue;
    double d[4] = {};
    seated->Bounds(d[0], d[1], d[2], d[3]);
    const double d0 = u ? d[0] : d[2], d1 = u ? d[1] : d[3];
    const double f0 = u ? f[0] : f[2], f1 = u ? f[1] : f[3];
    const double period = d1 - d0, inside = kInside * period;
    const std::optional<double> seam = seam_of(face, u, period);
    if (seam) {
      if (std::abs(*seam - d0) <= inside) continue;
      seated = with_origin(seated, u, *seam);
    } else if ((f0 < d0 - inside || f1 > d1 + inside) && f1 - f0 <= period + inside) {
      // The domain ends in the middle of the band the face leaves out (at the
      // face's start for a whole turn without a seam edge).
      seated = with_origin(seated, u, 0.5 * (f0 + f1 - period));
    }
  }
  return seated;
}

}  // namespace argil::io::detail
