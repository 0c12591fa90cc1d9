#pragma once
// Helpers of the session runner's tests: a run that writes the sculpted faces
// as JSON only, read back and compared bit for bit.
#include <catch2/catch.hpp>
#include <cstring>
#include <filesystem>
#include <utility>

#include "argil/io/files/model_files.hpp"
#include "argil/sculpt/run/session_runner.hpp"

namespace argil::sculpt::test {

/// Options for a run of `scene` with `script` into `out` writing the models
/// as JSON, recorded.csv, summary.json and the journal only.
inline RunOptions json_run(const std::filesystem::path& scene, const std::filesystem::path& script,
                           const std::filesystem::path& out, bool fresh = true) {
  RunOptions o{.scene = scene, .script = script, .out = out, .fresh = fresh};
  o.outputs = OutputOptions{.step = false,
                            .iges = false,
                            .json = true,
                            .forces = false,
                            .contacts = false,
                            .timing = false,
                            .pictures = false};
  return o;
}

/// The control points of the first face of a model file.
inline ControlNet poles_of(const std::filesystem::path& file) {
  const Result<io::Model> model = io::read_model(file);
  REQUIRE(model.ok());
  return model.value().faces[0].surface.control_points;
}

inline bool same_bits(const ControlNet& a, const ControlNet& b) {
  return a.size() == b.size() &&
         std::memcmp(a.data(), b.data(), sizeof(double) * static_cast<std::size_t>(a.size())) == 0;
}

/// The run's report; fails the test case (with the message) when it fails.
inline RunReport run_ok(const RunOptions& options) {
  Result<RunReport> report = run_session(options);
  INFO(report.status().message);
  REQUIRE(report.ok());
  return std::move(report).value();
}

}  // namespace argil::sculpt::test
