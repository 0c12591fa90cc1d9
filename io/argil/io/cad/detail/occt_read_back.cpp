#include "argil/io/cad/detail/occt_read_back.hpp"

#include <BRep_Tool.hxx>
#include <Geom_BSplineSurface.hxx>
#include <Geom_RectangularTrimmedSurface.hxx>
#include <IFSelect_ReturnStatus.hxx>
#include <IGESControl_Controller.hxx>
#include <IGESControl_Reader.hxx>
#include <STEPControl_Reader.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>

#include <algorithm>
#include <array>
#include <memory>
#include <optional>

namespace argil::io::detail {
namespace {

// Pole count and the box of the poles: the same for a surface and its reversal.
struct PoleBox {
  int count = 0;
  std::array<double, 3> min{}, max{};
  bool operator==(const PoleBox&) const = default;
};

std::optional<PoleBox> pole_box(const TopoDS_Face& face) {
  Handle(Geom_Surface) surface = BRep_Tool::Surface(face);
  const auto trimmed = Handle(Geom_RectangularTrimmedSurface)::DownCast(surface);
  if (!trimmed.IsNull()) surface = trimmed->BasisSurface();
  const auto bspline = Handle(Geom_BSplineSurface)::DownCast(surface);
  if (bspline.IsNull()) return std::nullopt;
  PoleBox box;
  box.count = bspline->NbUPoles() * bspline->NbVPoles();
  const gp_Pnt first = bspline->Pole(1, 1);
  box.min = box.max = {first.X(), first.Y(), first.Z()};
  for (int i = 1; i <= bspline->NbUPoles(); ++i) {
    for (int j = 1; j <= bspline->NbVPoles(); ++j) {
      const gp_Pnt p = bspline->Pole(i, j);
      for (int c = 0; c < 3; ++c) {
        box.min[c] = std::min(box.min[c], p.Coord(c + 1));
        box.max[c] = std::max(box.max[c], p.Coord(c + 1));
      }
    }
  }
  return box;
}

}  // namespace

Result<TopoDS_Shape> read_back_shape(const std::filesystem::path& file, CadFormat format) {
  std::unique_ptr<XSControl_Reader> reader;
  if (format == CadFormat::step) {
    reader = std::make_unique<STEPControl_Reader>();
  } else {
    IGESControl_Controller::Init();
    reader = std::make_unique<IGESControl_Reader>();
  }
  if (reader->ReadFile(file.c_str()) != IFSelect_RetDone) {
    return Status::error(StatusCode::io_error, "OpenCASCADE cannot read the file back");
  }
  reader->TransferRoots();
  return reader->OneShape();
}

Result<std::vector<TopoDS_Face>> read_back_faces(const std::filesystem::path& file,
                                                 CadFormat format) {
  const Result<TopoDS_Shape> shape = read_back_shape(file, format);
  if (!shape.ok()) return shape.status();
  std::vector<TopoDS_Face> faces;
  for (TopExp_Explorer e(shape.value(), TopAbs_FACE); e.More(); e.Next()) {
    faces.push_back(TopoDS::Face(e.Current()));
  }
  return faces;
}

std::vector<std::vector<TopoDS_Face>> faces_on_same_surface(const std::vector<TopoDS_Face>& written,
                                                            const std::vector<TopoDS_Face>& back) {
  std::vector<std::optional<PoleBox>> back_boxes;
  for (const TopoDS_Face& face : back) back_boxes.push_back(pole_box(face));
  std::vector<std::vector<TopoDS_Face>> matches(written.size());
  for (std::size_t w = 0; w < written.size(); ++w) {
    const std::optional<PoleBox> box = pole_box(written[w]);
    for (std::size_t b = 0; b < back.size(); ++b) {
      if (box && back_boxes[b] == box) matches[w].push_back(back[b]);
    }
  }
  return matches;
}

}  // namespace argil::io::detail
