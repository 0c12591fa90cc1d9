#include "argil/io/cad/detail/occt_topology_reader.hpp"

#include <BRepClass3d.hxx>
#include <BRep_Tool.hxx>
#include <NCollection_DataMap.hxx>
#include <StepBasic_Product.hxx>
#include <StepBasic_ProductDefinition.hxx>
#include <StepBasic_ProductDefinitionFormation.hxx>
#include <StepRepr_NextAssemblyUsageOccurrence.hxx>
#include <TCollection_HAsciiString.hxx>
#include <TopExp.hxx>
#include <TopExp_Explorer.hxx>
#include <TopTools_IndexedMapOfShape.hxx>
#include <TopTools_ShapeMapHasher.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Iterator.hxx>
#include <TopoDS_Shell.hxx>
#include <TopoDS_Solid.hxx>
#include <TopoDS_Vertex.hxx>
#include <XSControl_TransferReader.hxx>

#include "argil/io/cad/detail/occt_pcurve.hpp"

namespace argil::io::detail {
namespace {

using ShapeIndex = NCollection_DataMap<TopoDS_Shape, std::size_t, TopTools_ShapeMapHasher>;

std::string text(const Handle(TCollection_HAsciiString) & s) {
  return s.IsNull() ? std::string() : std::string(s->ToCString());
}

// The edge of `face.converted` that `edge` (of `face.original`) became, with
// the orientation `edge` has.
TopoDS_Edge converted_edge(const ReadFace& face, const TopoDS_Edge& edge) {
  if (face.converted.IsNull() || !face.edges.IsBound(edge)) return edge;
  return TopoDS::Edge(face.edges.Find(edge).Oriented(edge.Orientation()));
}

class TopologyReader {
 public:
  TopologyReader(const std::vector<ReadFace>& faces) : faces_(faces) {
    for (std::size_t f = 0; f < faces.size(); ++f) {
      if (!face_index_.IsBound(faces[f].original)) face_index_.Bind(faces[f].original, f);
    }
  }

  Status read_edges() {
    TopTools_IndexedMapOfShape edge_ids, vertex_ids;
    for (std::size_t f = 0; f < faces_.size(); ++f) {
      const ReadFace& face = faces_[f];
      const TopoDS_Face forward = TopoDS::Face(face.original.Oriented(TopAbs_FORWARD));
      const TopoDS_Face on =
          face.converted.IsNull() ? forward : TopoDS::Face(face.converted.Oriented(TopAbs_FORWARD));
      std::vector<std::vector<char>> taken;
      for (const ReadFace::Loop& loop : face.loops) taken.emplace_back(loop.edges.size(), 0);
      for (TopExp_Explorer x(forward, TopAbs_EDGE); x.More(); x.Next()) {
        const TopoDS_Edge& edge = TopoDS::Edge(x.Current());
        const std::size_t id = static_cast<std::size_t>(edge_ids.Add(edge)) - 1;
        if (id == topology_.edges.size()) topology_.edges.push_back(new_edge(edge, vertex_ids));
        Result<BSplineCurve> pcurve =
            edge_pcurve(converted_edge(face, edge), on, PcurveDirection::edge);
        if (!pcurve.ok()) {
          return Status::error(pcurve.status().code, "face " + std::to_string(f) + ": edge " +
                                                         std::to_string(id) + ": " +
                                                         pcurve.status().message);
        }
        EdgeUse use{f, std::move(pcurve).value()};
        place(use, face, converted_edge(face, edge), taken);
        topology_.edges[id].uses.push_back(std::move(use));
      }
    }
    return Status::success();
  }

  void read_shells(const TopoDS_Shape& shape) {
    TopTools_IndexedMapOfShape solids;
    TopExp::MapShapes(shape, TopAbs_SOLID, solids);
    for (int s = 1; s <= solids.Extent(); ++s) {
      const TopoDS_Solid& solid = TopoDS::Solid(solids(s));
      Solid record;
      const TopoDS_Shell outer = BRepClass3d::OuterShell(solid);
      if (!outer.IsNull()) record.shells.push_back(add_shell(outer));
      for (TopExp_Explorer x(solid, TopAbs_SHELL); x.More(); x.Next()) {
        if (!outer.IsNull() && x.Current().IsSame(outer)) continue;
        record.shells.push_back(add_shell(x.Current()));
      }
      if (record.shells.empty()) continue;  // a solid without shells holds no face
      solid_index_.Bind(solid, topology_.solids.size());
      topology_.solids.push_back(std::move(record));
    }
    for (TopExp_Explorer x(shape, TopAbs_SHELL, TopAbs_SOLID); x.More(); x.Next()) {
      if (!shell_index_.IsBound(x.Current())) add_shell(x.Current());
    }
  }

  // Products: the instance tree of the transferred shape, each node named by
  // what STEP says it instances.
  void read_products(const TopoDS_Shape& shape, const Handle(XSControl_WorkSession) & session,
                     bool step, const std::string& name) {
    session_ = step ? session : nullptr;
    Product root;
    root.name = name;
    if (const Handle(StepBasic_ProductDefinition) pd =
            Handle(StepBasic_ProductDefinition)::DownCast(entity(shape));
        !pd.IsNull()) {
      root.name = product_name(pd);
    }
    topology_.products.push_back(root);
    hold(shape, 0, shape.Location());
  }

  Topology take() { return std::move(topology_); }

 private:
  // The trim curve `edge` (a use on `face`, oriented as the face uses it)
  // became: the same edge in the same orientation (a seam is in the loop
  // twice, once each way), else the same edge.
  static void place(EdgeUse& use, const ReadFace& face, const TopoDS_Edge& edge,
                    std::vector<std::vector<char>>& taken) {
    for (const bool exact : {true, false}) {
      for (std::size_t l = 0; l < face.loops.size(); ++l) {
        const std::vector<TopoDS_Edge>& edges = face.loops[l].edges;
        for (std::size_t k = 0; k < edges.size(); ++k) {
          if (taken[l][k] != 0 || !edges[k].IsSame(edge)) continue;
          if (exact && edges[k].Orientation() != edge.Orientation()) continue;
          taken[l][k] = 1;
          use.loop = l;
          use.curve = k;
          use.along = (edges[k].Orientation() != TopAbs_REVERSED) != face.loops[l].reversed;
          return;
        }
      }
    }
  }

  Edge new_edge(const TopoDS_Edge& edge, TopTools_IndexedMapOfShape& vertex_ids) {
    Edge out;
    out.degenerate = BRep_Tool::Degenerated(edge);
    out.tolerance = BRep_Tool::Tolerance(edge);
    TopoDS_Vertex first, last;
    TopExp::Vertices(TopoDS::Edge(edge.Oriented(TopAbs_FORWARD)), first, last);
    out.start = vertex(first, vertex_ids);
    out.end = vertex(last, vertex_ids);
    return out;
  }

  std::size_t vertex(const TopoDS_Vertex& v, TopTools_IndexedMapOfShape& vertex_ids) {
    if (v.IsNull()) return kNoIndex;
    const std::size_t id = static_cast<std::size_t>(vertex_ids.Add(v)) - 1;
    if (id == topology_.vertices.size()) {
      const gp_Pnt p = BRep_Tool::Pnt(v);
      topology_.vertices.push_back({Eigen::Vector3d(p.X(), p.Y(), p.Z()), BRep_Tool::Tolerance(v)});
    }
    return id;
  }

  std::size_t add_shell(const TopoDS_Shape& shell) {
    Shell record;
    for (TopExp_Explorer x(shell, TopAbs_FACE); x.More(); x.Next()) {
      if (face_index_.IsBound(x.Current())) record.faces.push_back(face_index_.Find(x.Current()));
    }
    record.closed = closed(record.faces);
    const std::size_t index = topology_.shells.size();
    shell_index_.Bind(shell, index);
    topology_.shells.push_back(std::move(record));
    return index;
  }

  // No free edge: every edge of the shell's faces is degenerate or used at
  // least twice by them (a seam by one face twice).
  bool closed(const std::vector<std::size_t>& shell_faces) const {
    if (shell_faces.empty()) return false;
    std::vector<char> in_shell(faces_.size(), 0);
    for (const std::size_t f : shell_faces) in_shell[f] = 1;
    for (const Edge& edge : topology_.edges) {
      if (edge.degenerate) continue;
      std::size_t uses = 0;
      bool touches = false;
      for (const EdgeUse& use : edge.uses) {
        touches |= in_shell[use.face] != 0;
        uses += in_shell[use.face] != 0 ? 1u : 0u;
      }
      if (touches && uses < 2) return false;
    }
    return true;
  }

  Handle(Standard_Transient) entity(const TopoDS_Shape& shape) const {
    if (session_.IsNull() || session_->TransferReader().IsNull()) return nullptr;
    return session_->TransferReader()->EntityFromShapeResult(shape, -1);
  }

  static std::string product_name(const Handle(StepBasic_ProductDefinition) & pd) {
    if (pd.IsNull() || pd->Formation().IsNull() || pd->Formation()->OfProduct().IsNull()) {
      return "";
    }
    // Some systems leave the name empty and put it in the id (Ventilator.stp).
    const Handle(StepBasic_Product) product = pd->Formation()->OfProduct();
    const std::string name = text(product->Name());
    return name.empty() ? text(product->Id()) : name;
  }

  // Records what `shape` (located as in the whole) holds under product `p`;
  // `frame`: the location of product p's own frame.
  void hold(const TopoDS_Shape& shape, std::size_t p, const TopLoc_Location& frame) {
    switch (shape.ShapeType()) {
      case TopAbs_SOLID:
        if (solid_index_.IsBound(shape))
          topology_.products[p].solids.push_back(solid_index_.Find(shape));
        return;
      case TopAbs_SHELL:
        if (shell_index_.IsBound(shape))
          topology_.products[p].shells.push_back(shell_index_.Find(shape));
        return;
      case TopAbs_FACE:
        if (face_index_.IsBound(shape))
          topology_.products[p].faces.push_back(face_index_.Find(shape));
        return;
      case TopAbs_COMPOUND:
      case TopAbs_COMPSOLID:
        break;
      default:
        return;
    }
    for (TopoDS_Iterator it(shape); it.More(); it.Next()) {
      const TopoDS_Shape& child = it.Value();
      const auto usage = Handle(StepRepr_NextAssemblyUsageOccurrence)::DownCast(entity(child));
      if (usage.IsNull()) {
        hold(child, p, frame);
        continue;
      }
      Product product;
      product.name = product_name(usage->RelatedProductDefinition());
      product.instance = text(usage->Name());
      product.parent = p;
      const gp_Trsf relative = (frame.Inverted() * child.Location()).Transformation();
      for (int r = 0; r < 3; ++r) {
        for (int c = 0; c < 4; ++c) product.placement(r, c) = relative.Value(r + 1, c + 1);
      }
      const std::size_t index = topology_.products.size();
      topology_.products.push_back(std::move(product));
      hold(child, index, child.Location());
    }
  }

  const std::vector<ReadFace>& faces_;
  ShapeIndex face_index_, solid_index_, shell_index_;
  Handle(XSControl_WorkSession) session_;
  Topology topology_;
};

}  // namespace

Result<Topology> read_topology(const TopoDS_Shape& shape, const std::vector<ReadFace>& faces,
                               const Handle(XSControl_WorkSession) & session, bool step,
                               const std::string& name) {
  TopologyReader reader(faces);
  if (Status s = reader.read_edges(); !s.ok()) return s;
  reader.read_shells(shape);
  reader.read_products(shape, session, step, name);
  return reader.take();
}

}  // namespace argil::io::detail
