// TrimRegion::contains against OpenCASCADE's BRepClass_FaceClassifier on every
// face of the real CAD files, at random points of each face's parameter box
// and at points just beside its trim curves, on both sides.
#include <BRepBuilderAPI_NurbsConvert.hxx>
#include <BRepClass_FaceClassifier.hxx>
#include <BRepTools.hxx>
#include <BRep_Tool.hxx>
#include <Geom_BSplineSurface.hxx>
#include <TopoDS.hxx>
#include <gp_Pnt2d.hxx>

#include <catch2/catch.hpp>
#include <random>

#include "argil/io.hpp"
#include "occt_reader.hpp"
#include "support/trim_loops.hpp"
#include "test_files.hpp"

namespace argil::io {
namespace {

/// The face in the parameters argil imports it with: forward, and converted
/// to B-splines the way the importer converts analytic faces.
TopoDS_Face as_imported(const TopoDS_Face& oriented) {
  TopoDS_Face face = TopoDS::Face(oriented.Oriented(TopAbs_FORWARD));
  if (!test::as_bspline(BRep_Tool::Surface(face)).IsNull()) return face;
  BRepBuilderAPI_NurbsConvert convert(face, true);
  return TopoDS::Face(convert.Shape().Oriented(TopAbs_FORWARD));
}

struct Agreement {
  long compared = 0;   // points OCCT puts IN or OUT
  long near_edge = 0;  // of them, beside a trim curve
  long on = 0;         // points OCCT puts ON the boundary (within its tolerance)
  /// Points where OCCT differs but lies within 1e-5 of the face's (u, v) size
  /// of a curve, and a 20000-point polygon of the exact curves sides with us.
  long occt_tolerance = 0;
  long disagree = 0;
  std::string first_disagreement;
  std::string first_tolerance;
};

/// Dense polygons of a face's loops, the tie-breaker where OCCT disagrees.
std::vector<std::vector<Eigen::Vector2d>> dense_polygons(const FaceRecord& face) {
  std::vector<std::vector<Eigen::Vector2d>> out;
  for (const TrimLoop& loop : face.loops) out.push_back(test::dense_polygon(loop, 20000));
  return out;
}

void compare_point(const TopoDS_Face& face, const FaceRecord& record, const TrimRegion& region,
                   const Eigen::Vector2d& uv, bool near_edge, std::size_t f, double size,
                   Agreement& out) {
  // 1e-9 in (u, v): far below the offsets used, so ON means OCCT's own edge tolerance.
  BRepClass_FaceClassifier classifier(face, gp_Pnt2d(uv.x(), uv.y()), 1e-9);
  const TopAbs_State state = classifier.State();
  if (state != TopAbs_IN && state != TopAbs_OUT) {
    ++out.on;
    return;
  }
  ++out.compared;
  out.near_edge += near_edge ? 1 : 0;
  const bool ours = region.contains(uv);
  if (ours == (state == TopAbs_IN)) return;
  const std::string where = "face " + std::to_string(f) + " at (u, v) = " + vector_text(uv) +
                            ": OCCT says " + (state == TopAbs_IN ? "IN" : "OUT");
  const auto polygons = dense_polygons(record);
  const double distance = test::polygon_distance(polygons, uv);
  if (test::inside_polygons(polygons, uv) == ours && distance < 1e-5 * size) {
    if (out.occt_tolerance++ == 0) {
      out.first_tolerance = where + ", " + number_text(distance) + " from a curve";
    }
    return;
  }
  if (out.disagree++ == 0) out.first_disagreement = where;
}

Agreement classify_faces(const std::filesystem::path& path) {
  const Result<Model> model = read_model(path);
  REQUIRE(model.status().message == "");
  const test::OcctShape occt = test::occt_read(path);
  REQUIRE(model.value().faces.size() == occt.faces.size());
  Agreement out;
  std::mt19937_64 rng(17);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (std::size_t f = 0; f < occt.faces.size(); ++f) {
    const FaceRecord& record = model.value().faces[f];
    const Result<TrimRegion> region = TrimRegion::create(record.loops);
    INFO("face " << f << ": " << region.status().message);
    REQUIRE(region.ok());
    const TopoDS_Face face = as_imported(occt.faces[f]);
    double u0 = 0, u1 = 0, v0 = 0, v1 = 0;
    BRepTools::UVBounds(face, u0, u1, v0, v1);
    const double du = u1 - u0, dv = v1 - v0;
    // Untrimmed faces (their loops are the domain's sides) are compared inside the domain.
    const ParamRect domain = domain_of(record.surface);
    const double grow = record.trimmed() ? 0.05 : 0.0;
    for (int k = 0; k < 60; ++k) {
      Eigen::Vector2d uv(u0 - grow * du + (1 + 2 * grow) * du * unit(rng),
                         v0 - grow * dv + (1 + 2 * grow) * dv * unit(rng));
      if (!record.trimmed() && !domain.contains(uv)) continue;
      compare_point(face, record, region.value(), uv, false, f, std::hypot(du, dv), out);
    }
    const double size = std::hypot(du, dv);
    for (const TrimLoop& loop : record.loops) {
      for (const TrimCurve& curve : loop.curves) {
        for (int k = 0; k < 3; ++k) {
          const double t = curve.domain_start() +
                           (0.1 + 0.8 * unit(rng)) * (curve.domain_end() - curve.domain_start());
          const double h = 1e-6 * (curve.domain_end() - curve.domain_start());
          const Eigen::Vector2d tangent = evaluate(curve, t + h) - evaluate(curve, t - h);
          if (!(tangent.norm() > 0.0)) continue;  // a degenerate (collapsed) edge
          const Eigen::Vector2d normal = Eigen::Vector2d(-tangent.y(), tangent.x()).normalized();
          for (const double offset : {1e-2, 1e-4, 1e-6}) {
            for (const double side : {1.0, -1.0}) {
              compare_point(face, record, region.value(),
                            evaluate(curve, t) + side * offset * size * normal, true, f, size, out);
            }
          }
        }
      }
    }
  }
  return out;
}

}  // namespace

TEST_CASE("trim regions classify (u, v) as OpenCASCADE's face classifier does on real files",
          "[io][occt][trim][slow]") {
  for (const char* name :
       {"screw.step", "bearing.iges", "as1-oc-214.stp", "surf114.igs", "11752.stp"}) {
    SECTION(name) {
      const Agreement a = classify_faces(test::shared_data(name));
      WARN(name << ": " << a.compared << " points compared (" << a.near_edge
                << " beside a trim curve), " << a.on << " ON for OCCT, " << a.occt_tolerance
                << " within OCCT's tolerance of a curve"
                << (a.occt_tolerance > 0 ? " (first: " + a.first_tolerance + ")" : "") << ", "
                << a.disagree << " disagreements"
                << (a.disagree > 0 ? "; first: " + a.first_disagreement : ""));
      CHECK(a.compared > 0);
      CHECK(a.disagree == 0);
      CHECK(a.occt_tolerance * 1000 <= a.near_edge);  // rare: at most 1 in 1000 near points
    }
  }
}

}  // namespace argil::io
