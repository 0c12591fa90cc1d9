// argil info FILE: what a model file holds, and the surfaces evaluated at the
// centre of their domains (a quick check that the geometry is sound).
#include <cstdio>
#include <string>
#include <vector>

#include "argil/core/base/number_text.hpp"
#include "argil/core/geometry/evaluate.hpp"
#include "argil/io/files/model_files.hpp"
#include "commands.hpp"

namespace argil::cli {
namespace {

void print_vector(const char* label, const Eigen::Vector3d& p) {
  std::printf("%s(%.6g, %.6g, %.6g)", label, p.x(), p.y(), p.z());
}

// The B-rep in counts, and the product tree (one line per product).
void print_topology(const io::Topology& topology) {
  if (topology.empty()) {
    std::printf("topology: none (loose faces)\n");
    return;
  }
  const io::TopologyCounts c = io::count_topology(topology);
  std::printf(
      "topology: %zu products, %zu solids, %zu shells (%zu closed), %zu edges "
      "(%zu shared, %zu seams, %zu free, %zu degenerate), %zu vertices\n",
      c.products, c.solids, c.shells, c.closed_shells, c.edges, c.shared_edges, c.seam_edges,
      c.free_edges, c.degenerate_edges, c.vertices);
  for (std::size_t p = 0; p < topology.products.size(); ++p) {
    const io::Product& product = topology.products[p];
    int depth = 0;
    for (std::size_t up = product.parent; up != io::kNoIndex; up = topology.products[up].parent) {
      ++depth;
    }
    std::printf("  %*sproduct %zu \"%s\"%s%s: %zu solids, %zu shells, %zu faces\n", 2 * depth, "",
                p, product.name.c_str(), product.instance.empty() ? "" : " as ",
                product.instance.c_str(), product.solids.size(), product.shells.size(),
                product.faces.size());
  }
}

}  // namespace

const CommandDeclaration& info_command() {
  static const CommandDeclaration spec{
      .name = "info",
      .operands = {"FILE"},
      .summary = "faces, degrees, control nets, trims, units and bounding box of a model",
      .description =
          "FILE is STEP (.step .stp), IGES (.iges .igs) or argil JSON (.json). Lengths\n"
          "print in mm; each surface is also evaluated at the centre of its domain.",
      .options = {},
  };
  return spec;
}

int run_info(const std::vector<std::string>& args) {
  const ParseResult parsed = parse_arguments(info_command(), args);
  if (!parsed.arguments) return parsed.exit_status;
  const std::string& path = parsed.arguments->operands[0];
  const Result<io::Model> read = io::read_model(path);
  if (!read.ok()) {
    std::fprintf(stderr, "argil info: %s\n", read.status().message.c_str());
    return kExitFailure;
  }
  const io::Model& model = read.value();
  std::size_t trimmed = 0, rational = 0;
  for (const io::FaceRecord& face : model.faces) {
    trimmed += face.trimmed() ? 1u : 0u;
    rational += face.surface.is_rational() ? 1u : 0u;
  }
  std::printf("file: %s\n", path.c_str());
  std::printf("units: mm (source unit: %s, 1 source unit = %s mm)\n",
              model.source_unit.name.c_str(), number_text(model.source_unit.to_mm).c_str());
  std::printf("faces: %zu (%zu trimmed, %zu rational)\n", model.faces.size(), trimmed, rational);
  print_topology(model.topology);
  for (const std::string& warning : model.warnings) std::printf("warning: %s\n", warning.c_str());
  const Box3 box = io::model_box(model);
  std::printf("bounding box of the control points [mm]: ");
  print_vector("min ", box.min);
  print_vector(" max ", box.max);
  std::printf(" diagonal %.6g\n", box.diagonal());
  std::printf("\n%5s  %-7s  %-9s  %-8s  %-7s  %5s  %-8s  %s\n", "face", "degree", "poles",
              "rational", "trimmed", "loops", "source", "name");
  for (std::size_t f = 0; f < model.faces.size(); ++f) {
    const io::FaceRecord& face = model.faces[f];
    const BSplineSurface& s = face.surface;
    const std::string degree = std::to_string(s.degree[0]) + "x" + std::to_string(s.degree[1]);
    const std::string poles =
        std::to_string(s.count(Direction::u)) + "x" + std::to_string(s.count(Direction::v));
    std::printf("%5zu  %-7s  %-9s  %-8s  %-7s  %5zu  %-8s  %s\n", f, degree.c_str(), poles.c_str(),
                s.is_rational() ? "yes" : "no", face.trimmed() ? "yes" : "no", face.loops.size(),
                face.source_id.c_str(), face.name.c_str());
  }
  std::printf("\nsurface at the centre of its domain [mm] (normal on the face's side):\n");
  for (std::size_t f = 0; f < model.faces.size(); ++f) {
    const BSplineSurface& s = model.faces[f].surface;
    const double u = 0.5 * (s.domain_start(Direction::u) + s.domain_end(Direction::u));
    const double v = 0.5 * (s.domain_start(Direction::v) + s.domain_end(Direction::v));
    const SurfaceDerivatives d = evaluate_derivatives(s, u, v, 1);
    const double side = model.faces[f].reversed ? -1.0 : 1.0;
    std::printf("%5zu  (u, v) = (%.6g, %.6g)  ", f, u, v);
    print_vector("point ", d.point);
    print_vector("  normal ", side * unit_normal(s, u, v));
    std::printf("\n");
  }
  return kExitOk;
}

}  // namespace argil::cli
