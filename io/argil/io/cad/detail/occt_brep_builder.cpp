#include "argil/io/cad/detail/occt_brep_builder.hpp"

#include <BRepLib.hxx>
#include <BRep_Builder.hxx>
#include <BRep_Tool.hxx>
#include <Geom2dAPI_Interpolate.hxx>
#include <Precision.hxx>
#include <Standard_Failure.hxx>
#include <TColStd_Array1OfReal.hxx>
#include <TColStd_HArray1OfReal.hxx>
#include <TColgp_HArray1OfPnt2d.hxx>
#include <TopLoc_Location.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Compound.hxx>
#include <TopoDS_Edge.hxx>
#include <TopoDS_Shell.hxx>
#include <TopoDS_Solid.hxx>
#include <TopoDS_Vertex.hxx>
#include <TopoDS_Wire.hxx>

#include <algorithm>
#include <map>
#include <string>

#include "argil/io/cad/detail/occt_face_builder.hpp"
#include "argil/io/cad/detail/occt_geometry.hpp"

namespace argil::io::detail {
namespace {

// Samples along a degenerated edge's pcurve whose images its vertex must cover.
constexpr int kDegenerateSamples = 16;

// The fewest points along an edge at which a pcurve is paced to its 3D curve.
constexpr int kPaceSamples = 64;

// The pcurve mapped affinely onto [first, last]: the same image, the knots
// moved (a use read from another face may run over another range).
Handle(Geom2d_BSplineCurve) on_range(const BSplineCurve& pcurve, double first, double last) {
  Handle(Geom2d_BSplineCurve) curve = to_occt(pcurve);
  const double a = curve->FirstParameter(), b = curve->LastParameter();
  if (a == first && b == last) return curve;
  TColStd_Array1OfReal knots(1, curve->NbKnots());
  curve->Knots(knots);
  for (int k = knots.Lower(); k <= knots.Upper(); ++k) {
    knots(k) = k == knots.Lower()   ? first
               : k == knots.Upper() ? last
                                    : first + (knots(k) - a) * (last - first) / (b - a);
  }
  curve->SetKnots(knots);
  return curve;
}

gp_Pnt on_surface(const Handle(Geom_BSplineSurface) & surface, const Handle(Geom2d_Curve) & curve,
                  double t) {
  const gp_Pnt2d uv = curve->Value(t);
  return surface->Value(uv.X(), uv.Y());
}

// The parameter of `curve` on `surface` nearest to `target`, by Gauss-Newton
// from `guess`, kept within [low, high].
double nearest_parameter(const Handle(Geom_BSplineSurface) & surface,
                         const Handle(Geom2d_Curve) & curve, const gp_Pnt& target, double guess,
                         double low, double high) {
  double s = guess;
  for (int iteration = 0; iteration < 20; ++iteration) {
    gp_Pnt2d uv;
    gp_Vec2d duv;
    curve->D1(s, uv, duv);
    gp_Pnt p;
    gp_Vec su, sv;
    surface->D1(uv.X(), uv.Y(), p, su, sv);
    const gp_Vec tangent = su * duv.X() + sv * duv.Y();
    const double squared = tangent.SquareMagnitude();
    if (squared <= 0.0) break;
    const double step = gp_Vec(target, p).Dot(tangent) / squared;
    const double next = std::clamp(s - step, low, high);
    if (std::abs(next - s) <= 1e-14 * (std::abs(s) + 1.0)) return next;
    s = next;
  }
  return s;
}

class BrepBuilder {
 public:
  BrepBuilder(const Model& model, double tolerance) : model_(model), tolerance_(tolerance) {
    for (const FaceRecord& face : model.faces) surfaces_.push_back(to_occt(face.surface));
  }

  Result<BuiltBrep> build() {
    make_vertices();
    const Topology& t = model_.topology;
    for (std::size_t e = 0; e < t.edges.size(); ++e) {
      Result<TopoDS_Edge> edge = Status::error(StatusCode::invalid_surface, "");
      try {
        edge = make_edge(t.edges[e]);
      } catch (const Standard_Failure& failure) {
        edge = Status::error(StatusCode::invalid_surface, std::string("OpenCASCADE failed: ") +
                                                              failure.GetMessageString() + " (" +
                                                              failure.DynamicType()->Name() + ")");
      }
      if (!edge.ok()) {
        return Status::error(edge.status().code,
                             "edge " + std::to_string(e) + ": " + edge.status().message);
      }
      edges_.push_back(edge.value());
    }
    BuiltBrep out;
    for (std::size_t f = 0; f < model_.faces.size(); ++f) out.faces.push_back(make_face(f));
    // Per face: an edge's tolerance covers each of its pcurves on its surface.
    for (const TopoDS_Face& face : out.faces) update_tolerances(face, tolerance_);
    BRep_Builder builder;
    TopoDS_Compound all;
    builder.MakeCompound(all);
    for (const TopoDS_Face& face : out.faces) builder.Add(all, face);
    BRepLib::UpdateTolerances(all);
    assemble(out);
    out.edges = edges_;
    return out;
  }

 private:
  // Every vertex at the mean of its uses' end points, with a tolerance
  // covering them all.
  void make_vertices() {
    const Topology& t = model_.topology;
    std::vector<std::vector<gp_Pnt>> reached(t.vertices.size());
    for (const Edge& edge : t.edges) {
      for (const EdgeUse& use : edge.uses) {
        const Handle(Geom2d_BSplineCurve) pcurve = to_occt(use.pcurve);
        const Handle(Geom_BSplineSurface)& surface = surfaces_[use.face];
        const double t0 = pcurve->FirstParameter(), t1 = pcurve->LastParameter();
        if (edge.start != kNoIndex) reached[edge.start].push_back(on_surface(surface, pcurve, t0));
        if (edge.end != kNoIndex) reached[edge.end].push_back(on_surface(surface, pcurve, t1));
        if (edge.degenerate && edge.start != kNoIndex) {
          for (int k = 1; k < kDegenerateSamples; ++k) {
            const double at = t0 + (t1 - t0) * k / kDegenerateSamples;
            reached[edge.start].push_back(on_surface(surface, pcurve, at));
          }
        }
      }
    }
    BRep_Builder builder;
    for (std::size_t v = 0; v < t.vertices.size(); ++v) {
      gp_XYZ mean(t.vertices[v].point.x(), t.vertices[v].point.y(), t.vertices[v].point.z());
      if (!reached[v].empty()) {
        mean = gp_XYZ(0.0, 0.0, 0.0);
        for (const gp_Pnt& p : reached[v]) mean += p.XYZ();
        mean /= static_cast<double>(reached[v].size());
      }
      double spread = 0.0;
      for (const gp_Pnt& p : reached[v]) spread = std::max(spread, p.Distance(gp_Pnt(mean)));
      TopoDS_Vertex vertex;
      // Margin for the rounding of the checker's own evaluation.
      builder.MakeVertex(vertex, gp_Pnt(mean), std::max(tolerance_, spread * (1.0 + 1e-6)));
      vertices_.push_back(vertex);
    }
  }

  // The use's pcurve running at the pace of the reference points (the edge's
  // 3D curve at params[i]): as read, mapped affinely onto the edge's range,
  // when it stays within the tolerance; else re-parametrised through the
  // nearest points to the reference ones (a circle converted to a rational
  // B-spline on one face runs at another pace than on its neighbour: 1.3 mm
  // apart at one parameter on 11752.stp) and interpolated.
  Handle(Geom2d_BSplineCurve) paced(const EdgeUse& use, const std::vector<double>& params,
                                    const std::vector<gp_Pnt>& points) const {
    const double first = params.front(), last = params.back();
    const Handle(Geom2d_BSplineCurve) mapped = on_range(use.pcurve, first, last);
    const Handle(Geom_BSplineSurface)& surface = surfaces_[use.face];
    double gap = 0.0;
    for (std::size_t i = 0; i < params.size(); ++i) {
      gap = std::max(gap, points[i].Distance(on_surface(surface, mapped, params[i])));
    }
    if (gap <= tolerance_) return mapped;
    const int n = static_cast<int>(params.size());
    const Handle(TColgp_HArray1OfPnt2d) uv = new TColgp_HArray1OfPnt2d(1, n);
    const Handle(TColStd_HArray1OfReal) at = new TColStd_HArray1OfReal(1, n);
    double s = first;
    for (int i = 0; i < n; ++i) {
      const std::size_t k = static_cast<std::size_t>(i);
      if (i == n - 1) {
        s = last;
      } else if (i > 0) {
        s = nearest_parameter(surface, mapped, points[k], s + (params[k] - params[k - 1]), s, last);
      }
      uv->SetValue(i + 1, mapped->Value(s));
      at->SetValue(i + 1, params[k]);
    }
    // Where no interpolant exists (points that coincide on a crumpled face),
    // the tolerance covers the pace instead.
    try {
      Geom2dAPI_Interpolate interpolate(uv, at, false, Precision::PConfusion());
      interpolate.Perform();
      return interpolate.IsDone() ? interpolate.Curve() : mapped;
    } catch (const Standard_Failure&) {
      return mapped;
    }
  }

  // The edge with every use's pcurve; a face using it twice (a seam) gives
  // both pcurves at once, the one its loop runs along first.
  Result<TopoDS_Edge> make_edge(const Edge& edge) {
    BRep_Builder builder;
    TopoDS_Edge out;
    builder.MakeEdge(out);
    const Handle(Geom2d_BSplineCurve) reference = to_occt(edge.uses.front().pcurve);
    const double first = reference->FirstParameter(), last = reference->LastParameter();
    // The reference points every other pcurve is paced to.
    const int samples = std::max(kPaceSamples, 4 * reference->NbPoles());
    std::vector<double> params;
    std::vector<gp_Pnt> points;
    const Handle(Geom_BSplineSurface)& reference_surface = surfaces_[edge.uses.front().face];
    for (int i = 0; i <= samples; ++i) {
      params.push_back(i == samples ? last : first + (last - first) * i / samples);
      points.push_back(on_surface(reference_surface, reference, params.back()));
    }
    const auto pcurve = [&](const EdgeUse& use) -> Handle(Geom2d_BSplineCurve) {
      if (&use == &edge.uses.front() || edge.degenerate) return on_range(use.pcurve, first, last);
      return paced(use, params, points);
    };
    std::map<std::size_t, std::vector<const EdgeUse*>> by_face;
    for (const EdgeUse& use : edge.uses) by_face[use.face].push_back(&use);
    // The reference use's face first: BuildCurve3d approximates from the first pcurve.
    std::vector<std::size_t> order{edge.uses.front().face};
    for (const auto& [face, uses] : by_face) {
      if (face != order.front()) order.push_back(face);
    }
    for (const std::size_t face : order) {
      const std::vector<const EdgeUse*>& uses = by_face[face];
      const TopLoc_Location here;
      if (uses.size() == 2) {
        const EdgeUse& along = uses[0]->along ? *uses[0] : *uses[1];
        const EdgeUse& against = uses[0]->along ? *uses[1] : *uses[0];
        builder.UpdateEdge(out, pcurve(along), pcurve(against), surfaces_[face], here, tolerance_);
      } else if (uses.size() == 1) {
        builder.UpdateEdge(out, pcurve(*uses[0]), surfaces_[face], here, tolerance_);
      } else {
        return Status::error(StatusCode::invalid_surface,
                             "face " + std::to_string(face) + " uses it " +
                                 std::to_string(uses.size()) + " times (at most twice, a seam)");
      }
    }
    const TopoDS_Vertex start = edge.start == kNoIndex ? TopoDS_Vertex() : vertices_[edge.start];
    const TopoDS_Vertex end = edge.end == kNoIndex ? TopoDS_Vertex() : vertices_[edge.end];
    if (!start.IsNull()) builder.Add(out, start.Oriented(TopAbs_FORWARD));
    if (!end.IsNull()) builder.Add(out, end.Oriented(TopAbs_REVERSED));
    builder.Range(out, first, last);
    if (edge.degenerate) {
      builder.Degenerated(out, true);
      return out;
    }
    // Not BRepLib::SameParameter: it opened a closed pcurve of 11752.stp.
    if (!BRepLib::BuildCurve3d(out, tolerance_)) {
      return Status::error(StatusCode::invalid_surface, "no 3D curve could be approximated");
    }
    return out;
  }

  // The face's wires from its uses, loop by loop in curve order.
  TopoDS_Face make_face(std::size_t f) {
    const Topology& t = model_.topology;
    std::map<std::size_t, std::map<std::size_t, TopoDS_Edge>> loops;
    for (std::size_t e = 0; e < t.edges.size(); ++e) {
      for (const EdgeUse& use : t.edges[e].uses) {
        if (use.face != f) continue;
        loops[use.loop][use.curve] =
            TopoDS::Edge(edges_[e].Oriented(use.along ? TopAbs_FORWARD : TopAbs_REVERSED));
      }
    }
    BRep_Builder builder;
    TopoDS_Face face;
    builder.MakeFace(face, surfaces_[f], TopLoc_Location(), tolerance_);
    for (const auto& [loop, curves] : loops) {
      TopoDS_Wire wire;
      builder.MakeWire(wire);
      for (const auto& [curve, edge] : curves) builder.Add(wire, edge);
      wire.Closed(true);
      builder.Add(face, wire);
    }
    if (model_.faces[f].reversed) face.Reverse();
    return face;
  }

  // Shells, solids, and the products that hold them.
  void assemble(BuiltBrep& out) const {
    const Topology& t = model_.topology;
    BRep_Builder builder;
    std::vector<TopoDS_Shell> shells(t.shells.size());
    std::vector<char> face_held(model_.faces.size(), 0), shell_held(t.shells.size(), 0),
        solid_held(t.solids.size(), 0);
    for (std::size_t s = 0; s < t.shells.size(); ++s) {
      builder.MakeShell(shells[s]);
      for (const std::size_t f : t.shells[s].faces) {
        builder.Add(shells[s], out.faces[f]);
        face_held[f] = 1;
      }
      shells[s].Closed(BRep_Tool::IsClosed(shells[s]));
    }
    std::vector<TopoDS_Solid> solids(t.solids.size());
    for (std::size_t s = 0; s < t.solids.size(); ++s) {
      builder.MakeSolid(solids[s]);
      for (const std::size_t shell : t.solids[s].shells) {
        builder.Add(solids[s], shells[shell]);
        shell_held[shell] = 1;
      }
    }
    const auto compound = [&](const std::vector<std::size_t>& solid_list,
                              const std::vector<std::size_t>& shell_list,
                              const std::vector<std::size_t>& face_list) {
      TopoDS_Compound c;
      if (solid_list.empty() && shell_list.empty() && face_list.empty()) return c;
      builder.MakeCompound(c);
      for (const std::size_t s : solid_list) builder.Add(c, solids[s]);
      for (const std::size_t s : shell_list) builder.Add(c, shells[s]);
      for (const std::size_t f : face_list) builder.Add(c, out.faces[f]);
      return c;
    };
    std::vector<char> solid_in_product(t.solids.size(), 0), shell_in_product(t.shells.size(), 0),
        face_in_product(model_.faces.size(), 0);
    for (const Product& p : t.products) {
      out.products.push_back(compound(p.solids, p.shells, p.faces));
      for (const std::size_t s : p.solids) solid_in_product[s] = 1;
      for (const std::size_t s : p.shells) shell_in_product[s] = 1;
      for (const std::size_t f : p.faces) face_in_product[f] = 1;
    }
    std::vector<std::size_t> solid_rest, shell_rest, face_rest;
    for (std::size_t s = 0; s < t.solids.size(); ++s) {
      if (solid_in_product[s] == 0) solid_rest.push_back(s);
    }
    for (std::size_t s = 0; s < t.shells.size(); ++s) {
      if (shell_in_product[s] == 0 && shell_held[s] == 0) shell_rest.push_back(s);
    }
    for (std::size_t f = 0; f < model_.faces.size(); ++f) {
      if (face_in_product[f] == 0 && face_held[f] == 0) face_rest.push_back(f);
    }
    out.unheld = compound(solid_rest, shell_rest, face_rest);
  }

  const Model& model_;
  const double tolerance_;
  std::vector<Handle(Geom_BSplineSurface)> surfaces_;
  std::vector<TopoDS_Vertex> vertices_;
  std::vector<TopoDS_Edge> edges_;
};

}  // namespace

Result<BuiltBrep> build_occt_brep(const Model& model, double tolerance_mm) {
  return BrepBuilder(model, tolerance_mm).build();
}

}  // namespace argil::io::detail
