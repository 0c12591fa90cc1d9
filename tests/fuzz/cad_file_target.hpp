#pragma once
// The body of the STEP and IGES fuzz targets: the bytes become a file with the
// format's extension, read through argil::io::read_cad(), the path `argil info`
// and `argil convert` take (OpenCASCADE only reads files by name), with a
// shorter time limit than the default so that libFuzzer's own -timeout
// catches hangs in argil's code, not OpenCASCADE's. Crashes and hangs inside
// OpenCASCADE end in its child process; each is logged on stderr
// ("argil-fuzz: OCCT ...") so that a run reports how often it happened.
// Run with -detect_leaks=0: OpenCASCADE never frees its process-wide tables and
// leaks some entities of malformed files; none of that memory is argil's.

#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "argil/io/cad/cad_exchange.hpp"
#include "model_checks.hpp"

namespace argil::fuzz {

/// Inputs whose reader process crashed or hung are kept for triage (is the
/// crash inside OpenCASCADE?) in $ARGIL_FUZZ_CONTAINED_DIR, when set.
inline void keep_contained_input(const std::uint8_t* data, std::size_t size,
                                 const char* extension) {
  const char* folder = std::getenv("ARGIL_FUZZ_CONTAINED_DIR");
  if (folder == nullptr) return;
  static int count = 0;
  const auto path = std::filesystem::path(folder) / ("contained-" + std::to_string(::getpid()) +
                                                     "-" + std::to_string(count++) + extension);
  std::ofstream(path, std::ios::binary)
      .write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
}

inline int read_cad_bytes(const std::uint8_t* data, std::size_t size, const char* extension) {
  // One file per process, overwritten by every input.
  static const std::filesystem::path path =
      std::filesystem::temp_directory_path() /
      ("argil-fuzz-" + std::to_string(::getpid()) + extension);
  {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
    if (!out) fail("cannot write the temporary input file", 0);
  }
  const auto format = io::cad_format_for(path);
  if (!format) fail("not a CAD extension", 0);
  const Result<io::Model> model =
      io::read_cad(path, *format, {.time_limit_s = 5.0, .memory_limit_mb = 2048});
  // A crash, hang or lost report that the reader process contained.
  if (model.status().code == StatusCode::external_failure) {
    std::fprintf(stderr, "argil-fuzz: OCCT %s\n", model.status().message.c_str());
    keep_contained_input(data, size, extension);
  }
  if (model.ok()) {
    check_accepted_model(model.value());
  } else if (model.status().message.find(path.string()) == std::string::npos) {
    fail("rejection does not name the file", 0);
  }
  return 0;
}

}  // namespace argil::fuzz
