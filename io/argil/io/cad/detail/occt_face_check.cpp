#include "argil/io/cad/detail/occt_face_check.hpp"

#include <BRepCheck.hxx>
#include <BRepCheck_Analyzer.hxx>
#include <BRepCheck_ListOfStatus.hxx>
#include <BRepCheck_Result.hxx>
#include <BRep_Tool.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Vertex.hxx>

#include <algorithm>
#include <cctype>
#include <sstream>
#include <vector>

#include "argil/core/base/number_text.hpp"

namespace argil::io::detail {
namespace {

std::string status_name(BRepCheck_Status status) {
  std::ostringstream text;
  BRepCheck::Print(status, text);
  std::string name = text.str();
  while (!name.empty() && std::isspace(static_cast<unsigned char>(name.back()))) name.pop_back();
  return name;
}

const EdgeOrigin* origin_of(const BuiltFace& built, const TopoDS_Shape& edge) {
  for (const EdgeOrigin& origin : built.origins) {
    if (origin.edge.IsSame(edge)) return &origin;
  }
  return nullptr;
}

std::string tolerance_text(double tolerance) {
  return "tolerance " + number_text(tolerance) + " mm";
}

/// Names every sub-shape of the face the way the record knows it.
class Labels {
 public:
  explicit Labels(const BuiltFace& built) : built_(built) {}

  std::string of(const TopoDS_Shape& shape) const {
    switch (shape.ShapeType()) {
      case TopAbs_FACE:
        return "face (" + tolerance_text(BRep_Tool::Tolerance(TopoDS::Face(shape))) + ")";
      case TopAbs_WIRE:
        return wire(shape);
      case TopAbs_EDGE:
        return edge(shape);
      case TopAbs_VERTEX: {
        const TopoDS_Vertex& v = TopoDS::Vertex(shape);
        const gp_Pnt p = BRep_Tool::Pnt(v);
        return "vertex at " + vector_text(std::vector<double>{p.X(), p.Y(), p.Z()}) + " mm (" +
               tolerance_text(BRep_Tool::Tolerance(v)) + ")";
      }
      default:
        return "sub-shape";
    }
  }

 private:
  std::string wire(const TopoDS_Shape& shape) const {
    for (TopExp_Explorer e(shape, TopAbs_EDGE); e.More(); e.Next()) {
      if (const EdgeOrigin* origin = origin_of(built_, e.Current())) {
        return "loop " + std::to_string(origin->loop) + " (wire)";
      }
    }
    return "wire " + std::to_string(index_in_face(shape, TopAbs_WIRE));
  }

  std::string edge(const TopoDS_Shape& shape) const {
    const std::string tolerance = tolerance_text(BRep_Tool::Tolerance(TopoDS::Edge(shape)));
    if (const EdgeOrigin* origin = origin_of(built_, shape)) {
      return "loop " + std::to_string(origin->loop) + " curve " + std::to_string(origin->curve) +
             " (edge, " + tolerance + ")";
    }
    return "edge " + std::to_string(index_in_face(shape, TopAbs_EDGE)) + " (" + tolerance + ")";
  }

  std::size_t index_in_face(const TopoDS_Shape& shape, TopAbs_ShapeEnum kind) const {
    std::size_t index = 0;
    for (TopExp_Explorer e(built_.face, kind); e.More(); e.Next(), ++index) {
      if (e.Current().IsSame(shape)) return index;
    }
    return index;
  }

  const BuiltFace& built_;
};

}  // namespace

std::string face_defects(const BuiltFace& built) {
  const BRepCheck_Analyzer analyzer(built.face);
  if (analyzer.IsValid()) return "";
  const Labels labels(built);
  std::vector<std::string> findings;
  const auto add = [&](const TopoDS_Shape& shape, const BRepCheck_ListOfStatus& statuses) {
    for (const BRepCheck_Status status : statuses) {
      if (status == BRepCheck_NoError) continue;
      const std::string finding = labels.of(shape) + ": " + status_name(status);
      if (std::find(findings.begin(), findings.end(), finding) == findings.end()) {
        findings.push_back(finding);
      }
    }
  };
  const auto add_results = [&](const TopoDS_Shape& shape) {
    const Handle(BRepCheck_Result)& result = analyzer.Result(shape);
    if (result.IsNull()) return;
    add(shape, result->Status());
    for (result->InitContextIterator(); result->MoreShapeInContext();
         result->NextShapeInContext()) {
      add(shape, result->StatusOnShape());
    }
  };
  add_results(built.face);
  for (const TopAbs_ShapeEnum kind : {TopAbs_WIRE, TopAbs_EDGE, TopAbs_VERTEX}) {
    for (TopExp_Explorer e(built.face, kind); e.More(); e.Next()) add_results(e.Current());
  }
  if (findings.empty()) return "BRepCheck_Analyzer finds the face invalid without naming a defect";
  std::string text;
  for (const std::string& finding : findings) text += (text.empty() ? "" : "; ") + finding;
  return text;
}

}  // namespace argil::io::detail
