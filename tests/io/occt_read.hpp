#pragma once
// Plain OpenCASCADE reading of a STEP or IGES file, no argil code involved:
// the oracle side of the IO tests that compare with OCCT.

#include <BRepBndLib.hxx>
#include <Bnd_Box.hxx>
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

#include "argil/io.hpp"

namespace argil::io {

struct OcctShape {
  std::vector<TopoDS_Face> faces;
  double diagonal_mm = 0.0;
  std::string step_length_unit;  // STEP only
};

// Plain OpenCASCADE reading, no argil code involved.
inline OcctShape occt_read(const std::filesystem::path& path) {
  Message::DefaultMessenger()->RemovePrinters(STANDARD_TYPE(Message_PrinterOStream));
  OcctShape out;
  TopoDS_Shape shape;
  if (cad_format_for(path) == CadFormat::step) {
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

}  // namespace argil::io
