// Bad input never crashes: each case gives an error naming the file and, where
// known, the entity or field. Bad files are built here from good ones.
#include <catch2/catch.hpp>
#include <random>
#include <regex>

#include "argil/io.hpp"
#include "test_files.hpp"

namespace argil::io {
namespace {

// The error of reading `path`, which must fail.
Status read_error(const std::filesystem::path& path) {
  const Result<Model> result = read_model(path);
  REQUIRE_FALSE(result.ok());
  INFO(result.status().message);
  CHECK_THAT(result.status().message, Catch::Contains(path.string()));
  return result.status();
}

std::string replace_first(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  REQUIRE(at != std::string::npos);
  return text.replace(at, from.size(), to);
}

// Replaces the `index`-th number of the array that follows "key" in a JSON text.
std::string replace_array_number(std::string text, const std::string& key, int index,
                                 const std::string& replacement) {
  std::size_t at = text.find('[', text.find("\"" + key + "\""));
  REQUIRE(at != std::string::npos);
  for (int k = 0; k <= index; ++k) {
    at = text.find_first_of("-0123456789", at + 1);
    REQUIRE(at != std::string::npos);
    if (k == index) break;
    at = text.find(',', at);
  }
  const std::size_t end = text.find_first_of(",]", at);
  return text.replace(at, end - at, replacement);
}

std::string garbage(std::size_t size, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::string bytes(size, '\0');
  for (char& c : bytes) c = static_cast<char>(rng() & 0xff);
  return bytes;
}

const std::string& panel_text() {
  static const std::string text =
      test::read_bytes(test::source_file("examples/surfaces/panel.json"));
  return text;
}

}  // namespace

TEST_CASE("a missing file is an error naming it, in every format", "[io][bad]") {
  test::TempDir dir;
  for (const char* name : {"missing.step", "missing.iges", "missing.json"}) {
    CHECK(read_error(dir / name).code == StatusCode::io_error);
  }
}

TEST_CASE("an empty file is an error naming it, in every format", "[io][bad]") {
  test::TempDir dir;
  for (const char* name : {"empty.step", "empty.igs", "empty.json"}) {
    test::write_bytes(dir / name, "");
    CHECK_THAT(read_error(dir / name).message, Catch::Contains("empty"));
  }
}

TEST_CASE("garbage bytes are an error, not a crash, in every format", "[io][bad]") {
  test::TempDir dir;
  std::uint64_t seed = 1;
  for (const char* name : {"garbage.stp", "garbage.iges", "garbage.json"}) {
    for (std::size_t size : {1u, 100u, 100000u}) {
      test::write_bytes(dir / name, garbage(size, seed++));
      CHECK(read_error(dir / name).code == StatusCode::parse_error);
    }
  }
}

TEST_CASE("truncated STEP and IGES files are errors at any cut", "[io][bad]") {
  test::TempDir dir;
  for (const char* source : {"screw.step", "bearing.iges"}) {
    const std::string whole = test::read_bytes(test::shared_data(source));
    REQUIRE(whole.size() > 1000);
    for (double fraction : {0.02, 0.5, 0.97}) {
      const auto cut = static_cast<std::size_t>(fraction * static_cast<double>(whole.size()));
      const std::filesystem::path path = dir / (std::string("cut-") + source);
      test::write_bytes(path, whole.substr(0, cut));
      INFO(source << " cut at " << cut << " of " << whole.size() << " bytes");
      CHECK_THAT(read_error(path).message, Catch::Contains("truncated"));
    }
  }
}

TEST_CASE("STEP and IGES files corrupted in the middle are errors, not crashes", "[io][bad]") {
  test::TempDir dir;
  for (const char* source : {"screw.step", "bearing.iges"}) {
    const std::string whole = test::read_bytes(test::shared_data(source));
    for (std::uint64_t seed = 0; seed < 4; ++seed) {
      // Printable junk over five runs of up to 200 bytes, away from both ends so
      // the header and terminator checks pass and OCCT's parser meets the damage.
      std::mt19937_64 rng(seed);
      std::string damaged = whole;
      for (int run = 0; run < 5; ++run) {
        const std::size_t start = whole.size() / 10 + rng() % (whole.size() * 8 / 10);
        const std::size_t length = 1 + rng() % 200;
        for (std::size_t i = start; i < start + length; ++i) {
          damaged[i] = static_cast<char>(32 + rng() % 95);
        }
      }
      const std::filesystem::path path = dir / (std::string("damaged-") + source);
      test::write_bytes(path, damaged);
      INFO(source << " seed " << seed);
      CHECK_FALSE(read_error(path).ok());
    }
  }
}

TEST_CASE("a STEP file without faces is an error", "[io][bad]") {
  test::TempDir dir;
  const std::string screw = test::read_bytes(test::shared_data("screw.step"));
  const std::string header = screw.substr(0, screw.find("DATA;"));
  test::write_bytes(dir / "point.step", header +
                                            "DATA;\n#1 = CARTESIAN_POINT('',(0.,0.,0.));\n"
                                            "ENDSEC;\nEND-ISO-10303-21;\n");
  CHECK_THAT(read_error(dir / "point.step").message, Catch::Contains("no faces"));
}

TEST_CASE("unsupported entities are errors naming the entity", "[io][bad]") {
  test::TempDir dir;
  SECTION("STEP: an entity type no schema knows") {
    const std::string screw = test::read_bytes(test::shared_data("screw.step"));
    test::write_bytes(dir / "unknown.step",
                      replace_first(screw, "ADVANCED_FACE(", "ARGIL_UNKNOWN_FACE("));
    const Status error = read_error(dir / "unknown.step");
    CHECK(error.code == StatusCode::unsupported);
    CHECK_THAT(error.message, Catch::Contains("ARGIL_UNKNOWN_FACE"));
  }
  SECTION("IGES: an entity type number IGES does not define") {
    const std::string bearing = test::read_bytes(test::shared_data("bearing.iges"));
    // Directory entry D5 (the first surface, type 128) in both of its records.
    std::string edited = replace_first(bearing, "     128      19", "     999      19");
    edited = replace_first(edited, "     128       0       0      15",
                           "     999       0       0      15");
    test::write_bytes(dir / "unknown.iges", edited);
    const Status error = read_error(dir / "unknown.iges");
    CHECK(error.code == StatusCode::unsupported);
    CHECK_THAT(error.message, Catch::Contains("999"));
  }
}

TEST_CASE("JSON: non-finite numbers are rejected with their field path", "[io][bad][json]") {
  test::TempDir dir;
  for (const char* bad : {"NaN", "Infinity", "-Infinity", "null", "1e999"}) {
    const std::string text = replace_array_number(panel_text(), "knots_u", 7, bad);
    test::write_bytes(dir / "bad.json", text);
    INFO(bad);
    CHECK_THAT(read_error(dir / "bad.json").message,
               Catch::Contains("faces[0].surface.knots_u[7]"));
  }
}

TEST_CASE("JSON: invalid surfaces are rejected naming file, face and defect", "[io][bad][json]") {
  test::TempDir dir;
  const std::filesystem::path path = dir / "bad.json";
  SECTION("decreasing knots") {
    // Interior knots 1, 2, 3, 4 of knots_u become 1, 3, 2, 4.
    std::string text = replace_array_number(panel_text(), "knots_u", 5, "3.0");
    text = replace_array_number(text, "knots_u", 6, "2.0");
    test::write_bytes(path, text);
    const Status error = read_error(path);
    CHECK_THAT(error.message, Catch::Contains("faces[0]"));
    CHECK_THAT(error.message, Catch::Contains("knots_u[6]"));
  }
  SECTION("zero weight") {
    std::string text =
        replace_first(panel_text(), "\"control_points\"",
                      "\"weights\": [" + std::string(47 * 5, ' ') + "],\n  \"control_points\"");
    std::string weights = "0.0";
    for (int k = 1; k < 48; ++k) weights += ", 1.0";
    text = replace_first(text, "[" + std::string(47 * 5, ' ') + "]", "[" + weights + "]");
    test::write_bytes(path, text);
    const Status error = read_error(path);
    CHECK_THAT(error.message, Catch::Contains("faces[0]"));
    CHECK_THAT(error.message, Catch::Contains("weight"));
  }
  SECTION("count that disagrees with the knots") {
    test::write_bytes(path, replace_first(panel_text(), "\"count_u\": 8", "\"count_u\": 7"));
    CHECK_THAT(read_error(path).message, Catch::Contains("faces[0].surface.count_u"));
  }
  SECTION("too few control points") {
    std::string text = panel_text();
    const auto net = text.find("\"control_points\"");
    const auto first_point = text.find('[', text.find('[', net) + 1);
    const auto end_point = text.find(']', first_point);
    text.erase(first_point, end_point - first_point + 2);  // the point and its comma
    test::write_bytes(path, text);
    CHECK_THAT(read_error(path).message, Catch::Contains("faces[0].surface.control_points"));
  }
}

TEST_CASE("JSON: an unknown schema version or format is rejected", "[io][bad][json]") {
  test::TempDir dir;
  test::write_bytes(dir / "v2.json",
                    replace_first(panel_text(), "\"version\": 1", "\"version\": 2"));
  CHECK_THAT(read_error(dir / "v2.json").message, Catch::Contains("version 2"));
  test::write_bytes(dir / "other.json",
                    replace_first(panel_text(), "argil.surfaces", "someone.elses"));
  CHECK_THAT(read_error(dir / "other.json").message, Catch::Contains("format"));
}

TEST_CASE("a failed write leaves the existing file byte for byte intact", "[io][atomic]") {
  test::TempDir dir;
  const std::string old_bytes = "the previous content\n";
  const Result<Model> panel = read_model(test::source_file("examples/surfaces/panel.json"));
  REQUIRE(panel.ok());
  Model broken = panel.value();
  broken.faces[0].surface.control_points(5, 1) = std::nan("");
  for (const char* name : {"out.step", "out.iges", "out.json", "out.stl", "out.glb"}) {
    test::write_bytes(dir / name, old_bytes);
    const Status status = write_model(broken, dir / name);
    INFO(name << ": " << status.message);
    CHECK_FALSE(status.ok());
    CHECK_THAT(status.message, Catch::Contains("face 0"));
    CHECK(test::read_bytes(dir / name) == old_bytes);
  }
  SECTION("a writer that fails half way") {
    test::write_bytes(dir / "half.bin", old_bytes);
    const Status status = write_atomically(dir / "half.bin", [](const std::filesystem::path& tmp) {
      test::write_bytes(tmp, "partial");
      return Status::error(StatusCode::io_error, "disk full (simulated)");
    });
    CHECK_FALSE(status.ok());
    CHECK(test::read_bytes(dir / "half.bin") == old_bytes);
  }
  SECTION("a folder that does not exist") {
    const Status status = write_model(panel.value(), dir / "no-such-folder" / "out.step");
    CHECK_FALSE(status.ok());
    CHECK_THAT(status.message, Catch::Contains("no-such-folder"));
  }
  // No temporary is left behind by any of the failures.
  std::size_t files = 0;
  for ([[maybe_unused]] const auto& entry : std::filesystem::directory_iterator(dir.path()))
    ++files;
  CHECK(files <= 6);
}

TEST_CASE("a successful write replaces the file completely", "[io][atomic]") {
  test::TempDir dir;
  test::write_bytes(dir / "panel.json", std::string(100000, 'x'));
  const Result<Model> panel = read_model(test::source_file("examples/surfaces/panel.json"));
  REQUIRE(panel.ok());
  REQUIRE(write_model(panel.value(), dir / "panel.json").ok());
  const Result<Model> back = read_model(dir / "panel.json");
  REQUIRE(back.ok());
  CHECK(back.value().faces.size() == 1);
}

}  // namespace argil::io
