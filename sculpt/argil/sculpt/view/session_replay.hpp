#pragma once
// A finished sculpt run replayed from its output folder, for the viewer: the
// scene it ran (named in summary.json) stepped through recorded.csv, which
// replays the run bit for bit, keeping the surfaces at chosen ticks (frames)
// and the device, proxy and force of every tick. Nothing is written.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "argil/core/base/status.hpp"
#include "argil/io/model/model.hpp"
#include "argil/sculpt/scene/scene.hpp"

namespace argil::sculpt {

/// The surfaces at one tick of a replay.
struct ReplayFrame {
  long long tick = 0;
  double time = 0.0;  // [s]
  /// Why this tick: "tick" (every N-th), "stroke end", "undo", "redo", "end".
  std::string kind;
  /// Each deformable model's named faces as they are after the tick
  /// (Session::current_faces); empty for rigid models.
  std::vector<io::Model> models;
  std::vector<Eigen::Vector3d> contacts;  // contact points of the tick [mm]
};

/// What a run did, tick by tick.
struct SessionReplay {
  std::filesystem::path scene_path;
  Scene scene;                     // with the run's tolerance
  std::vector<ToolOptions> tools;  // the scene's
  /// The named faces of each model before the first tick (refined for the
  /// tool as the run refined them); LoadedModel::file_faces of each.
  std::vector<io::Model> before;
  std::vector<std::vector<int>> file_faces;
  std::vector<ReplayFrame> frames;
  // One entry per tick.
  std::vector<double> time;                     // [s]
  std::vector<Eigen::Vector3d> device;          // device position p_WD [mm]
  std::vector<Eigen::Quaterniond> orientation;  // device orientation R_WD
  std::vector<Eigen::Vector3d> proxy;           // tool proxy p_WT [mm]
  std::vector<bool> engaged;
  std::vector<Eigen::Vector3d> force;  // on the device [N]
  std::vector<int> tool_index;         // the tool held (index in `tools`)
  double haptic_rate = 0.0;            // [Hz]
};

struct ReplayOptions {
  std::filesystem::path folder;  // a finished `argil sculpt` output folder
  /// The scene; empty: summary.json's "scene" (as the run was given it,
  /// relative to the working directory).
  std::filesystem::path scene{};
  /// A frame every `every` ticks; 0: about 60 over the run. Every stroke's end,
  /// undo and redo, and the last tick are frames too.
  long long every = 0;
};

/// Replays the run in `options.folder`. Errors name the file: a folder that is
/// not a finished run (no summary.json, recorded.csv or finished journal), a
/// scene that changed since the run (its hash differs from the journal's), or
/// a replay that does not reach the state the journal recorded.
Result<SessionReplay> replay_session(const ReplayOptions& options);

}  // namespace argil::sculpt
