// argil collide A B [--face-a I] [--face-b J] [--tolerance E] [--refine] [--json]:
// intersection curves and contact regions between one face of each model.
#include <algorithm>
#include <cstdio>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "argil/core/base/number_text.hpp"
#include "argil/core/collision/surface_intersection.hpp"
#include "argil/core/geometry/bspline_surface.hpp"
#include "argil/core/hierarchy/surface_hierarchy.hpp"
#include "argil/core/operators/surface_operators.hpp"
#include "argil/io/files/model_files.hpp"
#include "commands.hpp"

namespace argil::cli {
namespace {

// eps when none is given: fine enough to resolve curves of CAD-sized models,
// coarse enough to stay interactive; scales with the two faces.
constexpr double kDefaultRelativeTolerance = 1e-4;

struct Options {
  std::string path_a, path_b;
  long face_a = 0, face_b = 0;
  double tolerance_mm = 0.0;  // 0: default
  bool refine = false;
  bool json = false;
};

Options options_from(const Arguments& a) {
  return {.path_a = a.operands[0],
          .path_b = a.operands[1],
          .face_a = a.index("--face-a").value_or(0),
          .face_b = a.index("--face-b").value_or(0),
          .tolerance_mm = a.number("--tolerance").value_or(0.0),
          .refine = a.flag("--refine"),
          .json = a.flag("--json")};
}

/// Reads `path`; prints the error.
std::optional<io::Model> read_file(const std::string& path) {
  Result<io::Model> read = io::read_model(path);
  if (!read.ok()) {
    std::fprintf(stderr, "argil collide: %s\n", read.status().message.c_str());
    return std::nullopt;
  }
  return std::move(read).value();
}

/// Copies face `index` out of the model read from `path`; prints the error.
bool copy_face(const io::Model& model, const std::string& path, long index, const char* side,
               BSplineSurface& out) {
  const auto& faces = model.faces;
  if (index >= static_cast<long>(faces.size())) {
    std::fprintf(stderr, "argil collide: --face-%s %ld is out of range: %s has %zu faces\n", side,
                 index, path.c_str(), faces.size());
    return false;
  }
  out = faces[static_cast<std::size_t>(index)].surface;
  return true;
}

/// Faces a and b; a file named twice is read once (a large model takes
/// seconds to read), and only one model is held at a time.
bool load_faces(const Options& o, BSplineSurface& a, BSplineSurface& b) {
  {
    const std::optional<io::Model> model_a = read_file(o.path_a);
    if (!model_a || !copy_face(*model_a, o.path_a, o.face_a, "a", a)) return false;
    if (o.path_b == o.path_a) return copy_face(*model_a, o.path_b, o.face_b, "b", b);
  }
  const std::optional<io::Model> model_b = read_file(o.path_b);
  return model_b && copy_face(*model_b, o.path_b, o.face_b, "b", b);
}

/// One region of contacts: contacts are grouped by region, deepest first, so
/// the first contact of a region is its representative.
struct RegionSummary {
  int contacts = 0;
  double deepest = 0.0;
  const Contact* representative = nullptr;
};

std::vector<RegionSummary> summarize_regions(const CollisionResult& r) {
  std::vector<RegionSummary> regions(static_cast<std::size_t>(r.region_count));
  for (const Contact& c : r.contacts) {
    if (c.region < 0 || c.region >= r.region_count) continue;
    RegionSummary& s = regions[static_cast<std::size_t>(c.region)];
    if (s.representative == nullptr || c.depth > s.deepest) s.deepest = c.depth;
    if (s.representative == nullptr) s.representative = &c;
    ++s.contacts;
  }
  return regions;
}

// ---- text output ---------------------------------------------------------

void print_text(const Options& o, double eps, const CollisionResult& r) {
  std::printf("a: %s face %ld\nb: %s face %ld\n", o.path_a.c_str(), o.face_a, o.path_b.c_str(),
              o.face_b);
  std::printf("tolerance: %s mm, refine: %s\n", number_text(eps).c_str(), o.refine ? "yes" : "no");
  const std::vector<RegionSummary> regions = summarize_regions(r);
  std::printf("\ncontact regions: %zu (%zu contacts)\n", regions.size(), r.contacts.size());
  for (std::size_t k = 0; k < regions.size(); ++k) {
    const RegionSummary& s = regions[k];
    if (s.representative == nullptr) continue;
    const Contact& c = *s.representative;
    std::printf(
        "  region %zu: %d contacts, deepest depth %.6g mm, point (%.9g, %.9g, %.9g), "
        "uv_a (%.9g, %.9g), uv_b (%.9g, %.9g)\n",
        k, s.contacts, s.deepest, c.point.x(), c.point.y(), c.point.z(), c.uv_a[0], c.uv_a[1],
        c.uv_b[0], c.uv_b[1]);
  }
  std::printf("\nintersection curves: %zu\n", r.curves.size());
  for (std::size_t k = 0; k < r.curves.size(); ++k) {
    const IntersectionCurve& c = r.curves[k];
    std::printf("  curve %zu: %zu points, length %.9g mm%s\n", k, c.points.size(), c.length(),
                c.closed() ? ", closed" : "");
    for (std::size_t e = 0; e < 2 && !c.points.empty(); ++e) {
      const std::size_t i = e == 0 ? 0 : c.points.size() - 1;
      std::printf("    %s (%.9g, %.9g, %.9g)  uv_a (%.9g, %.9g)  uv_b (%.9g, %.9g)\n",
                  e == 0 ? "start" : "end  ", c.points[i].x(), c.points[i].y(), c.points[i].z(),
                  c.uv_a[i][0], c.uv_a[i][1], c.uv_b[i][0], c.uv_b[i][1]);
    }
  }
  std::printf(
      "\ncounters: nodes visited %ld, nodes refreshed %ld, leaf pairs %ld, triangle tests %ld\n",
      r.counters.nodes_visited, r.counters.nodes_refreshed, r.counters.leaf_pairs,
      r.counters.triangle_tests);
}

// ---- JSON output -----------------------------------------------------------

template <class V>
nlohmann::ordered_json json_vector(const V& v) {
  nlohmann::ordered_json out = nlohmann::ordered_json::array();
  for (Eigen::Index k = 0; k < v.size(); ++k) out.push_back(v[k]);
  return out;
}

nlohmann::ordered_json json_contact(const Contact& c) {
  return {{"region", c.region},
          {"depth", c.depth},
          {"point", json_vector(c.point)},
          {"normal", json_vector(c.normal)},
          {"uv_a", json_vector(c.uv_a)},
          {"uv_b", json_vector(c.uv_b)}};
}

nlohmann::ordered_json json_curve(const IntersectionCurve& c) {
  nlohmann::ordered_json points = nlohmann::ordered_json::array();
  for (std::size_t i = 0; i < c.points.size(); ++i)
    points.push_back({{"point", json_vector(c.points[i])},
                      {"uv_a", json_vector(c.uv_a[i])},
                      {"uv_b", json_vector(c.uv_b[i])}});
  return {{"closed", c.closed()}, {"length", c.length()}, {"points", std::move(points)}};
}

/// nlohmann writes doubles in their shortest round-trip form.
void print_json(const Options& o, double eps, const CollisionResult& r) {
  nlohmann::ordered_json out;
  out["a"] = {{"file", o.path_a}, {"face", o.face_a}};
  out["b"] = {{"file", o.path_b}, {"face", o.face_b}};
  out["tolerance"] = eps;
  out["refine"] = o.refine;
  nlohmann::ordered_json regions = nlohmann::ordered_json::array();
  for (const RegionSummary& s : summarize_regions(r)) {
    if (s.representative == nullptr) continue;
    nlohmann::ordered_json region = json_contact(*s.representative);
    region.erase("region");
    region.erase("depth");
    regions.push_back({{"contacts", s.contacts}, {"deepest_depth", s.deepest}});
    regions.back().update(region);
  }
  out["regions"] = std::move(regions);
  nlohmann::ordered_json contacts = nlohmann::ordered_json::array();
  for (const Contact& c : r.contacts) contacts.push_back(json_contact(c));
  out["contacts"] = std::move(contacts);
  nlohmann::ordered_json curves = nlohmann::ordered_json::array();
  for (const IntersectionCurve& c : r.curves)
    if (!c.points.empty()) curves.push_back(json_curve(c));
  out["curves"] = std::move(curves);
  out["counters"] = {{"nodes_visited", r.counters.nodes_visited},
                     {"nodes_refreshed", r.counters.nodes_refreshed},
                     {"leaf_pairs", r.counters.leaf_pairs},
                     {"triangle_tests", r.counters.triangle_tests}};
  // A path that is not UTF-8 is written with replacement characters, not thrown on.
  std::fputs(
      (out.dump(-1, ' ', false, nlohmann::ordered_json::error_handler_t::replace) + "\n").c_str(),
      stdout);
}

}  // namespace

const CommandDeclaration& collide_command() {
  static const CommandDeclaration spec{
      .name = "collide",
      .operands = {"A", "B"},
      .summary = "intersection curves and contact regions between a face of A and one of B",
      .description =
          "A and B are model files (see argil help info). Prints each contact region\n"
          "and each intersection curve with its end points, in mm.",
      .options = {{.name = "--face-a",
                   .argument = "I",
                   .kind = ValueKind::index,
                   .description = "the face of A",
                   .default_text = "0"},
                  {.name = "--face-b",
                   .argument = "J",
                   .kind = ValueKind::index,
                   .description = "the face of B",
                   .default_text = "0"},
                  {.name = "--tolerance",
                   .argument = "E",
                   .kind = ValueKind::number,
                   .description = "eps, the distance within which the faces touch",
                   .range = kPositiveFinite,
                   .unit = "mm",
                   .default_text = "1e-4 of the larger face's size"},
                  {.name = "--refine",
                   .description = "Newton-refine contact points on the exact surfaces",
                   .default_text = "off"},
                  {.name = "--json",
                   .description = "print JSON instead of text",
                   .default_text = "off"}},
  };
  return spec;
}

int run_collide(const std::vector<std::string>& args) {
  const ParseResult parsed = parse_arguments(collide_command(), args);
  if (!parsed.arguments) return parsed.exit_status;
  const Options o = options_from(*parsed.arguments);
  BSplineSurface a, b;
  if (!load_faces(o, a, b)) return kExitFailure;
  OperatorCache cache;
  Result<SurfaceHierarchy> ha = SurfaceHierarchy::build(a, cache);
  Result<SurfaceHierarchy> hb = SurfaceHierarchy::build(b, cache);
  if (!ha.ok() || !hb.ok()) {
    std::fprintf(stderr, "argil collide: %s\n", (ha.ok() ? hb : ha).status().message.c_str());
    return kExitFailure;
  }
  const double size = std::max(control_point_box(a).diagonal(), control_point_box(b).diagonal());
  const double eps = o.tolerance_mm > 0.0 ? o.tolerance_mm : kDefaultRelativeTolerance * size;
  if (!(eps > 0.0)) {
    std::fprintf(stderr, "argil collide: both faces are degenerate (size 0); give --tolerance\n");
    return kExitFailure;
  }
  CollisionRequest request;
  request.tolerance = eps;
  request.refine = o.refine;
  const CollisionResult r = collide(ha.value(), hb.value(), request);
  if (!r.status.ok()) {
    std::fprintf(stderr, "argil collide: %s\n", r.status.message.c_str());
    return kExitFailure;
  }
  if (o.json) {
    print_json(o, eps, r);
  } else {
    print_text(o, eps, r);
  }
  return kExitOk;
}

}  // namespace argil::cli
