#pragma once
// A sculpting session: the scene's named faces loaded into a HapticWorld with
// its tool, stepped once per device sample, with undo and redo of strokes.
//
// Session::step reads no clock and starts no thread: the same scene and the
// same samples (and undo/redo calls) give bit-identical control points.
// Measure time around it, never inside.

#include <Eigen/Core>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "argil/core/base/status.hpp"
#include "argil/core/haptic/haptic_tick.hpp"
#include "argil/io/model/model.hpp"
#include "argil/sculpt/scene/scene.hpp"
#include "argil/sculpt/script/script.hpp"
#include "argil/sculpt/session/face_refinement.hpp"

namespace argil::sculpt {

/// A contact of the tool with one model face during a tick.
struct ContactRecord {
  int model = 0;                                    // index in Scene::models
  int face = 0;                                     // face index in the model's file
  Eigen::Vector2d uv = Eigen::Vector2d::Zero();     // on the face
  Eigen::Vector3d point = Eigen::Vector3d::Zero();  // p_WC [mm]
  /// Unit: S_u x S_v, or on a trimmed edge the direction from the edge point
  /// to the tool's centre.
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();
  double depth = 0.0;  // [mm], positive inside the tool
};

/// What one tick did, for logs and pictures.
struct TickReport {
  long long tick = 0;
  double time = 0.0;                                // [s]
  Eigen::Vector3d force = Eigen::Vector3d::Zero();  // on the device [N], clamped
  bool clamped = false;
  Eigen::Vector3d proxy = Eigen::Vector3d::Zero();  // p_WT, the tool proxy's position [mm]
  double max_depth = 0.0;                           // [mm]
  std::vector<ContactRecord> contacts;
  bool stroke_finished = false;  // this sample released the tool
  int tool = 0;                  // the scene tool held (index in Scene::tools)
};

/// One scene model as loaded: its whole file (the exports write it back with
/// the sculpted faces in place), and the faces the scene names with their
/// trims and bodies in the world, in the scene's order.
struct LoadedModel {
  ModelOptions spec;
  /// The file's model as read: every face in file order, every other field.
  io::Model file_model;
  /// The named faces only, as their bodies start: as read, or refined
  /// exactly (refine_faces). Metadata: the file's plus "sculpt_scene" and
  /// "sculpt_model".
  io::Model initial;
  std::vector<int> file_faces;    // face index in the file of each loaded face
  std::vector<TrimRegion> trims;  // of each loaded face (empty: untrimmed)
  std::vector<int> bodies;        // world body of each loaded face
};

class Session {
 public:
  /// Reads each model's file, keeps it whole (LoadedModel::file_model), and
  /// builds a body for each face the scene names (only those: deformable with
  /// the model's material and boundary conditions, or rigid) with the face's
  /// trims (contact only with material), and the tool `tool_name` (empty:
  /// the scene's first tool). Errors name the scene field ("models[1].faces[2]:
  /// face 9 is out of range ...", "models[0] face 12: loop 0 curve 3 ends at
  /// ...").
  /// With `tool_paths` (where the device goes while engaged: engaged_paths()
  /// of the script), the deformable faces they come near are first refined
  /// exactly to the scene's resolution (face_refinement.hpp; refinements()),
  /// for the finest and widest of `tool_name` and `later_tools` (the tools
  /// the script switches to, tools_held()).
  static Result<Session> create(const Scene& scene, const std::string& tool_name = "",
                                const std::vector<std::vector<Eigen::Vector3d>>& tool_paths = {},
                                const std::vector<std::string>& later_tools = {});

  /// One haptic tick of 1 / haptic_rate seconds with the device at `sample`.
  /// An engaged sample after a released one starts a stroke; a released one
  /// after an engaged one finishes it (TickReport::stroke_finished).
  Result<TickReport> step(const DeviceSample& sample);

  /// Strokes that can be undone (finished, not undone) and redone.
  int undo_depth() const { return static_cast<int>(strokes_.size()); }
  int redo_depth() const { return static_cast<int>(redo_.size()); }
  bool engaged() const { return engaged_; }
  /// Restores the state just before the last finished stroke began, exactly:
  /// the world is rebuilt and the inputs before the stroke replayed (cost:
  /// the ticks before it; HapticWorld has no state snapshot to restore).
  /// Free moves made after the stroke are dropped. Refused during a stroke or
  /// with nothing to undo.
  Status undo();
  /// Restores the state right after the last undone stroke finished: its
  /// samples are stepped again from its start (free moves made since the undo
  /// are dropped). A new stroke after an undo clears the redo list.
  Status redo();
  /// Puts the scene's tool `name` in the device's hand, between strokes only
  /// (refused during a stroke, or for a name not in the scene). Kept in the
  /// history: undo and redo replay each stroke with the tool it was made with.
  Status switch_tool(const std::string& name);

  const Scene& scene() const { return scene_; }
  /// The faces create() refined for the tool's path.
  const std::vector<FaceRefinement>& refinements() const { return refinements_; }
  const std::vector<LoadedModel>& models() const { return models_; }
  /// The faces the scene names of model `index` with their current
  /// (sculpted) surfaces: LoadedModel::initial's faces, in its order (face f
  /// is file face file_faces[f]).
  io::Model current_faces(int index) const;
  /// The whole of model `index`'s file as it is now: file_model, every face
  /// in file order, each named face's surface replaced by its current one
  /// (perhaps refined: more control points and knots, the same trims), the
  /// other faces as read, bit for bit; metadata as in `initial`. The run's
  /// STEP, IGES and JSON exports.
  io::Model current_file_model(int index) const;
  /// The shape of scene tool `index` once read (every tool create() was
  /// given: the one held and those the script switches to); null otherwise.
  const ToolShape* tool_shape(int index) const;
  /// The tool the device holds.
  const ToolOptions& tool() const { return scene_.tools[static_cast<std::size_t>(tool_index_)]; }
  /// FNV-1a hash of every body's control points and the proxy state: equal
  /// hashes mean (with overwhelming probability) bit-identical states.
  std::uint64_t state_hash() const;
  double time_step() const { return 1.0 / scene_.haptic_rate; }

 private:
  struct StrokeSpan {
    std::size_t start = 0;  // index in history_ of the stroke's first sample
    std::size_t end = 0;    // one past its release sample
  };
  /// From history_[at] on (at == history_.size(): from now), tool `tool`.
  struct ToolChange {
    std::size_t at = 0;
    int tool = 0;
  };
  /// An undone stroke, as a redo makes it again from the end of the stroke
  /// before it (`from`, 0 for none): the original samples from there through
  /// its release (free moves, then the stroke from `stroke_offset`), and the
  /// tool changes among them (`at` counted from `from`).
  struct RedoEntry {
    std::size_t from = 0;
    std::size_t stroke_offset = 0;
    std::vector<DeviceSample> samples;
    std::vector<ToolChange> changes;
  };
  Session() = default;
  Status rebuild_world();
  /// The shape of scene tool `index`, read once.
  Result<ToolShape> shape_of(int index);
  Status hold_tool(int index);
  /// Drops the tool changes from history index `at` on (the history was cut).
  void forget_tool_changes_from(std::size_t at);
  /// Takes `tool` back in hand if another is held, as a change from now.
  Status keep_holding(int tool);
  /// The tool held at history_[at].
  int tool_at(std::size_t at) const;
  /// A fresh world stepped through history_.
  Status replay_history();
  Result<TickReport> advance(const DeviceSample& sample);

  Scene scene_;
  int initial_tool_ = 0;
  int tool_index_ = 0;                            // the tool held now
  std::vector<std::optional<ToolShape>> shapes_;  // per scene tool, once read
  std::vector<ToolChange> tool_changes_;          // in history order
  std::vector<LoadedModel> models_;
  std::vector<FaceRefinement> refinements_;
  std::vector<std::pair<int, int>> body_owner_;  // body -> (model, loaded face)
  std::optional<HapticWorld> world_;
  std::vector<DeviceSample> history_;  // every sample the current state results from
  std::vector<StrokeSpan> strokes_;    // finished, undoable
  std::vector<RedoEntry> redo_;        // undone strokes, last on top
  std::size_t stroke_start_ = 0;
  bool engaged_ = false;
};

}  // namespace argil::sculpt
