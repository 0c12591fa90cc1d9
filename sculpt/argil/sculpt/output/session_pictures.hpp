#pragma once
// The pictures a sculpt run writes: the surfaces before and after with the
// tool path (after: coloured by how far each point moved along the normal, in
// or out), and the force plot.

#include <Eigen/Geometry>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "argil/core/base/status.hpp"
#include "argil/io/model/model.hpp"
#include "argil/sculpt/output/pictures.hpp"

namespace argil::sculpt {

/// File names of the pictures in the output folder.
inline constexpr const char* kBeforePicture = "before.png";
inline constexpr const char* kAfterPicture = "after.png";
inline constexpr const char* kForcePicture = "force.png";

/// A tool as the pictures draw it: a sphere of `radius_mm` (0: a point's
/// cross), or a B-spline tool's surface in its tool frame [mm].
struct PictureTool {
  double radius_mm = 0.0;
  std::optional<BSplineSurface> surface;
};

/// What the pictures of one run show.
struct SessionPicturesRequest {
  io::Model before;
  io::Model after;  // the same faces in the same order, sculpted
  ToolPath path;
  std::vector<double> times;            // one per tick [s]
  std::vector<Eigen::Vector3d> forces;  // force on the device per tick [N]
  std::string title;                    // prefix of every picture's title
  /// Displacements up to this are no change [mm] (the scene's eps).
  double tolerance_mm = 0.0;
  /// The scene's tools, and the one held at each tick (`tool_index`, one per
  /// tick; empty: tools[0] throughout). No tools: none is drawn.
  std::vector<PictureTool> tools;
  std::vector<int> tool_index;
  /// The device's orientation R_WD per tick, which poses a B-spline tool
  /// (empty: identity).
  std::vector<Eigen::Quaterniond> rotations;
};

/// The "after" picture's colouring: how far each vertex of `after_mesh` moved
/// from the same (face, u, v) of `before`, signed along the outward normal
/// before (negative: pushed in), on a scale symmetric about 0 up to the
/// largest |displacement|. When no point moved by more than `tolerance_mm`,
/// no colour and a note saying so, with the largest movement.
SurfacePictureOptions after_picture_options(const io::Model& before,
                                            const io::TriangleMesh& after_mesh, double tolerance_mm,
                                            const std::string& title);

/// Writes before.png, after.png (same camera, fitted to both surfaces and the
/// path) and force.png into `folder`, each atomically. Both surface pictures
/// draw the tool where the force on the device peaked while engaged (a
/// B-spline tool posed by the device's pose there, translucent); when the
/// visible change (points that moved more than a tenth of the largest
/// movement, and eps) spans less than a third of the model, after.png adds an
/// inset zoomed on it.
Status write_session_pictures(const SessionPicturesRequest& request,
                              const std::filesystem::path& folder);

}  // namespace argil::sculpt
