#include "argil/sculpt/scene/scene.hpp"

#include <cctype>
#include <cmath>
#include <fstream>
#include <set>
#include <sstream>

#include "argil/core/base/number_text.hpp"
#include "argil/core/deform/contact_response.hpp"
#include "argil/io/base/text_file.hpp"
#include "argil/sculpt/detail/json_reader.hpp"
#include "argil/sculpt/scene/detail/material_reader.hpp"

namespace argil::sculpt {
namespace {

using internal::Json;
using internal::JsonReader;

// Largest haptic rate accepted: beyond it a tick is shorter than any device period.
constexpr double kMaxHapticRate = 1e5;

class SceneReader {
 public:
  SceneReader(const std::string& source, std::filesystem::path base_dir)
      : r_(source), source_(source), base_dir_(std::move(base_dir)) {}

  Status error() const { return r_.error(); }

  bool scene(const Json& root, Scene& out) {
    if (!r_.only_known(root, "",
                       {"format", "version", "units", "tolerance", "haptic_rate", "coupling",
                        "models", "tools", "outputs", "script", "resolution"})) {
      return false;
    }
    if (!header(root, out.version)) return false;
    version_ = out.version;
    if (const Json* units = r_.member(root, "", "units", false)) {
      if (!this->units(*units)) return false;
    }
    const Json* tolerance = r_.member(root, "", "tolerance");
    if (tolerance == nullptr ||
        !r_.positive(*tolerance, "tolerance", out.tolerance, {.unit = "mm"}))
      return false;
    if (const Json* rate = r_.member(root, "", "haptic_rate", false)) {
      if (!r_.positive(*rate, "haptic_rate", out.haptic_rate, {.unit = "Hz"})) return false;
      if (out.haptic_rate > kMaxHapticRate) {
        return r_.fail("haptic_rate", "must be at most " + number_text(kMaxHapticRate) +
                                          " Hz, got " + number_text(out.haptic_rate) + " Hz");
      }
    }
    if (const Json* coupling = r_.member(root, "", "coupling", false)) {
      if (!this->coupling(*coupling, out.coupling)) return false;
    }
    if (const Json* resolution = r_.member(root, "", "resolution", false)) {
      double value = 0.0;
      if (!r_.positive(*resolution, "resolution", value, {.unit = "mm", .allow_zero = true}))
        return false;
      out.resolution = value;
    }
    if (!models(root, out.models) || !tools(root, out.tools)) return false;
    out.warnings = std::move(warnings_);
    if (const Json* outputs = r_.member(root, "", "outputs", false)) {
      if (!this->outputs(*outputs, out.outputs)) return false;
    }
    if (const Json* script = r_.member(root, "", "script", false)) {
      if (!file_path(*script, "script", out.script)) return false;
    }
    return true;
  }

 private:
  /// "models": a non-empty array with unique names and at least one deformable model.
  bool models(const Json& root, std::vector<ModelOptions>& out) {
    const Json* models = r_.member(root, "", "models");
    if (models == nullptr) return false;
    if (!models->is_array() || models->empty()) {
      return r_.fail("models", "expected a non-empty array of models");
    }
    std::set<std::string> names;
    bool any_deformable = false;
    for (std::size_t k = 0; k < models->size(); ++k) {
      ModelOptions model;
      const std::string path = JsonReader::index("models", k);
      if (!this->model((*models)[k], path, model)) return false;
      if (!names.insert(model.name).second) {
        return r_.fail(path + ".name", "\"" + model.name + "\" is used twice");
      }
      any_deformable = any_deformable || model.deformable;
      out.push_back(std::move(model));
    }
    return any_deformable || r_.fail("models", "no deformable model: nothing to sculpt");
  }

  /// "tools": a non-empty array with unique names.
  bool tools(const Json& root, std::vector<ToolOptions>& out) {
    const Json* tools = r_.member(root, "", "tools");
    if (tools == nullptr) return false;
    if (!tools->is_array() || tools->empty()) {
      return r_.fail("tools", "expected a non-empty array of tools");
    }
    std::set<std::string> names;
    for (std::size_t k = 0; k < tools->size(); ++k) {
      ToolOptions tool;
      const std::string path = JsonReader::index("tools", k);
      if (!this->tool((*tools)[k], path, tool)) return false;
      if (!names.insert(tool.name).second) {
        return r_.fail(path + ".name", "\"" + tool.name + "\" is used twice");
      }
      out.push_back(std::move(tool));
    }
    return true;
  }

  bool header(const Json& root, int& version) {
    long long read = 0;
    if (!r_.format_header(root, kSceneFormatName, kSceneOldestVersion, kSceneFormatVersion, read))
      return false;
    version = static_cast<int>(read);
    return true;
  }

  bool units(const Json& units) {
    if (!r_.only_known(units, "units", {"length", "time", "force"})) return false;
    const std::pair<const char*, const char*> expected[] = {
        {"length", "mm"}, {"time", "s"}, {"force", "N"}};
    for (const auto& [key, unit] : expected) {
      if (const Json* value = r_.member(units, "units", key, false)) {
        std::string text;
        const std::string path = JsonReader::join("units", key);
        if (!r_.string(*value, path, text)) return false;
        if (text != unit) {
          return r_.fail(path, std::string("must be \"") + unit +
                                   "\" (argil works in mm, s, N), got \"" + text + "\"");
        }
      }
    }
    return true;
  }

  /// "coupling": each field present against kCouplingRange, the range validate() uses.
  bool coupling(const Json& value, CouplingOptions& out) {
    if (!r_.only_known(value, "coupling", {"stiffness", "damping", "max_force"})) return false;
    const CouplingRange& range = kCouplingRange;
    const struct {
      const char* key;
      double* value;
      Interval range;
      const char* unit;
    } fields[] = {{"stiffness", &out.stiffness, range.stiffness, "N/mm"},
                  {"damping", &out.damping, range.damping, "N s/mm"},
                  {"max_force", &out.max_force, range.max_force, "N"}};
    for (const auto& f : fields) {
      const Json* v = r_.member(value, "coupling", f.key, false);
      if (v != nullptr &&
          !r_.within(*v, JsonReader::join("coupling", f.key), *f.value, f.range, f.unit)) {
        return false;
      }
    }
    return true;
  }

  bool name(const Json& object, const std::string& path, std::string& out) {
    const Json* value = r_.member(object, path, "name");
    if (value == nullptr || !r_.string(*value, path + ".name", out)) return false;
    if (out.empty()) return r_.fail(path + ".name", "must not be empty");
    for (const char c : out) {
      const bool allowed =
          std::isalnum(static_cast<unsigned char>(c)) != 0 || c == '_' || c == '-' || c == '.';
      if (!allowed || out == "." || out == "..") {
        return r_.fail(path + ".name", "\"" + out +
                                           "\" may hold only letters, digits, '_', '-' and '.' "
                                           "(it names output files)");
      }
    }
    return true;
  }

  bool file_path(const Json& value, const std::string& path, std::filesystem::path& out) {
    std::string text;
    if (!r_.string(value, path, text)) return false;
    if (text.empty()) return r_.fail(path, "must not be empty");
    const std::filesystem::path p(text);
    out = p.is_absolute() ? p : (base_dir_ / p).lexically_normal();
    return true;
  }

  bool model(const Json& value, const std::string& path, ModelOptions& out) {
    if (!r_.only_known(value, path,
                       {"name", "file", "faces", "kind", "material", "boundary", "friction"})) {
      return false;
    }
    if (!name(value, path, out.name)) return false;
    const Json* file = r_.member(value, path, "file");
    if (file == nullptr || !file_path(*file, path + ".file", out.file)) return false;
    if (const Json* faces = r_.member(value, path, "faces", false)) {
      const std::string faces_path = path + ".faces";
      if (faces->is_string() && faces->get<std::string>() == "all") {
        out.faces.clear();
      } else if (faces->is_array() && !faces->empty()) {
        std::set<long long> seen;
        for (std::size_t k = 0; k < faces->size(); ++k) {
          long long index = 0;
          const std::string face_path = JsonReader::index(faces_path, k);
          if (!r_.integer((*faces)[k], face_path, index)) return false;
          if (index < 0 || index > 1000000) {
            return r_.fail(face_path, "face index must be >= 0, got " + std::to_string(index));
          }
          if (!seen.insert(index).second) {
            return r_.fail(face_path, "face " + std::to_string(index) + " is listed twice");
          }
          out.faces.push_back(static_cast<int>(index));
        }
      } else {
        return r_.fail(faces_path, "expected \"all\" or a non-empty array of face indices");
      }
    }
    std::string kind = "deformable";
    if (const Json* k = r_.member(value, path, "kind", false)) {
      if (!r_.string(*k, path + ".kind", kind)) return false;
    }
    if (kind != "deformable" && kind != "rigid") {
      return r_.fail(path + ".kind", "expected \"deformable\" or \"rigid\", got \"" + kind + "\"");
    }
    out.deformable = kind == "deformable";
    const Json* material = r_.member(value, path, "material", false);
    const Json* boundary = r_.member(value, path, "boundary", false);
    if (const Json* friction = r_.member(value, path, "friction", false)) {
      if (out.deformable && version_ == 1) {
        return r_.fail(path + ".friction",
                       "a version-1 scene gives a deformable model's friction as "
                       "material.friction");
      }
      if (!this->friction(*friction, path + ".friction", out.friction)) return false;
    }
    if (!out.deformable && (material != nullptr || boundary != nullptr)) {
      return r_.fail(path + (material != nullptr ? ".material" : ".boundary"),
                     "a rigid model has no material or boundary conditions");
    }
    if (out.deformable && material == nullptr) {
      return r_.fail(path + ".material", "missing field (a deformable model needs a material)");
    }
    if (material != nullptr && !this->material(*material, path + ".material", out)) return false;
    if (boundary != nullptr && !this->boundary(*boundary, path + ".boundary", out.boundary)) {
      return false;
    }
    return true;
  }

  /// The tool-body pair's Coulomb coefficient, in [0, kMaxFriction].
  bool friction(const Json& value, const std::string& path, double& out) {
    if (!r_.positive(value, path, out, {.allow_zero = true})) return false;
    if (out <= kMaxFriction) return true;
    return r_.fail(path, out_of_interval_text(out, Interval{0.0, kMaxFriction}, ""));
  }

  /// The material of `model`; in version 1 also the tool's friction against it,
  /// and a warning that the old numbers were mapped.
  bool material(const Json& value, const std::string& path, ModelOptions& model) {
    if (version_ >= 2) return internal::read_material(r_, value, path, model.material);
    if (!internal::read_version1_material(r_, value, path, model.material)) return false;
    if (const Json* friction = r_.member(value, path, "friction", false)) {
      if (!this->friction(*friction, path + ".friction", model.friction)) return false;
    }
    const Material& m = model.material;
    warnings_.push_back(
        source_ + ": " + path + ": version-1 material mapped to physical units: density " +
        number_text(m.density) + " kg/m^3, thickness " + number_text(m.thickness) +
        " mm, youngs_modulus " + number_text(m.youngs_modulus) + " MPa, poisson_ratio " +
        number_text(m.poisson_ratio) + ", foundation_stiffness " +
        number_text(m.foundation_stiffness) +
        " N/mm^3; it feels different from version 1 (docs/formats.md, \"Version 1 scenes\"): "
        "write the scene in version 2 to choose the material");
    return true;
  }

  bool boundary(const Json& value, const std::string& path, BoundaryConditions& out) {
    if (!r_.only_known(value, path, {"fixed_edges", "fixed_corners"})) return false;
    if (const Json* edges = r_.member(value, path, "fixed_edges", false)) {
      const std::string edges_path = path + ".fixed_edges";
      if (!edges->is_array()) {
        return r_.fail(edges_path, "expected an array of \"u0\", \"u1\", \"v0\", \"v1\"");
      }
      for (std::size_t k = 0; k < edges->size(); ++k) {
        std::string edge;
        const std::string edge_path = JsonReader::index(edges_path, k);
        if (!r_.string((*edges)[k], edge_path, edge)) return false;
        if (edge == "u0")
          out.fixed_u0 = true;
        else if (edge == "u1")
          out.fixed_u1 = true;
        else if (edge == "v0")
          out.fixed_v0 = true;
        else if (edge == "v1")
          out.fixed_v1 = true;
        else
          return r_.fail(edge_path,
                         "expected \"u0\", \"u1\", \"v0\" or \"v1\", got \"" + edge + "\"");
      }
    }
    if (const Json* corners = r_.member(value, path, "fixed_corners", false)) {
      if (!r_.boolean(*corners, path + ".fixed_corners", out.fixed_corners)) return false;
    }
    return true;
  }

  bool length(const Json& object, const std::string& path, const char* key, double& out) {
    const Json* v = r_.member(object, path, key);
    return v != nullptr && r_.positive(*v, JsonReader::join(path, key), out, {.unit = "mm"});
  }

  bool tool(const Json& value, const std::string& path, ToolOptions& out) {
    if (!name(value, path, out.name)) return false;
    const Json* type = r_.member(value, path, "type");
    std::string text;
    if (type == nullptr || !r_.string(*type, path + ".type", text)) return false;
    const std::pair<const char*, ToolType> types[] = {
        {"sphere", ToolType::sphere}, {"bspline", ToolType::bspline}, {"point", ToolType::point}};
    bool found = false;
    for (const auto& [key, t] : types) {
      if (text == key) {
        out.type = t;
        found = true;
      }
    }
    if (!found) {
      return r_.fail(path + ".type",
                     "unknown tool type \"" + text + "\" (known: sphere, bspline, point)");
    }
    switch (out.type) {
      case ToolType::sphere:
        return r_.only_known(value, path, {"name", "type", "radius"}) &&
               length(value, path, "radius", out.radius);
      case ToolType::bspline: {
        if (!r_.only_known(value, path, {"name", "type", "file", "face"})) return false;
        const Json* file = r_.member(value, path, "file");
        if (file == nullptr || !file_path(*file, path + ".file", out.file)) return false;
        if (const Json* face = r_.member(value, path, "face", false)) {
          long long index = 0;
          if (!r_.integer(*face, path + ".face", index)) return false;
          if (index < 0 || index > 1000000) {
            return r_.fail(path + ".face", "face index must be >= 0, got " + std::to_string(index));
          }
          out.face = static_cast<int>(index);
        }
        return true;
      }
      case ToolType::point:
        return r_.only_known(value, path, {"name", "type"});
    }
    return false;
  }

  bool outputs(const Json& value, OutputOptions& out) {
    if (!r_.only_known(value, "outputs",
                       {"surfaces", "forces", "contacts", "timing", "pictures"})) {
      return false;
    }
    if (const Json* surfaces = r_.member(value, "outputs", "surfaces", false)) {
      if (!surfaces->is_array()) {
        return r_.fail("outputs.surfaces", "expected an array of \"step\", \"iges\", \"json\"");
      }
      out.step = out.iges = out.json = false;
      for (std::size_t k = 0; k < surfaces->size(); ++k) {
        std::string format;
        const std::string path = JsonReader::index("outputs.surfaces", k);
        if (!r_.string((*surfaces)[k], path, format)) return false;
        if (format == "step")
          out.step = true;
        else if (format == "iges")
          out.iges = true;
        else if (format == "json")
          out.json = true;
        else
          return r_.fail(path, "expected \"step\", \"iges\" or \"json\", got \"" + format + "\"");
      }
    }
    const std::pair<const char*, bool*> flags[] = {{"forces", &out.forces},
                                                   {"contacts", &out.contacts},
                                                   {"timing", &out.timing},
                                                   {"pictures", &out.pictures}};
    for (const auto& [key, flag] : flags) {
      if (const Json* v = r_.member(value, "outputs", key, false)) {
        if (!r_.boolean(*v, JsonReader::join("outputs", key), *flag)) return false;
      }
    }
    return true;
  }

  JsonReader r_;
  std::string source_;
  std::filesystem::path base_dir_;
  int version_ = kSceneFormatVersion;  // of the document being read
  std::vector<std::string> warnings_;
};

}  // namespace

const char* to_string(ToolType type) {
  switch (type) {
    case ToolType::sphere:
      return "sphere";
    case ToolType::bspline:
      return "bspline";
    case ToolType::point:
      return "point";
  }
  return "unknown";
}

int Scene::tool_index(std::string_view name) const {
  if (name.empty()) return tools.empty() ? -1 : 0;
  for (std::size_t k = 0; k < tools.size(); ++k) {
    if (tools[k].name == name) return static_cast<int>(k);
  }
  return -1;
}

Result<Scene> parse_scene(std::string_view text, const std::string& source_name,
                          const std::filesystem::path& base_dir) {
  Result<Json> root = internal::parse_json_text(text, source_name);
  if (!root.ok()) return root.status();
  SceneReader reader(source_name, base_dir);
  Scene scene;
  if (!reader.scene(root.value(), scene)) return reader.error();
  return scene;
}

Result<Scene> read_scene(const std::filesystem::path& path) {
  const Result<std::string> content = io::read_text_file(path);
  if (!content.ok()) return content.status();
  const std::filesystem::path folder = path.parent_path().empty() ? "." : path.parent_path();
  Result<Scene> scene = parse_scene(content.value(), path.string(), folder);
  if (scene.ok()) scene.value().source = path;
  return scene;
}

}  // namespace argil::sculpt
