#pragma once
// A depth-buffered triangle rasteriser for the pictures: each pixel shows the
// triangle nearest the viewer there. Sorting whole triangles back to front
// (the painter's order) cannot place a long thin triangle beside short ones:
// on a part of tubes inside a long shell, the tubes were painted over the
// shell in streaks.
#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <optional>
#include <vector>

#include "argil/core/geometry/bspline_surface.hpp"

namespace argil::sculpt {

/// One triangle as the camera sees it: pixel corners (x right, y down), each
/// corner's depth (larger is nearer, as Camera::depth), colour (RGB in
/// [0, 1]) and point in the world [mm] (for a clip box).
struct RasterTriangle {
  std::array<Eigen::Vector2d, 3> pixel;
  std::array<double, 3> depth{};
  std::array<Eigen::Vector3d, 3> colour;
  std::array<Eigen::Vector3d, 3> point;
};

/// An orthographic picture being drawn: depth and colour per pixel. Depth,
/// colour and world point are interpolated linearly across a triangle in
/// pixel space, which is exact for an orthographic projection. A pixel is
/// covered when its centre lies inside the triangle or on its edge (so two
/// triangles that share an edge leave no gap between them).
class DepthRaster {
 public:
  DepthRaster(int width, int height);

  /// Draws the triangle where it is nearer than what is there. With `clip`,
  /// only its points inside the box are drawn (a cut-away view of a region).
  void draw(const RasterTriangle& triangle, const std::optional<Box3>& clip = std::nullopt);

  /// Cairo's ARGB32 pixel (premultiplied, alpha in the top byte) at (x, y):
  /// opaque where a triangle was drawn, transparent elsewhere.
  std::uint32_t argb(int x, int y) const { return colour_[index(x, y)]; }

 private:
  std::size_t index(int x, int y) const {
    return static_cast<std::size_t>(y) * static_cast<std::size_t>(width_) +
           static_cast<std::size_t>(x);
  }

  int width_;
  int height_;
  std::vector<double> depth_;  // -inf where nothing is drawn
  std::vector<std::uint32_t> colour_;
};

}  // namespace argil::sculpt
