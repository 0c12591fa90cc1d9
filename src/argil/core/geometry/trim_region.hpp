#pragma once
// The material part of a trimmed face's parameter domain: closed loops of
// trim curves in (u, v), a point-in-region test on the exact curves, and the
// closest point of the boundary's image on the surface (the face's edge).

#include <Eigen/Core>
#include <limits>
#include <vector>

#include "argil/core/base/status.hpp"
#include "argil/core/geometry/bspline_curve.hpp"
#include "argil/core/geometry/bspline_surface.hpp"
#include "argil/core/geometry/param_rect.hpp"

namespace argil {

/// A closed chain of planar B-spline or NURBS curves in a surface's (u, v)
/// space (BSplineCurve with two point columns), each starting where the
/// previous one ends. Outer loops run counter-clockwise, holes (outer =
/// false) clockwise, so the material lies on the left of every curve.
struct TrimLoop {
  bool outer = true;
  std::vector<BSplineCurve> curves;
};

/// Largest gap between the end of a curve and the start of the next one in a
/// loop (the last one's end and the first one's start included), relative to
/// the diagonal of the loop's control-point box in (u, v). Pcurves of real CAD
/// files end within their edge's 3D tolerance, not exactly where the next one
/// starts: 11752.stp leaves gaps up to 1.6e-3 of the loop. A gap is closed by
/// a straight segment, which is then part of the boundary.
inline constexpr double kMaxTrimGapRatio = 1e-2;

/// Checks trim loops, in this order for each loop: it has curves; each curve
/// is valid (validate(const BSplineCurve&)) with two point columns (u, v);
/// consecutive curves meet within kMaxTrimGapRatio; the loop encloses an
/// area; it runs counter-clockwise when outer and clockwise when a hole.
/// invalid_surface with a message naming the loop and curve and the values
/// ("loop 1 curve 2 ends at (0.5, 0.25), 0.1 from the start of curve 3 ...").
/// An empty list is valid (an untrimmed face).
Status validate_trim_loops(const std::vector<TrimLoop>& loops);

/// A point of a face's edge (the image S(c(t)) of its trim boundary), as
/// the closest to a point in space.
struct TrimEdgePoint {
  Eigen::Vector2d uv = Eigen::Vector2d::Zero();     // c(t), clamped to the surface's domain
  Eigen::Vector3d point = Eigen::Vector3d::Zero();  // S(uv) [mm]
  /// |p - point| [mm]; +infinity when the region has no boundary (untrimmed).
  double distance = std::numeric_limits<double>::infinity();
  int loop = -1;   // index in loops()
  int curve = -1;  // index in the loop's curves; -1 on a straight segment closing a gap
  double t = 0.0;  // parameter on that curve (on a gap segment, 0 at its start to 1)
};

/// The region of (u, v) inside a face's trim loops (even-odd over all loops:
/// inside an outer loop and outside its holes). A value type: build it once
/// per face with create(); every query is const and allocation-light, so it
/// can run at haptic rate. Trims live in parameter space, so the region stays
/// valid while the surface's control points move.
class TrimRegion {
 public:
  /// The untrimmed face: every (u, v) is material and there is no edge.
  TrimRegion() = default;

  /// Validates the loops (validate_trim_loops) and caches each curve's Bezier
  /// pieces with a certified bound on their distance from their chords.
  static Result<TrimRegion> create(std::vector<TrimLoop> loops);

  bool empty() const { return loops_.empty(); }
  const std::vector<TrimLoop>& loops() const { return loops_; }

  /// True when (u, v) lies inside the region, decided on the exact trim
  /// curves: the crossing parity of a ray along +u is taken on the cached
  /// chords, and a piece is subdivided (de Casteljau, exact in homogeneous
  /// coordinates) only while (u, v) lies within its bound of its chord, i.e.
  /// possibly inside its control polygon's hull. Points on the boundary (to
  /// rounding) may fall either way. NaN is outside.
  bool contains(const Eigen::Vector2d& uv) const;

  /// Appends to `out` the pieces whose control-point box touches `rect`
  /// (closed): every piece of the boundary that may pass through it. Stops
  /// once more than `limit` are found (then false: the list is incomplete).
  bool pieces_touching(const ParamRect& rect, std::vector<int>& out,
                       std::size_t limit = std::numeric_limits<std::size_t>::max()) const;
  /// True when some piece's box touches `rect` (the boundary may cross it).
  bool boundary_may_touch(const ParamRect& rect) const;

  /// The point of piece `piece`'s edge image S(c(t)) closest to p_W: samples
  /// (eight intervals per knot span of the surface the piece's box reaches,
  /// at most 128), then Gauss-Newton on |S(c(t)) - p|^2 from the best. A local
  /// search on one piece, not certified; callers bound which pieces to search
  /// (closest_point on a TrimmedSurface, trimmed_contact.hpp).
  /// Precondition: validate(surface).ok().
  TrimEdgePoint closest_on_piece(int piece, const BSplineSurface& surface,
                                 const Eigen::Vector3d& p_W) const;

  /// The box of the cached control points: it holds every loop (empty
  /// region: a zero rectangle).
  ParamRect box() const { return ParamRect::from_corners(lo_, hi_); }

  /// Number of cached pieces (Bezier pieces after subdivision, and gap segments).
  std::size_t piece_count() const { return pieces_.size(); }

  /// A cached piece: a Bezier piece of one curve, or a straight segment
  /// closing a gap. Consecutive pieces of a loop share their end points
  /// bit for bit, so the chords form closed polygons.
  struct Piece {
    Eigen::Vector2d a = Eigen::Vector2d::Zero();   // chord start: the first control point
    Eigen::Vector2d b = Eigen::Vector2d::Zero();   // chord end: the last control point
    Eigen::Vector2d lo = Eigen::Vector2d::Zero();  // box of the control points
    Eigen::Vector2d hi = Eigen::Vector2d::Zero();
    double deviation = 0.0;  // largest distance of a control point from the chord
    int first = 0;           // its first homogeneous control point in the point list
    int degree = 1;
    int loop = 0;
    int curve = -1;             // -1 for a gap segment
    double t0 = 0.0, t1 = 1.0;  // curve parameters of its ends
  };
  /// Cached piece k, k < piece_count().
  const Piece& piece(int k) const { return pieces_[static_cast<std::size_t>(k)]; }

 private:
  /// A node of the bounding-volume tree over the pieces' boxes.
  struct BoxNode {
    Eigen::Vector2d lo = Eigen::Vector2d::Zero();
    Eigen::Vector2d hi = Eigen::Vector2d::Zero();
    int first = 0;  // leaf: pieces tree_pieces_[first, first + count); inner: left child
    int count = 0;  // leaf: > 0; inner: -(right child)
  };
  bool piece_parity(const Piece& piece, const Eigen::Vector2d& uv) const;
  int build_tree(std::vector<int>& order, int begin, int end);

  std::vector<TrimLoop> loops_;
  std::vector<Piece> pieces_;
  std::vector<Eigen::Vector3d> points_;  // homogeneous (w u, w v, w)
  // Horizontal slabs over the region's box, each listing the pieces that
  // reach into it, so contains() looks at the pieces at its v only.
  Eigen::Vector2d lo_ = Eigen::Vector2d::Zero();
  Eigen::Vector2d hi_ = Eigen::Vector2d::Zero();
  double slab_height_ = 1.0;
  std::vector<int> slab_start_;  // slab s lists slab_pieces_[slab_start_[s] .. slab_start_[s + 1])
  std::vector<int> slab_pieces_;
  std::vector<BoxNode> tree_;  // root at 0
  std::vector<int> tree_pieces_;
};

}  // namespace argil
