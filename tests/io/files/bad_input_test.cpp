// Bad files never crash the readers and writers of every format: each case gives
// an error naming the file and, where known, the entity. Bad files are built
// here from good ones. The JSON document's own checks are in tests/io/json,
// write_atomically() and read_text_file() in tests/io/base.
#include <catch2/catch.hpp>
#include <random>
#include <regex>

#include "argil/io.hpp"
#include "bad_input.hpp"
#include "test_files.hpp"

namespace argil::io {
namespace {

std::string garbage(std::size_t size, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::string bytes(size, '\0');
  for (char& c : bytes) c = static_cast<char>(rng() & 0xff);
  return bytes;
}

}  // namespace

TEST_CASE("a missing file is an error naming it, in every format", "[io][bad]") {
  test::TempDir dir;
  for (const char* name : {"missing.step", "missing.iges", "missing.json"}) {
    CHECK(test::read_error(dir / name).code == StatusCode::io_error);
  }
}

TEST_CASE("an empty file is an error naming it, in every format", "[io][bad]") {
  test::TempDir dir;
  for (const char* name : {"empty.step", "empty.igs", "empty.json"}) {
    test::write_bytes(dir / name, "");
    CHECK_THAT(test::read_error(dir / name).message, Catch::Contains("empty"));
  }
}

TEST_CASE("garbage bytes are an error, not a crash, in every format", "[io][bad]") {
  test::TempDir dir;
  std::uint64_t seed = 1;
  for (const char* name : {"garbage.stp", "garbage.iges", "garbage.json"}) {
    for (std::size_t size : {1u, 100u, 100000u}) {
      test::write_bytes(dir / name, garbage(size, seed++));
      CHECK(test::read_error(dir / name).code == StatusCode::parse_error);
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
      CHECK_THAT(test::read_error(path).message, Catch::Contains("truncated"));
    }
  }
}

TEST_CASE("STEP and IGES files corrupted in the middle are errors or warnings, not crashes",
          "[io][bad]") {
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
      // What OpenCASCADE reads past is read, but never silently: an error, or
      // warnings that name what was damaged.
      const Result<Model> read = read_model(path);
      if (read.ok()) {
        CHECK_FALSE(read.value().warnings.empty());
      } else {
        CHECK_THAT(read.status().message, Catch::Contains(path.string()));
      }
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
  CHECK_THAT(test::read_error(dir / "point.step").message, Catch::Contains("no faces"));
}

TEST_CASE("unsupported entities are warnings naming the entity", "[io][bad]") {
  test::TempDir dir;
  // The warning names the type and the entity; what transferred is read.
  const auto warned = [](const Model& model, const std::string& what) {
    for (const std::string& w : model.warnings) {
      if (w.find(what) != std::string::npos) return true;
    }
    return false;
  };
  SECTION("STEP: an entity type no schema knows") {
    const std::string screw = test::read_bytes(test::shared_data("screw.step"));
    const std::string edited = test::replace_first(screw, "ADVANCED_FACE(", "ARGIL_UNKNOWN_FACE(");
    test::write_bytes(dir / "unknown.step", edited);
    const Result<Model> read = read_model(dir / "unknown.step");
    REQUIRE(read.ok());
    CHECK(read.value().faces.size() == 9);  // the face it replaced is gone, and said so
    CHECK(warned(read.value(), "unsupported type ARGIL_UNKNOWN_FACE"));
    const auto at = edited.rfind('#', edited.find("ARGIL_UNKNOWN_FACE("));
    CHECK(warned(read.value(), edited.substr(at, edited.find('=', at) - at - 1)));
  }
  SECTION("STEP: presentation entities the geometry does not need") {
    const Result<Model> read = read_model(test::shared_data("face_recognition_sample_part.stp"));
    REQUIRE(read.ok());
    CHECK(read.value().faces.size() == 23);
    CHECK(warned(read.value(), "PRE_DEFINED_POINT_MARKER_SYMBOL skipped (#553)"));
  }
  SECTION("STEP: null names where the schema wants a string (Rhino)") {
    const Result<Model> read = read_model(test::shared_data("sliced_cylinder.step"));
    REQUIRE(read.ok());
    CHECK(read.value().faces.size() == 5);
    CHECK(warned(read.value(), "(#56, #57) TRIMMED_CURVE: Parameter n0.1 (name) not a quoted"));
  }
  SECTION("nothing transferable is still an error naming the file") {
    const std::string screw = test::read_bytes(test::shared_data("screw.step"));
    std::string edited = screw;
    for (std::size_t at = edited.find("ADVANCED_FACE("); at != std::string::npos;
         at = edited.find("ADVANCED_FACE(", at)) {
      edited.replace(at, 14, "ARGIL_UNKNOWN_FACE(");
    }
    test::write_bytes(dir / "none.step", edited);
    const Status error = test::read_error(dir / "none.step");
    CHECK(error.code == StatusCode::unsupported);
    CHECK_THAT(error.message, Catch::Contains("none.step"));
    CHECK_THAT(error.message, Catch::Contains("no faces; the reader met: "));
  }
  SECTION("IGES: an entity type number IGES does not define") {
    const std::string bearing = test::read_bytes(test::shared_data("bearing.iges"));
    // Directory entry D5 (the first surface, type 128) in both of its records.
    std::string edited = test::replace_first(bearing, "     128      19", "     999      19");
    edited = test::replace_first(edited, "     128       0       0      15",
                                 "     999       0       0      15");
    test::write_bytes(dir / "unknown.iges", edited);
    const Result<Model> read = read_model(dir / "unknown.iges");
    if (read.ok()) {
      CHECK(warned(read.value(), "type 999"));
    } else {
      CHECK_THAT(read.status().message, Catch::Contains("999"));
    }
  }
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
  SECTION("a folder that does not exist") {
    const Status status = write_model(panel.value(), dir / "no-such-folder" / "out.step");
    CHECK_FALSE(status.ok());
    CHECK_THAT(status.message, Catch::Contains("no-such-folder"));
  }
  // No temporary is left behind by any of the failures: only the five targets.
  std::size_t files = 0;
  for ([[maybe_unused]] const auto& entry : std::filesystem::directory_iterator(dir.path()))
    ++files;
  CHECK(files == 5);
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
