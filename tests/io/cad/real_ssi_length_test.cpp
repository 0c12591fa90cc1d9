// Refined intersection curves of real faces that cross have the length of
// OpenCASCADE's curves (GeomAPI_IntSS as the oracle): a refined polyline lies
// on the curve with chords within eps/3 of it, so it may fall short of the
// curve's length by a hair but not run past it (beyond the oracle's own
// precision); one that steps back and forth along the curve (refined points
// out of order) comes out longer.
#include <GCPnts_AbscissaPoint.hxx>
#include <GeomAPI_IntSS.hxx>
#include <GeomAdaptor_Curve.hxx>
#include <Geom_BSplineSurface.hxx>
#include <Precision.hxx>
#include <catch2/catch.hpp>

#include "argil/core.hpp"
#include "argil/io.hpp"
#include "support/built_hierarchy.hpp"
#include "support/occt_surface.hpp"
#include "test_files.hpp"

namespace argil::io {
namespace {

double occt_length(const BSplineSurface& a, const BSplineSurface& b) {
  GeomAPI_IntSS x(test::to_occt(a), test::to_occt(b), Precision::Confusion());
  REQUIRE(x.IsDone());
  double length = 0.0;
  for (int k = 1; k <= x.NbLines(); ++k)
    length += GCPnts_AbscissaPoint::Length(GeomAdaptor_Curve(x.Line(k)));
  return length;
}

double our_length(const CollisionResult& r) {
  double length = 0.0;
  for (const IntersectionCurve& c : r.curves) length += c.length();
  return length;
}

// surf114.igs faces 1 and 3 cross in one closed curve through transversal
// leaves; refined at 1e-4 of the size it once stepped back and forth at ten
// leaf edges and came out 0.23% longer than OpenCASCADE's.
TEST_CASE("refined curves of crossing real faces have OpenCASCADE's length (surf114.igs)") {
  Result<Model> read = read_model(test::shared_data("surf114.igs"));
  REQUIRE(read.ok());
  const Model& model = read.value();
  REQUIRE(model.faces.size() == 4);
  const BSplineSurface& a = model.faces[1].surface;
  const BSplineSurface& b = model.faces[3].surface;
  const SurfaceHierarchy ha = test::hierarchy_for(a);
  const SurfaceHierarchy hb = test::hierarchy_for(b);
  const double size = std::max(control_point_box(a).diagonal(), control_point_box(b).diagonal());
  const double expected = occt_length(a, b);
  REQUIRE(expected > 0.0);
  for (const double relative : {1e-3, 1e-4, 1e-6}) {
    const double eps = relative * size;
    INFO("eps " << relative << " of the size");
    const CollisionResult r = collide(ha, hb, {.tolerance = eps, .refine = true});
    REQUIRE(r.status.ok());
    REQUIRE(r.curves.size() == 1);
    CHECK(r.curves[0].closed());
    const double ours = our_length(r);
    CHECK(ours <= expected * (1.0 + 1e-4));
    CHECK(ours >= expected * (1.0 - 1e-3));
  }
}

}  // namespace
}  // namespace argil::io
