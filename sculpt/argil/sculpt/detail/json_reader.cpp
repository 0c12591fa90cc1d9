#include "argil/sculpt/detail/json_reader.hpp"

#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "argil/core/base/number_text.hpp"
#include "argil/io/json/json_literals.hpp"

namespace argil::sculpt::internal {

Result<Json> parse_json_text(std::string_view text, const std::string& source) {
  if (text.find_first_not_of(" \t\r\n") == std::string_view::npos) {
    return Status::error(StatusCode::parse_error, source + ": empty file");
  }
  Json root = Json::parse(io::quote_non_finite_literals(text), nullptr, /*allow_exceptions=*/false);
  if (root.is_discarded()) {
    // Parse again with exceptions for the message (line/column of the defect).
    try {
      root = Json::parse(io::quote_non_finite_literals(text));
    } catch (const std::exception& e) {
      return Status::error(StatusCode::parse_error, source + ": not valid JSON: " + e.what());
    }
  }
  return root;
}

std::string JsonReader::shown(const Json& value) {
  std::string text = value.dump(-1, ' ', false, Json::error_handler_t::replace);
  if (value.is_string()) {
    if (auto literal = io::non_finite_marker_literal(value.get_ref<const std::string&>()))
      return *literal;
  }
  if (text.size() > 40) text = text.substr(0, 37) + "...";
  return text;
}

bool JsonReader::fail(const std::string& path, const std::string& what) {
  if (error_.ok()) {
    error_ = Status::error(StatusCode::parse_error,
                           source_ + ": " + (path.empty() ? "(root)" : path) + ": " + what);
  }
  return false;
}

const Json* JsonReader::member(const Json& object, const std::string& path, const char* key,
                               bool required) {
  if (!object.is_object()) {
    fail(path, "expected an object");
    return nullptr;
  }
  const auto it = object.find(key);
  if (it == object.end()) {
    if (required) fail(join(path, key), "missing field");
    return nullptr;
  }
  return &*it;
}

bool JsonReader::only_known(const Json& object, const std::string& path,
                            const std::vector<std::string_view>& known) {
  if (!object.is_object()) return fail(path, "expected an object");
  for (const auto& item : object.items()) {
    bool found = false;
    for (const std::string_view k : known) found = found || item.key() == k;
    if (!found) {
      std::string list;
      for (const std::string_view k : known) list += (list.empty() ? "" : ", ") + std::string(k);
      return fail(join(path, item.key()), "unknown field (known: " + list + ")");
    }
  }
  return true;
}

bool JsonReader::number(const Json& value, const std::string& path, double& out) {
  if (value.is_string()) {
    if (auto literal = io::non_finite_marker_literal(value.get_ref<const std::string&>())) {
      return fail(path, *literal + " is not allowed (finite numbers only)");
    }
  }
  if (value.is_null()) return fail(path, "null where a number belongs (a NaN or infinity?)");
  if (!value.is_number()) return fail(path, "expected a number, got " + shown(value));
  out = value.get<double>();
  if (!std::isfinite(out)) return fail(path, "number out of range (not finite)");
  return true;
}

bool JsonReader::positive(const Json& value, const std::string& path, double& out,
                          const Quantity& q) {
  if (!number(value, path, out)) return false;
  if (q.allow_zero ? out < 0.0 : out <= 0.0) {
    const std::string unit = q.unit.empty() ? "" : " " + std::string(q.unit);
    return fail(path, std::string("must be ") + (q.allow_zero ? ">= 0" : "> 0") + unit + ", got " +
                          number_text(out) + unit);
  }
  return true;
}

bool JsonReader::within(const Json& value, const std::string& path, double& out,
                        const Interval& range, std::string_view unit) {
  if (!number(value, path, out)) return false;
  return range.contains(out) || fail(path, out_of_interval_text(out, range, unit));
}

bool JsonReader::integer(const Json& value, const std::string& path, long long& out) {
  if (!value.is_number_integer()) return fail(path, "expected an integer, got " + shown(value));
  if (value.is_number_unsigned() && value.get<unsigned long long>() > 1000000000000ULL) {
    return fail(path, "integer out of range");
  }
  out = value.get<long long>();
  if (out < -1000000000000LL || out > 1000000000000LL) return fail(path, "integer out of range");
  return true;
}

bool JsonReader::boolean(const Json& value, const std::string& path, bool& out) {
  if (!value.is_boolean()) return fail(path, "expected true or false, got " + shown(value));
  out = value.get<bool>();
  return true;
}

bool JsonReader::string(const Json& value, const std::string& path, std::string& out) {
  if (!value.is_string()) return fail(path, "expected a string, got " + shown(value));
  out = value.get<std::string>();
  return true;
}

bool JsonReader::numbers(const Json& value, const std::string& path, std::size_t count,
                         double* out) {
  if (!value.is_array() || value.size() != count) {
    return fail(path,
                "expected an array of " + std::to_string(count) + " numbers, got " + shown(value));
  }
  for (std::size_t k = 0; k < count; ++k) {
    if (!number(value[k], index(path, k), out[k])) return false;
  }
  return true;
}

std::string JsonReader::join(const std::string& path, std::string_view key) {
  return path.empty() ? std::string(key) : path + "." + std::string(key);
}

std::string JsonReader::index(const std::string& path, std::size_t k) {
  return path + "[" + std::to_string(k) + "]";
}

bool JsonReader::format_header(const Json& root, std::string_view format, long long version) {
  long long read = 0;
  return format_header(root, format, version, version, read);
}

bool JsonReader::format_header(const Json& root, std::string_view format, long long oldest,
                               long long newest, long long& read) {
  const Json* format_value = member(root, "", "format");
  const Json* version_value = member(root, "", "version");
  if (format_value == nullptr || version_value == nullptr) return false;
  std::string name;
  if (!string(*format_value, "format", name)) return false;
  if (name != format) {
    return fail("format", "expected \"" + std::string(format) + "\", got \"" + name + "\"");
  }
  if (!integer(*version_value, "version", read)) return false;
  if (read < oldest || read > newest) {
    const std::string readable =
        oldest == newest ? "version " + std::to_string(newest)
                         : "versions " + std::to_string(oldest) + " to " + std::to_string(newest);
    return fail("version", "unknown schema version " + std::to_string(read) +
                               " (this build reads " + readable + ")");
  }
  return true;
}

}  // namespace argil::sculpt::internal
