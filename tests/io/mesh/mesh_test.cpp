// Meshes: the adaptive tessellation is within its chord tolerance, crack-free
// and trimmed; STL, OBJ, PLY and glb files read back with assimp hold the same
// triangles, on the surface, with the surface normals.
#include <assimp/scene.h>
#include <assimp/Importer.hpp>

#include <catch2/catch.hpp>
#include <map>

#include "argil/core/geometry/evaluate.hpp"
#include "argil/io.hpp"
#include "support/random_surface.hpp"
#include "surface_projection.hpp"
#include "test_files.hpp"

namespace argil::io {
namespace {

// The panel example plus the asymmetric rational surface, trimmed by an ellipse
// with an elliptic hole, as a reversed face.
Model panel_and_trimmed_face() {
  Result<Model> model = read_model(test::source_file("examples/surfaces/panel.json"));
  REQUIRE(model.ok());
  FaceRecord face;
  face.surface = test::asymmetric_surface(true);
  const BSplineSurface& s = face.surface;
  const Eigen::Vector2d lo(s.domain_start(Direction::u), s.domain_start(Direction::v));
  const Eigen::Vector2d hi(s.domain_end(Direction::u), s.domain_end(Direction::v));
  const auto ellipse = [&](double scale, bool outer) {
    TrimLoop loop;
    loop.outer = outer;
    TrimCurve c;  // a full ellipse: 9-pole rational quadratic, counter-clockwise
    c.degree = 2;
    c.knots.resize(12);
    c.knots << 0, 0, 0, 1, 1, 2, 2, 3, 3, 4, 4, 4;
    c.points.resize(9, 2);
    c.weights.resize(9);
    const Eigen::Vector2d centre = 0.5 * (lo + hi), radii = scale * 0.5 * (hi - lo);
    const double corners[9][2] = {{1, 0},   {1, 1},  {0, 1},  {-1, 1}, {-1, 0},
                                  {-1, -1}, {0, -1}, {1, -1}, {1, 0}};
    for (int k = 0; k < 9; ++k) {
      c.points.row(k) = centre + radii.cwiseProduct(Eigen::Vector2d(corners[k][0], corners[k][1]));
      c.weights[k] = k % 2 == 1 ? std::sqrt(0.5) : 1.0;
    }
    if (!outer) {
      c.points = c.points.colwise().reverse().eval();
      c.weights = c.weights.reverse().eval();
    }
    loop.curves.push_back(c);
    return loop;
  };
  face.loops = {ellipse(0.9, true), ellipse(0.3, false)};
  face.reversed = true;
  model.value().faces.push_back(face);
  return std::move(model).value();
}

Eigen::Vector3d finite_difference_normal(const BSplineSurface& s, Eigen::Vector2d uv) {
  const double hu = 1e-6 * (s.domain_end(Direction::u) - s.domain_start(Direction::u));
  const double hv = 1e-6 * (s.domain_end(Direction::v) - s.domain_start(Direction::v));
  uv.x() = std::clamp(uv.x(), s.domain_start(Direction::u) + hu, s.domain_end(Direction::u) - hu);
  uv.y() = std::clamp(uv.y(), s.domain_start(Direction::v) + hv, s.domain_end(Direction::v) - hv);
  const Eigen::Vector3d su =
      (evaluate(s, uv.x() + hu, uv.y()) - evaluate(s, uv.x() - hu, uv.y())) / (2 * hu);
  const Eigen::Vector3d sv =
      (evaluate(s, uv.x(), uv.y() + hv) - evaluate(s, uv.x(), uv.y() - hv)) / (2 * hv);
  return su.cross(sv).normalized();
}

struct ChordReport {
  double max_error_mm = 0.0;
  std::size_t samples = 0;
};

// True chord error: centroids and edge midpoints of every triangle projected on
// the surface by Newton from their interpolated (u, v).
ChordReport chord_errors(const Model& model, const TriangleMesh& mesh) {
  ChordReport report;
  const double weights[4][3] = {
      {1.0 / 3, 1.0 / 3, 1.0 / 3}, {0.5, 0.5, 0}, {0, 0.5, 0.5}, {0.5, 0, 0.5}};
  for (Eigen::Index t = 0; t < mesh.triangles.rows(); ++t) {
    const int face = mesh.vertex_face[static_cast<std::size_t>(mesh.triangles(t, 0))];
    const BSplineSurface& s = model.faces[static_cast<std::size_t>(face)].surface;
    for (const auto& w : weights) {
      Eigen::Vector3d x = Eigen::Vector3d::Zero();
      Eigen::Vector2d uv = Eigen::Vector2d::Zero();
      for (int c = 0; c < 3; ++c) {
        x += w[c] * mesh.positions.row(mesh.triangles(t, c)).transpose();
        uv += w[c] * mesh.uv.row(mesh.triangles(t, c)).transpose();
      }
      report.max_error_mm = std::max(report.max_error_mm, test::project(s, x, uv).distance_mm);
      ++report.samples;
    }
  }
  return report;
}

}  // namespace

TEST_CASE("the tessellation is within the chord tolerance", "[io][mesh][slow]") {
  const Model panel = panel_and_trimmed_face();
  const Result<Model> bearing = read_model(test::shared_data("bearing.iges"));
  REQUIRE(bearing.ok());
  for (const Model* model : {&panel, &bearing.value()}) {
    for (double relative : {1e-2, 1e-3, 1e-4}) {
      TessellationOptions options;
      options.chord_tolerance_mm = relative * model_box(*model).diagonal();
      const Result<TriangleMesh> mesh = tessellate(*model, options);
      REQUIRE(mesh.ok());
      const ChordReport report = chord_errors(*model, mesh.value());
      INFO(model->faces.size() << " faces, tolerance " << options.chord_tolerance_mm);
      // Newton converges to ~1e-15 relative; the bound itself is exact.
      CHECK(report.max_error_mm <= options.chord_tolerance_mm * (1 + 1e-9));
      WARN(model->faces.size() << " faces at tolerance " << relative << " of the diagonal: "
                               << mesh.value().triangles.rows() << " triangles, max chord error "
                               << report.max_error_mm / options.chord_tolerance_mm
                               << " of the tolerance over " << report.samples << " samples");
    }
  }
}

TEST_CASE("an untrimmed face's mesh has no cracks: inner edges are shared by two triangles",
          "[io][mesh]") {
  const Model panel = panel_and_trimmed_face();
  TessellationOptions options;
  options.chord_tolerance_mm = 0.2;
  const TriangleMesh mesh = tessellate_face(panel.faces[0], options);
  std::map<std::pair<int, int>, int> uses;
  for (Eigen::Index t = 0; t < mesh.triangles.rows(); ++t) {
    for (int c = 0; c < 3; ++c) {
      const int a = mesh.triangles(t, c), b = mesh.triangles(t, (c + 1) % 3);
      ++uses[{std::min(a, b), std::max(a, b)}];
    }
  }
  const BSplineSurface& s = panel.faces[0].surface;
  const auto on_boundary = [&](int v) {
    const Eigen::Vector2d uv = mesh.uv.row(v);
    return uv.x() == s.domain_start(Direction::u) || uv.x() == s.domain_end(Direction::u) ||
           uv.y() == s.domain_start(Direction::v) || uv.y() == s.domain_end(Direction::v);
  };
  std::size_t boundary_edges = 0;
  for (const auto& [edge, count] : uses) {
    INFO("edge " << edge.first << "-" << edge.second);
    if (count == 1) {
      CHECK((on_boundary(edge.first) && on_boundary(edge.second)));
      ++boundary_edges;
    } else {
      CHECK(count == 2);
    }
  }
  CHECK(boundary_edges > 0);
}

TEST_CASE("trimmed faces are meshed conforming to their trims: outer loop and hole", "[io][mesh]") {
  const Model model = panel_and_trimmed_face();
  const FaceRecord& face = model.faces[1];
  TessellationOptions options;
  options.chord_tolerance_mm = 1e-3 * control_point_box(face.surface).diagonal();
  const TriangleMesh mesh = tessellate_face(face, options);
  REQUIRE(mesh.triangles.rows() > 0);
  const BSplineSurface& s = face.surface;
  const Eigen::Vector2d centre(0.5 * (s.domain_start(Direction::u) + s.domain_end(Direction::u)),
                               0.5 * (s.domain_start(Direction::v) + s.domain_end(Direction::v)));
  const Eigen::Vector2d half(0.5 * (s.domain_end(Direction::u) - s.domain_start(Direction::u)),
                             0.5 * (s.domain_end(Direction::v) - s.domain_start(Direction::v)));
  // Elliptic radius in (u, v): the hole is at 0.3, the outer loop at 0.9.
  const auto radius = [&](const Eigen::Vector2d& uv) {
    return (uv - centre).cwiseQuotient(half).norm();
  };
  double area = 0.0;
  std::map<std::pair<int, int>, int> uses;
  for (Eigen::Index t = 0; t < mesh.triangles.rows(); ++t) {
    const Eigen::Vector2d a = mesh.uv.row(mesh.triangles(t, 0)),
                          b = mesh.uv.row(mesh.triangles(t, 1)),
                          c = mesh.uv.row(mesh.triangles(t, 2));
    const double r = radius((a + b + c) / 3.0);
    CHECK(r > 0.3);
    CHECK(r < 0.9);
    area += 0.5 * std::abs((b - a).x() * (c - a).y() - (b - a).y() * (c - a).x());
    for (int k = 0; k < 3; ++k) {
      const int e0 = mesh.triangles(t, k), e1 = mesh.triangles(t, (k + 1) % 3);
      ++uses[{std::min(e0, e1), std::max(e0, e1)}];
    }
  }
  // Conforming: every edge on the mesh's border runs between points of one trim.
  std::size_t border = 0;
  for (const auto& [edge, count] : uses) {
    if (count != 1) continue;
    ++border;
    const double r0 = radius(mesh.uv.row(edge.first)), r1 = radius(mesh.uv.row(edge.second));
    INFO("border edge at elliptic radii " << r0 << ", " << r1);
    const bool on_hole = std::abs(r0 - 0.3) < 1e-6 && std::abs(r1 - 0.3) < 1e-6;
    const bool on_outer = std::abs(r0 - 0.9) < 1e-6 && std::abs(r1 - 0.9) < 1e-6;
    CHECK((on_hole || on_outer));
  }
  CHECK(border > 0);
  // The (u, v) area is the ring's pi (0.9^2 - 0.3^2) of the half-axes product,
  // less the chords' sagittas.
  const double ring = M_PI * (0.81 - 0.09) * half.x() * half.y();
  CHECK(area < ring);
  CHECK(area > 0.99 * ring);
}

TEST_CASE("every face of real models gets triangles, the thinnest trimmed strips too",
          "[io][mesh][slow]") {
  // Ventilator's 13 blade strips are narrower than a cell of the surface's own
  // tessellation; trimming by centroid used to leave them empty.
  for (const char* name : {"Ventilator.stp", "screw.step", "bearing.iges"}) {
    const Result<Model> model = read_model(test::shared_data(name));
    REQUIRE(model.ok());
    TessellationOptions options;
    options.chord_tolerance_mm = 1e-3 * model_box(model.value()).diagonal();
    const Result<TriangleMesh> mesh = tessellate(model.value(), options);
    REQUIRE(mesh.ok());
    std::vector<int> triangles(model.value().faces.size(), 0);
    for (Eigen::Index t = 0; t < mesh.value().triangles.rows(); ++t)
      ++triangles[static_cast<std::size_t>(
          mesh.value().vertex_face[static_cast<std::size_t>(mesh.value().triangles(t, 0))])];
    for (std::size_t f = 0; f < triangles.size(); ++f) {
      INFO(name << " face " << f);
      CHECK(triangles[f] > 0);
    }
    const ChordReport report = chord_errors(model.value(), mesh.value());
    CHECK(report.max_error_mm <= options.chord_tolerance_mm * (1 + 1e-9));
  }
}

/// glb holds metres with +Y up: back to millimetres with +Z up.
Eigen::Vector3d from_file(const aiVector3D& p, bool glb, double scale) {
  return glb ? Eigen::Vector3d(scale * p.x, -scale * p.z, scale * p.y)
             : Eigen::Vector3d(p.x, p.y, p.z);
}

TEST_CASE("STL, OBJ, PLY and glb read back with the same triangles on the surface", "[io][mesh]") {
  const Model model = panel_and_trimmed_face();
  const double size = model_box(model).diagonal();
  WriteOptions options;
  options.tessellation.chord_tolerance_mm = 1e-3 * size;
  const Result<TriangleMesh> mesh = tessellate(model, options.tessellation);
  REQUIRE(mesh.ok());
  const TriangleMesh& m = mesh.value();
  const double coordinate_scale = m.positions.cwiseAbs().maxCoeff();
  test::TempDir dir;
  for (const char* name : {"mesh.stl", "mesh.obj", "mesh.ply", "mesh.glb"}) {
    SECTION(name) {
      REQUIRE(write_model(model, dir / name, options).message == "");
      Assimp::Importer importer;
      // No post-processing: vertices are neither joined nor reordered.
      const aiScene* scene = importer.ReadFile((dir / name).string(), 0);
      REQUIRE(scene != nullptr);
      const bool glb = std::string(name) == "mesh.glb";
      std::size_t triangles = 0;
      for (unsigned k = 0; k < scene->mNumMeshes; ++k) triangles += scene->mMeshes[k]->mNumFaces;
      // This model has no triangle that float32 storage flattens.
      REQUIRE(triangles == static_cast<std::size_t>(m.triangles.rows()));
      const bool has_normals = std::string(name) != "mesh.stl";  // STL: facet normals only
      double max_distance = 0.0, max_normal_error = 0.0;
      Eigen::Index t = 0;
      for (unsigned k = 0; k < scene->mNumMeshes; ++k) {
        const aiMesh* in = scene->mMeshes[k];
        for (unsigned f = 0; f < in->mNumFaces; ++f, ++t) {
          REQUIRE(in->mFaces[f].mNumIndices == 3);
          for (int c = 0; c < 3; ++c) {
            const unsigned index = in->mFaces[f].mIndices[c];
            const Eigen::Vector3d position = from_file(in->mVertices[index], glb, 1e3);
            const int ours = m.triangles(t, c);
            // Same vertex, up to float32 storage (and the glb's mm -> m).
            REQUIRE((position - m.positions.row(ours).transpose()).norm() <=
                    4e-7 * coordinate_scale);
            const FaceRecord& face =
                model
                    .faces[static_cast<std::size_t>(m.vertex_face[static_cast<std::size_t>(ours)])];
            const Eigen::Vector2d uv = m.uv.row(ours);
            max_distance =
                std::max(max_distance, test::project(face.surface, position, uv).distance_mm);
            if (has_normals && in->mNormals != nullptr) {
              const Eigen::Vector3d n = from_file(in->mNormals[index], glb, 1.0);
              Eigen::Vector3d expected = finite_difference_normal(face.surface, uv);
              if (face.reversed) expected = -expected;
              max_normal_error = std::max(max_normal_error, (n - expected).norm());
            }
          }
        }
      }
      // float32 positions: 6e-8 of the largest coordinate, well below 1e-6 of the size.
      CHECK(max_distance <= 1e-6 * size);
      if (has_normals) {
        REQUIRE(scene->mMeshes[0]->mNormals != nullptr);
        // Central differences (step 1e-6 of the domain) and float32 storage: ~1e-7.
        CHECK(max_normal_error <= 1e-5);
      }
    }
  }
}

TEST_CASE("glb holds one mesh per face in a node named after it, in metres with Y up",
          "[io][mesh]") {
  const Result<Model> screw = read_model(test::shared_data("screw.step"));
  REQUIRE(screw.ok());
  const Model& model = screw.value();
  test::TempDir dir;
  WriteOptions options;
  options.tessellation.chord_tolerance_mm = 1e-3 * model_box(model).diagonal();
  REQUIRE(write_model(model, dir / "screw.glb", options).message == "");
  Assimp::Importer importer;
  const aiScene* scene = importer.ReadFile((dir / "screw.glb").string(), 0);
  REQUIRE(scene != nullptr);
  REQUIRE(scene->mNumMeshes == model.faces.size());
  REQUIRE(scene->mRootNode->mNumChildren == model.faces.size());
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(HUGE_VAL), hi = -lo;
  for (unsigned k = 0; k < scene->mNumMeshes; ++k) {
    const std::string expected = "face " + std::to_string(k) + " " + model.faces[k].source_id;
    CHECK(std::string(scene->mMeshes[k]->mName.C_Str()).rfind(expected, 0) == 0);
    const aiNode* node = scene->mRootNode->mChildren[k];
    CHECK(std::string(node->mName.C_Str()) == scene->mMeshes[k]->mName.C_Str());
    REQUIRE(node->mNumMeshes == 1);
    CHECK(node->mMeshes[0] == k);
    for (unsigned v = 0; v < scene->mMeshes[k]->mNumVertices; ++v) {
      const aiVector3D& p = scene->mMeshes[k]->mVertices[v];
      lo = lo.cwiseMin(Eigen::Vector3d(p.x, p.y, p.z));
      hi = hi.cwiseMax(Eigen::Vector3d(p.x, p.y, p.z));
    }
  }
  // The screw's axis is z in the STEP file: its length is the glb's height (y), in metres.
  const Result<TriangleMesh> mesh = tessellate(model, options.tessellation);
  REQUIRE(mesh.ok());
  const Eigen::Vector3d mm_lo = mesh.value().positions.colwise().minCoeff();
  const Eigen::Vector3d mm_hi = mesh.value().positions.colwise().maxCoeff();
  // float32 storage of metres: each coordinate within 6e-8 of the largest, a
  // difference of two within a few times that.
  CHECK(std::abs((hi.y() - lo.y()) - 1e-3 * (mm_hi.z() - mm_lo.z())) <= 3e-7 * hi.norm());
  CHECK(std::abs(hi.z() + 1e-3 * mm_lo.y()) <= 3e-7 * hi.norm());
  CHECK(std::abs(hi.x() - 1e-3 * mm_hi.x()) <= 3e-7 * hi.norm());
  CHECK(hi.y() - lo.y() < 1.0);  // a 62 mm screw is not 62 m tall
}

TEST_CASE("mesh files hold no zero-area triangles, and lose no others", "[io][mesh]") {
  // bearing.iges: 0.16 mm across, with faces that collapse to a point: float32
  // storage flattens some triangles.
  const Result<Model> bearing = read_model(test::shared_data("bearing.iges"));
  REQUIRE(bearing.ok());
  WriteOptions options;
  options.tessellation.chord_tolerance_mm = 1e-3 * model_box(bearing.value()).diagonal();
  const Result<TriangleMesh> mesh = tessellate(bearing.value(), options.tessellation);
  REQUIRE(mesh.ok());
  const TriangleMesh& m = mesh.value();
  test::TempDir dir;
  for (const char* name : {"bearing.stl", "bearing.glb"}) {
    const bool glb = std::string(name) == "bearing.glb";
    // The triangles float32 storage flattens, counted here on their own, and
    // the vertices the others use.
    std::size_t flat = 0;
    std::vector<bool> used(static_cast<std::size_t>(m.positions.rows()), false);
    for (Eigen::Index t = 0; t < m.triangles.rows(); ++t) {
      Eigen::Vector3f corner[3];
      for (int c = 0; c < 3; ++c) {
        const Eigen::Vector3d p = m.positions.row(m.triangles(t, c));
        corner[c] = glb ? Eigen::Vector3d(1e-3 * p.x(), 1e-3 * p.z(), -1e-3 * p.y()).cast<float>()
                        : p.cast<float>();
      }
      if ((corner[1] - corner[0]).cross(corner[2] - corner[0]).squaredNorm() == 0.0f) {
        ++flat;
      } else {
        for (int c = 0; c < 3; ++c) used[static_cast<std::size_t>(m.triangles(t, c))] = true;
      }
    }
    REQUIRE(write_model(bearing.value(), dir / name, options).message == "");
    Assimp::Importer importer;
    const aiScene* scene = importer.ReadFile((dir / name).string(), 0);
    REQUIRE(scene != nullptr);
    std::size_t triangles = 0, zero_area = 0, vertices = 0;
    for (unsigned k = 0; k < scene->mNumMeshes; ++k) {
      const aiMesh* in = scene->mMeshes[k];
      vertices += in->mNumVertices;
      for (unsigned f = 0; f < in->mNumFaces; ++f) {
        ++triangles;
        const aiVector3D& a = in->mVertices[in->mFaces[f].mIndices[0]];
        const aiVector3D& b = in->mVertices[in->mFaces[f].mIndices[1]];
        const aiVector3D& c = in->mVertices[in->mFaces[f].mIndices[2]];
        const aiVector3D n = (b - a) ^ (c - a);
        if (n.x == 0 && n.y == 0 && n.z == 0) ++zero_area;
      }
    }
    INFO(name << ": " << flat << " of " << m.triangles.rows() << " flattened by float32");
    CHECK(flat > 0);  // the case this test is about occurs
    CHECK(zero_area == 0);
    CHECK(triangles + flat == static_cast<std::size_t>(m.triangles.rows()));
    // No vertex joined to another (assimp's glTF export joins vertices closer
    // than 1e-4 of a mesh's size unless their (u, v) differ): the glb keeps
    // every vertex where the surface put it. STL stores corners per triangle.
    if (glb)
      CHECK(vertices == static_cast<std::size_t>(std::count(used.begin(), used.end(), true)));
  }
}

TEST_CASE("a tessellation past its triangle limit fails, and the estimate predicts the count",
          "[io][mesh]") {
  const Model panel = panel_and_trimmed_face();
  TessellationOptions options;
  options.chord_tolerance_mm = 1e-3 * model_box(panel).diagonal();
  const Result<TriangleMesh> full = tessellate(panel, options);
  REQUIRE(full.ok());
  options.max_triangles = static_cast<std::size_t>(full.value().triangles.rows()) / 2;
  const Result<TriangleMesh> limited = tessellate(panel, options);
  REQUIRE_FALSE(limited.ok());
  CHECK_THAT(limited.status().message,
             Catch::Contains("limit of " + std::to_string(options.max_triangles) + " triangles"));
  options.max_triangles = 0;

  const Result<Model> bearing = read_model(test::shared_data("bearing.iges"));
  const Result<Model> screw = read_model(test::shared_data("screw.step"));
  REQUIRE(bearing.ok());
  REQUIRE(screw.ok());
  for (const Model* model : {&panel, &bearing.value(), &screw.value()}) {
    for (double relative : {1e-2, 1e-3, 1e-4}) {
      options.chord_tolerance_mm = relative * model_box(*model).diagonal();
      const Result<std::size_t> estimate = estimate_triangle_count(*model, options);
      const Result<TriangleMesh> mesh = tessellate(*model, options);
      REQUIRE(estimate.ok());
      REQUIRE(mesh.ok());
      const auto count = static_cast<double>(mesh.value().triangles.rows());
      const auto guess = static_cast<double>(estimate.value());
      INFO(model->faces.size() << " faces at " << relative << " of the size: " << count
                               << " triangles, estimated " << guess);
      // Two coarse samples of a power law: right within a factor of two is
      // what the refusal of huge meshes needs.
      CHECK(guess >= 0.5 * count);
      CHECK(guess <= 2.0 * count);
    }
  }
}

}  // namespace argil::io

namespace argil::io {

TEST_CASE("tessellation is deterministic and refuses tolerances finer than float32", "[io][mesh]") {
  const Result<Model> panel = read_model(test::source_file("examples/surfaces/panel.json"));
  REQUIRE(panel.ok());
  TessellationOptions options;
  options.chord_tolerance_mm = 0.5;
  const Result<TriangleMesh> a = tessellate(panel.value(), options);
  const Result<TriangleMesh> b = tessellate(panel.value(), options);
  REQUIRE(a.ok());
  REQUIRE(b.ok());
  CHECK(a.value().triangles == b.value().triangles);
  CHECK(a.value().positions == b.value().positions);
  for (double tolerance : {0.0, -1.0, 1e-9}) {
    options.chord_tolerance_mm = tolerance;
    CHECK_FALSE(tessellate(panel.value(), options).ok());
  }
}

}  // namespace argil::io
