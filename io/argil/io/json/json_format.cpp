// The one translation unit that uses nlohmann-json.
#include "argil/io/json/json_format.hpp"

#include "argil/io/base/text_file.hpp"

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "argil/io/base/atomic_write.hpp"
#include "argil/io/json/json_literals.hpp"
#include "argil/io/model/trim_curve.hpp"

namespace argil::io {
namespace {

using Json = nlohmann::ordered_json;

// Reading context: the source name and the error, kept so that helpers can
// return bool and the caller builds one message.
class Reader {
 public:
  explicit Reader(std::string source) : source_(std::move(source)) {}

  Status error() const { return error_; }
  bool fail(const std::string& path, const std::string& what) {
    if (error_.ok()) {
      error_ = Status::error(StatusCode::parse_error, source_ + ": " + path + ": " + what);
    }
    return false;
  }

  const Json* member(const Json& object, const std::string& path, const char* key,
                     bool required = true) {
    if (!object.is_object()) {
      fail(path, "expected an object");
      return nullptr;
    }
    const auto it = object.find(key);
    if (it == object.end()) {
      if (required) fail(path, std::string("missing field \"") + key + "\"");
      return nullptr;
    }
    return &*it;
  }

  bool number(const Json& value, const std::string& path, double& out) {
    if (value.is_string()) {
      const std::string& text = value.get_ref<const std::string&>();
      if (text.rfind(kNonFiniteMarker, 0) == 0) {
        return fail(path,
                    text.substr(kNonFiniteMarker.size()) + " is not allowed (finite numbers only)");
      }
    }
    if (value.is_null()) return fail(path, "null where a number belongs (a NaN or infinity?)");
    if (!value.is_number()) return fail(path, "expected a number");
    out = value.get<double>();
    if (!std::isfinite(out)) return fail(path, "number out of range (not finite)");
    return true;
  }

  bool integer(const Json& value, const std::string& path, int& out) {
    if (!value.is_number_integer()) return fail(path, "expected an integer");
    const auto wide = value.get<long long>();
    if (wide < -1000000000LL || wide > 1000000000LL) return fail(path, "integer out of range");
    out = static_cast<int>(wide);
    return true;
  }

  bool vector(const Json& value, const std::string& path, Eigen::VectorXd& out) {
    if (!value.is_array()) return fail(path, "expected an array of numbers");
    out.resize(static_cast<Eigen::Index>(value.size()));
    for (std::size_t k = 0; k < value.size(); ++k) {
      if (!number(value[k], path + "[" + std::to_string(k) + "]",
                  out[static_cast<Eigen::Index>(k)])) {
        return false;
      }
    }
    return true;
  }

  template <int Columns, class Matrix>
  bool points(const Json& value, const std::string& path, Matrix& out) {
    if (!value.is_array()) return fail(path, "expected an array of points");
    out.resize(static_cast<Eigen::Index>(value.size()), Columns);
    for (std::size_t k = 0; k < value.size(); ++k) {
      const std::string point_path = path + "[" + std::to_string(k) + "]";
      if (!value[k].is_array() || value[k].size() != Columns) {
        return fail(point_path, "expected " + std::to_string(Columns) + " coordinates");
      }
      for (int c = 0; c < Columns; ++c) {
        if (!number(value[k][static_cast<std::size_t>(c)],
                    point_path + "[" + std::to_string(c) + "]",
                    out(static_cast<Eigen::Index>(k), c))) {
          return false;
        }
      }
    }
    return true;
  }

  bool surface(const Json& value, const std::string& path, BSplineSurface& out) {
    const char* suffix[2] = {"_u", "_v"};
    std::array<int, 2> counts{0, 0};
    for (int d = 0; d < 2; ++d) {
      const std::string degree_key = std::string("degree") + suffix[d];
      const std::string knots_key = std::string("knots") + suffix[d];
      const std::string count_key = std::string("count") + suffix[d];
      const Json* degree = member(value, path, degree_key.c_str());
      const Json* knots = member(value, path, knots_key.c_str());
      const Json* count = member(value, path, count_key.c_str());
      if (degree == nullptr || knots == nullptr || count == nullptr) return false;
      if (!integer(*degree, path + "." + degree_key, out.degree[static_cast<std::size_t>(d)]) ||
          !vector(*knots, path + "." + knots_key, out.knots[static_cast<std::size_t>(d)]) ||
          !integer(*count, path + "." + count_key, counts[static_cast<std::size_t>(d)])) {
        return false;
      }
      const Eigen::Index implied = out.knots[static_cast<std::size_t>(d)].size() -
                                   out.degree[static_cast<std::size_t>(d)] - 1;
      if (counts[static_cast<std::size_t>(d)] != implied) {
        return fail(path + "." + count_key, std::to_string(counts[static_cast<std::size_t>(d)]) +
                                                " but " + knots_key + " and " + degree_key +
                                                " imply " + std::to_string(implied));
      }
    }
    const Json* net = member(value, path, "control_points");
    if (net == nullptr || !points<3>(*net, path + ".control_points", out.control_points)) {
      return false;
    }
    const long long expected = static_cast<long long>(counts[0]) * counts[1];
    if (out.control_points.rows() != expected) {
      return fail(path + ".control_points",
                  "has " + std::to_string(out.control_points.rows()) +
                      " points, count_u * count_v = " + std::to_string(expected));
    }
    out.weights.resize(0);
    if (const Json* weights = member(value, path, "weights", false)) {
      if (!vector(*weights, path + ".weights", out.weights)) return false;
      if (out.weights.size() != expected) {
        return fail(path + ".weights",
                    "has " + std::to_string(out.weights.size()) +
                        " weights, count_u * count_v = " + std::to_string(expected));
      }
    }
    return true;
  }

  bool curve(const Json& value, const std::string& path, TrimCurve& out) {
    const Json* degree = member(value, path, "degree");
    const Json* knots = member(value, path, "knots");
    const Json* poles = member(value, path, "poles");
    if (degree == nullptr || knots == nullptr || poles == nullptr) return false;
    if (!integer(*degree, path + ".degree", out.degree) ||
        !vector(*knots, path + ".knots", out.knots) ||
        !points<2>(*poles, path + ".poles", out.points)) {
      return false;
    }
    out.weights.resize(0);
    if (const Json* weights = member(value, path, "weights", false)) {
      if (!vector(*weights, path + ".weights", out.weights)) return false;
    }
    const Status check = validate_trim_curve(out);
    return check.ok() || fail(path, check.message);
  }

  // A list index; -1 in the file is kNoIndex where `optional`.
  bool index(const Json& value, const std::string& path, std::size_t& out, bool optional = false) {
    if (!value.is_number_integer()) return fail(path, "expected an index");
    const auto wide = value.get<long long>();
    if (optional && wide == -1) {
      out = kNoIndex;
      return true;
    }
    if (wide < 0 || wide > 1000000000LL) return fail(path, "index out of range");
    out = static_cast<std::size_t>(wide);
    return true;
  }

  bool indices(const Json& object, const std::string& path, const char* key,
               std::vector<std::size_t>& out) {
    const Json* list = member(object, path, key, false);
    if (list == nullptr) return true;
    const std::string list_path = path + "." + key;
    if (!list->is_array()) return fail(list_path, "expected an array of indices");
    out.resize(list->size());
    for (std::size_t k = 0; k < list->size(); ++k) {
      if (!index((*list)[k], list_path + "[" + std::to_string(k) + "]", out[k])) return false;
    }
    return true;
  }

  bool array(const Json& object, const std::string& path, const char* key, const Json*& out) {
    out = member(object, path, key, false);
    if (out == nullptr) return true;
    return out->is_array() || fail(path + "." + key, "expected an array");
  }

  bool product(const Json& value, const std::string& path, Product& out) {
    if (const Json* name = member(value, path, "name", false)) {
      if (!name->is_string()) return fail(path + ".name", "expected a string");
      out.name = name->get<std::string>();
    }
    if (const Json* instance = member(value, path, "instance", false)) {
      if (!instance->is_string()) return fail(path + ".instance", "expected a string");
      out.instance = instance->get<std::string>();
    }
    if (const Json* parent = member(value, path, "parent", false)) {
      if (!index(*parent, path + ".parent", out.parent, true)) return false;
    }
    if (const Json* placement = member(value, path, "placement", false)) {
      Eigen::VectorXd numbers;
      if (!vector(*placement, path + ".placement", numbers)) return false;
      if (numbers.size() != 12) {
        return fail(path + ".placement", "expected 12 numbers (3 rows of 4)");
      }
      for (int r = 0; r < 3; ++r) {
        for (int c = 0; c < 4; ++c) out.placement(r, c) = numbers[4 * r + c];
      }
    }
    return indices(value, path, "solids", out.solids) &&
           indices(value, path, "shells", out.shells) && indices(value, path, "faces", out.faces);
  }

  bool edge(const Json& value, const std::string& path, Edge& out) {
    if (const Json* start = member(value, path, "start", false)) {
      if (!index(*start, path + ".start", out.start, true)) return false;
    }
    if (const Json* end = member(value, path, "end", false)) {
      if (!index(*end, path + ".end", out.end, true)) return false;
    }
    if (const Json* degenerate = member(value, path, "degenerate", false)) {
      if (!degenerate->is_boolean()) return fail(path + ".degenerate", "expected true or false");
      out.degenerate = degenerate->get<bool>();
    }
    if (const Json* tolerance = member(value, path, "tolerance", false)) {
      if (!number(*tolerance, path + ".tolerance", out.tolerance)) return false;
    }
    const Json* uses = member(value, path, "uses");
    if (uses == nullptr) return false;
    if (!uses->is_array()) return fail(path + ".uses", "expected an array");
    out.uses.resize(uses->size());
    for (std::size_t u = 0; u < uses->size(); ++u) {
      const std::string use_path = path + ".uses[" + std::to_string(u) + "]";
      const Json* face_index = member((*uses)[u], use_path, "face");
      const Json* pcurve = member((*uses)[u], use_path, "pcurve");
      if (face_index == nullptr || pcurve == nullptr ||
          !index(*face_index, use_path + ".face", out.uses[u].face) ||
          !curve(*pcurve, use_path + ".pcurve", out.uses[u].pcurve)) {
        return false;
      }
      // Placement in the face's loops: optional (files written before it).
      EdgeUse& use = out.uses[u];
      if (const Json* loop = member((*uses)[u], use_path, "loop", false)) {
        if (!index(*loop, use_path + ".loop", use.loop, true)) return false;
      }
      if (const Json* curve_index = member((*uses)[u], use_path, "curve", false)) {
        if (!index(*curve_index, use_path + ".curve", use.curve, true)) return false;
      }
      if (const Json* along = member((*uses)[u], use_path, "along", false)) {
        if (!along->is_boolean()) return fail(use_path + ".along", "expected true or false");
        use.along = along->get<bool>();
      }
    }
    return true;
  }

  bool topology(const Json& value, Topology& out) {
    const std::string path = "topology";
    const Json *products = nullptr, *solids = nullptr, *shells = nullptr, *edges = nullptr,
               *vertices = nullptr;
    if (!array(value, path, "products", products) || !array(value, path, "solids", solids) ||
        !array(value, path, "shells", shells) || !array(value, path, "edges", edges) ||
        !array(value, path, "vertices", vertices)) {
      return false;
    }
    const auto item = [&](const char* list, std::size_t k) {
      return path + "." + list + "[" + std::to_string(k) + "]";
    };
    for (std::size_t k = 0; products != nullptr && k < products->size(); ++k) {
      if (!product((*products)[k], item("products", k), out.products.emplace_back())) return false;
    }
    for (std::size_t k = 0; solids != nullptr && k < solids->size(); ++k) {
      if (!indices((*solids)[k], item("solids", k), "shells", out.solids.emplace_back().shells)) {
        return false;
      }
    }
    for (std::size_t k = 0; shells != nullptr && k < shells->size(); ++k) {
      Shell& shell = out.shells.emplace_back();
      if (!indices((*shells)[k], item("shells", k), "faces", shell.faces)) return false;
      if (const Json* closed = member((*shells)[k], item("shells", k), "closed", false)) {
        if (!closed->is_boolean())
          return fail(item("shells", k) + ".closed", "expected true or false");
        shell.closed = closed->get<bool>();
      }
    }
    for (std::size_t k = 0; edges != nullptr && k < edges->size(); ++k) {
      if (!edge((*edges)[k], item("edges", k), out.edges.emplace_back())) return false;
    }
    for (std::size_t k = 0; vertices != nullptr && k < vertices->size(); ++k) {
      Vertex& vertex = out.vertices.emplace_back();
      const Json* point = member((*vertices)[k], item("vertices", k), "point");
      if (point == nullptr) return false;
      Eigen::VectorXd xyz;
      if (!vector(*point, item("vertices", k) + ".point", xyz)) return false;
      if (xyz.size() != 3) return fail(item("vertices", k) + ".point", "expected 3 coordinates");
      vertex.point = xyz;
      if (const Json* tolerance = member((*vertices)[k], item("vertices", k), "tolerance", false)) {
        if (!number(*tolerance, item("vertices", k) + ".tolerance", vertex.tolerance)) return false;
      }
    }
    return true;
  }

  bool face(const Json& value, const std::string& path, FaceRecord& out) {
    const Json* surface_json = member(value, path, "surface");
    if (surface_json == nullptr || !surface(*surface_json, path + ".surface", out.surface)) {
      return false;
    }
    const Status check = validate(out.surface);
    if (!check.ok()) return fail(path + ".surface", check.message);
    if (const Json* id = member(value, path, "source_id", false)) {
      if (!id->is_string()) return fail(path + ".source_id", "expected a string");
      out.source_id = id->get<std::string>();
    }
    if (const Json* name = member(value, path, "name", false)) {
      if (!name->is_string()) return fail(path + ".name", "expected a string");
      out.name = name->get<std::string>();
    }
    if (const Json* reversed = member(value, path, "reversed", false)) {
      if (!reversed->is_boolean()) return fail(path + ".reversed", "expected true or false");
      out.reversed = reversed->get<bool>();
    }
    if (const Json* trims = member(value, path, "trims", false)) {
      if (!trims->is_array()) return fail(path + ".trims", "expected an array of loops");
      for (std::size_t l = 0; l < trims->size(); ++l) {
        const std::string loop_path = path + ".trims[" + std::to_string(l) + "]";
        TrimLoop loop;
        const Json* outer = member((*trims)[l], loop_path, "outer");
        const Json* curves = member((*trims)[l], loop_path, "curves");
        if (outer == nullptr || curves == nullptr) return false;
        if (!outer->is_boolean()) return fail(loop_path + ".outer", "expected true or false");
        loop.outer = outer->get<bool>();
        if (!curves->is_array() || curves->empty()) {
          return fail(loop_path + ".curves", "expected a non-empty array of curves");
        }
        loop.curves.resize(curves->size());
        for (std::size_t c = 0; c < curves->size(); ++c) {
          if (!curve((*curves)[c], loop_path + ".curves[" + std::to_string(c) + "]",
                     loop.curves[c])) {
            return false;
          }
        }
        out.loops.push_back(std::move(loop));
      }
    }
    return true;
  }

  bool model(const Json& root, Model& out) {
    const Json* format = member(root, "(root)", "format");
    const Json* version = member(root, "(root)", "version");
    if (format == nullptr || version == nullptr) return false;
    if (!format->is_string() || format->get<std::string>() != kJsonFormatName) {
      return fail("format", "expected \"" + std::string(kJsonFormatName) + "\"");
    }
    int version_number = 0;
    if (!integer(*version, "version", version_number)) return false;
    if (version_number < 1 || version_number > kJsonFormatVersion) {
      return fail("version", "unknown schema version " + std::to_string(version_number) +
                                 " (this build reads versions 1 to " +
                                 std::to_string(kJsonFormatVersion) + ")");
    }
    if (const Json* units = member(root, "(root)", "units", false)) {
      if (const Json* length = member(*units, "units", "length", false)) {
        if (!length->is_string() || length->get<std::string>() != "mm") {
          return fail("units.length", "must be \"mm\": argil files always hold millimetres");
        }
      }
      if (const Json* source = member(*units, "units", "source", false)) {
        const Json* name = member(*source, "units.source", "name");
        const Json* to_mm = member(*source, "units.source", "to_mm");
        if (name == nullptr || to_mm == nullptr) return false;
        if (!name->is_string()) return fail("units.source.name", "expected a string");
        out.source_unit.name = name->get<std::string>();
        if (!number(*to_mm, "units.source.to_mm", out.source_unit.to_mm)) return false;
        if (!(out.source_unit.to_mm > 0.0)) return fail("units.source.to_mm", "must be positive");
      }
    }
    if (const Json* metadata = member(root, "(root)", "metadata", false)) {
      if (!metadata->is_object()) return fail("metadata", "expected an object");
      for (const auto& [key, value] : metadata->items()) {
        if (!value.is_string()) return fail("metadata." + key, "expected a string");
        out.metadata[key] = value.get<std::string>();
      }
    }
    const Json* faces = member(root, "(root)", "faces");
    if (faces == nullptr) return false;
    if (!faces->is_array()) return fail("faces", "expected an array");
    out.faces.resize(faces->size());
    for (std::size_t f = 0; f < faces->size(); ++f) {
      if (!face((*faces)[f], "faces[" + std::to_string(f) + "]", out.faces[f])) return false;
    }
    if (version_number < 2) return true;  // version 1: loose faces, no warnings
    if (const Json* warnings = member(root, "(root)", "warnings", false)) {
      if (!warnings->is_array()) return fail("warnings", "expected an array of strings");
      for (std::size_t k = 0; k < warnings->size(); ++k) {
        if (!(*warnings)[k].is_string()) {
          return fail("warnings[" + std::to_string(k) + "]", "expected a string");
        }
        out.warnings.push_back((*warnings)[k].get<std::string>());
      }
    }
    if (const Json* t = member(root, "(root)", "topology", false)) {
      if (!topology(*t, out.topology)) return false;
      const Status valid = validate_topology(out);
      if (!valid.ok()) return fail("topology", valid.message);
    }
    return true;
  }

 private:
  std::string source_;
  Status error_;
};

Json vector_json(const Eigen::VectorXd& values) {
  Json array = Json::array();
  for (Eigen::Index k = 0; k < values.size(); ++k) array.push_back(values[k]);
  return array;
}

template <class Matrix>
Json points_json(const Matrix& points) {
  Json array = Json::array();
  for (Eigen::Index r = 0; r < points.rows(); ++r) {
    Json point = Json::array();
    for (Eigen::Index c = 0; c < points.cols(); ++c) point.push_back(points(r, c));
    array.push_back(std::move(point));
  }
  return array;
}

template <class Curve>
Json curve_json(const Curve& curve) {
  Json c;
  c["degree"] = curve.degree;
  c["knots"] = vector_json(curve.knots);
  c["poles"] = points_json(curve.points);
  if (curve.is_rational()) c["weights"] = vector_json(curve.weights);
  return c;
}

// kNoIndex as -1.
Json index_json(std::size_t index) { return index == kNoIndex ? Json(-1) : Json(index); }

Json topology_json(const Topology& t) {
  Json out;
  Json products = Json::array();
  for (const Product& p : t.products) {
    Json placement = Json::array();
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < 4; ++c) placement.push_back(p.placement(r, c));
    }
    products.push_back({{"name", p.name},
                        {"instance", p.instance},
                        {"parent", index_json(p.parent)},
                        {"placement", std::move(placement)},
                        {"solids", p.solids},
                        {"shells", p.shells},
                        {"faces", p.faces}});
  }
  out["products"] = std::move(products);
  Json solids = Json::array();
  for (const Solid& s : t.solids) solids.push_back({{"shells", s.shells}});
  out["solids"] = std::move(solids);
  Json shells = Json::array();
  for (const Shell& s : t.shells) shells.push_back({{"faces", s.faces}, {"closed", s.closed}});
  out["shells"] = std::move(shells);
  Json edges = Json::array();
  for (const Edge& e : t.edges) {
    Json uses = Json::array();
    for (const EdgeUse& use : e.uses) {
      uses.push_back({{"face", use.face},
                      {"loop", index_json(use.loop)},
                      {"curve", index_json(use.curve)},
                      {"along", use.along},
                      {"pcurve", curve_json(use.pcurve)}});
    }
    edges.push_back({{"start", index_json(e.start)},
                     {"end", index_json(e.end)},
                     {"degenerate", e.degenerate},
                     {"tolerance", e.tolerance},
                     {"uses", std::move(uses)}});
  }
  out["edges"] = std::move(edges);
  Json vertices = Json::array();
  for (const Vertex& v : t.vertices) {
    vertices.push_back(
        {{"point", {v.point.x(), v.point.y(), v.point.z()}}, {"tolerance", v.tolerance}});
  }
  out["vertices"] = std::move(vertices);
  return out;
}

}  // namespace

Result<Model> parse_json(std::string_view text, const std::string& source_name) {
  if (text.find_first_not_of(" \t\r\n") == std::string_view::npos) {
    return Status::error(StatusCode::parse_error, source_name + ": empty file");
  }
  Json root;
  try {
    root = Json::parse(quote_non_finite_literals(text));
  } catch (const std::exception& e) {
    return Status::error(StatusCode::parse_error, source_name + ": not valid JSON: " + e.what());
  }
  Reader reader(source_name);
  Model model;
  if (!reader.model(root, model)) return reader.error();
  return model;
}

Result<Model> read_json(const std::filesystem::path& path) {
  const Result<std::string> content = read_text_file(path);
  if (!content.ok()) return content.status();
  return parse_json(content.value(), path.string());
}

Result<std::string> to_json(const Model& model) {
  if (!(model.source_unit.to_mm > 0.0) || !std::isfinite(model.source_unit.to_mm)) {
    return Status::error(StatusCode::invalid_argument,
                         "source unit factor to_mm must be positive and finite");
  }
  Json root;
  root["format"] = kJsonFormatName;
  root["version"] = kJsonFormatVersion;
  root["units"] = {
      {"length", "mm"},
      {"source", {{"name", model.source_unit.name}, {"to_mm", model.source_unit.to_mm}}}};
  Json metadata = Json::object();
  for (const auto& [key, value] : model.metadata) metadata[key] = value;
  root["metadata"] = std::move(metadata);
  Json faces = Json::array();
  for (std::size_t f = 0; f < model.faces.size(); ++f) {
    const FaceRecord& face = model.faces[f];
    const Status check = validate_face(face, f);
    if (!check.ok()) return check;
    const BSplineSurface& s = face.surface;
    Json surface;
    surface["degree_u"] = s.degree[0];
    surface["degree_v"] = s.degree[1];
    surface["count_u"] = s.count(Direction::u);
    surface["count_v"] = s.count(Direction::v);
    surface["knots_u"] = vector_json(s.knots[0]);
    surface["knots_v"] = vector_json(s.knots[1]);
    surface["control_points"] = points_json(s.control_points);
    if (s.is_rational()) surface["weights"] = vector_json(s.weights);
    Json trims = Json::array();
    for (const TrimLoop& loop : face.loops) {
      Json curves = Json::array();
      for (const TrimCurve& curve : loop.curves) curves.push_back(curve_json(curve));
      trims.push_back({{"outer", loop.outer}, {"curves", std::move(curves)}});
    }
    Json entry;
    entry["source_id"] = face.source_id;
    entry["name"] = face.name;
    entry["reversed"] = face.reversed;
    entry["surface"] = std::move(surface);
    entry["trims"] = std::move(trims);
    faces.push_back(std::move(entry));
  }
  root["faces"] = std::move(faces);
  root["warnings"] = model.warnings;
  if (!model.topology.empty()) {
    const Status valid = validate_topology(model);
    if (!valid.ok()) return Status::error(valid.code, "topology: " + valid.message);
    root["topology"] = topology_json(model.topology);
  }
  try {
    // Invalid UTF-8 in names would throw; replace it rather than fail the export.
    return root.dump(1, ' ', false, Json::error_handler_t::replace) + "\n";
  } catch (const std::exception& e) {
    return Status::error(StatusCode::invalid_argument, std::string("JSON export: ") + e.what());
  }
}

Status write_json(const Model& model, const std::filesystem::path& path) {
  Result<std::string> text = to_json(model);
  if (!text.ok()) {
    return Status::error(text.status().code, path.string() + ": " + text.status().message);
  }
  return write_bytes_atomically(path, text.value());
}

}  // namespace argil::io
