// Presses a sphere into the middle of one face of a CAD file and reports the
// contacts the certified query finds within a tolerance of 1e-4 of the face's
// size. Usage: collide_sphere FILE [FACE]
#include <cstdio>
#include <cstdlib>

#include "argil/core.hpp"
#include "argil/io.hpp"

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: collide_sphere FILE [FACE]\n");
    return 2;
  }
  const argil::Result<argil::io::Model> model = argil::io::read_model(argv[1]);
  if (!model.ok()) {
    std::fprintf(stderr, "collide_sphere: %s\n", model.status().message.c_str());
    return 1;
  }
  const std::size_t face = argc > 2 ? std::strtoul(argv[2], nullptr, 10) : 0;
  if (face >= model.value().faces.size()) {
    std::fprintf(stderr, "collide_sphere: face %zu is out of range\n", face);
    return 1;
  }
  const argil::BSplineSurface& surface = model.value().faces[face].surface;

  // The hierarchy is built once per surface structure; its bounds are lazy.
  argil::OperatorCache cache;
  argil::Result<argil::SurfaceHierarchy> hierarchy = argil::SurfaceHierarchy::build(surface, cache);
  if (!hierarchy.ok()) {
    std::fprintf(stderr, "collide_sphere: %s\n", hierarchy.status().message.c_str());
    return 1;
  }

  // A sphere of 5% of the face's size, sunk a quarter of its radius into the
  // face at the middle of its parameter domain.
  using argil::Direction;
  const argil::Box3 box = argil::control_point_box(surface);
  const double size = box.diagonal();
  const double radius = 0.05 * size;
  const double u = 0.5 * (surface.domain_start(Direction::u) + surface.domain_end(Direction::u));
  const double v = 0.5 * (surface.domain_start(Direction::v) + surface.domain_end(Direction::v));
  const Eigen::Vector3d p_WC =
      argil::evaluate(surface, u, v) + 0.75 * radius * argil::unit_normal(surface, u, v);
  const auto sphere = argil::make_sphere(p_WC, radius);

  const argil::CollisionResult result =
      argil::collide(hierarchy.value(), *sphere, {.tolerance = 1e-4 * size});
  if (!result.status.ok()) {
    std::fprintf(stderr, "collide_sphere: %s\n", result.status.message.c_str());
    return 1;
  }
  double deepest = 0.0;
  for (const argil::Contact& c : result.contacts) deepest = std::max(deepest, c.depth);
  std::printf("face %zu (%g mm across): sphere of radius %g mm at (%g, %g, %g) mm\n", face, size,
              radius, p_WC.x(), p_WC.y(), p_WC.z());
  std::printf(
      "  %zu contacts in %d regions, deepest %g mm (the sphere was sunk %g mm at the centre)\n",
      result.contacts.size(), result.region_count, deepest, 0.25 * radius);
  return result.contacts.empty() ? 1 : 0;
}
