// Census (hidden: run `io_occt_oracle_tests "[.census]"`, about 10 minutes):
// every face of each real file exported alone to STEP and IGES, as read and
// deformed five ways, counting the faces written and the faces OpenCASCADE
// reads back as one BRepCheck-valid face. docs/io.md quotes the table.
#include <BRepCheck_Analyzer.hxx>

#include <catch2/catch.hpp>
#include <cstdio>
#include <functional>
#include <string>

#include "argil/io.hpp"
#include "deformed_faces.hpp"
#include "occt_reader.hpp"
#include "test_files.hpp"

namespace argil::io {
namespace {

struct Count {
  std::size_t written = 0;
  std::size_t valid = 0;
};

struct Variant {
  const char* name;
  std::function<FaceRecord(const FaceRecord&, std::uint64_t seed)> apply;
};

TEST_CASE("census: faces of the real files that export valid, as read and deformed", "[.census]") {
  const Variant variants[] = {
      {"as read", [](const FaceRecord& f, std::uint64_t) { return f; }},
      {"5 %",
       [](const FaceRecord& f, std::uint64_t seed) { return test::deformed(f, 0.05, seed); }},
      {"50 %",
       [](const FaceRecord& f, std::uint64_t seed) { return test::deformed(f, 0.5, seed); }},
      {"apex split 1e-6",
       [](const FaceRecord& f, std::uint64_t seed) { return test::apex_split(f, 1e-6, seed); }},
      {"side 1e-8",
       [](const FaceRecord& f, std::uint64_t seed) { return test::side_collapsed(f, 1e-8, seed); }},
      {"runaway 1e7",
       [](const FaceRecord& f, std::uint64_t seed) { return test::deformed(f, 1e7, seed); }},
  };
  test::TempDir dir;
  for (const char* name :
       {"screw.step", "bearing.iges", "11752.stp", "as1-oc-214.stp", "surf114.igs"}) {
    const Result<Model> read = read_model(test::shared_data(name));
    REQUIRE(read.ok());
    for (const Variant& variant : variants) {
      Count step, iges;
      for (std::size_t f = 0; f < read.value().faces.size(); ++f) {
        Model one;
        one.source_unit = read.value().source_unit;
        one.faces.push_back(variant.apply(read.value().faces[f], f));
        for (Count* count : {&step, &iges}) {
          const std::filesystem::path path = dir / (count == &step ? "face.step" : "face.iges");
          std::filesystem::remove(path);
          if (!write_model(one, path).ok()) continue;
          ++count->written;
          const test::OcctShape back = test::occt_read(path);
          if (back.faces.size() == 1 && BRepCheck_Analyzer(back.faces[0]).IsValid()) ++count->valid;
        }
      }
      std::printf("| %s | %s | %zu | %zu / %zu | %zu / %zu |\n", name, variant.name,
                  read.value().faces.size(), step.written, step.valid, iges.written, iges.valid);
      std::fflush(stdout);
    }
  }
}

}  // namespace
}  // namespace argil::io
