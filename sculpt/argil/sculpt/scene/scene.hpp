#pragma once
// A sculpting scene (docs/formats.md, "argil.scene" version 2; version 1 still
// reads): which faces of which files are modelled and how (rigid or deformable,
// material, boundary conditions), the tools, the tolerance eps, the haptic rate
// and the outputs. Loading checks every field and names the bad one; it reads
// no model file.

#include <filesystem>
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "argil/core/base/status.hpp"
#include "argil/core/deform/material.hpp"
#include "argil/core/haptic/virtual_coupling.hpp"

namespace argil::sculpt {

/// The "format" value of a scene file, the schema version this build writes
/// and documents, and the oldest it still reads (version 1 materials are
/// mapped to physical units: version1_material.hpp).
inline constexpr std::string_view kSceneFormatName = "argil.scene";
inline constexpr int kSceneFormatVersion = 2;
inline constexpr int kSceneOldestVersion = 1;

/// One model: faces of a CAD or JSON file.
struct ModelOptions {
  std::string name;             // unique in the scene; names the output files
  std::filesystem::path file;   // resolved against the scene file's folder
  std::vector<int> faces;       // face indices in the file; empty: every face
  bool deformable = true;       // rigid models collide but never move
  Material material;            // deformable models only (units: material.hpp)
  BoundaryConditions boundary;  // deformable models only
  /// Coulomb coefficient mu [-] of the tool against this model, in [0,
  /// kMaxFriction]: the one friction setting (a property of the tool-body
  /// pair). Read from the model's "friction" (version 1: "material.friction"
  /// of a deformable model).
  double friction = 0.3;
};

enum class ToolType { sphere, bspline, point };
const char* to_string(ToolType type);

/// A tool, in its own frame T (origin at the device point); the device pose
/// X_WD places it in the world. The haptic tick (argil/core/haptic/haptic_tick.hpp)
/// drives an implicit sphere, a rigid B-spline surface, or a point.
struct ToolOptions {
  std::string name;
  ToolType type = ToolType::sphere;
  double radius = 0.0;         // sphere [mm], centred on the tool frame origin
  std::filesystem::path file;  // bspline: surface file, resolved like models
  int face = 0;                // bspline: face index in `file`
};

/// Mesh and picture formats a run writes, and the logs.
struct OutputOptions {
  bool step = true, iges = true, json = true;
  bool forces = true, contacts = true, timing = true, pictures = true;
};

struct Scene {
  std::filesystem::path source;      // the scene file (empty when parsed from text)
  std::vector<ModelOptions> models;  // at least one deformable
  std::vector<ToolOptions> tools;    // at least one
  double tolerance = 0.0;            // eps [mm], > 0
  double haptic_rate = 1000.0;       // [Hz]
  CouplingOptions coupling;          // read directly from "coupling"
  /// Longest knot span [mm] wanted on a deformable face where the tool
  /// works (docs/deformation.md, Refinement); 0 turns refinement off; unset:
  /// derived from the tool (a sphere's radius; none for a point).
  std::optional<double> resolution;
  OutputOptions outputs;
  std::filesystem::path script;       // default script, resolved; empty: none
  int version = kSceneFormatVersion;  // the file's schema version
  /// What the reader changed, each starting with the file and the field (a
  /// version-1 material mapped to physical units); `argil sculpt` prints them.
  std::vector<std::string> warnings;

  /// Index of the tool called `name` (the first tool when `name` is empty); -1 if none.
  int tool_index(std::string_view name) const;
};

/// Parses a scene document. `source_name` starts every error message; relative
/// paths are resolved against `base_dir`. Does not open the files it names.
Result<Scene> parse_scene(std::string_view text, const std::string& source_name,
                          const std::filesystem::path& base_dir);

/// Reads and parses a scene file; paths are relative to its folder.
Result<Scene> read_scene(const std::filesystem::path& path);

}  // namespace argil::sculpt
