// STEP and IGES export through OpenCASCADE (one of the two OCCT seams; the other
// is occt_import.cpp). OCCT types stay in this file and in cad/detail/.
#include <BRepCheck_Analyzer.hxx>
#include <BRep_Builder.hxx>
#include <IFSelect_ReturnStatus.hxx>
#include <IGESControl_Controller.hxx>
#include <IGESControl_Writer.hxx>
#include <IGESData_IGESModel.hxx>
#include <IGESData_IGESWriter.hxx>
#include <IGESSelect_WorkLibrary.hxx>
#include <Interface_FloatWriter.hxx>
#include <Interface_Static.hxx>
#include <STEPControl_Controller.hxx>
#include <STEPControl_Writer.hxx>
#include <Standard_Failure.hxx>
#include <StepData_Protocol.hxx>
#include <StepData_StepModel.hxx>
#include <StepData_StepWriter.hxx>
#include <TopoDS_Compound.hxx>
#include <XSControl_WorkSession.hxx>

#include <algorithm>
#include <fstream>
#include <string>
#include <vector>

#include "argil/io/base/atomic_write.hpp"
#include "argil/io/cad/cad_exchange.hpp"
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
                    const std::string& what) {
  std::string message = std::to_string(failures.size()) + " of " + std::to_string(face_count) +
                        " faces " + what + ", nothing written: ";
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

Status write_step_file(const TopoDS_Shape& shape, const std::filesystem::path& temporary) {
  // The controller defines the writer's settings: setting one before it exists
  // does nothing, as the first write of a process found.
  STEPControl_Controller::Init();
  // Must precede the writer's construction, else the file declares metres.
  Interface_Static::SetCVal("write.step.unit", "MM");
  // The file's uncertainty, which readers take as their precision: the smallest
  // tolerance in the shape (-1) rather than the average (0, the default), at
  // which OpenCASCADE's reader dropped runaway faces (135 of 11752.stp's 1018
  // moved by 1e7 face sizes; 18 at the smallest, docs/io.md).
  Interface_Static::SetIVal("write.precision.mode", -1);
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

Status write_file(const TopoDS_Shape& shape, const std::filesystem::path& file, CadFormat format) {
  return format == CadFormat::step ? write_step_file(shape, file) : write_iges_file(shape, file);
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
  try {
    const Result<std::vector<TopoDS_Face>> faces =
        checked_faces(model, export_tolerance(model, options.tolerance_mm));
    if (!faces.ok()) return failed(faces.status());
    const TopoDS_Shape shape = compound_of(faces.value());
    return write_atomically(path, [&](const std::filesystem::path& temporary) {
      try {
        const Status written = write_file(shape, temporary, format);
        if (!written.ok()) return failed(written);
        if (!options.read_back) return written;
        const std::vector<std::string> failures =
            read_back_failures(model, faces.value(), temporary, format);
        if (failures.empty()) return written;
        return failed(failed_faces(failures, model.faces.size(), "do not read back valid"));
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
