#include "argil/sculpt/view/view_page.hpp"

#include <algorithm>
#include <cstdint>
#include <nlohmann/json.hpp>

#include "argil/core/geometry/evaluate.hpp"
#include "argil/io/files/model_files.hpp"
#include "argil/io/mesh/tessellate.hpp"
#include "argil/sculpt/view/detail/base64.hpp"
#include "argil/sculpt/view/detail/viewer_script.hpp"

namespace argil::sculpt {
namespace {

using detail::base64_of;
using nlohmann::json;

constexpr double kChordRelative = 5e-4;
constexpr std::size_t kMaxTriangles = 2'000'000;

/// One model of the page: its faces as the page starts (before) and, for a
/// replayed deformable model, at each frame.
struct PageModel {
  std::string name{};
  bool deformable = false;
  const io::Model* before = nullptr;
  const std::vector<int>* file_faces = nullptr;  // null: face f is file face f
  std::vector<const io::Model*> frames{};        // one per page frame, or none
};

/// One face's share of a model's mesh: its vertices' (u, v) and its triangles
/// renumbered from 0.
struct FaceMesh {
  std::vector<Eigen::Vector2d> uv;
  std::vector<std::uint32_t> indices;
};

std::vector<FaceMesh> split_by_face(const io::TriangleMesh& mesh, std::size_t faces) {
  std::vector<FaceMesh> out(faces);
  std::vector<std::uint32_t> local(static_cast<std::size_t>(mesh.positions.rows()));
  for (Eigen::Index k = 0; k < mesh.positions.rows(); ++k) {
    FaceMesh& face = out[static_cast<std::size_t>(mesh.vertex_face[static_cast<std::size_t>(k)])];
    local[static_cast<std::size_t>(k)] = static_cast<std::uint32_t>(face.uv.size());
    face.uv.emplace_back(mesh.uv(k, 0), mesh.uv(k, 1));
  }
  for (Eigen::Index t = 0; t < mesh.triangles.rows(); ++t) {
    FaceMesh& face = out[static_cast<std::size_t>(
        mesh.vertex_face[static_cast<std::size_t>(mesh.triangles(t, 0))])];
    for (int c = 0; c < 3; ++c)
      face.indices.push_back(local[static_cast<std::size_t>(mesh.triangles(t, c))]);
  }
  return out;
}

std::vector<float> positions_at(const io::FaceRecord& face,
                                const std::vector<Eigen::Vector2d>& uv) {
  std::vector<float> out;
  out.reserve(3 * uv.size());
  for (const Eigen::Vector2d& p : uv) {
    const Eigen::Vector3d x = evaluate(face.surface, p.x(), p.y());
    for (int c = 0; c < 3; ++c) out.push_back(static_cast<float>(x[c]));
  }
  return out;
}

std::vector<float> normals_at(const io::FaceRecord& face, const std::vector<Eigen::Vector2d>& uv) {
  std::vector<float> out;
  out.reserve(3 * uv.size());
  for (const Eigen::Vector2d& p : uv) {
    const Eigen::Vector3d n =
        (face.reversed ? -1.0 : 1.0) * unit_normal(face.surface, p.x(), p.y());
    for (int c = 0; c < 3; ++c) out.push_back(static_cast<float>(n[c]));
  }
  return out;
}

/// "#120 Fillet": the face's source entity and name, as far as it has them.
std::string face_label(const io::FaceRecord& face) {
  if (face.source_id.empty() || face.name.empty()) return face.source_id + face.name;
  return face.source_id + " " + face.name;
}

bool same_surface(const BSplineSurface& a, const BSplineSurface& b) {
  return a.control_points.rows() == b.control_points.rows() &&
         (a.control_points.array() == b.control_points.array()).all();
}

template <class T>
std::string vector3_base64(const std::vector<T>& values) {
  std::vector<float> flat;
  flat.reserve(3 * values.size());
  for (const T& v : values)
    for (int c = 0; c < 3; ++c) flat.push_back(static_cast<float>(v[c]));
  return base64_of(flat);
}

double chord_for(const std::vector<PageModel>& models, double eps, const ViewPageOptions& options) {
  if (options.chord_tolerance_mm > 0.0) return options.chord_tolerance_mm;
  Box3 box = io::model_box(*models.front().before);
  for (const PageModel& m : models) {
    const Box3 b = io::model_box(*m.before);
    box = {box.min.cwiseMin(b.min), box.max.cwiseMax(b.max)};
  }
  return std::max(box.diagonal() * kChordRelative, std::min(eps, box.diagonal() * 1e-2));
}

/// The page's data (argil.view version 1): faces, frames (only the faces
/// that changed since the frame before), and the run.
Result<json> page_data(const std::vector<PageModel>& models, const std::vector<json>& frame_heads,
                       double eps, const ViewPageOptions& options) {
  io::TessellationOptions tessellation;
  tessellation.chord_tolerance_mm = chord_for(models, eps, options);
  tessellation.max_triangles = kMaxTriangles;
  json data = {{"format", "argil.view"},
               {"version", 1},
               {"title", options.title},
               {"tolerance_mm", eps},
               {"chord_mm", tessellation.chord_tolerance_mm},
               {"models", json::array()},
               {"faces", json::array()}};
  data["scale_mm"] = options.scale_mm ? json(*options.scale_mm) : json(nullptr);
  std::vector<json> frames = frame_heads;
  for (json& frame : frames) frame["faces"] = json::object();
  std::size_t triangles = 0;
  for (std::size_t m = 0; m < models.size(); ++m) {
    const PageModel& model = models[m];
    data["models"].push_back({{"name", model.name}, {"deformable", model.deformable}});
    // Meshed as the run left it: the dent is where the triangles must be.
    const io::Model& shape = model.frames.empty() ? *model.before : *model.frames.back();
    tessellation.max_triangles = kMaxTriangles - triangles;
    Result<io::TriangleMesh> mesh = io::tessellate(shape, tessellation);
    if (!mesh.ok())
      return Status::error(mesh.status().code, model.name + ": " + mesh.status().message);
    triangles += static_cast<std::size_t>(mesh.value().triangles.rows());
    const std::vector<FaceMesh> faces = split_by_face(mesh.value(), shape.faces.size());
    for (std::size_t f = 0; f < faces.size(); ++f) {
      const io::FaceRecord& before = model.before->faces[f];
      std::vector<double> uv;
      for (const Eigen::Vector2d& p : faces[f].uv) uv.insert(uv.end(), {p.x(), p.y()});
      const int file_face = model.file_faces ? (*model.file_faces)[f] : static_cast<int>(f);
      const std::size_t page_face = data["faces"].size();
      data["faces"].push_back({{"model", m},
                               {"face", file_face},
                               {"name", face_label(before)},
                               {"positions", base64_of(positions_at(before, faces[f].uv))},
                               {"normals", base64_of(normals_at(before, faces[f].uv))},
                               {"uv", base64_of(uv)},
                               {"indices", base64_of(faces[f].indices)}});
      const BSplineSurface* shown = &before.surface;
      for (std::size_t k = 0; k < model.frames.size(); ++k) {
        const io::FaceRecord& now = model.frames[k]->faces[f];
        if (same_surface(now.surface, *shown)) continue;
        frames[k]["faces"][std::to_string(page_face)] = base64_of(positions_at(now, faces[f].uv));
        shown = &now.surface;
      }
    }
  }
  data["frames"] = frames;
  return data;
}

/// The HTML page around the data. Every '<' in the JSON is written \u003c,
/// so no text in it (a face name, a path) can end or confuse its script
/// element.
Result<std::string> page_html(const json& data, const std::string& title) {
  const std::string_view script = detail::viewer_script();
  if (script.empty()) {
    return Status::error(StatusCode::failed_precondition,
                         "this argil was built without the viewer script (web/'s packages were "
                         "missing when it was configured: run make, which installs them)");
  }
  // Invalid UTF-8 in a name read from a file is replaced, not thrown on.
  const std::string text = data.dump(-1, ' ', false, json::error_handler_t::replace);
  std::string escaped;
  escaped.reserve(text.size());
  for (const char c : text) {
    if (c == '<')
      escaped += "\\u003c";  // '<' only inside strings; \u003c reads back the same
    else
      escaped += c;
  }
  std::string html_title;
  for (const char c : title) {
    if (c == '<')
      html_title += "&lt;";
    else if (c == '&')
      html_title += "&amp;";
    else
      html_title += c;
  }
  std::string page;
  page.reserve(escaped.size() + script.size() + 512);
  page += "<!doctype html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n<title>";
  page += html_title;
  page +=
      " - argil view</title>\n</head>\n<body>\n<script id=\"argil-data\" "
      "type=\"application/json\">";
  page += escaped;
  page += "</script>\n<script>\n";
  page += script;
  page += "\n</script>\n</body>\n</html>\n";
  return page;
}

/// The scene tools the run held, in order of first use (the page's tools).
std::vector<int> tools_used(const SessionReplay& replay) {
  std::vector<int> used;
  for (const int t : replay.tool_index)
    if (std::find(used.begin(), used.end(), t) == used.end()) used.push_back(t);
  if (used.empty()) used.push_back(0);
  return used;
}

json run_data(const SessionReplay& replay, const std::vector<int>& used) {
  std::vector<float> orientation;
  for (const Eigen::Quaterniond& q : replay.orientation) {
    orientation.insert(orientation.end(), {static_cast<float>(q.w()), static_cast<float>(q.x()),
                                           static_cast<float>(q.y()), static_cast<float>(q.z())});
  }
  std::vector<std::uint8_t> engaged(replay.engaged.begin(), replay.engaged.end());
  std::vector<std::uint8_t> tool;  // index in the page's tools
  for (const int t : replay.tool_index) {
    tool.push_back(
        static_cast<std::uint8_t>(std::find(used.begin(), used.end(), t) - used.begin()));
  }
  return {{"rate", replay.haptic_rate},
          {"time", base64_of(replay.time)},
          {"device", vector3_base64(replay.device)},
          {"proxy", vector3_base64(replay.proxy)},
          {"orientation", base64_of(orientation)},
          {"engaged", base64_of(engaged)},
          {"force", vector3_base64(replay.force)},
          {"tool", base64_of(tool)}};
}

/// The tool as the page draws it: a sphere's radius, or a B-spline tool's
/// mesh in its own frame.
Result<json> tool_data(const ToolOptions& tool, double chord) {
  json out = {{"name", tool.name}, {"radius", tool.radius}};
  if (tool.type == ToolType::sphere) {
    out["type"] = "sphere";
  } else if (tool.type == ToolType::point) {
    out["type"] = "point";
  } else {
    out["type"] = "bspline";
    Result<io::Model> model = io::read_model(tool.file);
    if (!model.ok()) return model.status();
    const io::FaceRecord& face = model.value().faces.at(static_cast<std::size_t>(tool.face));
    io::TessellationOptions options;
    options.chord_tolerance_mm = chord;
    const io::TriangleMesh mesh = io::tessellate_face(face, options);
    std::vector<float> positions(mesh.positions.data(),
                                 mesh.positions.data() + mesh.positions.size());
    std::vector<float> normals(mesh.normals.data(), mesh.normals.data() + mesh.normals.size());
    std::vector<std::uint32_t> indices(mesh.triangles.data(),
                                       mesh.triangles.data() + mesh.triangles.size());
    out["mesh"] = {{"positions", base64_of(positions)},
                   {"normals", base64_of(normals)},
                   {"indices", base64_of(indices)}};
  }
  return out;
}

}  // namespace

Result<std::string> model_view_page(const io::Model& model, const std::string& source,
                                    const ViewPageOptions& options) {
  const std::vector<PageModel> models = {
      {.name = std::filesystem::path(source).stem().string(), .before = &model}};
  Result<json> data = page_data(models, {}, 0.0, options);
  if (!data.ok()) return data.status();
  data.value()["source"] = source;
  data.value()["run"] = nullptr;
  data.value()["tools"] = json::array();
  data.value()["script"] = nullptr;
  return page_html(data.value(), options.title);
}

Result<std::string> session_view_page(const SessionReplay& replay, const ViewPageOptions& options) {
  std::vector<PageModel> models;
  for (std::size_t m = 0; m < replay.before.size(); ++m) {
    PageModel model{.name = replay.scene.models[m].name,
                    .deformable = replay.scene.models[m].deformable,
                    .before = &replay.before[m],
                    .file_faces = &replay.file_faces[m]};
    if (model.deformable) {
      for (const ReplayFrame& frame : replay.frames) model.frames.push_back(&frame.models[m]);
    }
    models.push_back(std::move(model));
  }
  std::vector<json> heads;
  for (const ReplayFrame& frame : replay.frames) {
    heads.push_back({{"tick", frame.tick},
                     {"time", frame.time},
                     {"kind", frame.kind},
                     {"contacts", vector3_base64(frame.contacts)}});
  }
  Result<json> data = page_data(models, heads, replay.scene.tolerance, options);
  if (!data.ok()) return data.status();
  // Tools held once each (the page indexes them per tick); at most 255.
  const std::vector<int> used = tools_used(replay);
  if (used.size() > 255) {
    return Status::error(StatusCode::invalid_argument, "the run held more than 255 tools");
  }
  json tools = json::array();
  for (const int t : used) {
    Result<json> tool = tool_data(replay.tools[static_cast<std::size_t>(t)],
                                  data.value()["chord_mm"].get<double>());
    if (!tool.ok()) return tool.status();
    tools.push_back(tool.value());
  }
  data.value()["source"] = replay.scene_path.string();
  data.value()["run"] = run_data(replay, used);
  data.value()["tools"] = tools;
  data.value()["script"] = {{"scene", replay.scene_path.string()}};
  return page_html(data.value(), options.title);
}

}  // namespace argil::sculpt
