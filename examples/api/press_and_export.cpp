// Presses a sphere tool into one face of a CAD file for a few hundred haptic
// ticks (1 kHz), reports the force felt and how far the face moved, and
// writes the sculpted face to a new file (STEP, IGES, JSON or a mesh).
// Usage: press_and_export FILE OUT [FACE]
#include <cstdio>
#include <cstdlib>

#include "argil/core.hpp"
#include "argil/io.hpp"

namespace {

/// The device handle at p_WD, not rotated, the tool engaged.
argil::DeviceSample device_at(const Eigen::Vector3d& p_WD) {
  return {.X_WD = argil::Pose::at(p_WD), .engaged = true};
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 3) {
    std::fprintf(stderr, "usage: press_and_export FILE OUT [FACE]\n");
    return 2;
  }
  const argil::Result<argil::io::Model> model = argil::io::read_model(argv[1]);
  if (!model.ok()) {
    std::fprintf(stderr, "press_and_export: %s\n", model.status().message.c_str());
    return 1;
  }
  const std::size_t face = argc > 3 ? std::strtoul(argv[3], nullptr, 10) : 0;
  if (face >= model.value().faces.size()) {
    std::fprintf(stderr, "press_and_export: face %zu is out of range\n", face);
    return 1;
  }
  const argil::BSplineSurface& surface = model.value().faces[face].surface;

  // A sphere of 5% of the face's size, tolerance 1e-3 of it.
  using argil::Direction;
  const double size = argil::control_point_box(surface).diagonal();
  const double radius = 0.05 * size;
  argil::WorldOptions options;
  options.tolerance = 1e-3 * size;
  argil::Result<argil::HapticWorld> created =
      argil::HapticWorld::create(argil::SphereToolShape{radius}, options);
  if (!created.ok()) {
    std::fprintf(stderr, "press_and_export: %s\n", created.status().message.c_str());
    return 1;
  }
  argil::HapticWorld world = std::move(created).value();
  // Default material, free edges, Coulomb friction 0.3 between tool and face.
  const argil::Result<int> body =
      world.add_deformable(surface, argil::Material{}, argil::BoundaryConditions{}, 0.3);
  if (!body.ok()) {
    std::fprintf(stderr, "press_and_export: %s\n", body.status().message.c_str());
    return 1;
  }

  // The device comes down along the normal at the face's middle to half a
  // radius below the surface, holds, and lifts off.
  const double u = 0.5 * (surface.domain_start(Direction::u) + surface.domain_end(Direction::u));
  const double v = 0.5 * (surface.domain_start(Direction::v) + surface.domain_end(Direction::v));
  const Eigen::Vector3d p_WS = argil::evaluate(surface, u, v);
  const Eigen::Vector3d n_W = argil::unit_normal(surface, u, v);
  const double dt = 1e-3;  // [s]
  double peak_force = 0.0;
  for (int tick = 0; tick < 400; ++tick) {
    const double s = std::min(1.0, tick / 200.0);  // 0 -> 1 over 0.2 s, then hold
    const double height = tick < 350 ? (1.0 - 1.5 * s) * radius : 2.0 * radius;
    const argil::TickResult r = world.step(device_at(p_WS + height * n_W), dt);
    if (!r.status.ok()) {
      std::fprintf(stderr, "press_and_export: tick %d: %s\n", tick, r.status.message.c_str());
      return 1;
    }
    peak_force = std::max(peak_force, r.force.norm());
  }

  argil::io::Model out = model.value();
  out.faces = {out.faces[face]};
  out.topology = {};  // one face alone: the model's B-rep (shared edges, solid) is not its
  out.faces[0].surface = world.surface(body.value());
  const double moved =
      (out.faces[0].surface.control_points - surface.control_points).rowwise().norm().maxCoeff();
  std::printf("face %zu: peak force %g N, control points moved up to %g mm\n", face, peak_force,
              moved);
  const argil::Status written = argil::io::write_model(out, argv[2]);
  if (!written.ok()) {
    std::fprintf(stderr, "press_and_export: %s\n", written.message.c_str());
    return 1;
  }
  std::printf("wrote %s\n", argv[2]);
  return peak_force > 0.0 ? 0 : 1;  // no force: the tool never reached the face
}
