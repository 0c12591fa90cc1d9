#pragma once
// Private to argil::sculpt (included by .cpp files only): reading nlohmann-json
// values with errors that name the source and the field path, e.g.
// "scene.json: models[1].material.youngs_modulus: must be in [0, 1e+07] MPa, got -3 MPa".

#include <nlohmann/json.hpp>
#include <string>
#include <string_view>
#include <vector>

#include "argil/core/base/number_text.hpp"
#include "argil/core/base/status.hpp"

namespace argil::sculpt::internal {

using Json = nlohmann::ordered_json;

/// Parses `text` after quoting non-finite literals (so NaN is reported with its
/// field path). Errors start with `source`.
Result<Json> parse_json_text(std::string_view text, const std::string& source);

/// Reads fields of a parsed document; the first error wins and is kept.
class JsonReader {
 public:
  explicit JsonReader(std::string source) : source_(std::move(source)) {}

  Status error() const { return error_; }
  bool failed() const { return !error_.ok(); }
  /// Records "source: path: what" (unless an error is already recorded); false.
  bool fail(const std::string& path, const std::string& what);

  /// The member `key` of `object` at `path`; null (and an error when required)
  /// when absent or when `object` is not an object.
  const Json* member(const Json& object, const std::string& path, const char* key,
                     bool required = true);
  /// Fails on members of `object` outside `known` (catches misspelt keys).
  bool only_known(const Json& object, const std::string& path,
                  const std::vector<std::string_view>& known);

  bool number(const Json& value, const std::string& path, double& out);
  /// A number > 0 (or >= 0 when `allow_zero`); a rejection states the bound
  /// and the value in `unit`, the unit the file gives the field in.
  struct Quantity {
    std::string_view unit{};  // "mm", "N/mm"; empty for pure numbers
    bool allow_zero = false;
  };
  bool positive(const Json& value, const std::string& path, double& out, const Quantity& q);
  /// A number inside `range`; a rejection states the range and the value in
  /// `unit` (empty for pure numbers).
  bool within(const Json& value, const std::string& path, double& out, const Interval& range,
              std::string_view unit);
  bool integer(const Json& value, const std::string& path, long long& out);
  bool boolean(const Json& value, const std::string& path, bool& out);
  bool string(const Json& value, const std::string& path, std::string& out);
  /// The document header: "format" equal to `format` and "version" equal to
  /// `version` (an unknown version is named with the one this build reads).
  bool format_header(const Json& root, std::string_view format, long long version);
  /// The same for a format whose readers take versions `oldest` to `newest`;
  /// `read` gets the document's version.
  bool format_header(const Json& root, std::string_view format, long long oldest, long long newest,
                     long long& read);
  /// An array of exactly `count` finite numbers.
  bool numbers(const Json& value, const std::string& path, std::size_t count, double* out);

  /// A value for an error message: its JSON text, cut short when long.
  static std::string shown(const Json& value);
  /// Path of member `key` below `path` ("models[1]" + "material" -> "models[1].material").
  static std::string join(const std::string& path, std::string_view key);
  static std::string index(const std::string& path, std::size_t k);

 private:
  std::string source_;
  Status error_;
};

}  // namespace argil::sculpt::internal
