// The full haptic tick (docs/benchmarks.md): proxy move, collide, contact and
// friction forces, implicit deformation of the control net, device force.
//  - ticks: a sphere tool and a B-spline tool pressing and dragging on 16x16,
//    32x32 and 64x64 bicubic panels, and a sphere on the high-degree C0 plate
//    and on real faces read from STEP/IGES (bearing.iges, 11752.stp,
//    Ventilator.stp when it imports), all with the clay preset;
//  - refine: dent depth and peak force against exact refinement of the face,
//    foam and clay;
//  - create: the one-off cost of a deformable body;
//  - sleep: untouched faces 50 mm from a pressed plate, sleep on and off
//    (at most 2000 ticks a run, 300 with sleep off);
//  - resolve: the one-off cost of refining every face of the real files for a tool;
//  - scale: a sphere on one spot against the scene's size (1 to 1000 faces,
//    one face of 16x16 to 1024x1024 poles, all of 11752.stp).
// Arguments: [ticks] [ticks|refine|create|sleep|resolve|scale|all] [case filter]: the filter is a
// substring of the case names; CAD files are read only when it is empty or
// names the file.
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "argil/core.hpp"
#include "argil/io.hpp"
#include "bench_faces.hpp"
#include "bench_surfaces.hpp"
#include "haptic_loop_sections.hpp"
#include "haptic_stroke.hpp"

namespace {

using argil::bench::BenchFace;

constexpr int kRepeats = 3;

BenchFace panel_face(int poles) {
  return {std::to_string(poles) + "x" + std::to_string(poles) + " panel",
          argil::bench::bicubic_panel(poles), false, "bicubic, 10 mm pitch, 20 mm wave"};
}

/// The panels' stroke: a 5 mm sphere (or the cap) 2 mm under the rest surface
/// along z, dragged at 100 mm/s over 0.4 of the panel's width.
argil::bench::StrokeOptions panel_stroke(int poles, bool bspline_tool) {
  const double width = 10.0 * (poles - 1);  // [mm]
  return {.radius = 5.0,
          .bspline_tool = bspline_tool,
          .press = 2.0,
          .lift = 10.0,
          .tolerance = 0.05,
          .pass_seconds = 0.4 * width / 100.0,
          .vertical = true};
}

/// The faces of a CAD file the tables use: its largest polynomial and
/// largest rational nets with interior control points that the clay preset
/// accepts (larger nets it refuses are reported).
std::vector<BenchFace> file_faces(const std::string& file) {
  const auto model = argil::bench::read_bench_model(std::string(ARGIL_BENCH_DATA_DIR) + "/" + file);
  std::vector<BenchFace> faces;
  if (!model.ok()) return faces;
  const argil::Material clay = *argil::material_preset("clay");
  for (const bool rational : {false, true}) {
    for (const int index : argil::bench::faces_by_net_size(model.value(), rational)) {
      BenchFace face = argil::bench::model_face(model.value(), index, file);
      argil::OperatorCache cache;
      const auto body = argil::DeformableBody::create(face.surface, clay, {}, cache);
      if (body.ok()) {
        faces.push_back(std::move(face));
        break;
      }
      std::printf("%s (%s, size %.3g mm): clay refused: %s\n", face.name.c_str(),
                  face.origin.c_str(), argil::bench::face_size(face.surface),
                  body.status().message.c_str());
    }
  }
  return faces;
}

/// The size table's scenes: `count` 16x16 panels in rows of 32, the first
/// pressed; one n x n panel; every face of 11752.stp, its largest polynomial
/// net that clay accepts pressed. The panels' pitch is the 2 mm sphere's
/// radius, the spans a session refines a face to for it by default.
std::vector<argil::bench::ScaleCase> scale_cases() {
  using argil::bench::BenchFace;
  std::vector<argil::bench::ScaleCase> cases;
  for (const int count : {1, 10, 100, 1000}) {
    cases.push_back({std::to_string(count) + (count == 1 ? " face" : " faces") + " of 16x16",
                     [count](int& pressed) {
                       std::vector<BenchFace> faces;
                       for (int k = 0; k < count; ++k) {
                         BenchFace f{"panel " + std::to_string(k),
                                     argil::bench::flat_panel(16, 2.0), false, ""};
                         f.surface.control_points.rowwise() +=
                             Eigen::RowVector3d(32.0 * (k % 32), 32.0 * (k / 32), 0.0);
                         faces.push_back(std::move(f));
                       }
                       pressed = 0;
                       return faces;
                     }});
  }
  for (const int poles : {16, 64, 256, 1024}) {
    cases.push_back({"one face of " + std::to_string(poles) + "x" + std::to_string(poles),
                     [poles](int& pressed) {
                       pressed = 0;
                       return std::vector<BenchFace>{
                           {"panel", argil::bench::flat_panel(poles, 2.0), false, ""}};
                     }});
  }
  cases.push_back({"11752.stp, all faces",
                   [](int& pressed) {
                     std::vector<BenchFace> faces;
                     const auto model = argil::bench::read_bench_model(
                         std::string(ARGIL_BENCH_DATA_DIR) + "/11752.stp");
                     if (!model.ok()) return faces;
                     for (int i = 0; i < static_cast<int>(model.value().faces.size()); ++i)
                       faces.push_back(argil::bench::model_face(model.value(), i, "11752.stp"));
                     const argil::Material clay = *argil::material_preset("clay");
                     for (const int index : argil::bench::faces_by_net_size(model.value(), false)) {
                       argil::OperatorCache cache;
                       if (argil::DeformableBody::create(
                               faces[static_cast<std::size_t>(index)].surface, clay, {}, cache)
                               .ok()) {
                         pressed = index;
                         break;
                       }
                     }
                     return faces;
                   },
                   true});
  return cases;
}

bool wanted(const std::string& name, const std::string& filter) {
  return filter.empty() || name.find(filter) != std::string::npos;
}

}  // namespace

int main(int argc, char** argv) {
  const int ticks = argc > 1 ? std::atoi(argv[1]) : 10000;
  const std::string section = argc > 2 ? argv[2] : "all";
  const std::string filter = argc > 3 ? argv[3] : "";
  if (ticks < 1 ||
      (section != "all" && section != "ticks" && section != "refine" && section != "create" &&
       section != "sleep" && section != "resolve" && section != "scale")) {
    std::fprintf(
        stderr,
        "usage: %s [ticks >= 1] [ticks|refine|create|sleep|resolve|scale|all] [case filter]\n",
        argv[0]);
    return 2;
  }

  const BenchFace plate{"C0 plate", argil::bench::c0_plate(), false,
                        "20 x 20 mm, C0 line at v = 0.5"};
  const BenchFace flat{"flat panel", argil::bench::flat_panel(8, 10.0), false,
                       "8x8 bicubic, 70 x 70 mm"};
  std::vector<BenchFace> real;
  for (const std::string file : {"bearing.iges", "11752.stp", "Ventilator.stp"}) {
    // Reading 11752.stp takes tens of seconds: only when a case may use it.
    if (!filter.empty() && file.find(filter) == std::string::npos &&
        filter.find(file) == std::string::npos)
      continue;
    for (BenchFace& f : file_faces(file)) {
      std::printf("%s: %s, size %.4g mm\n", f.name.c_str(), f.origin.c_str(),
                  argil::bench::face_size(f.surface));
      real.push_back(std::move(f));
    }
  }

  if (section == "all" || section == "ticks") {
    std::vector<argil::bench::TickCase> cases;
    for (const int poles : {16, 32, 64}) {
      for (const bool bspline_tool : {false, true}) {
        cases.push_back({panel_face(poles).name + (bspline_tool ? ", B-spline tool" : ", sphere"),
                         panel_face(poles), panel_stroke(poles, bspline_tool)});
      }
    }
    cases.push_back({"C0 plate, sphere", plate, argil::bench::scaled_stroke(plate.surface)});
    for (const BenchFace& f : real)
      cases.push_back({f.name + ", sphere", f, argil::bench::scaled_stroke(f.surface)});
    std::erase_if(cases, [&](const auto& c) { return !wanted(c.name, filter); });
    argil::bench::tick_section(cases, ticks, kRepeats);
  }

  if (section == "all" || section == "refine") {
    std::vector<argil::bench::RefinementCase> cases = {
        {"flat panel at its centre", flat},
        // (0.4, 0.4) is a Greville point of the 8x8 net and of both refinements;
        // the centre is one of the refined nets only.
        {"flat panel at a Greville point", flat, 0.4, 0.4},
        {"C0 plate on its C0 line", plate, 0.5, 0.5},
        {"C0 plate off its C0 line", plate, 0.5, 0.25},
    };
    // The real face: 11752.stp's largest polynomial net.
    for (const BenchFace& f : real) {
      if (f.name.starts_with("11752.stp") && !f.surface.is_rational()) cases.push_back({f.name, f});
    }
    std::erase_if(cases, [&](const auto& c) { return !wanted(c.name, filter); });
    argil::bench::refinement_section(cases);
  }

  if (section == "all" || section == "create") {
    std::vector<BenchFace> faces;
    for (const int poles : {16, 32, 64}) faces.push_back(panel_face(poles));
    faces.push_back(flat);
    faces.push_back(plate);
    for (const BenchFace& f : real) faces.push_back(f);
    // The refined nets of the refinement table.
    for (std::size_t i = 3, n = faces.size(); i < n; ++i) {
      for (int level = 1; level <= 2; ++level) {
        faces.push_back({faces[i].name + " level " + std::to_string(level),
                         argil::bench::refine_midpoints(faces[i].surface, level), faces[i].reversed,
                         ""});
      }
    }
    std::erase_if(faces, [&](const auto& f) { return !wanted(f.name, filter); });
    argil::bench::creation_section(faces, kRepeats);
  }
  if (section == "all" || section == "resolve") {
    std::vector<std::string> files = {"screw.step", "bearing.iges", "as1-oc-214.stp", "surf114.igs",
                                      "11752.stp"};
    std::erase_if(files, [&](const auto& f) { return !wanted(f, filter); });
    argil::bench::tool_refinement_section(files, 1.0 / 30.0);
  }
  if (section == "all" || section == "scale") {
    std::vector<argil::bench::ScaleCase> cases = scale_cases();
    std::erase_if(cases, [&](const auto& c) { return !wanted(c.name, filter); });
    argil::bench::scale_section(cases, std::min(ticks, 2000), kRepeats, 600);
  }
  if (section == "all" || section == "sleep")
    argil::bench::sleep_section(std::min(ticks, 2000), std::min(ticks, 300), kRepeats);
  return 0;
}
