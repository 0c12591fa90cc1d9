#pragma once
// The B-rep around a model's faces: which faces meet along which edges and at
// which vertices, the shells and solids they close, and the products (parts and
// assemblies) that hold them. Faces are indices into Model::faces; everything
// is in the model's world frame [mm], as the faces are.

#include <Eigen/Core>
#include <array>
#include <cstddef>
#include <string>
#include <vector>

#include "argil/core/base/status.hpp"
#include "argil/core/geometry/bspline_curve.hpp"

namespace argil::io {

/// "None": a product without a parent, an edge without a vertex.
inline constexpr std::size_t kNoIndex = static_cast<std::size_t>(-1);

/// One face's use of an edge: the edge's curve in that face's (u, v), running
/// from the edge's start vertex to its end. Two uses need not share a
/// parametrisation (a circle converted to a rational B-spline is not), only
/// their images: the same 3D curve within the edge's tolerance.
///
/// Where the use sits in the face's boundary: curve `curve` of loop `loop`, as
/// the face was read (the face's trim loops when it is trimmed; a face whose
/// boundary is its whole domain, recorded untrimmed, keeps the numbering of the
/// loop it was read with), running along the edge or against it. This is what
/// rebuilds the face's wires from shared edges on export; kNoIndex: unknown.
struct EdgeUse {
  std::size_t face = 0;
  BSplineCurve pcurve;  // two columns, (u, v)
  std::size_t loop = kNoIndex;
  std::size_t curve = kNoIndex;
  bool along = true;  // the loop runs from the edge's start to its end
};

/// A B-rep edge. One use: a free (boundary) edge; uses on two distinct faces:
/// a shared edge; two uses by one face: the seam of a closed surface.
struct Edge {
  std::vector<EdgeUse> uses;
  std::size_t start = kNoIndex, end = kNoIndex;  // into Topology::vertices
  bool degenerate = false;                       // collapses to a point (a sphere's pole)
  double tolerance = 0.0;                        // [mm], as the source gave it
};

struct Vertex {
  Eigen::Vector3d point = Eigen::Vector3d::Zero();  // [mm]
  double tolerance = 0.0;                           // [mm]
};

/// A connected set of faces; closed when it bounds a volume (no free edges).
struct Shell {
  std::vector<std::size_t> faces;
  bool closed = false;
};

/// A volume: its outer shell first, then the shells of its cavities.
struct Solid {
  std::vector<std::size_t> shells;
};

/// A part or an assembly (an instance of it, where the source instances one
/// part several times: each instance has its own faces in the model).
struct Product {
  std::string name;               // the product's name in the source
  std::string instance;           // the instance's name (STEP: the usage occurrence), may be empty
  std::size_t parent = kNoIndex;  // into Topology::products
  Eigen::Matrix<double, 3, 4> placement = Eigen::Matrix<double, 3, 4>::Identity();  // in the parent
  std::vector<std::size_t> solids;                                                  // directly held
  std::vector<std::size_t> shells;  // directly held, outside any solid
  std::vector<std::size_t> faces;   // directly held, outside any shell
};

struct Topology {
  std::vector<Product> products;
  std::vector<Solid> solids;
  std::vector<Shell> shells;
  std::vector<Edge> edges;
  std::vector<Vertex> vertices;

  /// No B-rep recorded: the model is a set of loose faces.
  bool empty() const {
    return products.empty() && solids.empty() && shells.empty() && edges.empty() &&
           vertices.empty();
  }
};

/// What `argil info` and the tests compare with OpenCASCADE.
struct TopologyCounts {
  std::size_t products = 0, solids = 0, shells = 0, closed_shells = 0;
  std::size_t edges = 0, shared_edges = 0, free_edges = 0, seam_edges = 0, degenerate_edges = 0;
  std::size_t vertices = 0;
};

/// Counts as defined on Edge: shared: uses on at least two distinct faces;
/// seam: two uses, one face; free: one use, not degenerate.
TopologyCounts count_topology(const Topology& topology);

/// Checks every index against the lists it points into (`face_count` faces),
/// every pcurve (validate_trim_curve rules) and every number for finiteness;
/// the message names the field ("edges[12].uses[1].face: 40 of 38 faces").
Status validate_topology(const Topology& topology, std::size_t face_count);

/// True when every use knows its place in its face's boundary (loop, curve).
bool uses_placed(const Topology& topology);

struct Model;

/// validate_topology(model.topology, faces) and, where the uses are placed,
/// that they number each face's loops without gap or repeat, and that a
/// trimmed face's uses are its trim loops: one use per trim curve, the same
/// curve (reversed where the loop runs against the edge) within 1e-9 of the
/// face's domain. The message names the edge, use or face and loop.
Status validate_topology(const Model& model);

}  // namespace argil::io
