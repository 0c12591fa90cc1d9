#include "bench_faces.hpp"

#include <algorithm>
#include <cstdio>
#include <utility>

#include "bench_surfaces.hpp"
#include "support/test_plates.hpp"
#include "support/uniform_refinement.hpp"

namespace argil::bench {

BSplineSurface flat_panel(int n, double pitch) { return test::wavy_sheet(n, pitch, 0.0); }

BSplineSurface c0_plate() {
  return test::flat_plate(
      {.width = 20.0, .height = 20.0, .spans_u = 1, .degree_v = 10, .pieces_v = 2, .join_v = 10});
}

BSplineSurface refine_midpoints(const BSplineSurface& surface, int levels) {
  return test::halved_spans(surface, levels);
}

std::string net_text(const BSplineSurface& s) {
  char text[96];
  std::snprintf(text, sizeof text, "degree %dx%d, %dx%d poles%s", s.degree[0], s.degree[1],
                s.count(Direction::u), s.count(Direction::v), s.is_rational() ? ", rational" : "");
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
