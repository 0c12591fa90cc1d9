// Reads a CAD file (STEP, IGES or argil JSON) and reports one face: its
// B-spline structure, its trims, and the point and normal at its centre.
// Usage: read_face FILE [FACE]
#include <cstdio>
#include <cstdlib>

#include "argil/io.hpp"

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: read_face FILE [FACE]\n");
    return 2;
  }
  const argil::Result<argil::io::Model> model = argil::io::read_model(argv[1]);
  if (!model.ok()) {
    std::fprintf(stderr, "read_face: %s\n", model.status().message.c_str());
    return 1;
  }
  const auto& faces = model.value().faces;
  const long index = argc > 2 ? std::strtol(argv[2], nullptr, 10) : 0;
  if (index < 0 || index >= static_cast<long>(faces.size())) {
    std::fprintf(stderr, "read_face: face %ld is out of range (the file has %zu faces)\n", index,
                 faces.size());
    return 1;
  }
  const argil::io::FaceRecord& face = faces[static_cast<std::size_t>(index)];
  const argil::BSplineSurface& s = face.surface;
  using argil::Direction;
  std::printf("%s: %zu faces; face %ld (%s)\n", argv[1], faces.size(), index,
              face.source_id.c_str());
  std::printf("  degree %d x %d, %d x %d control points, %s, %zu trim loops\n",
              s.degree_in(Direction::u), s.degree_in(Direction::v), s.count(Direction::u),
              s.count(Direction::v), s.is_rational() ? "rational" : "polynomial",
              face.loops.size());
  const double u = 0.5 * (s.domain_start(Direction::u) + s.domain_end(Direction::u));
  const double v = 0.5 * (s.domain_start(Direction::v) + s.domain_end(Direction::v));
  const Eigen::Vector3d p = argil::evaluate(s, u, v);
  const Eigen::Vector3d n = argil::unit_normal(s, u, v);
  std::printf("  centre (u, v) = (%g, %g): point (%g, %g, %g) mm, normal (%g, %g, %g)\n", u, v,
              p.x(), p.y(), p.z(), n.x(), n.y(), n.z());
  return 0;
}
