// The OpenCASCADE topology oracle (tests/support/occt_topology.hpp) checked
// against what the real CAD files are known to hold (tests/data/README.md):
// faces and solids per file, a closed valid solid for screw.step. Prints each
// file's census as a Markdown table row, so the log holds the whole table.
#include <catch2/catch.hpp>
#include <cstdio>
#include <stdexcept>
#include <string>

#include "support/occt_topology.hpp"
#include "test_files.hpp"

namespace argil::io {
namespace {

using test::OcctTopology;

struct KnownCounts {
  const char* file;
  int faces;
  int solids;  // -1: not documented (IGES files hold faces, not solids)
};

void print_header() {
  std::printf(
      "| file | products | solids (parts) | shells / closed | faces (distinct) | edges | shared "
      "| seam | free | degenerated | loose | vertices | valid | volume [mm^3] | product names |\n");
  std::printf("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
}

void print_row(const char* file, const OcctTopology& t) {
  std::string names;
  for (const std::string& name : t.product_names)
    names += (names.empty() ? "'" : ", '") + name + "'";
  std::printf(
      "| %s | %d | %d (%d) | %d / %d | %d (%d) | %d | %d | %d | %d | %d | %d | %d | %s | %.6g | %s "
      "|\n",
      file, t.products, t.solids, t.distinct_solids, t.shells, t.closed_shells, t.faces,
      t.distinct_faces, t.edges, t.shared_edges, t.seam_edges, t.free_edges, t.degenerated_edges,
      t.loose_edges, t.vertices, t.valid ? "yes" : "no", t.volume, names.c_str());
  std::fflush(stdout);
}

bool is_step(const std::string& file) { return file.ends_with(".step") || file.ends_with(".stp"); }

TEST_CASE(
    "occt topology census: OpenCASCADE reads the documented faces and solids of every real CAD "
    "file") {
  const KnownCounts known[] = {
      {"screw.step", 10, 1},
      {"11752.stp", 1018, 1},
      {"Ventilator.stp", 305, 1},
      {"as1-oc-214.stp", 160, 18},
      {"face_recognition_sample_part.stp", 23, 1},
      {"sliced_cylinder.step", 5, 1},
      {"bearing.iges", 213, -1},
      {"surf114.igs", 4, -1},
  };
  print_header();
  for (const KnownCounts& k : known) {
    INFO(k.file);
    const OcctTopology t = test::occt_topology(test::shared_data(k.file));
    print_row(k.file, t);

    CHECK(t.faces == k.faces);
    if (k.solids >= 0) CHECK(t.solids == k.solids);

    // Properties of the definitions, whatever the file.
    CHECK(t.distinct_faces <= t.faces);
    CHECK(t.distinct_solids <= t.solids);
    CHECK(t.closed_shells <= t.shells);
    // Every edge is of exactly one kind (a seam that is also shared counted once).
    CHECK(t.degenerated_edges + t.loose_edges + t.free_edges + t.shared_edges + t.seam_edges -
              t.seam_shared_edges ==
          t.edges);
    if (is_step(k.file)) {
      CHECK(t.products >= 1);
      CHECK(t.product_names.size() == static_cast<std::size_t>(t.products));
    } else {
      CHECK(t.products == 1);
      CHECK(t.product_names.empty());
    }
  }
}

TEST_CASE("occt topology census: a closed solid has closed shells, no free edges and a volume") {
  const OcctTopology screw = test::occt_topology(test::shared_data("screw.step"));
  CHECK(screw.solids == 1);
  CHECK(screw.shells == 1);
  CHECK(screw.closed_shells == 1);
  CHECK(screw.free_edges == 0);
  CHECK(screw.valid);
  CHECK(screw.volume > 0.0);
}

TEST_CASE("occt topology census: a file OpenCASCADE cannot read is refused by name") {
  test::TempDir dir;
  const std::filesystem::path missing = dir / "missing.step";
  CHECK_THROWS_WITH(test::occt_topology(missing), Catch::Contains(missing.string()));
  const std::filesystem::path garbage = dir / "garbage.IGS";
  test::write_bytes(garbage, "not an IGES file\n");
  CHECK_THROWS_WITH(test::occt_topology(garbage), Catch::Contains(garbage.string()));
  const std::filesystem::path mesh = dir / "part.stl";
  test::write_bytes(mesh, "solid part\nendsolid part\n");
  CHECK_THROWS_WITH(test::occt_topology(mesh), Catch::Contains(mesh.string()));
}

}  // namespace
}  // namespace argil::io
