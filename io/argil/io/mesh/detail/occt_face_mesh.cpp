#include "argil/io/mesh/detail/occt_face_mesh.hpp"

#include <BRepMesh_IncrementalMesh.hxx>
#include <BRep_Tool.hxx>
#include <Poly_Triangulation.hxx>
#include <TopLoc_Location.hxx>

#include <algorithm>

#include "argil/core/base/number_text.hpp"
#include "argil/core/geometry/bspline_surface.hpp"
#include "argil/io/cad/cad_exchange.hpp"
#include "argil/io/cad/detail/occt_face_builder.hpp"

namespace argil::io::detail {

Result<FaceTriangles> occt_face_triangles(const FaceRecord& face, double deflection_mm) {
  // The face's edges as exported, with 3D curves at the export tolerance (the
  // mesher discretizes edges by them; without, it takes minutes).
  const double tolerance = std::max(
      kMinExportTolerance, kExportRelativeTolerance * control_point_box(face.surface).diagonal());
  const Result<TopoDS_Face> built = build_occt_mesh_face(face, tolerance);
  if (!built.ok()) return built.status();
  constexpr double kAngularDeflection = 0.5;  // rad; the chord check decides, not the angle
  const BRepMesh_IncrementalMesh mesher(built.value(), deflection_mm, false, kAngularDeflection,
                                        false);
  TopLoc_Location location;
  const Handle(Poly_Triangulation) mesh = BRep_Tool::Triangulation(built.value(), location);
  if (mesh.IsNull() || mesh->NbTriangles() == 0 || !mesh->HasUVNodes()) {
    return Status::error(StatusCode::invalid_argument,
                         "OpenCASCADE's mesher made no triangles at deflection " +
                             number_text(deflection_mm) + " mm");
  }
  FaceTriangles out;
  out.uv.reserve(static_cast<std::size_t>(mesh->NbNodes()));
  for (int n = 1; n <= mesh->NbNodes(); ++n) {
    const gp_Pnt2d p = mesh->UVNode(n);
    out.uv.emplace_back(p.X(), p.Y());
  }
  out.triangles.reserve(static_cast<std::size_t>(mesh->NbTriangles()));
  for (int t = 1; t <= mesh->NbTriangles(); ++t) {
    int a = 0, b = 0, c = 0;
    mesh->Triangle(t).Get(a, b, c);
    std::array<int, 3> tri{a - 1, b - 1, c - 1};
    // Counter-clockwise in (u, v), whatever the face's orientation in OCCT.
    const Eigen::Vector2d e1 =
        out.uv[static_cast<std::size_t>(tri[1])] - out.uv[static_cast<std::size_t>(tri[0])];
    const Eigen::Vector2d e2 =
        out.uv[static_cast<std::size_t>(tri[2])] - out.uv[static_cast<std::size_t>(tri[0])];
    if (e1.x() * e2.y() - e1.y() * e2.x() < 0.0) std::swap(tri[1], tri[2]);
    out.triangles.push_back(tri);
  }
  return out;
}

}  // namespace argil::io::detail
