#pragma once
// Plain OpenCASCADE reading of a STEP or IGES file, no argil code involved: the
// oracle for what argil writes. Only targets that link argil_occt include it.

#include <BRepBndLib.hxx>
#include <BRep_Tool.hxx>
#include <Bnd_Box.hxx>
#include <Geom_BSplineSurface.hxx>
#include <Geom_RectangularTrimmedSurface.hxx>
#include <IGESControl_Controller.hxx>
#include <IGESControl_Reader.hxx>
#include <Interface_Static.hxx>
#include <Message.hxx>
#include <Message_Messenger.hxx>
#include <Message_PrinterOStream.hxx>
#include <STEPControl_Reader.hxx>
#include <TColStd_SequenceOfAsciiString.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Face.hxx>

#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "argil/io/cad/cad_exchange.hpp"

namespace argil::test {

struct OcctShape {
  std::vector<TopoDS_Face> faces;
  double diagonal_mm = 0.0;
  std::string step_length_unit;  // STEP only
};

/// Every face of the file in TopExp_Explorer order, in millimetres.
inline OcctShape occt_read(const std::filesystem::path& path) {
  Message::DefaultMessenger()->RemovePrinters(STANDARD_TYPE(Message_PrinterOStream));
  OcctShape out;
  TopoDS_Shape shape;
  if (io::cad_format_for(path) == io::CadFormat::step) {
    Interface_Static::SetCVal("xstep.cascade.unit", "MM");
    STEPControl_Reader reader;
    REQUIRE(reader.ReadFile(path.c_str()) == IFSelect_RetDone);
    reader.TransferRoots();
    shape = reader.OneShape();
    TColStd_SequenceOfAsciiString lengths, angles, solids;
    reader.FileUnits(lengths, angles, solids);
    if (lengths.Length() > 0) out.step_length_unit = lengths(1).ToCString();
  } else {
    IGESControl_Controller::Init();
    Interface_Static::SetCVal("xstep.cascade.unit", "MM");
    IGESControl_Reader reader;
    REQUIRE(reader.ReadFile(path.c_str()) == IFSelect_RetDone);
    reader.TransferRoots();
    shape = reader.OneShape();
  }
  for (TopExp_Explorer e(shape, TopAbs_FACE); e.More(); e.Next()) {
    out.faces.push_back(TopoDS::Face(e.Current()));
  }
  Bnd_Box box;
  BRepBndLib::Add(shape, box);
  out.diagonal_mm = std::sqrt(box.SquareExtent());
  return out;
}

/// The B-spline surface under a face's surface (through a rectangular trim), or null.
inline Handle(Geom_BSplineSurface) as_bspline(Handle(Geom_Surface) surface) {
  const auto trimmed = Handle(Geom_RectangularTrimmedSurface)::DownCast(surface);
  if (!trimmed.IsNull()) surface = trimmed->BasisSurface();
  return Handle(Geom_BSplineSurface)::DownCast(surface);
}

}  // namespace argil::test
