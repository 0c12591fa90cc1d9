// Refined intersection curves of real faces that cross have the length of
// OpenCASCADE's curves (GeomAPI_IntSS as the oracle): a refined polyline lies
// on the curve with chords within eps/3 of it, so it may fall short of the
// curve's length by a hair but not run past it (beyond the oracle's own
// precision); one that steps back and forth along the curve (refined points
// out of order) comes out longer.
#include <GCPnts_AbscissaPoint.hxx>
#include <GeomAPI_IntSS.hxx>
#include <GeomAPI_ProjectPointOnSurf.hxx>
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

/// The length of b's boundary that lies on a: consecutive samples of each of
/// b's four domain edges (`per_side` chords each) that OpenCASCADE projects
/// onto a within `within`. Falls short of the true length by at most two
/// chords per run (`chord`: the longest between samples on a).
struct SampledLength {
  double length = 0.0, chord = 0.0;
  int runs = 0;
};

SampledLength boundary_length_on(const BSplineSurface& a, const BSplineSurface& b, int per_side,
                                 double within) {
  const Handle(Geom_BSplineSurface) oa = test::to_occt(a);
  const auto on_a = [&](const Eigen::Vector3d& p) {
    GeomAPI_ProjectPointOnSurf projection(gp_Pnt(p.x(), p.y(), p.z()), oa);
    return projection.NbPoints() > 0 && projection.LowerDistance() <= within;
  };
  const double u0 = b.domain_start(Direction::u), u1 = b.domain_end(Direction::u);
  const double v0 = b.domain_start(Direction::v), v1 = b.domain_end(Direction::v);
  SampledLength out;
  for (int side = 0; side < 4; ++side) {
    const auto at = [&](int k) -> Eigen::Vector3d {
      const double t = static_cast<double>(k) / per_side;
      const double u = u0 + t * (u1 - u0), v = v0 + t * (v1 - v0);
      return side == 0   ? evaluate(b, u, v0)
             : side == 1 ? evaluate(b, u, v1)
             : side == 2 ? evaluate(b, u0, v)
                         : evaluate(b, u1, v);
    };
    Eigen::Vector3d previous = at(0);
    bool previous_on = on_a(previous);
    bool in_run = false;  // the last chord was on a
    for (int k = 1; k <= per_side; ++k) {
      const Eigen::Vector3d p = at(k);
      const bool on = on_a(p);
      if (on && previous_on) {
        if (!in_run) ++out.runs;
        out.length += (p - previous).norm();
        out.chord = std::max(out.chord, (p - previous).norm());
      }
      in_run = on && previous_on;
      previous = p;
      previous_on = on;
    }
  }
  return out;
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

// A face standing on another with its edge: the curve runs along the edge,
// where the refinement's Gauss-Newton system has a direction made only of
// rounding (the edge lies in the other face's plane). Solving along it slid
// points a millimetre along the curve, and as1-oc-214.stp's half circle of
// 15.71 mm came out 22.46 mm long, joined back and forth. OpenCASCADE is the
// oracle there; on face_recognition_sample_part.stp its curve stops short
// (3.06 mm of a 7.85 mm quarter circle), so the oracle is the length of the
// standing face's boundary that OpenCASCADE projects onto the other face.
TEST_CASE("refined curves along a face's edge lying on another face have the edge's length") {
  struct Case {
    const char* file;
    std::size_t a, b;
    bool intss_oracle;
  };
  for (const Case& x : {Case{"as1-oc-214.stp", 66, 77, true},
                        Case{"face_recognition_sample_part.stp", 6, 13, false}}) {
    Result<Model> read = read_model(test::shared_data(x.file));
    REQUIRE(read.ok());
    const Model& model = read.value();
    REQUIRE(model.faces.size() > std::max(x.a, x.b));
    const BSplineSurface& a = model.faces[x.a].surface;
    const BSplineSurface& b = model.faces[x.b].surface;
    const SurfaceHierarchy ha = test::hierarchy_for(a);
    const SurfaceHierarchy hb = test::hierarchy_for(b);
    const double size = std::max(control_point_box(a).diagonal(), control_point_box(b).diagonal());
    // The sampled oracle falls short by up to two of its chords.
    const SampledLength sampled = x.intss_oracle ? SampledLength{occt_length(a, b), 0.0}
                                                 : boundary_length_on(a, b, 4000, 1e-9 * size);
    const double expected = sampled.length;
    REQUIRE(expected > 0.0);
    const double slack = std::max(1e-4 * expected, 2.0 * sampled.chord * sampled.runs);
    for (const double relative : {1e-4, 1e-6}) {
      const double eps = relative * size;
      INFO(x.file << " faces " << x.a << " and " << x.b << ", eps " << relative
                  << " of the size, expected " << expected);
      const CollisionResult r = collide(ha, hb, {.tolerance = eps, .refine = true});
      REQUIRE(r.status.ok());
      REQUIRE(r.curves.size() == 1);
      const double ours = our_length(r);
      CHECK(ours <= expected + slack);
      CHECK(ours >= expected * (1.0 - 1e-3));
    }
  }
}

}  // namespace
}  // namespace argil::io
