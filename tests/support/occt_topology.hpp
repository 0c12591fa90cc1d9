#pragma once
// What OpenCASCADE itself reads from a STEP or IGES file: products, solids,
// shells, faces, edges by kind, vertices, validity and volume. The independent
// oracle for argil's B-rep import and export. OCCT stays in the .cpp: targets
// that include this header link argil_test_occt, not OCCT's headers.

#include <filesystem>
#include <string>
#include <vector>

namespace argil::test {

/// Counts of the shape OpenCASCADE transfers from a file (all roots, as
/// `OneShape()`). "Distinct" means TopExp::MapShapes, which identifies shapes by
/// IsSame (TShape and Location, orientation ignored): an assembly's instances of
/// one part count once per instance. Edge kinds are counted on these located
/// edges; a degenerated edge (a sphere's or cone's pole) is only degenerated.
struct OcctTopology {
  /// STEP: PRODUCT entities (StepBasic_Product) in the file's model; IGES: 1.
  int products = 0;
  /// TopAbs_SOLID, distinct (one per assembly instance).
  int solids = 0;
  /// Solids with distinct TShapes: the parts, each counted once however many
  /// times it is instanced.
  int distinct_solids = 0;
  /// TopAbs_SHELL, distinct.
  int shells = 0;
  /// Shells for which BRep_Tool::IsClosed(shell) holds: every non-degenerated
  /// edge of the shell occurs an even number of times in it (no free boundary;
  /// seams occur twice). Chosen over the shape-wide `free_edges` because it is
  /// OpenCASCADE's own definition and judges each shell alone: two open shells
  /// glued along an edge are not closed.
  int closed_shells = 0;
  /// Faces as TopExp_Explorer visits them: every instance each time, as argil
  /// counts faces.
  int faces = 0;
  /// Faces with distinct TShapes: a part's face once however many instances.
  int distinct_faces = 0;
  /// TopAbs_EDGE, distinct (located). Each is of exactly one kind: degenerated,
  /// loose, free, or shared and/or seam:
  /// edges = degenerated + loose + free + shared + seam - seam_shared.
  int edges = 0;
  /// Non-degenerated edges with at least two distinct face ancestors
  /// (TopExp::MapShapesAndUniqueAncestors).
  int shared_edges = 0;
  /// Non-degenerated edges that one of their faces uses twice
  /// (BRep_Tool::IsClosed(edge, face)): the seam of a cylinder or a torus. An
  /// edge can be both a seam and shared (non-manifold); `seam_shared_edges` says how
  /// many are.
  int seam_edges = 0;
  int seam_shared_edges = 0;
  /// Non-degenerated edges with exactly one face ancestor that are no seam of it:
  /// the boundary of an open shell, or a gap in a solid's.
  int free_edges = 0;
  /// Edges flagged BRep_Tool::Degenerated (collapsed to a point in 3D).
  int degenerated_edges = 0;
  /// Non-degenerated edges that bound no face: wires and curves beside the
  /// faces, such as the PMI presentation curves some STEP files carry.
  int loose_edges = 0;
  /// TopAbs_VERTEX, distinct.
  int vertices = 0;
  /// BRepCheck_Analyzer(shape).IsValid() on the whole transferred shape.
  bool valid = false;
  /// Sum of BRepGProp::VolumeProperties (adaptive, 1e-7 relative) over the distinct solids [mm^3]
  /// (a solid whose shells face inwards adds a negative volume).
  double volume = 0.0;
  /// STEP: each PRODUCT's name attribute (its second, not the id) in file order,
  /// "" for an empty or null (`$`) name; IGES: empty.
  std::vector<std::string> product_names;
};

/// Reads `path` (.step/.stp or .iges/.igs, any case) with OpenCASCADE's own
/// readers (STEPControl_Reader, IGESControl_Reader), lengths in millimetres
/// (xstep.cascade.unit MM), transfers every root and counts. OCCT's console
/// printers are removed for the rest of the process. Not thread-safe (OCCT's
/// readers and statics are global).
/// Throws std::runtime_error naming the file when the extension is neither,
/// the reader fails or nothing transfers.
OcctTopology occt_topology(const std::filesystem::path& path);

}  // namespace argil::test
