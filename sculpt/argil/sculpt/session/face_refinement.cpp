#include "argil/sculpt/session/face_refinement.hpp"

#include <algorithm>
#include <string>
#include <variant>

#include "argil/core/base/number_text.hpp"
#include "argil/sculpt/session/session.hpp"

namespace argil::sculpt {

double tool_bound_radius(const ToolShape& tool) {
  if (const auto* sphere = std::get_if<SphereToolShape>(&tool)) return sphere->radius;
  const BSplineSurface& s = std::get<SurfaceToolShape>(tool).surface;
  return s.control_points.rowwise().norm().maxCoeff();  // convex hull property
}

double refinement_resolution(const Scene& scene, const ToolShape& tool) {
  if (scene.resolution) return *scene.resolution;
  return tool_bound_radius(tool);
}

namespace {

/// The box of (u, v) near any of `paths` (region_near_path of each, joined).
std::optional<ParamRect> region_near_paths(const BSplineSurface& s,
                                           const std::vector<std::vector<Eigen::Vector3d>>& paths,
                                           double reach) {
  std::optional<ParamRect> out;
  for (const std::vector<Eigen::Vector3d>& path : paths) {
    const std::optional<ParamRect> r = region_near_path(s, path, reach);
    if (!r) continue;
    if (!out) {
      out = r;
      continue;
    }
    out = ParamRect{std::min(out->u0, r->u0), std::max(out->u1, r->u1), std::min(out->v0, r->v0),
                    std::max(out->v1, r->v1)};
  }
  return out;
}

}  // namespace

Result<std::vector<FaceRefinement>> refine_faces(
    std::vector<LoadedModel>& models, const ToolShape& tool, double resolution,
    const std::vector<std::vector<Eigen::Vector3d>>& paths) {
  std::vector<FaceRefinement> out;
  if (!(resolution > 0.0) || paths.empty()) return out;
  const double reach = 2.0 * tool_bound_radius(tool) + resolution;
  RefinementGoal goal;
  goal.resolution = resolution;
  for (std::size_t m = 0; m < models.size(); ++m) {
    LoadedModel& model = models[m];
    if (!model.spec.deformable) continue;
    for (std::size_t f = 0; f < model.initial.faces.size(); ++f) {
      BSplineSurface& surface = model.initial.faces[f].surface;
      const std::optional<ParamRect> region = region_near_paths(surface, paths, reach);
      if (!region) continue;
      Result<Refinement> refined = refine_region(surface, *region, goal);
      if (!refined.ok()) {
        return Status::error(refined.status().code,
                             "models[" + std::to_string(m) + "] face " +
                                 std::to_string(model.file_faces[f]) +
                                 ": refinement: " + refined.status().message);
      }
      if (!refined.value().report.changed()) continue;
      surface = std::move(refined.value().surface);
      out.push_back({static_cast<int>(m), model.file_faces[f], refined.value().report});
    }
  }
  return out;
}

std::string refinement_text(const FaceRefinement& r) {
  const RefinementReport& k = r.report;
  const auto pair = [](const std::array<int, 2>& a) {
    return std::to_string(a[0]) + " x " + std::to_string(a[1]);
  };
  std::string text =
      "models[" + std::to_string(r.model) + "] face " + std::to_string(r.face) + ": ";
  if (k.degree_before != k.degree_after)
    text += "degree " + pair(k.degree_before) + " -> " + pair(k.degree_after) + ", ";
  text += pair(k.count_before) + " -> " + pair(k.count_after) +
          " control points (spans <= " + limit_text(k.resolution, LimitSide::lower) +
          " mm near the tool" +
          (k.capped ? ", capped at " + std::to_string(kMaxRefinedCount) + " per direction" : "") +
          ")";
  return text;
}

}  // namespace argil::sculpt
