// STEP and IGES export through OpenCASCADE (one of the two OCCT seams; the other
// is occt_import.cpp). OCCT types stay in this file.
#include <BRepBuilderAPI_MakeEdge.hxx>
#include <BRepBuilderAPI_MakeFace.hxx>
#include <BRepCheck_Analyzer.hxx>
#include <BRepLib.hxx>
#include <BRep_Builder.hxx>
#include <Geom2d_BSplineCurve.hxx>
#include <Geom_BSplineSurface.hxx>
#include <IFSelect_ReturnStatus.hxx>
#include <IGESControl_Controller.hxx>
#include <IGESControl_Writer.hxx>
#include <IGESData_IGESModel.hxx>
#include <IGESData_IGESWriter.hxx>
#include <IGESSelect_WorkLibrary.hxx>
#include <Interface_FloatWriter.hxx>
#include <Interface_Static.hxx>
#include <Precision.hxx>
#include <STEPControl_Writer.hxx>
#include <ShapeFix_Face.hxx>
#include <Standard_Failure.hxx>
#include <StepData_Protocol.hxx>
#include <StepData_StepModel.hxx>
#include <StepData_StepWriter.hxx>
#include <TColStd_Array1OfInteger.hxx>
#include <TColStd_Array1OfReal.hxx>
#include <TColStd_Array2OfReal.hxx>
#include <TColgp_Array1OfPnt2d.hxx>
#include <TColgp_Array2OfPnt.hxx>
#include <TopLoc_Location.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Compound.hxx>
#include <TopoDS_Edge.hxx>
#include <TopoDS_Face.hxx>
#include <TopoDS_Vertex.hxx>
#include <TopoDS_Wire.hxx>
#include <XSControl_WorkSession.hxx>

#include <cmath>
#include <fstream>
#include <string>
#include <vector>

#include "argil/io/base/atomic_write.hpp"
#include "argil/io/cad/cad_exchange.hpp"
#include "argil/io/cad/detail/occt_session.hpp"
#include "argil/io/model/trim_curve.hpp"

namespace argil::io {
namespace {

// The float writer formats into a 24-byte buffer: "%#.17G" of a number below
// 1e-99 needs a three-digit exponent and would overflow it.
double writable(double x) { return std::abs(x) < 1e-99 ? 0.0 : x; }

struct OcctKnots {
  TColStd_Array1OfReal values;
  TColStd_Array1OfInteger multiplicities;
};

// Flat clamped knot vector to distinct values and multiplicities (exact comparison).
OcctKnots occt_knots(const Eigen::VectorXd& flat) {
  std::vector<double> values;
  std::vector<int> counts;
  for (Eigen::Index k = 0; k < flat.size(); ++k) {
    const double t = writable(flat[k]);
    if (!values.empty() && values.back() == t) {
      ++counts.back();
    } else {
      values.push_back(t);
      counts.push_back(1);
    }
  }
  const int n = static_cast<int>(values.size());
  OcctKnots out{TColStd_Array1OfReal(1, n), TColStd_Array1OfInteger(1, n)};
  for (int i = 0; i < n; ++i) {
    out.values(i + 1) = values[static_cast<std::size_t>(i)];
    out.multiplicities(i + 1) = counts[static_cast<std::size_t>(i)];
  }
  return out;
}

Handle(Geom_BSplineSurface) to_occt(const BSplineSurface& s) {
  const int nu = s.count(Direction::u), nv = s.count(Direction::v);
  TColgp_Array2OfPnt poles(1, nu, 1, nv);
  TColStd_Array2OfReal weights(1, nu, 1, nv);
  for (int i = 0; i < nu; ++i) {
    for (int j = 0; j < nv; ++j) {
      const Eigen::Index row = s.pole_index(i, j);
      poles(i + 1, j + 1) =
          gp_Pnt(writable(s.control_points(row, 0)), writable(s.control_points(row, 1)),
                 writable(s.control_points(row, 2)));
      weights(i + 1, j + 1) = s.is_rational() ? s.weights[row] : 1.0;
    }
  }
  const OcctKnots u = occt_knots(s.knots[0]);
  const OcctKnots v = occt_knots(s.knots[1]);
  if (s.is_rational()) {
    return new Geom_BSplineSurface(poles, weights, u.values, v.values, u.multiplicities,
                                   v.multiplicities, s.degree[0], s.degree[1]);
  }
  return new Geom_BSplineSurface(poles, u.values, v.values, u.multiplicities, v.multiplicities,
                                 s.degree[0], s.degree[1]);
}

Handle(Geom2d_BSplineCurve) to_occt(const TrimCurve& c) {
  const int n = c.count();
  TColgp_Array1OfPnt2d poles(1, n);
  TColStd_Array1OfReal weights(1, n);
  for (int i = 0; i < n; ++i) {
    poles(i + 1) = gp_Pnt2d(writable(c.points(i, 0)), writable(c.points(i, 1)));
    weights(i + 1) = c.is_rational() ? c.weights[i] : 1.0;
  }
  const OcctKnots k = occt_knots(c.knots);
  if (c.is_rational()) {
    return new Geom2d_BSplineCurve(poles, weights, k.values, k.multiplicities, c.degree);
  }
  return new Geom2d_BSplineCurve(poles, k.values, k.multiplicities, c.degree);
}

gp_Pnt surface_point(const Handle(Geom_BSplineSurface) & s, const gp_Pnt2d& uv) {
  return s->Value(uv.X(), uv.Y());
}

// True when the curve maps to a single 3D point (a surface pole or collapsed
// side): such an edge is "degenerated" in OCCT and has no 3D curve.
bool is_degenerate(const Handle(Geom2d_BSplineCurve) & curve,
                   const Handle(Geom_BSplineSurface) & surface, double tolerance) {
  const gp_Pnt start = surface_point(surface, curve->StartPoint());
  for (double f : {0.25, 0.5, 0.75, 1.0}) {
    const double t =
        curve->FirstParameter() + f * (curve->LastParameter() - curve->FirstParameter());
    if (start.Distance(surface_point(surface, curve->Value(t))) > tolerance) return false;
  }
  return true;
}

// A wire through the loop's pcurves. Consecutive curves share one vertex whose
// tolerance covers the 3D gap between the curve ends.
Result<TopoDS_Wire> make_wire(const TrimLoop& loop, const Handle(Geom_BSplineSurface) & surface) {
  BRep_Builder builder;
  std::vector<Handle(Geom2d_BSplineCurve)> curves;
  for (const TrimCurve& c : loop.curves) curves.push_back(to_occt(c));
  const std::size_t n = curves.size();
  std::vector<TopoDS_Vertex> vertices(n);
  std::vector<gp_Pnt> positions(n);
  std::vector<double> tolerances(n);
  for (std::size_t k = 0; k < n; ++k) {
    const gp_Pnt start = surface_point(surface, curves[k]->StartPoint());
    const gp_Pnt previous_end = surface_point(surface, curves[(k + n - 1) % n]->EndPoint());
    positions[k] = gp_Pnt((start.XYZ() + previous_end.XYZ()) * 0.5);
    tolerances[k] = std::max(Precision::Confusion(), 0.6 * start.Distance(previous_end));
  }
  std::vector<bool> degenerate(n);
  for (std::size_t k = 0; k < n; ++k) {
    degenerate[k] = is_degenerate(curves[k], surface, Precision::Confusion());
  }
  for (std::size_t k = 0; k < n; ++k) {
    // Loop corners at one 3D point are one vertex: the ends of a curve closed in
    // 3D (a full circle, a collapsed side) and the two ends of a seam.
    bool shared = false;
    for (std::size_t j = 0; j < k && !shared; ++j) {
      if (positions[k].Distance(positions[j]) <= std::max(tolerances[k], tolerances[j])) {
        vertices[k] = vertices[j];
        shared = true;
      }
    }
    if (!shared) builder.MakeVertex(vertices[k], positions[k], tolerances[k]);
  }
  TopoDS_Wire wire;
  builder.MakeWire(wire);
  for (std::size_t k = 0; k < n; ++k) {
    const TopoDS_Vertex& first = vertices[k];
    const TopoDS_Vertex& last = vertices[(k + 1) % n];
    if (degenerate[k]) {
      TopoDS_Edge edge;
      builder.MakeEdge(edge);
      builder.UpdateEdge(edge, curves[k], surface, TopLoc_Location(), Precision::Confusion());
      builder.Degenerated(edge, true);
      builder.Add(edge, first.Oriented(TopAbs_FORWARD));
      builder.Add(edge, last.Oriented(TopAbs_REVERSED));
      builder.Range(edge, curves[k]->FirstParameter(), curves[k]->LastParameter());
      builder.Add(wire, edge);
      continue;
    }
    BRepBuilderAPI_MakeEdge edge(curves[k], surface, first, last, curves[k]->FirstParameter(),
                                 curves[k]->LastParameter());
    if (!edge.IsDone()) {
      return Status::error(StatusCode::invalid_argument,
                           "trim curve " + std::to_string(k) + " gives no edge (error " +
                               std::to_string(static_cast<int>(edge.Error())) + ")");
    }
    builder.Add(wire, edge.Edge());
  }
  wire.Closed(true);
  return wire;
}

Result<TopoDS_Face> make_face(const FaceRecord& record) {
  const Handle(Geom_BSplineSurface) surface = to_occt(record.surface);
  TopoDS_Face face;
  if (!record.trimmed()) {
    BRepBuilderAPI_MakeFace make(surface, Precision::Confusion());
    if (!make.IsDone()) return Status::error(StatusCode::invalid_argument, "no face");
    face = make.Face();
  } else {
    std::vector<TopoDS_Wire> wires;
    for (const TrimLoop& loop : record.loops) {
      Result<TopoDS_Wire> wire = make_wire(loop, surface);
      if (!wire.ok()) return wire.status();
      wires.push_back(wire.value());
    }
    BRepBuilderAPI_MakeFace make(surface, wires.front(), true);
    for (std::size_t w = 1; w < wires.size() && make.IsDone(); ++w) make.Add(wires[w]);
    if (!make.IsDone()) {
      return Status::error(StatusCode::invalid_argument,
                           "trim loops give no face (error " + std::to_string(make.Error()) + ")");
    }
    face = make.Face();
    BRepLib::BuildCurves3d(face);
    // Tolerances, seam and small-edge repairs that CAD readers rely on.
    ShapeFix_Face fix(face);
    fix.Perform();
    face = fix.Face();
  }
  if (record.reversed) face.Reverse();
  return face;
}

Result<TopoDS_Shape> make_shape(const Model& model) {
  BRep_Builder builder;
  TopoDS_Compound compound;
  builder.MakeCompound(compound);
  for (std::size_t f = 0; f < model.faces.size(); ++f) {
    const std::string where = "face " + std::to_string(f);
    const Status check = validate_face(model.faces[f], f);
    if (!check.ok()) return check;
    Result<TopoDS_Face> face = make_face(model.faces[f]);
    if (!face.ok()) return Status::error(face.status().code, where + ": " + face.status().message);
    if (!BRepCheck_Analyzer(face.value()).IsValid()) {
      return Status::error(StatusCode::invalid_argument,
                           where + ": the built face fails BRepCheck_Analyzer (bad trims?)");
    }
    builder.Add(compound, face.value());
  }
  return TopoDS_Shape(compound);
}

Status write_step_file(const TopoDS_Shape& shape, const std::filesystem::path& temporary) {
  // Must precede the writer's construction, else the file declares metres.
  Interface_Static::SetCVal("write.step.unit", "MM");
  STEPControl_Writer writer;
  if (writer.Transfer(shape, STEPControl_AsIs) != IFSelect_RetDone) {
    return Status::error(StatusCode::io_error, "STEP transfer failed");
  }
  const auto protocol = Handle(StepData_Protocol)::DownCast(writer.WS()->Protocol());
  StepData_StepWriter step(writer.Model());
  step.FloatWriter().SetFormat("%#.17G");
  step.SendModel(protocol);
  std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
  if (!out || !step.Print(out)) return Status::error(StatusCode::io_error, "STEP write failed");
  out.close();
  if (!out) return Status::error(StatusCode::io_error, "STEP write failed (disk full?)");
  return Status::success();
}

Status write_iges_file(const TopoDS_Shape& shape, const std::filesystem::path& temporary) {
  IGESControl_Controller::Init();
  Interface_Static::SetIVal("write.iges.brep.mode", 0);  // faces: 144 over 128
  IGESControl_Writer writer("MM", 0);
  if (!writer.AddShape(shape)) return Status::error(StatusCode::io_error, "IGES transfer failed");
  writer.ComputeModel();
  IGESData_IGESWriter iges(writer.Model());
  iges.FloatWriter().SetFormat("%#.17G");
  iges.SendModel(IGESSelect_WorkLibrary::DefineProtocol());
  std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
  if (!out || !iges.Print(out)) return Status::error(StatusCode::io_error, "IGES write failed");
  out.close();
  if (!out) return Status::error(StatusCode::io_error, "IGES write failed (disk full?)");
  return Status::success();
}

}  // namespace

Status write_cad(const Model& model, const std::filesystem::path& path, CadFormat format) {
  detail::silence_occt_console();
  const auto lock = detail::lock_occt_exchange();
  const auto failed = [&](const Status& status) {
    return Status::error(status.code, path.string() + ": " + status.message);
  };
  if (model.faces.empty()) {
    return failed(Status::error(StatusCode::invalid_argument, "the model has no faces"));
  }
  try {
    Result<TopoDS_Shape> shape = make_shape(model);
    if (!shape.ok()) return failed(shape.status());
    return write_atomically(path, [&](const std::filesystem::path& temporary) {
      try {
        const Status status = format == CadFormat::step ? write_step_file(shape.value(), temporary)
                                                        : write_iges_file(shape.value(), temporary);
        return status.ok() ? status : failed(status);
      } catch (const Standard_Failure& failure) {
        return failed(Status::error(StatusCode::io_error, std::string("OpenCASCADE failed: ") +
                                                              failure.GetMessageString()));
      }
    });
  } catch (const Standard_Failure& failure) {
    return failed(Status::error(StatusCode::invalid_argument,
                                std::string("OpenCASCADE failed: ") + failure.GetMessageString()));
  }
}

}  // namespace argil::io
