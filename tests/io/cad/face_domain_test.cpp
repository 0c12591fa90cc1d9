// A closed surface's domain moved to where its face wraps (detail::seated_on_face),
// on faces built by OpenCASCADE itself: the face's parameters then lie inside
// the domain, and the surface is the same at them.
#include <BRepBuilderAPI_MakeFace.hxx>
#include <BRepTools.hxx>
#include <GeomConvert.hxx>
#include <Geom_CylindricalSurface.hxx>
#include <Geom_RectangularTrimmedSurface.hxx>
#include <gp_Ax3.hxx>

#include <catch2/catch.hpp>
#include <cmath>

#include "argil/io/cad/detail/occt_face_domain.hpp"

namespace argil::io {
namespace {

constexpr double kPi = 3.14159265358979323846;

/// A cylinder of radius 5 and height 10 as a periodic rational B-spline over
/// u in [0, 2 pi] (OpenCASCADE's conversion: its parameter is not the angle).
Handle(Geom_BSplineSurface) periodic_cylinder() {
  const Handle(Geom_Surface) cylinder = new Geom_RectangularTrimmedSurface(
      new Geom_CylindricalSurface(gp_Ax3(gp::XOY()), 5.0), 0.0, 2.0 * kPi, 0.0, 10.0);
  Handle(Geom_BSplineSurface) s = GeomConvert::SurfaceToBSplineSurface(cylinder);
  REQUIRE(!s.IsNull());
  REQUIRE(s->IsUClosed());
  s->SetUPeriodic();
  return s;
}

/// `seated` holds the face's parameter box and equals `original` there.
void check_seated(const Handle(Geom_BSplineSurface) & original, const TopoDS_Face& face) {
  const Handle(Geom_BSplineSurface) seated = detail::seated_on_face(original, face);
  double u0 = 0, u1 = 0, v0 = 0, v1 = 0, f0 = 0, f1 = 0, g0 = 0, g1 = 0;
  seated->Bounds(u0, u1, v0, v1);
  BRepTools::UVBounds(face, f0, f1, g0, g1);
  INFO("domain u [" << u0 << ", " << u1 << "], face u [" << f0 << ", " << f1 << "]");
  CHECK(u0 <= f0 + 1e-9);
  CHECK(f1 <= u1 + 1e-9);
  for (int i = 0; i <= 16; ++i) {
    for (int j = 0; j <= 4; ++j) {
      const double u = f0 + (f1 - f0) * i / 16.0, v = g0 + (g1 - g0) * j / 4.0;
      CHECK(seated->Value(u, v).Distance(original->Value(u, v)) <= 1e-12 * 10.0);
    }
  }
}

}  // namespace

TEST_CASE("a face across a closed surface's seam gets a domain that holds it",
          "[io][occt][import]") {
  const Handle(Geom_BSplineSurface) s = periodic_cylinder();
  SECTION("a face that does not wrap, across the domain's start") {
    check_seated(s, BRepBuilderAPI_MakeFace(s, -0.5, 0.5, 0.0, 10.0, 1e-7).Face());
  }
  SECTION("a face that does not wrap, across the domain's end") {
    check_seated(
        s, BRepBuilderAPI_MakeFace(s, 2.0 * kPi - 0.4, 2.0 * kPi + 0.7, 0.0, 10.0, 1e-7).Face());
  }
  SECTION("a whole turn from inside the domain (two edges where a seam would be)") {
    check_seated(s, BRepBuilderAPI_MakeFace(s, 0.3, 0.3 + 2.0 * kPi, 0.0, 10.0, 1e-7).Face());
  }
  SECTION("a face inside the domain keeps the surface as it is") {
    const TopoDS_Face face = BRepBuilderAPI_MakeFace(s, 1.0, 2.0, 0.0, 10.0, 1e-7).Face();
    CHECK(detail::seated_on_face(s, face) == s);
  }
}

}  // namespace argil::io
