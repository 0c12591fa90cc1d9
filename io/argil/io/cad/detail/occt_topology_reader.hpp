#pragma once
// Internal to argil_io: the B-rep of a transferred shape (products, solids,
// shells, edges, vertices) in terms of the model's faces.

#include <TopTools_DataMapOfShapeShape.hxx>
#include <TopoDS_Edge.hxx>
#include <TopoDS_Face.hxx>
#include <TopoDS_Shape.hxx>
#include <XSControl_WorkSession.hxx>

#include <string>
#include <vector>

#include "argil/core/base/status.hpp"
#include "argil/io/model/topology.hpp"

namespace argil::io::detail {

/// One model face as read: its shape in the transferred shape, and the face
/// its record was made from (the same face, or its conversion to B-splines,
/// whose parameters the record's surface and trims use).
struct ReadFace {
  TopoDS_Face original;                // located and oriented, as TopExp_Explorer gave it
  TopoDS_Face converted;               // FORWARD; null: `original` itself
  TopTools_DataMapOfShapeShape edges;  // an edge of `original` -> its edge on `converted`
  /// The face's loops as read, in the order of its trim loops: per trim curve,
  /// the edge it came from, oriented as in its wire on the FORWARD face
  /// (`converted` when not null), and whether the loop was reversed to run
  /// the right way round in (u, v).
  struct Loop {
    std::vector<TopoDS_Edge> edges;
    bool reversed = false;
  };
  std::vector<Loop> loops;
};

/// The topology of `shape`, whose faces `faces` are in TopExp_Explorer order.
/// Products: STEP's product tree (the usage occurrences, their placements and
/// names) when `step`, else one product named `name`; a shape that maps to no
/// product is held by one root product named `name`.
Result<Topology> read_topology(const TopoDS_Shape& shape, const std::vector<ReadFace>& faces,
                               const Handle(XSControl_WorkSession) & session, bool step,
                               const std::string& name);

}  // namespace argil::io::detail
