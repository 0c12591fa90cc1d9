#include "argil/io/cad/detail/occt_pcurve.hpp"

#include <BRep_Tool.hxx>
#include <Geom2dConvert.hxx>
#include <Geom2d_BSplineCurve.hxx>
#include <Geom2d_TrimmedCurve.hxx>
#include <TColStd_Array1OfReal.hxx>

namespace argil::io::detail {
namespace {

BSplineCurve to_argil(const Handle(Geom2d_BSplineCurve) & c) {
  BSplineCurve out;
  out.degree = c->Degree();
  TColStd_Array1OfReal knots(1, c->NbPoles() + c->Degree() + 1);
  c->KnotSequence(knots);
  out.knots.resize(knots.Length());
  for (int k = knots.Lower(); k <= knots.Upper(); ++k) out.knots[k - knots.Lower()] = knots(k);
  out.points.resize(c->NbPoles(), 2);
  for (int i = 1; i <= c->NbPoles(); ++i) {
    out.points.row(i - 1) << c->Pole(i).X(), c->Pole(i).Y();
  }
  if (c->IsRational()) {
    out.weights.resize(c->NbPoles());
    for (int i = 1; i <= c->NbPoles(); ++i) out.weights[i - 1] = c->Weight(i);
  }
  return out;
}

}  // namespace

Result<BSplineCurve> edge_pcurve(const TopoDS_Edge& edge, const TopoDS_Face& face,
                                 PcurveDirection direction) {
  double first = 0.0, last = 0.0;
  const Handle(Geom2d_Curve) pcurve = BRep_Tool::CurveOnSurface(edge, face, first, last);
  if (pcurve.IsNull()) {
    return Status::error(StatusCode::unsupported, "edge without a parameter-space curve");
  }
  Handle(Geom2d_BSplineCurve) bspline = Handle(Geom2d_BSplineCurve)::DownCast(pcurve);
  if (bspline.IsNull() || bspline->FirstParameter() != first || bspline->LastParameter() != last) {
    bspline = Geom2dConvert::CurveToBSplineCurve(new Geom2d_TrimmedCurve(pcurve, first, last));
  } else {
    bspline = Handle(Geom2d_BSplineCurve)::DownCast(bspline->Copy());
  }
  if (bspline->IsPeriodic()) bspline->SetNotPeriodic();
  const int degree = bspline->Degree();
  if (bspline->Multiplicity(1) <= degree || bspline->Multiplicity(bspline->NbKnots()) <= degree) {
    // Unclamped ends: segmenting to the full range clamps them, same curve.
    bspline->Segment(bspline->FirstParameter(), bspline->LastParameter());
  }
  if (direction == PcurveDirection::wire && edge.Orientation() == TopAbs_REVERSED) {
    bspline->Reverse();
  }
  return to_argil(bspline);
}

}  // namespace argil::io::detail
