// Malformed JSON documents give errors naming the file and the field path, read
// from files (the path starts the message) and parsed from text (the source name
// does).
#include <catch2/catch.hpp>
#include <string>

#include "argil/io.hpp"
#include "bad_input.hpp"
#include "test_files.hpp"

namespace argil::io {
namespace {

// The bundled panel: a valid document that the bad ones are edited from.
const std::string& panel_text() {
  static const std::string text =
      test::read_bytes(test::source_file("examples/surfaces/panel.json"));
  return text;
}

}  // namespace

TEST_CASE("JSON: non-finite numbers are rejected with their field path", "[io][bad][json]") {
  test::TempDir dir;
  for (const char* bad : {"NaN", "Infinity", "-Infinity", "null", "1e999"}) {
    const std::string text = test::replace_array_number(panel_text(), "knots_u", 7, bad);
    test::write_bytes(dir / "bad.json", text);
    INFO(bad);
    CHECK_THAT(test::read_error(dir / "bad.json").message,
               Catch::Contains("faces[0].surface.knots_u[7]"));
  }
}

TEST_CASE("JSON: invalid surfaces are rejected naming file, face and defect", "[io][bad][json]") {
  test::TempDir dir;
  const std::filesystem::path path = dir / "bad.json";
  SECTION("decreasing knots") {
    // Interior knots 1, 2, 3, 4 of knots_u become 1, 3, 2, 4.
    std::string text = test::replace_array_number(panel_text(), "knots_u", 5, "3.0");
    text = test::replace_array_number(text, "knots_u", 6, "2.0");
    test::write_bytes(path, text);
    const Status error = test::read_error(path);
    CHECK_THAT(error.message, Catch::Contains("faces[0]"));
    CHECK_THAT(error.message, Catch::Contains("knots_u[6]"));
  }
  SECTION("zero weight") {
    std::string text = test::replace_first(
        panel_text(), "\"control_points\"",
        "\"weights\": [" + std::string(47 * 5, ' ') + "],\n  \"control_points\"");
    std::string weights = "0.0";
    for (int k = 1; k < 48; ++k) weights += ", 1.0";
    text = test::replace_first(text, "[" + std::string(47 * 5, ' ') + "]", "[" + weights + "]");
    test::write_bytes(path, text);
    const Status error = test::read_error(path);
    CHECK_THAT(error.message, Catch::Contains("faces[0]"));
    CHECK_THAT(error.message, Catch::Contains("weight"));
  }
  SECTION("count that disagrees with the knots") {
    test::write_bytes(path, test::replace_first(panel_text(), "\"count_u\": 8", "\"count_u\": 7"));
    CHECK_THAT(test::read_error(path).message, Catch::Contains("faces[0].surface.count_u"));
  }
  SECTION("too few control points") {
    std::string text = panel_text();
    const auto net = text.find("\"control_points\"");
    const auto first_point = text.find('[', text.find('[', net) + 1);
    const auto end_point = text.find(']', first_point);
    text.erase(first_point, end_point - first_point + 2);  // the point and its comma
    test::write_bytes(path, text);
    CHECK_THAT(test::read_error(path).message, Catch::Contains("faces[0].surface.control_points"));
  }
}

TEST_CASE("JSON: an unknown schema version or format is rejected", "[io][bad][json]") {
  test::TempDir dir;
  test::write_bytes(dir / "v3.json",
                    test::replace_first(panel_text(), "\"version\": 1", "\"version\": 3"));
  CHECK_THAT(test::read_error(dir / "v3.json").message, Catch::Contains("version 3"));
  test::write_bytes(dir / "other.json",
                    test::replace_first(panel_text(), "argil.surfaces", "someone.elses"));
  CHECK_THAT(test::read_error(dir / "other.json").message, Catch::Contains("format"));
}

TEST_CASE("parse_json names the source and the field of a missing or mistyped value",
          "[io][bad][json]") {
  const auto error_of = [](const std::string& text) {
    const Result<Model> result = parse_json(text, "edited-panel");
    REQUIRE_FALSE(result.ok());
    INFO(result.status().message);
    CHECK(result.status().code == StatusCode::parse_error);
    CHECK_THAT(result.status().message, Catch::StartsWith("edited-panel"));
    return result.status().message;
  };
  SECTION("a required field is missing") {
    const std::string text =
        test::replace_first(panel_text(), "\"count_u\": 8", "\"not_count_u\": 8");
    const std::string message = error_of(text);
    CHECK_THAT(message, Catch::Contains("faces[0].surface"));
    CHECK_THAT(message, Catch::Contains("count_u"));
  }
  SECTION("an array where a number belongs") {
    const std::string text = test::replace_array_number(panel_text(), "knots_v", 0, "[0]");
    CHECK_THAT(error_of(text), Catch::Contains("faces[0].surface.knots_v[0]"));
  }
  SECTION("a string where a number belongs") {
    const std::string text = test::replace_array_number(panel_text(), "knots_u", 2, "\"0.5\"");
    CHECK_THAT(error_of(text), Catch::Contains("faces[0].surface.knots_u[2]"));
  }
  SECTION("faces is not an array") {
    CHECK_THAT(error_of(R"({"format": "argil.surfaces", "version": 1, "faces": 3})"),
               Catch::Contains("faces"));
  }
  SECTION("a negative unit scale") {
    CHECK_THAT(error_of(R"({"format": "argil.surfaces", "version": 1,
                            "units": {"source": {"name": "inch", "to_mm": -25.4}},
                            "faces": []})"),
               Catch::Contains("units.source.to_mm"));
  }
  SECTION("text that is not JSON at all") {
    CHECK_THAT(error_of("{\"format\": \"argil.surfaces\", "), Catch::Contains("not valid JSON"));
  }
}

}  // namespace argil::io
