#pragma once
// The viewer page `argil view` writes: one self-contained HTML file (the
// three.js viewer and the data embedded; it opens from file:// with no
// network) showing a model, or a sculpt run replayed: the surfaces before and
// at each frame, coloured by signed deviation, the tool, its path, the
// contacts and the force, with picking. docs/view.md.

#include <optional>
#include <string>

#include "argil/core/base/status.hpp"
#include "argil/io/model/model.hpp"
#include "argil/sculpt/view/session_replay.hpp"

namespace argil::sculpt {

struct ViewPageOptions {
  std::string title;
  /// Chord tolerance of the page's meshes [mm]; 0: 5e-4 of the models' box
  /// diagonal (and no coarser than eps).
  double chord_tolerance_mm = 0.0;
  /// A fixed scale for the deviation colours [mm]; empty: the largest movement.
  std::optional<double> scale_mm{};
};

/// The page of a model file's faces (`source`: the file, for the page and
/// the script hints). Fails when a face does not tessellate (the message
/// names it) or the page would hold more than 2 million triangles.
Result<std::string> model_view_page(const io::Model& model, const std::string& source,
                                    const ViewPageOptions& options);

/// The page of a replayed run. Each model is meshed once (its faces as the
/// run left them, so a dent is resolved) and every frame is evaluated at the
/// same (face, u, v) vertices, so a vertex's movement is that of its surface
/// point.
Result<std::string> session_view_page(const SessionReplay& replay, const ViewPageOptions& options);

}  // namespace argil::sculpt
