#pragma once
// The pictures a sculpt run writes: the surfaces before and after with the
// tool path (after: coloured by how far each point moved), and the force plot.

#include <filesystem>
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

/// What the pictures of one run show.
struct SessionPicturesRequest {
  io::Model before;
  io::Model after;  // the same faces in the same order, sculpted
  ToolPath path;
  std::vector<double> times;            // one per tick [s]
  std::vector<Eigen::Vector3d> forces;  // force on the device per tick [N]
  std::string title;                    // prefix of every picture's title
};

/// Writes before.png, after.png (same camera, fitted to both surfaces and the
/// path) and force.png into `folder`, each atomically.
Status write_session_pictures(const SessionPicturesRequest& request,
                              const std::filesystem::path& folder);

}  // namespace argil::sculpt
