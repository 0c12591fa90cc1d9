#include "bench_faces.hpp"

#include <algorithm>
#include <cstdio>
#include <utility>

#include "bench_surfaces.hpp"

namespace argil::bench {

namespace {

/// Midpoints of the non-empty knot spans inside the domain of direction d.
std::vector<double> span_midpoints(const BSplineSurface& s, Direction d) {
  const Eigen::VectorXd& k = s.knots_in(d);
  std::vector<double> mids;
  for (Eigen::Index i = s.degree_in(d); i < s.count(d); ++i)
    if (k[i + 1] > k[i]) mids.push_back(0.5 * (k[i] + k[i + 1]));
  return mids;
}

}  // namespace

BSplineSurface flat_panel(int n, double pitch) {
  BSplineSurface s;
  s.degree = {3, 3};
  s.knots = {uniform_knots(3, n), uniform_knots(3, n)};
  s.control_points.resize(static_cast<Eigen::Index>(n) * n, 3);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) s.control_points.row(s.pole_index(i, j)) << pitch * i, pitch * j, 0.0;
  return s;
}

BSplineSurface c0_plate() {
  BSplineSurface s;
  s.degree = {1, 10};
  s.knots[0].resize(4);
  s.knots[0] << 0, 0, 1, 1;
  s.knots[1].resize(32);
  s.knots[1].head(11).setZero();
  s.knots[1].segment(11, 10).setConstant(0.5);
  s.knots[1].tail(11).setOnes();
  s.control_points.resize(2 * 21, 3);
  for (int i = 0; i <= 1; ++i)
    for (int j = 0; j <= 20; ++j) s.control_points.row(s.pole_index(i, j)) << 20.0 * i, j, 0.0;
  return s;
}

Result<BSplineSurface> refine_midpoints(const BSplineSurface& surface, int levels) {
  BSplineSurface s = surface;
  for (int level = 0; level < levels; ++level) {
    for (const Direction d : kDirections) {
      for (const double t : span_midpoints(s, d)) {
        Result<BSplineSurface> r = insert_knot(s, d, t);
        if (!r.ok()) return r.status();
        s = std::move(r).value();
      }
    }
  }
  return s;
}

std::string net_text(const BSplineSurface& s) {
  char text[96];
  std::snprintf(text, sizeof text, "degree %dx%d, %dx%d poles%s", s.degree[0], s.degree[1],
                s.count(Direction::u), s.count(Direction::v),
                s.is_rational() ? ", rational" : "");
  return text;
}

double face_size(const BSplineSurface& surface) { return control_point_box(surface).diagonal(); }

std::vector<int> faces_by_net_size(const io::Model& model, bool rational) {
  const auto poles = [&](int f) {
    const BSplineSurface& s = model.faces[static_cast<std::size_t>(f)].surface;
    return static_cast<long>(s.count(Direction::u)) * s.count(Direction::v);
  };
  std::vector<int> faces;
  for (int f = 0; f < static_cast<int>(model.faces.size()); ++f) {
    const BSplineSurface& s = model.faces[static_cast<std::size_t>(f)].surface;
    if (s.is_rational() == rational && s.count(Direction::u) >= 3 && s.count(Direction::v) >= 3)
      faces.push_back(f);
  }
  std::stable_sort(faces.begin(), faces.end(), [&](int a, int b) { return poles(a) > poles(b); });
  return faces;
}

BenchFace model_face(const io::Model& model, int index, const std::string& file) {
  const io::FaceRecord& face = model.faces[static_cast<std::size_t>(index)];
  BenchFace out;
  out.name = file + " face " + std::to_string(index);
  out.surface = face.surface;
  out.reversed = face.reversed;
  out.origin = "index " + std::to_string(index) + ", source " + face.source_id + ", " +
               net_text(face.surface) +
               (face.trimmed() ? ", trimmed (the deformable body is the whole surface)" : "");
  return out;
}

Result<io::Model> read_bench_model(const std::filesystem::path& path) {
  Result<io::Model> model = io::read_model(path);
  if (!model.ok())
    std::printf("%s: does not import: %s\n", path.filename().c_str(),
                model.status().message.c_str());
  return model;
}

}  // namespace argil::bench
