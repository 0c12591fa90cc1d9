#include "argil/sculpt/output/detail/depth_raster.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace argil::sculpt {

namespace {

std::uint32_t opaque_argb(const Eigen::Vector3d& rgb) {
  const auto channel = [](double c) {
    return static_cast<std::uint32_t>(std::lround(255.0 * std::clamp(c, 0.0, 1.0)));
  };
  return 0xff000000u | (channel(rgb.x()) << 16) | (channel(rgb.y()) << 8) | channel(rgb.z());
}

bool inside(const Box3& box, const Eigen::Vector3d& p) {
  return (p.array() >= box.min.array()).all() && (p.array() <= box.max.array()).all();
}

}  // namespace

DepthRaster::DepthRaster(int width, int height)
    : width_(std::max(width, 0)),
      height_(std::max(height, 0)),
      depth_(static_cast<std::size_t>(width_) * static_cast<std::size_t>(height_),
             -std::numeric_limits<double>::infinity()),
      colour_(depth_.size(), 0u) {}

void DepthRaster::draw(const RasterTriangle& t, const std::optional<Box3>& clip) {
  const Eigen::Vector2d& a = t.pixel[0];
  const Eigen::Vector2d& b = t.pixel[1];
  const Eigen::Vector2d& c = t.pixel[2];
  // Twice the signed area; edge-on or degenerate triangles cover nothing.
  const double area = (b - a).x() * (c - a).y() - (b - a).y() * (c - a).x();
  if (!(std::abs(area) > 0.0) || !std::isfinite(area)) return;
  // Pixel centres (x + 1/2, y + 1/2) within the triangle's box, clamped to the picture.
  const double lo_x = std::min({a.x(), b.x(), c.x()}), hi_x = std::max({a.x(), b.x(), c.x()});
  const double lo_y = std::min({a.y(), b.y(), c.y()}), hi_y = std::max({a.y(), b.y(), c.y()});
  // Clamped as doubles first: a corner far off the picture (a zoomed inset)
  // must not overflow the conversion to int.
  const auto column = [&](double x) { return std::clamp(x, -1.0, static_cast<double>(width_)); };
  const auto row = [&](double y) { return std::clamp(y, -1.0, static_cast<double>(height_)); };
  const int x0 = std::max(0, static_cast<int>(std::ceil(column(lo_x - 0.5))));
  const int x1 = std::min(width_ - 1, static_cast<int>(std::floor(column(hi_x - 0.5))));
  const int y0 = std::max(0, static_cast<int>(std::ceil(row(lo_y - 0.5))));
  const int y1 = std::min(height_ - 1, static_cast<int>(std::floor(row(hi_y - 0.5))));
  if (x0 > x1 || y0 > y1) return;
  // Barycentric weights of a point p: w_k is the area of the sub-triangle
  // opposite corner k over the whole, so the three are >= 0 inside.
  const Eigen::Vector2d corners[3] = {a, b, c};
  const auto weights = [&](const Eigen::Vector2d& p) {
    Eigen::Vector3d w;
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector2d& u = corners[(k + 1) % 3];
      const Eigen::Vector2d& v = corners[(k + 2) % 3];
      w[k] = ((v - u).x() * (p - u).y() - (v - u).y() * (p - u).x()) / area;
    }
    return w;
  };
  // A hair of slack so a pixel centre exactly on a shared edge is covered by
  // both triangles despite rounding.
  const double slack = -1e-12;
  for (int y = y0; y <= y1; ++y) {
    for (int x = x0; x <= x1; ++x) {
      const Eigen::Vector3d w = weights({x + 0.5, y + 0.5});
      if (w.minCoeff() < slack) continue;
      const double d = w[0] * t.depth[0] + w[1] * t.depth[1] + w[2] * t.depth[2];
      const std::size_t i = index(x, y);
      if (!(d > depth_[i])) continue;
      if (clip && !inside(*clip, w[0] * t.point[0] + w[1] * t.point[1] + w[2] * t.point[2]))
        continue;
      depth_[i] = d;
      colour_[i] = opaque_argb(w[0] * t.colour[0] + w[1] * t.colour[1] + w[2] * t.colour[2]);
    }
  }
}

}  // namespace argil::sculpt
