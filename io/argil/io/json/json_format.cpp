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
    if (version_number != kJsonFormatVersion) {
      return fail("version", "unknown schema version " + std::to_string(version_number) +
                                 " (this build reads version " +
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
      for (const TrimCurve& curve : loop.curves) {
        Json c;
        c["degree"] = curve.degree;
        c["knots"] = vector_json(curve.knots);
        c["poles"] = points_json(curve.points);
        if (curve.is_rational()) c["weights"] = vector_json(curve.weights);
        curves.push_back(std::move(c));
      }
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
