// STEP and IGES import through OpenCASCADE (one of the two OCCT seams; the other
// is occt_export.cpp). OCCT types stay in this file.
#include <BRepBuilderAPI_NurbsConvert.hxx>
#include <BRepTools.hxx>
#include <BRepTools_WireExplorer.hxx>
#include <BRep_Tool.hxx>
#include <Geom2dConvert.hxx>
#include <Geom2d_BSplineCurve.hxx>
#include <Geom2d_TrimmedCurve.hxx>
#include <GeomConvert.hxx>
#include <Geom_BSplineSurface.hxx>
#include <Geom_RectangularTrimmedSurface.hxx>
#include <IFSelect_ReturnStatus.hxx>
#include <IGESControl_Controller.hxx>
#include <IGESControl_Reader.hxx>
#include <IGESData_GlobalSection.hxx>
#include <IGESData_IGESEntity.hxx>
#include <IGESData_IGESModel.hxx>
#include <IGESData_UndefinedEntity.hxx>
#include <IGESGeom_BSplineSurface.hxx>
#include <IGESGeom_TrimmedSurface.hxx>
#include <IGESSolid_Face.hxx>
#include <Interface_Check.hxx>
#include <Interface_CheckIterator.hxx>
#include <Interface_InterfaceModel.hxx>
#include <Interface_Static.hxx>
#include <NCollection_DataMap.hxx>
#include <Precision.hxx>
#include <STEPControl_Reader.hxx>
#include <Standard_Failure.hxx>
#include <StepBasic_Product.hxx>
#include <StepData_StepModel.hxx>
#include <StepData_UndefinedEntity.hxx>
#include <StepGeom_BSplineSurface.hxx>
#include <StepRepr_RepresentationItem.hxx>
#include <StepShape_FaceSurface.hxx>
#include <StepToGeom.hxx>
#include <TColStd_Array1OfInteger.hxx>
#include <TColStd_Array1OfReal.hxx>
#include <TColStd_Array2OfReal.hxx>
#include <TColStd_SequenceOfAsciiString.hxx>
#include <TColgp_Array1OfPnt2d.hxx>
#include <TColgp_Array2OfPnt.hxx>
#include <TCollection_HAsciiString.hxx>
#include <TopExp.hxx>
#include <TopExp_Explorer.hxx>
#include <TopTools_ShapeMapHasher.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Edge.hxx>
#include <TopoDS_Face.hxx>
#include <TopoDS_TShape.hxx>
#include <TopoDS_Wire.hxx>
#include <TransferBRep.hxx>
#include <Transfer_TransientProcess.hxx>
#include <XSControl_Reader.hxx>
#include <XSControl_TransferReader.hxx>
#include <XSControl_WorkSession.hxx>

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <fstream>
#include <map>
#include <memory>
#include <string>

#include "argil/core/geometry/param_rect.hpp"
#include "argil/io/cad/cad_exchange.hpp"
#include "argil/io/cad/detail/isolated_read.hpp"
#include "argil/io/cad/detail/occt_face_domain.hpp"
#include "argil/io/cad/detail/occt_pcurve.hpp"
#include "argil/io/cad/detail/occt_session.hpp"
#include "argil/io/cad/detail/occt_topology_reader.hpp"
#include "argil/io/model/trim_curve.hpp"

namespace argil::io {
namespace {

Status file_error(const std::filesystem::path& path, StatusCode code, const std::string& what) {
  return Status::error(code, path.string() + ": " + what);
}

std::string lower(std::string text) {
  std::transform(text.begin(), text.end(), text.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return text;
}

// The head and tail of a file, for the cheap structural checks OCCT's parsers
// skip (they accept a truncated file and return whatever they parsed).
struct FileEnds {
  std::string head, tail;
};

Result<FileEnds> read_ends(const std::filesystem::path& path) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) {
    return file_error(path, StatusCode::io_error, "no such file");
  }
  if (!std::filesystem::is_regular_file(path, ec)) {
    return file_error(path, StatusCode::io_error, "not a regular file");
  }
  const auto size = std::filesystem::file_size(path, ec);
  if (ec) return file_error(path, StatusCode::io_error, "cannot read: " + ec.message());
  if (size == 0) return file_error(path, StatusCode::parse_error, "empty file");
  std::ifstream in(path, std::ios::binary);
  if (!in) return file_error(path, StatusCode::io_error, "cannot open");
  constexpr std::uintmax_t kWindow = 4096;
  FileEnds ends;
  ends.head.resize(static_cast<std::size_t>(std::min(size, kWindow)));
  in.read(ends.head.data(), static_cast<std::streamsize>(ends.head.size()));
  const std::uintmax_t tail_size = std::min(size, kWindow);
  in.seekg(static_cast<std::streamoff>(size - tail_size));
  ends.tail.resize(static_cast<std::size_t>(tail_size));
  in.read(ends.tail.data(), static_cast<std::streamsize>(ends.tail.size()));
  if (!in) return file_error(path, StatusCode::io_error, "read failed");
  return ends;
}

std::string trim_right(std::string text) {
  while (!text.empty() && std::isspace(static_cast<unsigned char>(text.back()))) text.pop_back();
  return text;
}

// ISO 10303-21: the exchange structure starts with ISO-10303-21; and ends with
// END-ISO-10303-21;.
Status check_step_structure(const std::filesystem::path& path, const FileEnds& ends) {
  const auto first = ends.head.find_first_not_of(" \t\r\n");
  if (first == std::string::npos || ends.head.compare(first, 13, "ISO-10303-21;") != 0) {
    return file_error(path, StatusCode::parse_error,
                      "not a STEP file (does not start with ISO-10303-21;)");
  }
  const std::string tail = trim_right(ends.tail);
  const std::string terminator = "END-ISO-10303-21;";
  if (tail.size() < terminator.size() ||
      tail.compare(tail.size() - terminator.size(), terminator.size(), terminator) != 0) {
    return file_error(path, StatusCode::parse_error,
                      "truncated STEP file (no END-ISO-10303-21; at the end)");
  }
  return Status::success();
}

// IGES 5.3: fixed 80-column records, the section letter in column 73; the last
// record is the Terminate section ('T').
Status check_iges_structure(const std::filesystem::path& path, const FileEnds& ends) {
  const auto line_end = ends.head.find_first_of("\r\n");
  const std::string first = ends.head.substr(0, line_end);
  if (first.size() < 73 || (first[72] != 'S' && first[72] != 'G' && first[72] != 'C')) {
    return file_error(path, StatusCode::parse_error,
                      "not an IGES file (first record has no section letter in column 73)");
  }
  const std::string tail = trim_right(ends.tail);
  const auto last_start = tail.find_last_of("\r\n");
  const std::string last = last_start == std::string::npos ? tail : tail.substr(last_start + 1);
  if (last.size() < 73 || last[72] != 'T') {
    return file_error(path, StatusCode::parse_error,
                      "truncated IGES file (the last record is not the Terminate section)");
  }
  return Status::success();
}

// Length unit names as STEP and IGES spell them, to millimetres.
double unit_to_mm(const std::string& name) {
  const std::string n = lower(name);
  if (n == "mm" || n == "millimetre" || n == "millimeter") return 1.0;
  if (n == "m" || n == "metre" || n == "meter") return 1000.0;
  if (n == "cm" || n == "centimetre" || n == "centimeter") return 10.0;
  if (n == "in" || n == "inch") return 25.4;
  if (n == "ft" || n == "foot") return 304.8;
  if (n == "um" || n == "micrometre" || n == "micrometer" || n == "micron") return 1e-3;
  if (n == "km" || n == "kilometre" || n == "kilometer") return 1e6;
  if (n == "mil") return 0.0254;
  return 0.0;
}

// IGES 5.3 global parameter 14 (unit flag); 3 means "see the unit name".
double iges_unit_to_mm(int flag, const std::string& name) {
  switch (flag) {
    case 1:
      return 25.4;
    case 2:
      return 1.0;
    case 4:
      return 304.8;
    case 5:
      return 1609344.0;
    case 6:
      return 1000.0;
    case 7:
      return 1e6;
    case 8:
      return 0.0254;
    case 9:
      return 1e-3;
    case 10:
      return 10.0;
    case 11:
      return 2.54e-5;
    default:
      return unit_to_mm(name);
  }
}

// OCCT's knots-with-multiplicities to argil's flat clamped knot vector.
Eigen::VectorXd flat_knots(const TColStd_Array1OfReal& sequence) {
  Eigen::VectorXd knots(sequence.Length());
  for (int k = sequence.Lower(); k <= sequence.Upper(); ++k) {
    knots[k - sequence.Lower()] = sequence(k);
  }
  return knots;
}

BSplineSurface to_argil(const Handle(Geom_BSplineSurface) & s) {
  BSplineSurface out;
  out.degree = {s->UDegree(), s->VDegree()};
  TColStd_Array1OfReal uk(1, s->NbUPoles() + s->UDegree() + 1);
  TColStd_Array1OfReal vk(1, s->NbVPoles() + s->VDegree() + 1);
  s->UKnotSequence(uk);
  s->VKnotSequence(vk);
  out.knots = {flat_knots(uk), flat_knots(vk)};
  const int nu = s->NbUPoles(), nv = s->NbVPoles();
  TColgp_Array2OfPnt poles(1, nu, 1, nv);
  s->Poles(poles);
  out.control_points.resize(static_cast<Eigen::Index>(nu) * nv, 3);
  const bool rational = s->IsURational() || s->IsVRational();
  TColStd_Array2OfReal weights(1, nu, 1, nv);
  if (rational) {
    s->Weights(weights);
    out.weights.resize(static_cast<Eigen::Index>(nu) * nv);
  }
  for (int i = 0; i < nu; ++i) {
    for (int j = 0; j < nv; ++j) {
      const Eigen::Index row = out.pole_index(i, j);
      const gp_Pnt& p = poles(i + 1, j + 1);
      out.control_points.row(row) << p.X(), p.Y(), p.Z();
      if (rational) out.weights[row] = weights(i + 1, j + 1);
    }
  }
  return out;
}

// True when `s` is periodic along `u` (else v) with its period's first knot of
// multiplicity equal to the degree: the form the STEP and IGES readers give a
// clamped surface closed within Precision::Confusion() (ShapeCustom_Surface::
// ConvertToPeriodic, run on every B-spline surface by StepToTopoDS_TranslateFace
// and by the IGES reader): the first row of poles is the one the seam interpolates.
bool seam_at_full_knot(const Handle(Geom_BSplineSurface) & s, bool u) {
  return u ? s->IsUPeriodic() && s->UMultiplicity(1) == s->UDegree()
           : s->IsVPeriodic() && s->VMultiplicity(1) == s->VDegree();
}

// The clamped surface equal to `s`, periodic as in seam_at_full_knot along u
// and/or v: the seam knot raised to degree + 1 at both ends and the first row of
// poles and weights repeated after the last. Inserting a knot of multiplicity p
// into a degree p spline only repeats a pole, so no value changes; OCCT's
// SetUNotPeriodic and Segment instead go through weighted poles (P w / w) and
// move poles of non-unit weight by an ulp.
Handle(Geom_BSplineSurface) exactly_unwrapped(const Handle(Geom_BSplineSurface) & s) {
  const bool u = seam_at_full_knot(s, true), v = seam_at_full_knot(s, false);
  const int nu = s->NbUPoles(), nv = s->NbVPoles();
  const int mu = nu + (u ? 1 : 0), mv = nv + (v ? 1 : 0);
  TColgp_Array2OfPnt poles(1, mu, 1, mv);
  TColStd_Array2OfReal weights(1, mu, 1, mv);
  for (int i = 1; i <= mu; ++i) {
    for (int j = 1; j <= mv; ++j) {
      const int from_i = i > nu ? 1 : i, from_j = j > nv ? 1 : j;
      poles(i, j) = s->Pole(from_i, from_j);
      weights(i, j) = s->Weight(from_i, from_j);
    }
  }
  TColStd_Array1OfReal uk(1, s->NbUKnots()), vk(1, s->NbVKnots());
  TColStd_Array1OfInteger um(1, s->NbUKnots()), vm(1, s->NbVKnots());
  s->UKnots(uk);
  s->VKnots(vk);
  s->UMultiplicities(um);
  s->VMultiplicities(vm);
  if (u) {
    ++um(um.Lower());
    ++um(um.Upper());
  }
  if (v) {
    ++vm(vm.Lower());
    ++vm(vm.Upper());
  }
  const bool keep_u = s->IsUPeriodic() && !u, keep_v = s->IsVPeriodic() && !v;
  if (s->IsURational() || s->IsVRational()) {
    return new Geom_BSplineSurface(poles, weights, uk, vk, um, vm, s->UDegree(), s->VDegree(),
                                   keep_u, keep_v);
  }
  return new Geom_BSplineSurface(poles, uk, vk, um, vm, s->UDegree(), s->VDegree(), keep_u, keep_v);
}

// Clamped, non-periodic copy of a B-spline surface: same geometry and parameters.
Handle(Geom_BSplineSurface) clamped_copy(const Handle(Geom_BSplineSurface) & s) {
  Handle(Geom_BSplineSurface) copy = Handle(Geom_BSplineSurface)::DownCast(s->Copy());
  if (seam_at_full_knot(copy, true) || seam_at_full_knot(copy, false)) {
    copy = exactly_unwrapped(copy);
  }
  if (copy->IsUPeriodic()) copy->SetUNotPeriodic();
  if (copy->IsVPeriodic()) copy->SetVNotPeriodic();
  // Non-periodic OCCT surfaces may still have end knots of lower multiplicity
  // (unclamped); segmenting to the full domain clamps them without changing
  // the parametrisation.
  const bool clamped = copy->UMultiplicity(1) == copy->UDegree() + 1 &&
                       copy->UMultiplicity(copy->NbUKnots()) == copy->UDegree() + 1 &&
                       copy->VMultiplicity(1) == copy->VDegree() + 1 &&
                       copy->VMultiplicity(copy->NbVKnots()) == copy->VDegree() + 1;
  if (!clamped) {
    double u0 = 0.0, u1 = 0.0, v0 = 0.0, v1 = 0.0;
    copy->Bounds(u0, u1, v0, v1);
    copy->Segment(u0, u1, v0, v1);
  }
  return copy;
}

double signed_area(const std::vector<Eigen::Vector2d>& polygon) {
  double area = 0.0;
  for (std::size_t i = 0, j = polygon.size() - 1; i < polygon.size(); j = i++) {
    area += (polygon[j].x() - polygon[i].x()) * (polygon[j].y() + polygon[i].y());
  }
  return 0.5 * area;
}

std::vector<Eigen::Vector2d> coarse_polygon(const TrimLoop& loop) {
  std::vector<Eigen::Vector2d> points;
  for (const TrimCurve& c : loop.curves) {
    for (Eigen::Index i = 0; i + 1 < c.points.rows(); ++i) points.push_back(c.points.row(i));
  }
  return points;
}

// Points along the loop's curves themselves: a curved loop's control polygon
// can enclose more than a straight loop around it (a rational circle's does).
std::vector<Eigen::Vector2d> sampled_polygon(const TrimLoop& loop) {
  constexpr int kSamplesPerCurve = 32;
  std::vector<Eigen::Vector2d> points;
  for (const TrimCurve& c : loop.curves) {
    const double t0 = c.knots[0], t1 = c.knots[c.knots.size() - 1];
    for (int k = 0; k < kSamplesPerCurve; ++k) {
      points.push_back(evaluate_trim_curve(c, t0 + (t1 - t0) * k / kSamplesPerCurve));
    }
  }
  return points;
}

void reverse_loop(TrimLoop& loop) {
  std::reverse(loop.curves.begin(), loop.curves.end());
  for (TrimCurve& c : loop.curves) {
    const double a = c.knots[0], b = c.knots[c.knots.size() - 1];
    // eval(): the mirror reads the vector it writes (aliasing), which left
    // repeated knots 1e-15 apart and out of order (Ventilator.stp #361).
    c.knots = (a + b - c.knots.reverse().array()).matrix().eval();
    c.points = c.points.colwise().reverse().eval();
    if (c.is_rational()) c.weights = c.weights.reverse().eval();
  }
}

// True when the loops are exactly the four sides of the surface domain.
bool is_natural_boundary(const std::vector<TrimLoop>& loops, const BSplineSurface& s) {
  if (loops.size() != 1) return false;
  const ParamRect d = domain_of(s);
  // Pcurves are computed to about 1e-9 of the domain; no real trim is that close.
  const double tol_u = 1e-9 * d.width(), tol_v = 1e-9 * d.height();
  for (const TrimCurve& c : loops[0].curves) {
    // All poles on one side line: the curve lies on it (convex hull property).
    const auto on = [&](int col, double value, double tol) {
      return ((c.points.col(col).array() - value).abs() <= tol).all();
    };
    if (!on(0, d.u0, tol_u) && !on(0, d.u1, tol_u) && !on(1, d.v0, tol_v) && !on(1, d.v1, tol_v)) {
      return false;
    }
  }
  const double area = std::abs(signed_area(coarse_polygon(loops[0])));
  const double domain_area = d.width() * d.height();
  return std::abs(area - domain_area) <= 1e-9 * domain_area;
}

// The face's trim loops, outer first, each running the right way round;
// `read` learns the edge behind each trim curve.
Result<std::vector<TrimLoop>> face_loops(const TopoDS_Face& face,
                                         std::vector<detail::ReadFace::Loop>& read) {
  struct Read {
    TrimLoop loop;
    detail::ReadFace::Loop edges;
  };
  std::vector<Read> loops;
  const auto add = [&](Read& out, const TopoDS_Edge& edge) -> Status {
    Result<TrimCurve> curve = detail::edge_pcurve(edge, face, detail::PcurveDirection::wire);
    if (!curve.ok()) return curve.status();
    out.loop.curves.push_back(std::move(curve).value());
    out.edges.edges.push_back(edge);
    return Status::success();
  };
  for (TopExp_Explorer w(face, TopAbs_WIRE); w.More(); w.Next()) {
    const TopoDS_Wire& wire = TopoDS::Wire(w.Current());
    Read read_loop;
    int edges_in_order = 0;
    for (BRepTools_WireExplorer e(wire, face); e.More(); e.Next()) {
      if (Status s = add(read_loop, e.Current()); !s.ok()) return s;
      ++edges_in_order;
    }
    int edges = 0;
    for (TopExp_Explorer e(wire, TopAbs_EDGE); e.More(); e.Next()) ++edges;
    if (edges_in_order != edges) {
      // A wire OCCT cannot chain: keep its stored order rather than drop edges.
      read_loop = Read{};
      for (TopExp_Explorer e(wire, TopAbs_EDGE); e.More(); e.Next()) {
        if (Status s = add(read_loop, TopoDS::Edge(e.Current())); !s.ok()) return s;
      }
    }
    if (read_loop.loop.curves.empty()) continue;
    loops.push_back(std::move(read_loop));
  }
  // The outer loop encloses the most area: OpenCASCADE's OuterWire can name
  // a hole (Ventilator.stp #361: a hexagonal nut face, its round hole "outer").
  std::vector<double> areas;
  for (const Read& l : loops) areas.push_back(signed_area(sampled_polygon(l.loop)));
  std::size_t largest = 0;
  for (std::size_t l = 0; l < loops.size(); ++l) {
    if (std::abs(areas[l]) > std::abs(areas[largest])) largest = l;
  }
  for (std::size_t l = 0; l < loops.size(); ++l) {
    TrimLoop& loop = loops[l].loop;
    loop.outer = l == largest;
    if ((loop.outer && areas[l] < 0.0) || (!loop.outer && areas[l] > 0.0)) {
      reverse_loop(loop);
      std::reverse(loops[l].edges.edges.begin(), loops[l].edges.edges.end());
      loops[l].edges.reversed = true;
    }
  }
  // Outer loop first.
  std::stable_partition(loops.begin(), loops.end(), [](const Read& l) { return l.loop.outer; });
  std::vector<TrimLoop> out;
  for (Read& l : loops) {
    out.push_back(std::move(l.loop));
    read.push_back(std::move(l.edges));
  }
  return out;
}

// How the file itself names an entity: "#<id>" in STEP, "D<directory entry>" in IGES.
std::string entity_label(const Handle(Interface_InterfaceModel) & model,
                         const Handle(Standard_Transient) & entity, CadFormat format) {
  const int number = model->Number(entity);
  if (number <= 0) return "";
  if (format == CadFormat::step) {
    const auto step = Handle(StepData_StepModel)::DownCast(model);
    const int id = step.IsNull() ? 0 : step->IdentLabel(entity);
    return "#" + std::to_string(id > 0 ? id : number);
  }
  return "D" + std::to_string(2 * number - 1);
}

// The file's entity each face was made from, found for every face in one
// pass. XSControl_TransferReader::EntityFromShapeResult answers one shape by
// a pass over every transferred entity: asked for each face (and again in
// mode -1 when mode 1 finds nothing), reading 11752.stp (1018 faces) spent
// 1.4 s of its 12 s there. The answers are the same, in the same order of
// preference: the first entity whose result is the face itself, else the
// last whose result is the face in another orientation, else the last whose
// result shares its underlying face at another location.
class FaceSources {
 public:
  explicit FaceSources(const Handle(XSControl_WorkSession) & session) {
    const Handle(XSControl_TransferReader) reader = session->TransferReader();
    if (reader.IsNull()) return;
    const Handle(Transfer_TransientProcess) process = reader->TransientProcess();
    if (process.IsNull()) return;
    for (Standard_Integer i = 1; i <= process->NbMapped(); ++i) {
      const Handle(Standard_Transient) entity = process->Mapped(i);
      const TopoDS_Shape shape = TransferBRep::ShapeResult(process, entity);
      if (shape.IsNull() || shape.ShapeType() != TopAbs_FACE) continue;
      if (!same_.IsBound(shape)) same_.Bind(shape, Found{});
      Found& found = same_.ChangeFind(shape);
      Handle(Standard_Transient)& equal =
          found.equal[static_cast<std::size_t>(shape.Orientation())];
      if (equal.IsNull()) equal = entity;
      found.same = entity;
      partner_[shape.TShape().get()] = entity;
    }
  }

  // Null when the reader does not say.
  Handle(Standard_Transient) of(const TopoDS_Shape& face) const {
    if (const Found* found = same_.Seek(face)) {
      const Handle(Standard_Transient)& equal =
          found->equal[static_cast<std::size_t>(face.Orientation())];
      return equal.IsNull() ? found->same : equal;
    }
    const auto partner = partner_.find(face.TShape().get());
    return partner == partner_.end() ? nullptr : partner->second;
  }

 private:
  struct Found {
    std::array<Handle(Standard_Transient), 4> equal;  // the first, per orientation
    Handle(Standard_Transient) same;                  // the last
  };
  NCollection_DataMap<TopoDS_Shape, Found, TopTools_ShapeMapHasher> same_;
  std::map<const TopoDS_TShape*, Handle(Standard_Transient)> partner_;  // the last
};

// Where a face came from: "#<entity>" in STEP, "D<directory entry>" in IGES.
void describe_source(const Handle(Interface_InterfaceModel) & model,
                     const Handle(Standard_Transient) & entity, CadFormat format,
                     FaceRecord& record) {
  if (entity.IsNull()) return;
  record.source_id = entity_label(model, entity, format);
  if (format == CadFormat::step) {
    const auto item = Handle(StepRepr_RepresentationItem)::DownCast(entity);
    if (!item.IsNull() && !item->Name().IsNull()) record.name = item->Name()->ToCString();
  } else {
    const auto iges = Handle(IGESData_IGESEntity)::DownCast(entity);
    if (!iges.IsNull() && iges->HasName()) record.name = iges->NameValue()->ToCString();
  }
}

// A face's control net as its entity in the file holds it, row by row along u:
// before any placement; STEP's scaled to mm by StepToGeom, IGES's as written.
struct WrittenNet {
  int nu = 0, nv = 0;
  std::vector<gp_Pnt> poles;
  std::vector<double> weights;
};

// The net of the B-spline surface the face entity names; empty when the
// entity is not a face on a B-spline surface. STEP: the surface as
// StepToGeom makes it, before StepToTopoDS_TranslateFace makes it periodic.
WrittenNet written_net(const Handle(Standard_Transient) & entity, CadFormat format) {
  WrittenNet net;
  if (entity.IsNull()) return net;
  if (format == CadFormat::step) {
    const auto face = Handle(StepShape_FaceSurface)::DownCast(entity);
    if (face.IsNull()) return net;
    const auto step = Handle(StepGeom_BSplineSurface)::DownCast(face->FaceGeometry());
    if (step.IsNull()) return net;
    const Handle(Geom_BSplineSurface) s = StepToGeom::MakeBSplineSurface(step);
    if (s.IsNull()) return net;
    net.nu = s->NbUPoles();
    net.nv = s->NbVPoles();
    for (int i = 1; i <= net.nu; ++i) {
      for (int j = 1; j <= net.nv; ++j) {
        net.poles.push_back(s->Pole(i, j));
        net.weights.push_back(s->Weight(i, j));
      }
    }
    return net;
  }
  Handle(IGESData_IGESEntity) surface = Handle(IGESData_IGESEntity)::DownCast(entity);
  if (const auto face = Handle(IGESSolid_Face)::DownCast(entity); !face.IsNull()) {
    surface = face->Surface();
  } else if (const auto trimmed = Handle(IGESGeom_TrimmedSurface)::DownCast(entity);
             !trimmed.IsNull()) {
    surface = trimmed->Surface();
  }
  const auto iges = Handle(IGESGeom_BSplineSurface)::DownCast(surface);
  if (iges.IsNull()) return net;
  net.nu = iges->NbPolesU();
  net.nv = iges->NbPolesV();
  for (int i = 0; i < net.nu; ++i) {  // IGES numbers poles from 0
    for (int j = 0; j < net.nv; ++j) {
      net.poles.push_back(iges->Pole(i, j));
      net.weights.push_back(iges->Weight(i, j));
    }
  }
  return net;
}

// The readers make every B-spline surface closed within Precision::Confusion()
// periodic, dropping its last row of poles for a copy of the first; clamped
// again (exactly_unwrapped) that row is the first row, which the file's may
// differ from by up to that distance. Puts the file's last row back (u and/or
// v as `unwrapped_u`, `unwrapped_v`), only when the rest of the net is the
// file's bit for bit (no unit factor, no placement, the same orientation) and
// the row lies within Precision::Confusion() of the copy.
void restore_seam(BSplineSurface& s, const WrittenNet& net, bool unwrapped_u, bool unwrapped_v) {
  const int nu = s.count(Direction::u), nv = s.count(Direction::v);
  if (net.nu != nu || net.nv != nv) return;
  const auto on_seam = [&](int i, int j) {
    return (unwrapped_u && i == nu - 1) || (unwrapped_v && j == nv - 1);
  };
  for (int i = 0; i < nu; ++i) {
    for (int j = 0; j < nv; ++j) {
      const Eigen::Index row = s.pole_index(i, j);
      const gp_Pnt& p = net.poles[static_cast<std::size_t>(i * nv + j)];
      const double w = net.weights[static_cast<std::size_t>(i * nv + j)];
      if (w != (s.is_rational() ? s.weights[row] : 1.0)) return;
      const gp_Pnt ours(s.control_points(row, 0), s.control_points(row, 1),
                        s.control_points(row, 2));
      const bool same = p.X() == ours.X() && p.Y() == ours.Y() && p.Z() == ours.Z();
      if (!same && !(on_seam(i, j) && p.Distance(ours) <= Precision::Confusion())) return;
    }
  }
  for (int i = 0; i < nu; ++i) {
    for (int j = 0; j < nv; ++j) {
      if (!on_seam(i, j)) continue;
      const gp_Pnt& p = net.poles[static_cast<std::size_t>(i * nv + j)];
      s.control_points.row(s.pole_index(i, j)) << p.X(), p.Y(), p.Z();
    }
  }
}

// `written`: the face's net as its file entity holds it (restore_seam).
// `source` learns which face the record was made from (for the topology).
Result<FaceRecord> face_record(const TopoDS_Face& oriented_face, const WrittenNet& written,
                               detail::ReadFace& source) {
  source.original = oriented_face;
  FaceRecord record;
  record.reversed = oriented_face.Orientation() == TopAbs_REVERSED;
  TopoDS_Face face = TopoDS::Face(oriented_face.Oriented(TopAbs_FORWARD));
  Handle(Geom_Surface) surface = BRep_Tool::Surface(face);  // with the face's location
  if (surface.IsNull()) return Status::error(StatusCode::unsupported, "face without a surface");
  const auto trimmed = Handle(Geom_RectangularTrimmedSurface)::DownCast(surface);
  if (!trimmed.IsNull()) surface = trimmed->BasisSurface();
  Handle(Geom_BSplineSurface) bspline = Handle(Geom_BSplineSurface)::DownCast(surface);
  if (bspline.IsNull()) {
    // Converts surface and pcurves together, so the trims follow the new parameters.
    BRepBuilderAPI_NurbsConvert convert(face, true);
    if (!convert.IsDone()) {
      return Status::error(
          StatusCode::unsupported,
          std::string("cannot convert ") + surface->DynamicType()->Name() + " to a B-spline");
    }
    for (TopExp_Explorer e(face, TopAbs_EDGE); e.More(); e.Next()) {
      const TopoDS_Shape forward = e.Current().Oriented(TopAbs_FORWARD);
      if (!source.edges.IsBound(forward))
        source.edges.Bind(forward, convert.ModifiedShape(forward));
    }
    face = TopoDS::Face(convert.Shape().Oriented(TopAbs_FORWARD));
    source.converted = face;
    Handle(Geom_Surface) converted = BRep_Tool::Surface(face);
    const auto converted_trimmed = Handle(Geom_RectangularTrimmedSurface)::DownCast(converted);
    if (!converted_trimmed.IsNull()) converted = converted_trimmed->BasisSurface();
    bspline = Handle(Geom_BSplineSurface)::DownCast(converted);
    if (bspline.IsNull()) {
      return Status::error(StatusCode::unsupported, std::string("conversion of ") +
                                                        surface->DynamicType()->Name() +
                                                        " gave no B-spline surface");
    }
  }
  bspline = detail::seated_on_face(bspline, face);
  record.surface = to_argil(clamped_copy(bspline));
  restore_seam(record.surface, written, seam_at_full_knot(bspline, true),
               seam_at_full_knot(bspline, false));
  const Status check = validate(record.surface);
  if (!check.ok()) return Status::error(StatusCode::invalid_surface, check.message);
  Result<std::vector<TrimLoop>> loops = face_loops(face, source.loops);
  if (!loops.ok()) return loops.status();
  record.loops = std::move(loops).value();
  if (is_natural_boundary(record.loops, record.surface)) record.loops.clear();
  // Unprefixed: the caller names the face.
  if (const Status valid = validate_face(record); !valid.ok()) return valid;
  return record;
}

const char* format_name(CadFormat format) { return format == CadFormat::step ? "STEP" : "IGES"; }

// Defects of one kind: how many entities, and the first few by label.
struct DefectGroup {
  std::size_t count = 0;
  std::string first;  // "#56, #60, #64"
};

constexpr std::size_t kLabelsListed = 3;

void add_to(DefectGroup& group, const std::string& label) {
  if (group.count < kLabelsListed) group.first += (group.count == 0 ? "" : ", ") + label;
  ++group.count;
}

std::string listed(const DefectGroup& group) {
  return group.first + (group.count > kLabelsListed ? ", ..." : "");
}

// Entities the reader loaded with a defect (a null name where the schema wants
// a string, a styling value it does not know), grouped by type and message.
// OpenCASCADE transfers them as far as it can, so each group is a warning.
std::vector<std::string> load_warnings(const Handle(XSControl_WorkSession) & session,
                                       CadFormat format) {
  const Handle(Interface_InterfaceModel) model = session->Model();
  std::map<std::string, DefectGroup> groups;
  const Interface_CheckIterator checks = session->ModelCheckList();
  for (checks.Start(); checks.More(); checks.Next()) {
    const Handle(Interface_Check) check = checks.Value();
    if (!check->HasFailed() || check->NbFails() == 0) continue;
    const int number = checks.Number();
    std::string type = "the file header", label;
    if (number > 0 && number <= model->NbEntities()) {
      type = model->TypeName(model->Value(number), false);
      label = entity_label(model, model->Value(number), format);
    }
    add_to(groups[type + ": " + std::string(check->CFail(1))], label);
  }
  std::vector<std::string> warnings;
  for (const auto& [what, group] : groups) {
    warnings.push_back(std::to_string(group.count) + " " + format_name(format) +
                       (group.count == 1 ? " entity" : " entities") + " read despite a defect (" +
                       listed(group) + ") " + what);
  }
  return warnings;
}

// Entities of types the reader does not know, grouped by type. The transfer
// skips them; when geometry needed one, its face fails to transfer and
// transfer_warnings says so.
std::vector<std::string> unknown_entity_warnings(const Handle(Interface_InterfaceModel) & model,
                                                 CadFormat format) {
  std::map<std::string, DefectGroup> groups;
  for (int n = 1; n <= model->NbEntities(); ++n) {
    const Handle(Standard_Transient) entity = model->Value(n);
    std::string type;
    if (format == CadFormat::step) {
      const auto unknown = Handle(StepData_UndefinedEntity)::DownCast(entity);
      if (!unknown.IsNull()) type = unknown->StepType();
    } else {
      const auto unknown = Handle(IGESData_UndefinedEntity)::DownCast(entity);
      if (!unknown.IsNull()) type = "type " + std::to_string(unknown->TypeNumber());
    }
    if (!type.empty()) add_to(groups[type], entity_label(model, entity, format));
  }
  std::vector<std::string> warnings;
  for (const auto& [type, group] : groups) {
    warnings.push_back(std::to_string(group.count) + " " + format_name(format) +
                       (group.count == 1 ? " entity" : " entities") + " of unsupported type " +
                       type + " skipped (" + listed(group) + ")");
  }
  return warnings;
}

// Entities whose transfer failed (geometry OpenCASCADE could not build).
std::vector<std::string> transfer_warnings(const Handle(XSControl_WorkSession) & session,
                                           CadFormat format) {
  const Handle(XSControl_TransferReader) reader = session->TransferReader();
  if (reader.IsNull() || reader->TransientProcess().IsNull()) return {};
  const Handle(Interface_InterfaceModel) model = session->Model();
  std::map<std::string, DefectGroup> groups;
  const Interface_CheckIterator checks = reader->TransientProcess()->CheckList(false);
  for (checks.Start(); checks.More(); checks.Next()) {
    const Handle(Interface_Check) check = checks.Value();
    if (!check->HasFailed() || check->NbFails() == 0) continue;
    const Handle(Standard_Transient) entity = check->Entity();
    std::string type = "entity", label;
    if (!entity.IsNull() && model->Number(entity) > 0) {
      type = model->TypeName(entity, false);
      label = entity_label(model, entity, format);
    }
    add_to(groups[type + ": " + std::string(check->CFail(1))], label);
  }
  std::vector<std::string> warnings;
  for (const auto& [what, group] : groups) {
    warnings.push_back(std::to_string(group.count) + " " + format_name(format) +
                       (group.count == 1 ? " entity" : " entities") + " did not transfer (" +
                       listed(group) + ") " + what);
  }
  return warnings;
}

// The reader for the format, with the import settings made first (the IGES
// controller must be initialised before its settings exist).
std::unique_ptr<XSControl_Reader> make_reader(CadFormat format) {
  if (format == CadFormat::step) {
    Interface_Static::SetCVal("xstep.cascade.unit", "MM");
    return std::make_unique<STEPControl_Reader>();
  }
  IGESControl_Controller::Init();
  Interface_Static::SetCVal("xstep.cascade.unit", "MM");
  // 0: keep B-splines as written; the default 1 may remove knots to raise continuity.
  Interface_Static::SetIVal("read.iges.bspline.continuity", 0);
  return std::make_unique<IGESControl_Reader>();
}

// The unit the file declares: STEP's first length unit, IGES's global section.
SourceUnit declared_unit(XSControl_Reader& reader, CadFormat format) {
  SourceUnit unit;
  if (format == CadFormat::step) {
    TColStd_SequenceOfAsciiString lengths, angles, solid_angles;
    static_cast<STEPControl_Reader&>(reader).FileUnits(lengths, angles, solid_angles);
    if (lengths.Length() > 0) unit.name = lower(lengths(1).ToCString());
    unit.to_mm = unit_to_mm(unit.name);
    return unit;
  }
  const auto iges = Handle(IGESData_IGESModel)::DownCast(reader.WS()->Model());
  if (!iges.IsNull()) {
    const IGESData_GlobalSection& global = iges->GlobalSection();
    if (!global.UnitName().IsNull()) unit.name = lower(global.UnitName()->ToCString());
    unit.to_mm = iges_unit_to_mm(global.UnitFlag(), unit.name);
  }
  return unit;
}

// A file read and transferred, with the session that knows its entities.
struct LoadedShape {
  TopoDS_Shape shape;
  Handle(XSControl_WorkSession) session;
  SourceUnit unit;
  std::vector<std::string> warnings;  // what the reader recovered from
};

// The error for a file that gave no faces, with what the reader met in it.
Status nothing_read(const std::filesystem::path& path, const std::string& what,
                    const std::vector<std::string>& warnings) {
  std::string message = what;
  if (!warnings.empty()) message += "; the reader met: " + warnings.front();
  if (warnings.size() > 1) message += " (and " + std::to_string(warnings.size() - 1) + " more)";
  return file_error(path, StatusCode::unsupported, message);
}

// Reads and transfers the file; STEP and IGES differ only in the reader.
Result<LoadedShape> load_shape(const std::filesystem::path& path, CadFormat format) {
  const std::string kind = format_name(format);
  const std::unique_ptr<XSControl_Reader> reader = make_reader(format);
  LoadedShape out;
  out.session = reader->WS();
  if (reader->ReadFile(path.c_str()) != IFSelect_RetDone) {
    return file_error(path, StatusCode::parse_error, "malformed " + kind + " file");
  }
  // What OpenCASCADE transfers, we read: defects it reads past are warnings,
  // and an error only when nothing transfers (naming what the reader met).
  out.warnings = load_warnings(out.session, format);
  for (std::string& w : unknown_entity_warnings(out.session->Model(), format)) {
    out.warnings.push_back(std::move(w));
  }
  const auto nothing = [&](const std::string& what) {
    return nothing_read(path, what, out.warnings);
  };
  out.unit = declared_unit(*reader, format);
  if (reader->NbRootsForTransfer() == 0) return nothing("no shapes to transfer (no faces)");
  reader->TransferRoots();
  for (std::string& w : transfer_warnings(out.session, format))
    out.warnings.push_back(std::move(w));
  out.shape = reader->OneShape();
  if (out.shape.IsNull()) return nothing("no shape could be read (no faces)");
  return out;
}

// Every face of the shape as a record, or the first face's failure naming
// its index and source entity.
// `sources`: the face each record was made from.
Result<std::vector<FaceRecord>> face_records(const std::filesystem::path& path,
                                             const LoadedShape& loaded, CadFormat format,
                                             std::vector<detail::ReadFace>& sources) {
  std::vector<FaceRecord> faces;
  const FaceSources entities(loaded.session);
  const Handle(Interface_InterfaceModel) model = loaded.session->Model();
  int index = 0;
  for (TopExp_Explorer e(loaded.shape, TopAbs_FACE); e.More(); e.Next(), ++index) {
    const Handle(Standard_Transient) entity = entities.of(e.Current());
    const WrittenNet written = written_net(entity, format);
    Result<FaceRecord> record =
        face_record(TopoDS::Face(e.Current()), written, sources.emplace_back());
    if (!record.ok()) {
      FaceRecord source;  // only for the entity id in the message
      describe_source(model, entity, format, source);
      return file_error(path, record.status().code,
                        "face " + std::to_string(index) +
                            (source.source_id.empty() ? "" : " (" + source.source_id + ")") + ": " +
                            record.status().message);
    }
    describe_source(model, entity, format, record.value());
    faces.push_back(std::move(record).value());
  }
  return faces;
}

// The name of the one product a file without a product tree holds: STEP's
// first PRODUCT, else the file's name without extension.
std::string product_name(const LoadedShape& loaded, const std::filesystem::path& path,
                         CadFormat format) {
  if (format == CadFormat::step) {
    const Handle(Interface_InterfaceModel) model = loaded.session->Model();
    for (int n = 1; n <= model->NbEntities(); ++n) {
      const auto product = Handle(StepBasic_Product)::DownCast(model->Value(n));
      if (product.IsNull()) continue;
      // Some systems leave the name empty and put it in the id (Ventilator.stp).
      for (const auto& text : {product->Name(), product->Id()}) {
        if (!text.IsNull() && text->Length() > 0) return text->ToCString();
      }
    }
  }
  return path.stem().string();
}

Result<Model> read_with_occt(const std::filesystem::path& path, CadFormat format) {
  Result<LoadedShape> loaded = load_shape(path, format);
  if (!loaded.ok()) return loaded.status();
  Model model;
  model.source_unit = loaded.value().unit;
  if (!(model.source_unit.to_mm > 0.0)) {
    // The reader still converted to mm; only the record of the factor is missing.
    model.source_unit.to_mm = 1.0;
    model.metadata["source_unit_note"] = "unit name not recognised, factor unknown";
  }
  model.metadata["source_file"] = path.filename().string();
  model.metadata["source_format"] = format_name(format);
  model.warnings = loaded.value().warnings;
  std::vector<detail::ReadFace> sources;
  Result<std::vector<FaceRecord>> faces = face_records(path, loaded.value(), format, sources);
  if (!faces.ok()) return faces.status();
  model.faces = std::move(faces).value();
  if (model.faces.empty()) {
    return nothing_read(path, std::string(format_name(format)) + " file has no faces",
                        model.warnings);
  }
  Result<Topology> topology =
      detail::read_topology(loaded.value().shape, sources, loaded.value().session,
                            format == CadFormat::step, product_name(loaded.value(), path, format));
  if (!topology.ok()) return file_error(path, topology.status().code, topology.status().message);
  model.topology = std::move(topology).value();
  return model;
}

}  // namespace

std::optional<CadFormat> cad_format_for(const std::filesystem::path& path) {
  const std::string ext = lower(path.extension().string());
  if (ext == ".step" || ext == ".stp") return CadFormat::step;
  if (ext == ".iges" || ext == ".igs") return CadFormat::iges;
  return std::nullopt;
}

Result<Model> read_cad(const std::filesystem::path& path, CadFormat format,
                       const CadReadOptions& options) {
  detail::silence_occt_console();
  const auto lock = detail::lock_occt_exchange();
  Result<FileEnds> ends = read_ends(path);
  if (!ends.ok()) return ends.status();
  const Status structure = format == CadFormat::step ? check_step_structure(path, ends.value())
                                                     : check_iges_structure(path, ends.value());
  if (!structure.ok()) return structure;
  const auto read = [&]() -> Result<Model> {
    try {
      return read_with_occt(path, format);
    } catch (const Standard_Failure& failure) {
      return file_error(path, StatusCode::parse_error,
                        std::string("OpenCASCADE failed: ") + failure.GetMessageString());
    } catch (const std::exception& e) {
      return file_error(path, StatusCode::parse_error, std::string("read failed: ") + e.what());
    }
  };
  if (!options.isolate) return read();
  return detail::read_in_child_process(
      read, {.time_limit_s = options.time_limit_s, .memory_limit_mb = options.memory_limit_mb},
      path.string());
}

}  // namespace argil::io
