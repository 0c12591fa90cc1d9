#include "support/occt_topology.hpp"

#include <BRepCheck_Analyzer.hxx>
#include <BRepGProp.hxx>
#include <BRep_Tool.hxx>
#include <GProp_GProps.hxx>
#include <IFSelect_ReturnStatus.hxx>
#include <IGESControl_Controller.hxx>
#include <IGESControl_Reader.hxx>
#include <Interface_Static.hxx>
#include <Message.hxx>
#include <Message_Messenger.hxx>
#include <Message_PrinterOStream.hxx>
#include <STEPControl_Controller.hxx>
#include <STEPControl_Reader.hxx>
#include <Standard_Failure.hxx>
#include <StepBasic_Product.hxx>
#include <StepData_StepModel.hxx>
#include <TCollection_HAsciiString.hxx>
#include <TopExp.hxx>
#include <TopExp_Explorer.hxx>
#include <TopTools_IndexedDataMapOfShapeListOfShape.hxx>
#include <TopTools_IndexedMapOfShape.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Edge.hxx>
#include <TopoDS_Face.hxx>
#include <TopoDS_Shape.hxx>

#include <algorithm>
#include <cctype>
#include <stdexcept>
#include <unordered_set>

namespace argil::test {
namespace {

enum class Format { step, iges };

Format format_of(const std::filesystem::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (ext == ".step" || ext == ".stp") return Format::step;
  if (ext == ".iges" || ext == ".igs") return Format::iges;
  throw std::runtime_error("occt_topology: " + path.string() +
                           ": not a STEP (.step, .stp) or IGES (.iges, .igs) file");
}

[[noreturn]] void fail(const std::filesystem::path& path, const std::string& what) {
  throw std::runtime_error("occt_topology: OpenCASCADE cannot read " + path.string() + ": " + what);
}

void read_in_millimetres(const std::filesystem::path& path) {
  // The static exists once the controller is initialised; set it after that, or
  // the call fails silently.
  if (!Interface_Static::SetCVal("xstep.cascade.unit", "MM")) fail(path, "xstep.cascade.unit");
}

struct Transferred {
  TopoDS_Shape shape;
  int products = 0;
  std::vector<std::string> product_names;
};

Transferred read_step(const std::filesystem::path& path) {
  STEPControl_Controller::Init();
  read_in_millimetres(path);
  STEPControl_Reader reader;
  if (reader.ReadFile(path.c_str()) != IFSelect_RetDone) fail(path, "STEPControl_Reader::ReadFile");
  Transferred out;
  const Handle(StepData_StepModel) model = reader.StepModel();
  for (int i = 1; i <= model->NbEntities(); ++i) {
    const auto product = Handle(StepBasic_Product)::DownCast(model->Value(i));
    if (product.IsNull()) continue;
    ++out.products;
    const Handle(TCollection_HAsciiString) name = product->Name();
    out.product_names.emplace_back(name.IsNull() ? "" : name->ToCString());
  }
  if (reader.TransferRoots() == 0) fail(path, "no root transferred");
  out.shape = reader.OneShape();
  return out;
}

Transferred read_iges(const std::filesystem::path& path) {
  IGESControl_Controller::Init();
  read_in_millimetres(path);
  IGESControl_Reader reader;
  if (reader.ReadFile(path.c_str()) != IFSelect_RetDone) fail(path, "IGESControl_Reader::ReadFile");
  if (reader.TransferRoots() == 0) fail(path, "no root transferred");
  Transferred out;
  out.products = 1;
  out.shape = reader.OneShape();
  return out;
}

int distinct(const TopoDS_Shape& shape, TopAbs_ShapeEnum type) {
  TopTools_IndexedMapOfShape map;
  TopExp::MapShapes(shape, type, map);
  return map.Extent();
}

void count_edges(const TopoDS_Shape& shape, OcctTopology& out) {
  out.edges = distinct(shape, TopAbs_EDGE);
  // Maps every edge of `shape`, with an empty list for an edge outside every face.
  TopTools_IndexedDataMapOfShapeListOfShape faces_of;
  TopExp::MapShapesAndUniqueAncestors(shape, TopAbs_EDGE, TopAbs_FACE, faces_of);
  for (int i = 1; i <= faces_of.Extent(); ++i) {
    const TopoDS_Edge& edge = TopoDS::Edge(faces_of.FindKey(i));
    const TopTools_ListOfShape& faces = faces_of(i);
    if (BRep_Tool::Degenerated(edge)) {
      ++out.degenerated_edges;
      continue;
    }
    if (faces.IsEmpty()) {
      ++out.loose_edges;
      continue;
    }
    bool seam = false;
    for (const TopoDS_Shape& face : faces)
      seam = seam || BRep_Tool::IsClosed(edge, TopoDS::Face(face));
    const bool shared = faces.Extent() >= 2;
    if (seam) ++out.seam_edges;
    if (shared) ++out.shared_edges;
    if (seam && shared) ++out.seam_shared_edges;
    if (!seam && faces.Extent() == 1) ++out.free_edges;
  }
}

OcctTopology census(const Transferred& read) {
  const TopoDS_Shape& shape = read.shape;
  OcctTopology out;
  out.products = read.products;
  out.product_names = read.product_names;

  TopTools_IndexedMapOfShape solids;
  TopExp::MapShapes(shape, TopAbs_SOLID, solids);
  out.solids = solids.Extent();
  std::unordered_set<const TopoDS_TShape*> parts;
  for (int i = 1; i <= solids.Extent(); ++i) {
    parts.insert(solids(i).TShape().get());
    GProp_GProps props;
    // Adaptive to 1e-7 relative: the fixed Gauss rule is off by 0.8 % on
    // rational B-spline faces (screw.step converted).
    BRepGProp::VolumeProperties(solids(i), props, 1e-7);
    out.volume += props.Mass();
  }
  out.distinct_solids = static_cast<int>(parts.size());

  TopTools_IndexedMapOfShape shells;
  TopExp::MapShapes(shape, TopAbs_SHELL, shells);
  out.shells = shells.Extent();
  for (int i = 1; i <= shells.Extent(); ++i) {
    if (BRep_Tool::IsClosed(shells(i))) ++out.closed_shells;
  }

  std::unordered_set<const TopoDS_TShape*> face_tshapes;
  for (TopExp_Explorer e(shape, TopAbs_FACE); e.More(); e.Next()) {
    ++out.faces;
    face_tshapes.insert(e.Current().TShape().get());
  }
  out.distinct_faces = static_cast<int>(face_tshapes.size());

  count_edges(shape, out);
  out.vertices = distinct(shape, TopAbs_VERTEX);
  out.valid = BRepCheck_Analyzer(shape).IsValid();
  return out;
}

}  // namespace

OcctTopology occt_topology(const std::filesystem::path& path) {
  const Format format = format_of(path);
  Message::DefaultMessenger()->RemovePrinters(STANDARD_TYPE(Message_PrinterOStream));
  try {
    const Transferred read = format == Format::step ? read_step(path) : read_iges(path);
    if (read.shape.IsNull()) fail(path, "the transferred shape is null");
    return census(read);
  } catch (const Standard_Failure& e) {
    fail(path, std::string("OpenCASCADE exception ") + e.DynamicType()->Name() + ": " +
                   e.GetMessageString());
  }
}

}  // namespace argil::test
