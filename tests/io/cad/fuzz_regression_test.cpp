// Inputs the fuzzers (tests/fuzz) found crashing, read through the normal
// loaders: each must now give a clean result, never a crash. And the child
// process that contains OpenCASCADE's own crashes and hangs.
#include <unistd.h>

#include <algorithm>
#include <catch2/catch.hpp>
#include <csignal>
#include <vector>

#include "argil/core/geometry/evaluate.hpp"
#include "argil/io.hpp"
#include "argil/io/cad/detail/isolated_read.hpp"
#include "support/random_surface.hpp"
#include "test_files.hpp"

namespace argil::io {
namespace {

std::vector<std::filesystem::path> regression_files() {
  std::vector<std::filesystem::path> files;
  for (const auto& entry :
       std::filesystem::directory_iterator(test::shared_data("fuzz-regressions"))) {
    if (entry.path().extension() != ".md") files.push_back(entry.path());
  }
  std::sort(files.begin(), files.end());
  return files;
}

}  // namespace

TEST_CASE("every fuzz regression input reads to a clean error or a valid model", "[io][fuzz]") {
  const auto files = regression_files();
  REQUIRE_FALSE(files.empty());
  for (const auto& path : files) {
    DYNAMIC_SECTION(path.filename().string()) {
      const Result<Model> model = read_model(path);
      if (!model.ok()) {
        INFO(model.status().message);
        CHECK_THAT(model.status().message, Catch::Contains(path.string()));
        continue;
      }
      for (std::size_t f = 0; f < model.value().faces.size(); ++f) {
        const FaceRecord& face = model.value().faces[f];
        REQUIRE(validate_face(face, f).ok());
        const BSplineSurface& s = face.surface;
        const SurfaceDerivatives d =
            evaluate_derivatives(s, s.domain_start(Direction::u), s.domain_end(Direction::v));
        CHECK((d.point.allFinite() && d.du.allFinite() && d.dv.allFinite()));
      }
    }
  }
}

TEST_CASE("a crash in the reader process is an error naming the signal", "[io][isolation]") {
  const Result<Model> model = detail::read_in_child_process(
      []() -> Result<Model> {
        std::raise(SIGSEGV);
        return Model{};
      },
      {}, "crash.step");
  REQUIRE_FALSE(model.ok());
  CHECK(model.status().code == StatusCode::external_failure);
  CHECK_THAT(model.status().message, Catch::StartsWith("crash.step: "));
  CHECK_THAT(model.status().message, Catch::Contains("signal " + std::to_string(SIGSEGV)));
}

TEST_CASE("a reader process over its time limit is stopped with an error", "[io][isolation]") {
  const Result<Model> model = detail::read_in_child_process(
      []() -> Result<Model> {
        ::sleep(30);
        return Model{};
      },
      {.time_limit_s = 0.2}, "slow.iges");
  REQUIRE_FALSE(model.ok());
  CHECK(model.status().code == StatusCode::external_failure);
  CHECK_THAT(model.status().message, Catch::Contains("did not finish"));
}

TEST_CASE("the reader process passes errors and models back unchanged", "[io][isolation]") {
  const Result<Model> error = detail::read_in_child_process(
      []() -> Result<Model> { return Status::error(StatusCode::unsupported, "entity #7"); }, {},
      "x.step");
  REQUIRE_FALSE(error.ok());
  CHECK(error.status().code == StatusCode::unsupported);
  CHECK(error.status().message == "entity #7");

  Model sent;
  sent.source_unit = {"inch", 25.4};
  sent.metadata["origin"] = "child";
  FaceRecord face;
  face.surface = test::asymmetric_surface(true);
  face.name = "asymmetric";
  face.source_id = "#12";
  face.reversed = true;
  sent.faces.push_back(face);
  const Result<Model> received =
      detail::read_in_child_process([&]() -> Result<Model> { return sent; }, {}, "x.step");
  REQUIRE(received.ok());
  const Model& got = received.value();
  CHECK(got.source_unit.name == "inch");
  CHECK(got.source_unit.to_mm == 25.4);
  CHECK(got.metadata == sent.metadata);
  REQUIRE(got.faces.size() == 1);
  CHECK(got.faces[0].name == "asymmetric");
  CHECK(got.faces[0].source_id == "#12");
  CHECK(got.faces[0].reversed);
  const BSplineSurface& a = sent.faces[0].surface;
  const BSplineSurface& b = got.faces[0].surface;
  CHECK(a.degree == b.degree);
  CHECK(a.knots[0] == b.knots[0]);
  CHECK(a.knots[1] == b.knots[1]);
  CHECK(a.control_points == b.control_points);  // bit-exact
  CHECK(a.weights == b.weights);
}

}  // namespace argil::io
