// STEP and IGES export through OpenCASCADE (one of the two OCCT seams; the other
// is occt_import.cpp). OCCT types stay in this file and in cad/detail/.
#include <BRepBuilderAPI_Transform.hxx>
#include <BRepCheck.hxx>
#include <BRepCheck_Analyzer.hxx>
#include <BRepCheck_ListOfStatus.hxx>
#include <BRepCheck_Result.hxx>
#include <BRep_Builder.hxx>
#include <BRep_Tool.hxx>
#include <IFSelect_ReturnStatus.hxx>
#include <IGESControl_Controller.hxx>
#include <IGESControl_Writer.hxx>
#include <IGESData_IGESModel.hxx>
#include <IGESData_IGESWriter.hxx>
#include <IGESSelect_WorkLibrary.hxx>
#include <Interface_FloatWriter.hxx>
#include <Interface_Static.hxx>
#include <STEPCAFControl_Writer.hxx>
#include <STEPControl_Controller.hxx>
#include <STEPControl_Writer.hxx>
#include <Standard_Failure.hxx>
#include <StepData_Protocol.hxx>
#include <StepData_StepModel.hxx>
#include <StepData_StepWriter.hxx>
#include <TDataStd_Name.hxx>
#include <TDocStd_Document.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS_Compound.hxx>
#include <XCAFApp_Application.hxx>
#include <XCAFDoc_DocumentTool.hxx>
#include <XCAFDoc_ShapeTool.hxx>
#include <XSControl_WorkSession.hxx>

#include <algorithm>
#include <fstream>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "argil/core/base/number_text.hpp"
#include "argil/io/base/atomic_write.hpp"
#include "argil/io/cad/cad_exchange.hpp"
#include "argil/io/cad/detail/occt_brep_builder.hpp"
#include "argil/io/cad/detail/occt_face_builder.hpp"
#include "argil/io/cad/detail/occt_face_check.hpp"
#include "argil/io/cad/detail/occt_read_back.hpp"
#include "argil/io/cad/detail/occt_session.hpp"
#include "argil/io/model/trim_curve.hpp"

namespace argil::io {
namespace {

// Failing faces listed in one message; the rest are counted.
constexpr std::size_t kFacesListed = 10;

// "face 3 (#4577 "Face1")": the index, and the source entity and name when known.
std::string face_label(const FaceRecord& record, std::size_t index) {
  std::string label = "face " + std::to_string(index);
  std::string source = record.source_id;
  if (!record.name.empty()) source += (source.empty() ? "\"" : " \"") + record.name + "\"";
  return source.empty() ? label : label + " (" + source + ")";
}

// The face of one record, checked; the error names the face.
Result<TopoDS_Face> checked_face(const FaceRecord& record, std::size_t index, double tolerance) {
  const std::string label = face_label(record, index);
  const Status valid = validate_face(record);
  if (!valid.ok()) return Status::error(valid.code, label + ": " + valid.message);
  try {
    Result<detail::BuiltFace> built = detail::build_occt_face(record, tolerance);
    if (!built.ok()) {
      return Status::error(built.status().code, label + ": " + built.status().message);
    }
    const std::string defects = detail::face_defects(built.value());
    if (!defects.empty()) {
      return Status::error(StatusCode::invalid_surface,
                           label + " fails BRepCheck_Analyzer: " + defects);
    }
    return built.value().face;
  } catch (const Standard_Failure& failure) {
    return Status::error(StatusCode::invalid_surface,
                         label + ": OpenCASCADE failed: " + failure.GetMessageString());
  }
}

// The error for faces that failed: how many, and each one's message (the first
// kFacesListed, then a count).
Status failed_faces(const std::vector<std::string>& failures, std::size_t face_count,
                    const std::string& what, const char* outcome = ", nothing written: ") {
  std::string message = std::to_string(failures.size()) + " of " + std::to_string(face_count) +
                        " faces " + what + outcome;
  for (std::size_t k = 0; k < std::min(failures.size(), kFacesListed); ++k) {
    message += (k == 0 ? "" : " | ") + failures[k];
  }
  if (failures.size() > kFacesListed) {
    message += " | and " + std::to_string(failures.size() - kFacesListed) + " more";
  }
  return Status::error(StatusCode::invalid_surface, message);
}

// Every face built and checked; the error lists every face that failed.
Result<std::vector<TopoDS_Face>> checked_faces(const Model& model, double tolerance) {
  std::vector<TopoDS_Face> faces;
  std::vector<std::string> failures;
  StatusCode code = StatusCode::ok;
  for (std::size_t f = 0; f < model.faces.size(); ++f) {
    Result<TopoDS_Face> face = checked_face(model.faces[f], f, tolerance);
    if (face.ok()) {
      faces.push_back(face.value());
    } else {
      if (failures.empty()) code = face.status().code;
      failures.push_back(face.status().message);
    }
  }
  if (failures.empty()) return faces;
  Status failed = failed_faces(failures, model.faces.size(), "cannot be exported valid");
  failed.code = code;
  return failed;
}

TopoDS_Shape compound_of(const std::vector<TopoDS_Face>& faces) {
  BRep_Builder builder;
  TopoDS_Compound compound;
  builder.MakeCompound(compound);
  for (const TopoDS_Face& face : faces) builder.Add(compound, face);
  return compound;
}

// The writers' settings: the controller defines them, so setting one before
// it exists does nothing, as the first write of a process found.
void set_step_options() {
  STEPControl_Controller::Init();
  // Must precede the writer's construction, else the file declares metres.
  Interface_Static::SetCVal("write.step.unit", "MM");
  // The file's uncertainty, which readers take as their precision: the smallest
  // tolerance in the shape (-1) rather than the average (0, the default), at
  // which OpenCASCADE's reader dropped runaway faces (135 of 11752.stp's 1018
  // moved by 1e7 face sizes; 18 at the smallest, docs/io.md).
  Interface_Static::SetIVal("write.precision.mode", -1);
}

// The transferred model printed with 17 significant digits.
Status print_step(STEPControl_Writer& writer, const std::filesystem::path& temporary) {
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

Status write_step_file(const TopoDS_Shape& shape, const std::filesystem::path& temporary) {
  set_step_options();
  STEPControl_Writer writer;
  if (writer.Transfer(shape, STEPControl_AsIs) != IFSelect_RetDone) {
    return Status::error(StatusCode::io_error, "STEP transfer failed");
  }
  return print_step(writer, temporary);
}

gp_Trsf placement_trsf(const Eigen::Matrix<double, 3, 4>& m) {
  gp_Trsf t;
  t.SetValues(m(0, 0), m(0, 1), m(0, 2), m(0, 3), m(1, 0), m(1, 1), m(1, 2), m(1, 3), m(2, 0),
              m(2, 1), m(2, 2), m(2, 3));
  return t;
}

// A product's content in its own frame: the world-frame shapes moved back by
// its world placement (geometry transformed: XCAF would make a located shape
// an assembly of one). The caller skips unplaced products, which keep their
// geometry bit for bit.
TopoDS_Shape in_own_frame(const TopoDS_Shape& shape, const gp_Trsf& world) {
  if (shape.IsNull()) return shape;
  return BRepBuilderAPI_Transform(shape, world.Inverted(), true).Shape();
}

// The product tree as an XCAF document: one part per product holding shapes,
// assemblies for products with children (their own shapes one more part in
// them), every product named, every instance placed and named.
void fill_products(const Handle(TDocStd_Document) & document, const Topology& topology,
                   const detail::BuiltBrep& brep) {
  const Handle(XCAFDoc_ShapeTool) tool = XCAFDoc_DocumentTool::ShapeTool(document->Main());
  const std::size_t n = topology.products.size();
  std::vector<gp_Trsf> world(n);
  std::vector<char> placed(n, 0);  // moved from the world frame: geometry transformed
  std::vector<std::vector<std::size_t>> children(n);
  for (std::size_t p = 0; p < n; ++p) {
    const Product& product = topology.products[p];
    world[p] = placement_trsf(product.placement);
    placed[p] = product.placement.isIdentity(0.0) ? 0 : 1;
    if (product.parent != kNoIndex) {
      world[p] = world[product.parent] * world[p];
      placed[p] = placed[p] != 0 || placed[product.parent] != 0 ? 1 : 0;
      children[product.parent].push_back(p);
    }
  }
  const auto named = [](const TDF_Label& label, const std::string& name) {
    if (!name.empty()) TDataStd_Name::Set(label, TCollection_ExtendedString(name.c_str(), true));
  };
  std::vector<TDF_Label> labels(n);
  for (std::size_t p = n; p-- > 0;) {  // children come after their parents
    const Product& product = topology.products[p];
    const TopoDS_Shape own =
        placed[p] ? in_own_frame(brep.products[p], world[p]) : brep.products[p];
    if (children[p].empty()) {
      // A product holding nothing (a wireframe part) is still a product.
      labels[p] = own.IsNull() ? tool->NewShape() : tool->AddShape(own, false);
    } else {
      labels[p] = tool->NewShape();
      if (!own.IsNull())
        tool->AddComponent(labels[p], tool->AddShape(own, false), TopLoc_Location());
      for (const std::size_t c : children[p]) {
        const TDF_Label instance = tool->AddComponent(
            labels[p], labels[c], TopLoc_Location(placement_trsf(topology.products[c].placement)));
        named(instance, topology.products[c].instance);
      }
    }
    named(labels[p], product.name);
  }
  if (!brep.unheld.IsNull()) tool->AddShape(brep.unheld, false);
  tool->UpdateAssemblies();
}

// STEP with the products, their names and placements (XCAF).
Status write_step_products(const Model& model, const detail::BuiltBrep& brep,
                           const std::filesystem::path& temporary) {
  set_step_options();
  const Handle(XCAFApp_Application) app = XCAFApp_Application::GetApplication();
  Handle(TDocStd_Document) document;
  app->NewDocument("MDTV-XCAF", document);
  if (document.IsNull()) return Status::error(StatusCode::io_error, "no XCAF document");
  // The application keeps every open document: closed however this returns.
  struct Closer {
    const Handle(XCAFApp_Application) & app;
    Handle(TDocStd_Document) & document;
    ~Closer() { app->Close(document); }
  } closer{app, document};
  // Products are named from the model; unnamed ones stay unnamed ("COMPOUND" otherwise).
  XCAFDoc_ShapeTool::SetAutoNaming(false);
  fill_products(document, model.topology, brep);
  STEPCAFControl_Writer writer;
  writer.SetNameMode(true);
  if (!writer.Transfer(document, STEPControl_AsIs)) {
    return Status::error(StatusCode::invalid_surface, "STEP transfer of the B-rep failed");
  }
  return print_step(writer.ChangeWriter(), temporary);
}

// `brep`: solids and shells as 186/514/510 (MSBO, shell, face), else trimmed
// surfaces (144 over 128).
Status write_iges_file(const TopoDS_Shape& shape, const std::filesystem::path& temporary,
                       bool brep) {
  IGESControl_Controller::Init();
  Interface_Static::SetIVal("write.iges.brep.mode", brep ? 1 : 0);
  IGESControl_Writer writer("MM", brep ? 1 : 0);
  if (!writer.AddShape(shape)) {
    return Status::error(brep ? StatusCode::invalid_surface : StatusCode::io_error,
                         "IGES transfer failed");
  }
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

Status write_file(const TopoDS_Shape& shape, const std::filesystem::path& file, CadFormat format) {
  return format == CadFormat::step ? write_step_file(shape, file)
                                   : write_iges_file(shape, file, false);
}

// A face read back from `file` that fails BRepCheck_Analyzer, named as in the model.
std::string invalid_read_back(const FaceRecord& record, std::size_t index,
                              const TopoDS_Face& face) {
  return face_label(record, index) +
         " reads back invalid: " + detail::face_defects(detail::BuiltFace{face, {}});
}

// The faces of `model` (built as `faces`) that do not come back from `file` as
// one BRepCheck-valid face each; empty when all do.
std::vector<std::string> read_back_failures(const Model& model,
                                            const std::vector<TopoDS_Face>& faces,
                                            const std::filesystem::path& file, CadFormat format) {
  const Result<std::vector<TopoDS_Face>> back = detail::read_back_faces(file, format);
  if (!back.ok()) return {back.status().message};
  std::vector<std::string> failures;
  if (back.value().size() == faces.size()) {
    for (std::size_t f = 0; f < faces.size(); ++f) {
      if (!BRepCheck_Analyzer(back.value()[f]).IsValid()) {
        failures.push_back(invalid_read_back(model.faces[f], f, back.value()[f]));
      }
    }
    return failures;
  }
  // The reader lost or split faces: find which by their surfaces.
  const std::vector<std::vector<TopoDS_Face>> matches =
      detail::faces_on_same_surface(faces, back.value());
  for (std::size_t f = 0; f < faces.size(); ++f) {
    if (matches[f].size() != 1) {
      failures.push_back(face_label(model.faces[f], f) + " reads back as " +
                         std::to_string(matches[f].size()) + " faces");
    } else if (!BRepCheck_Analyzer(matches[f][0]).IsValid()) {
      failures.push_back(invalid_read_back(model.faces[f], f, matches[f][0]));
    }
  }
  if (failures.empty()) {  // two faces on one surface, say: the count alone is known
    failures.push_back("the file reads back with " + std::to_string(back.value().size()) +
                       " faces, " + std::to_string(faces.size()) + " written");
  }
  return failures;
}

// What BRepCheck_Analyzer finds wrong with the shells and solids of `shape`
// ("shell 2: BRepCheck_NotClosed"); empty when they are valid.
std::string brep_defects(const TopoDS_Shape& shape) {
  BRepCheck_Analyzer analyzer(shape);
  if (analyzer.IsValid()) return "";
  std::ostringstream out;
  for (const auto& [type, name] : {std::pair{TopAbs_SOLID, "solid"}, {TopAbs_SHELL, "shell"}}) {
    int index = 0;
    for (TopExp_Explorer x(shape, type); x.More(); x.Next(), ++index) {
      const Handle(BRepCheck_Result) result = analyzer.Result(x.Current());
      if (result.IsNull()) continue;
      for (const BRepCheck_Status status : result->Status()) {
        if (status == BRepCheck_NoError) continue;
        out << (out.tellp() > 0 ? "; " : "") << name << " " << index << ": ";
        BRepCheck::Print(status, out);
      }
    }
  }
  const std::string found = out.str();
  return found.empty() ? "an edge or vertex shared by faces" : found;
}

// Every face built on its shared edges and checked, then the shells and
// solids; the error lists every face that failed.
Result<detail::BuiltBrep> checked_brep(const Model& model, double tolerance) {
  if (const Status s = validate_topology(model); !s.ok()) {
    return Status::error(s.code, "topology: " + s.message);
  }
  Result<detail::BuiltBrep> brep = detail::build_occt_brep(model, tolerance);
  if (!brep.ok()) return brep.status();
  std::vector<std::string> failures;
  for (std::size_t f = 0; f < model.faces.size(); ++f) {
    const std::string defects = detail::face_defects(detail::BuiltFace{brep.value().faces[f], {}});
    if (!defects.empty()) {
      failures.push_back(face_label(model.faces[f], f) + " fails BRepCheck_Analyzer: " + defects);
    }
  }
  if (!failures.empty()) {
    return failed_faces(failures, model.faces.size(), "cannot be built on shared edges", ": ");
  }
  return brep;
}

TopoDS_Shape everything(const detail::BuiltBrep& brep) {
  BRep_Builder builder;
  TopoDS_Compound compound;
  builder.MakeCompound(compound);
  for (const TopoDS_Shape& shape : brep.products) {
    if (!shape.IsNull()) builder.Add(compound, shape);
  }
  if (!brep.unheld.IsNull()) builder.Add(compound, brep.unheld);
  return compound;
}

// Open shells are not compared: a writer wraps loose faces in shells of their own.
struct ShellCensus {
  int solids = 0, closed_shells = 0;
  bool operator==(const ShellCensus&) const = default;
};

ShellCensus shell_census(const TopoDS_Shape& shape) {
  ShellCensus c;
  for (TopExp_Explorer x(shape, TopAbs_SOLID); x.More(); x.Next()) ++c.solids;
  for (TopExp_Explorer x(shape, TopAbs_SHELL); x.More(); x.Next()) {
    c.closed_shells += BRep_Tool::IsClosed(x.Current()) ? 1 : 0;
  }
  return c;
}

std::string census_text(const ShellCensus& c) {
  return std::to_string(c.solids) + " solids and " + std::to_string(c.closed_shells) +
         " closed shells";
}

// The written file read back holds the solids and closed shells that were
// written, valid; else what differs.
std::string brep_read_back(const TopoDS_Shape& written, const std::filesystem::path& file,
                           CadFormat format) {
  const Result<TopoDS_Shape> back = detail::read_back_shape(file, format);
  if (!back.ok()) return back.status().message;
  const ShellCensus expected = shell_census(written), got = shell_census(back.value());
  if (!(expected == got)) {
    return "the file reads back with " + census_text(got) + ", " + census_text(expected) +
           " written";
  }
  const std::string defects = brep_defects(back.value());
  return defects.empty() ? "" : "the file reads back invalid: " + defects;
}

// An OpenCASCADE exception as a status.
template <typename Write>
Status guarded(Write&& write) {
  try {
    return write();
  } catch (const Standard_Failure& failure) {
    return Status::error(StatusCode::invalid_surface, std::string("OpenCASCADE failed: ") +
                                                          failure.GetMessageString() + " (" +
                                                          failure.DynamicType()->Name() + ")");
  }
}

// Shared edges whose faces came apart by more than eps beyond the source's
// tolerance (the edge's tolerance grew to cover the gap): a line naming how
// many and the widest, or "".
std::string open_edges(const Model& model, const detail::BuiltBrep& brep, double eps) {
  std::size_t open = 0, widest = 0;
  double widest_gap = 0.0;
  for (std::size_t e = 0; e < model.topology.edges.size(); ++e) {
    const Edge& edge = model.topology.edges[e];
    bool shared = false;
    for (const EdgeUse& use : edge.uses) shared |= use.face != edge.uses.front().face;
    if (!shared || edge.degenerate) continue;
    const double gap = BRep_Tool::Tolerance(brep.edges[e]);
    // Beyond what the source itself allowed: Ventilator.stp has edges of
    // tolerance 0.014 mm, which a move of 1e-4 mm must not report at eps 0.01.
    if (gap <= edge.tolerance + eps) continue;
    ++open;
    if (gap > widest_gap) widest_gap = gap, widest = e;
  }
  if (open == 0) return "";
  const Edge& edge = model.topology.edges[widest];
  std::string faces;
  for (const EdgeUse& use : edge.uses) {
    faces += (faces.empty() ? "" : " and ") + face_label(model.faces[use.face], use.face);
  }
  return std::to_string(open) + " shared edges are open wider than eps (" + number_text(eps) +
         " mm), written with tolerances that cover the gaps; the widest, edge " +
         std::to_string(widest) + " between " + faces + ", by " + number_text(widest_gap) + " mm";
}

// Writes the model's B-rep whole, checked as built and as read back; `notes`
// receives what the caller should hear about it (edges left open).
Status write_whole(const Model& model, const std::filesystem::path& path, CadFormat format,
                   double tolerance, double eps, bool read_back, std::vector<std::string>& notes) {
  Result<detail::BuiltBrep> built = checked_brep(model, tolerance);
  if (!built.ok()) return built.status();
  const detail::BuiltBrep& brep = built.value();
  if (eps > 0.0) {
    if (std::string open = open_edges(model, brep, eps); !open.empty()) {
      notes.push_back(std::move(open));
    }
  }
  const TopoDS_Shape shape = everything(brep);
  if (const std::string defects = brep_defects(shape); !defects.empty()) {
    return Status::error(StatusCode::invalid_surface,
                         "the B-rep fails BRepCheck_Analyzer: " + defects);
  }
  return write_atomically(path, [&](const std::filesystem::path& temporary) {
    return guarded([&] {
      const Status written = format == CadFormat::step ? write_step_products(model, brep, temporary)
                                                       : write_iges_file(shape, temporary, true);
      if (!written.ok() || !read_back) return written;
      const std::vector<std::string> failures =
          read_back_failures(model, brep.faces, temporary, format);
      if (!failures.empty()) {
        return failed_faces(failures, model.faces.size(), "do not read back valid", ": ");
      }
      const std::string lost = brep_read_back(shape, temporary, format);
      return lost.empty() ? written : Status::error(StatusCode::invalid_surface, lost);
    });
  });
}

// Writes every face alone, checked as built and as read back.
Status write_faces(const Model& model, const std::filesystem::path& path, CadFormat format,
                   double tolerance, bool read_back) {
  const Result<std::vector<TopoDS_Face>> faces = checked_faces(model, tolerance);
  if (!faces.ok()) return faces.status();
  const TopoDS_Shape shape = compound_of(faces.value());
  return write_atomically(path, [&](const std::filesystem::path& temporary) {
    return guarded([&] {
      const Status written = write_file(shape, temporary, format);
      if (!written.ok() || !read_back) return written;
      const std::vector<std::string> failures =
          read_back_failures(model, faces.value(), temporary, format);
      if (failures.empty()) return written;
      return failed_faces(failures, model.faces.size(), "do not read back valid");
    });
  });
}

}  // namespace

double export_tolerance(const Model& model, double eps_mm) {
  const double relative = kExportRelativeTolerance * model_box(model).diagonal();
  return std::max(kMinExportTolerance, eps_mm > 0.0 ? std::min(eps_mm, relative) : relative);
}

Status write_cad(const Model& model, const std::filesystem::path& path, CadFormat format,
                 const CadWriteOptions& options) {
  detail::silence_occt_console();
  const auto lock = detail::lock_occt_exchange();
  const auto failed = [&](const Status& status) {
    return Status::error(status.code, path.string() + ": " + status.message);
  };
  if (model.faces.empty()) {
    return failed(Status::error(StatusCode::invalid_argument, "the model has no faces"));
  }
  const double tolerance = export_tolerance(model, options.tolerance_mm);
  // IGES writes a B-rep only around solids: loose faces are trimmed surfaces
  // (144), which more systems read. Models without placed uses (JSON written
  // before they were recorded, models built in code) are loose faces.
  const bool has_brep = !model.topology.edges.empty() &&
                        (format == CadFormat::step || !model.topology.solids.empty());
  const bool whole = has_brep && uses_placed(model.topology);
  std::string torn;
  if (has_brep && !whole) {
    torn = "some edge uses do not say which trim curve they are (loop, curve)";
  }
  if (whole) {
    std::vector<std::string> notes;
    const Status written = guarded([&] {
      return write_whole(model, path, format, tolerance, options.tolerance_mm, options.read_back,
                         notes);
    });
    if (written.ok()) {
      for (const std::string& note : notes) {
        if (options.warnings != nullptr) options.warnings->push_back(path.string() + ": " + note);
      }
      return written;
    }
    if (written.code == StatusCode::io_error) return failed(written);
    // Faces sculpted apart across their shared edges make no valid B-rep;
    // the faces alone may still be valid, and the user is told.
    torn = written.message;
  }
  const Status written =
      guarded([&] { return write_faces(model, path, format, tolerance, options.read_back); });
  if (!written.ok()) return failed(written);
  // The reason names what went wrong with the whole B-rep (faces it lost on
  // reading back, say), not with the file written: say which is which.
  if (!torn.empty() && options.warnings != nullptr) {
    options.warnings->push_back(
        path.string() + ": the B-rep could not be written whole (" + torn +
        "); its faces were written one by one instead (no shared edges, shells or solids)" +
        (options.read_back ? ", and every one of them reads back valid" : ""));
  }
  return written;
}

}  // namespace argil::io
