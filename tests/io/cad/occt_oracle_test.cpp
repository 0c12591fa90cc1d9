// OpenCASCADE as the independent oracle: face counts, surface points, trims and
// orientation of imported faces; validity, entities and units of exported files.
#include <BRepCheck_Analyzer.hxx>
#include <BRepTools.hxx>
#include <BRep_Tool.hxx>
#include <GeomAPI_ProjectPointOnSurf.hxx>
#include <GeomLProp_SLProps.hxx>
#include <Geom_BSplineSurface.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>

#include <catch2/catch.hpp>
#include <map>
#include <random>
#include <sstream>

#include "argil/core/geometry/evaluate.hpp"
#include "argil/io.hpp"
#include "occt_reader.hpp"
#include "support/random_surface.hpp"
#include "surface_projection.hpp"
#include "test_files.hpp"

namespace argil::io {
namespace {

using test::as_bspline;
using test::occt_read;
using test::OcctShape;

Eigen::Vector3d to_eigen(const gp_XYZ& p) { return {p.X(), p.Y(), p.Z()}; }

struct Agreement {
  double max_point_error_mm = 0.0;  // surface points at corresponding parameters
  double max_trim_error_mm = 0.0;   // trim curves mapped to 3D vs the original surface
  double max_trim_tolerance_mm = 0.0;
  std::size_t reparametrised_faces = 0;
};

Agreement compare_with_occt(const Model& model, const OcctShape& occt) {
  Agreement result;
  for (std::size_t f = 0; f < occt.faces.size(); ++f) {
    INFO("face " << f << " (" << model.faces[f].source_id << ")");
    const TopoDS_Face& face = occt.faces[f];
    const BSplineSurface& ours = model.faces[f].surface;
    const Handle(Geom_Surface) original = BRep_Tool::Surface(face);
    double u0 = 0, u1 = 0, v0 = 0, v1 = 0;
    BRepTools::UVBounds(face, u0, u1, v0, v1);
    const bool same_parameters = !as_bspline(original).IsNull();
    if (!same_parameters) ++result.reparametrised_faces;
    constexpr int kGrid = 9;
    for (int i = 0; i < kGrid; ++i) {
      for (int j = 0; j < kGrid; ++j) {
        const double u = u0 + (i + 0.5) / kGrid * (u1 - u0);
        const double v = v0 + (j + 0.5) / kGrid * (v1 - v0);
        gp_Pnt p;
        gp_Vec du, dv;
        original->D1(u, v, p, du, dv);
        const Eigen::Vector3d oracle = to_eigen(p.XYZ());
        Eigen::Vector2d uv(u, v);
        double error = 0.0;
        if (same_parameters) {
          error = (evaluate(ours, u, v) - oracle).norm();
        } else {
          // Converted analytic faces: the B-spline's knots sit at the original
          // parameters but spans are reparametrised, so the corresponding
          // parameter is the closest point, found by Newton from (u, v).
          const test::Projection projection = test::project(ours, oracle, uv);
          uv = projection.uv;
          error = projection.distance_mm;
        }
        result.max_point_error_mm = std::max(result.max_point_error_mm, error);
        // Orientation: our normal on the face's side agrees with OCCT's.
        Eigen::Vector3d occt_normal = to_eigen(du.Crossed(dv).XYZ());
        if (face.Orientation() == TopAbs_REVERSED) occt_normal = -occt_normal;
        Eigen::Vector3d normal = unit_normal(evaluate_derivatives(ours, uv.x(), uv.y(), 1));
        if (model.faces[f].reversed) normal = -normal;
        if (occt_normal.norm() > 1e-12 && normal.norm() > 0.0) {
          CHECK(normal.dot(occt_normal) > 0.0);
        }
      }
    }
    // Trims: every trim curve, mapped through our surface, lies on the original
    // surface within the tolerance OCCT gives the face's edges.
    double tolerance = BRep_Tool::Tolerance(face);
    for (TopExp_Explorer e(face, TopAbs_EDGE); e.More(); e.Next()) {
      tolerance = std::max(tolerance, BRep_Tool::Tolerance(TopoDS::Edge(e.Current())));
    }
    result.max_trim_tolerance_mm = std::max(result.max_trim_tolerance_mm, tolerance);
    for (const TrimLoop& loop : model.faces[f].loops) {
      for (const TrimCurve& curve : loop.curves) {
        for (int k = 0; k <= 8; ++k) {
          const double t =
              curve.knots[0] + k / 8.0 * (curve.knots[curve.knots.size() - 1] - curve.knots[0]);
          const Eigen::Vector2d uv = evaluate_trim_curve(curve, t);
          const Eigen::Vector3d x = evaluate(ours, uv.x(), uv.y());
          GeomAPI_ProjectPointOnSurf projector(gp_Pnt(x.x(), x.y(), x.z()), original,
                                               u0 - (u1 - u0), u1 + (u1 - u0), v0 - (v1 - v0),
                                               v1 + (v1 - v0), Precision::Confusion());
          REQUIRE(projector.NbPoints() > 0);
          const double error = projector.LowerDistance();
          result.max_trim_error_mm = std::max(result.max_trim_error_mm, error);
          CHECK(error <= tolerance);
        }
      }
    }
  }
  return result;
}

}  // namespace

TEST_CASE("imported faces match OpenCASCADE's count, points, trims and orientation", "[io][occt]") {
  for (const char* name : {"bearing.iges", "screw.step"}) {
    SECTION(name) {
      const std::filesystem::path path = test::shared_data(name);
      const Result<Model> model = read_model(path);
      REQUIRE(model.status().message == "");
      const OcctShape occt = occt_read(path);
      REQUIRE(model.value().faces.size() == occt.faces.size());
      const Agreement agreement = compare_with_occt(model.value(), occt);
      // The bound: 1e-9 of the model size; conversions are exact up to rounding.
      CHECK(agreement.max_point_error_mm <= 1e-9 * occt.diagonal_mm);
      WARN(name << ": " << occt.faces.size() << " faces, " << agreement.reparametrised_faces
                << " converted; max point deviation " << agreement.max_point_error_mm
                << " mm = " << agreement.max_point_error_mm / occt.diagonal_mm
                << " of the diagonal; max trim deviation " << agreement.max_trim_error_mm
                << " mm (edge tolerance up to " << agreement.max_trim_tolerance_mm << " mm)");
    }
  }
}

TEST_CASE("exported STEP and IGES pass BRepCheck and declare millimetres", "[io][occt]") {
  Model generated;
  std::mt19937_64 rng(99);
  for (int k = 0; k < 10; ++k) {
    test::RandomSurfaceOptions options;
    options.max_degree = 9;
    options.rational = k % 2 == 0;
    generated.faces.push_back(
        FaceRecord{test::random_surface(rng, options), {}, k % 3 == 0, "", ""});
  }
  const Result<Model> bearing = read_model(test::shared_data("bearing.iges"));
  const Result<Model> screw = read_model(test::shared_data("screw.step"));
  REQUIRE(bearing.ok());
  REQUIRE(screw.ok());
  test::TempDir dir;
  for (const auto& [label, model] :
       {std::pair{"generated", static_cast<const Model*>(&generated)},
        std::pair{"bearing", &bearing.value()}, std::pair{"screw", &screw.value()}}) {
    for (const char* extension : {".step", ".iges"}) {
      const std::filesystem::path path = dir / (std::string(label) + extension);
      INFO(path.filename());
      REQUIRE(write_model(*model, path).message == "");
      const OcctShape occt = occt_read(path);
      REQUIRE(occt.faces.size() == model->faces.size());
      for (std::size_t f = 0; f < occt.faces.size(); ++f) {
        INFO("face " << f);
        CHECK(BRepCheck_Analyzer(occt.faces[f]).IsValid());
        CHECK(!as_bspline(BRep_Tool::Surface(occt.faces[f])).IsNull());
        // Orientation survives STEP; IGES 144 has no face orientation (docs/io.md).
        if (std::string(extension) == ".step") {
          CHECK((occt.faces[f].Orientation() == TopAbs_REVERSED) == model->faces[f].reversed);
        }
      }
      const std::string text = test::read_bytes(path);
      if (std::string(extension) == ".step") {
        CHECK(occt.step_length_unit == "millimetre");
        CHECK_THAT(text, Catch::Contains("SI_UNIT(.MILLI.,.METRE.)"));
        CHECK_THAT(text, Catch::Contains("ADVANCED_FACE("));
        CHECK_THAT(text, Catch::Contains("B_SPLINE_SURFACE_WITH_KNOTS("));
        const bool rational =
            std::any_of(model->faces.begin(), model->faces.end(),
                        [](const FaceRecord& r) { return r.surface.is_rational(); });
        if (rational) CHECK_THAT(text, Catch::Contains("RATIONAL_B_SPLINE_SURFACE("));
      } else {
        // Global section: unit flag 2 and name MM; directory entries: loose
        // faces as 144 over 128, a solid as 186 over 514 shells and 510 faces.
        CHECK_THAT(text, Catch::Contains(",2,2HMM,"));
        std::istringstream lines(text);
        std::string line;
        std::map<int, std::size_t> entities;
        bool odd = true;
        while (std::getline(lines, line)) {
          if (line.size() < 73 || line[72] != 'D') continue;
          if (odd) ++entities[std::stoi(line.substr(0, 8))];
          odd = !odd;
        }
        CHECK(entities[128] == model->faces.size());
        if (model->topology.solids.empty()) {
          CHECK(entities[144] == model->faces.size());
        } else {
          CHECK(entities[186] == model->topology.solids.size());
          CHECK(entities[510] == model->faces.size());
          CHECK(entities[144] == 0);
        }
      }
    }
  }
}

}  // namespace argil::io
