#pragma once
// The pictures a sculpt run writes: the surfaces before and after with the
// tool path (after: coloured by how far each point moved), and the force plot.

#include <filesystem>
#include <vector>

#include "argil/core/base/status.hpp"
#include "argil/io/model/model.hpp"
#include "argil/sculpt/output/pictures.hpp"

namespace argil::sculpt {

/// File names of the pictures in the output folder.
inline constexpr const char* kBeforePicture = "before.png";
inline constexpr const char* kAfterPicture = "after.png";
inline constexpr const char* kForcePicture = "force.png";

/// Writes before.png, after.png (same camera, fitted to both surfaces and the
/// path) and force.png into `folder`, each atomically. `before` and `after`
/// hold the same faces in the same order (after = sculpted).
Status write_session_pictures(const io::Model& before, const io::Model& after, const ToolPath& path,
                              const std::vector<double>& times,
                              const std::vector<Eigen::Vector3d>& forces, const std::string& title,
                              const std::filesystem::path& folder);

}  // namespace argil::sculpt
