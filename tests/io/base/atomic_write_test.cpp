// write_atomically() and its read side read_text_file(): a target is either
// left byte for byte as it was or replaced completely, never half written, and
// read failures name the file.
#include <catch2/catch.hpp>
#include <filesystem>
#include <stdexcept>
#include <string>

#include "argil/io.hpp"
#include "test_files.hpp"

namespace argil::io {
namespace {

const std::string kOldBytes = "the previous content\n";

// Files in `dir`, temporaries included (they start with a dot).
std::size_t file_count(const test::TempDir& dir) {
  std::size_t files = 0;
  for ([[maybe_unused]] const auto& entry : std::filesystem::directory_iterator(dir.path()))
    ++files;
  return files;
}

}  // namespace

TEST_CASE("a failed atomic write leaves the old file intact and no temporary behind",
          "[io][atomic]") {
  test::TempDir dir;
  const std::filesystem::path target = dir / "target.bin";
  test::write_bytes(target, kOldBytes);
  SECTION("a writer that fails half way") {
    const Status status = write_atomically(target, [](const std::filesystem::path& tmp) {
      test::write_bytes(tmp, "partial");
      return Status::error(StatusCode::io_error, "disk full (simulated)");
    });
    CHECK_FALSE(status.ok());
    CHECK_THAT(status.message, Catch::Contains("disk full"));
  }
  SECTION("a writer that throws") {
    const Status status = write_atomically(target, [](const std::filesystem::path& tmp) -> Status {
      test::write_bytes(tmp, "partial");
      throw std::runtime_error("simulated writer bug");
    });
    CHECK(status.code == StatusCode::io_error);
    CHECK_THAT(status.message, Catch::Contains(target.string()));
  }
  SECTION("a writer that removes its temporary and claims success") {
    const Status status = write_atomically(target, [](const std::filesystem::path& tmp) {
      std::filesystem::remove(tmp);
      return Status::success();
    });
    CHECK_FALSE(status.ok());
    CHECK_THAT(status.message, Catch::Contains(target.string()));
  }
  CHECK(test::read_bytes(target) == kOldBytes);
  CHECK(file_count(dir) == 1);
}

TEST_CASE("a successful atomic write replaces the old file completely", "[io][atomic]") {
  test::TempDir dir;
  const std::filesystem::path target = dir / "target.bin";
  // Longer old content: a replacement that only overwrote would leave its tail.
  test::write_bytes(target, std::string(100000, 'x'));
  const std::string bytes("new\0content\n\xff\x01", 14);
  REQUIRE(write_bytes_atomically(target, bytes).ok());
  CHECK(test::read_bytes(target) == bytes);
  CHECK(file_count(dir) == 1);
  SECTION("and creates a file that did not exist") {
    REQUIRE(write_bytes_atomically(dir / "fresh.bin", "fresh").ok());
    CHECK(test::read_bytes(dir / "fresh.bin") == "fresh");
  }
}

TEST_CASE("atomic writes to a missing folder or onto a folder fail naming the target",
          "[io][atomic]") {
  test::TempDir dir;
  const std::filesystem::path missing = dir / "no-such-folder" / "out.bin";
  const Status into_missing = write_bytes_atomically(missing, "x");
  CHECK(into_missing.code == StatusCode::io_error);
  CHECK_THAT(into_missing.message, Catch::Contains("no-such-folder"));
  const Status onto_folder = write_bytes_atomically(dir.path(), "x");
  CHECK_FALSE(onto_folder.ok());
  CHECK_THAT(onto_folder.message, Catch::Contains(dir.path().string()));
  CHECK(std::filesystem::is_directory(dir.path()));
}

TEST_CASE("read_text_file returns every byte, and an error naming a missing file",
          "[io][text_file]") {
  test::TempDir dir;
  std::string bytes(3000, '\0');
  for (std::size_t k = 0; k < bytes.size(); ++k) bytes[k] = static_cast<char>(k * 7 % 256);
  test::write_bytes(dir / "bytes.bin", bytes);
  const Result<std::string> read = read_text_file(dir / "bytes.bin");
  REQUIRE(read.ok());
  CHECK(read.value() == bytes);
  const Result<std::string> missing = read_text_file(dir / "missing.txt");
  REQUIRE_FALSE(missing.ok());
  CHECK(missing.status().code == StatusCode::io_error);
  CHECK_THAT(missing.status().message, Catch::Contains((dir / "missing.txt").string()));
}

}  // namespace argil::io
