#include "argil/core/geometry/trim_region.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <utility>

#include "argil/core/geometry/basis.hpp"
#include "argil/core/geometry/detail/validation_message.hpp"
#include "argil/core/geometry/knot_insertion.hpp"

namespace argil {

namespace {

using detail::defect;
using Piece = TrimRegion::Piece;
using Hull = std::array<Eigen::Vector3d, kMaxDegree + 1>;

/// Pieces are halved when built until their chord bound is at most this
/// fraction of their loop's size, so that few points need refinement.
constexpr double kPieceDeviationRatio = 1e-2;
/// At most this many halvings of one Bezier piece when built.
constexpr int kMaxBuildSplits = 10;
/// contains() stops refining after this many halvings: the piece around
/// (u, v) is then a few ulps wide, and (u, v) lies on the curve to rounding.
constexpr int kMaxQuerySplits = 60;

Eigen::Vector2d cartesian(const Eigen::Vector3d& h) { return h.head<2>() / h.z(); }

double segment_distance(const Eigen::Vector2d& p, const Eigen::Vector2d& a,
                        const Eigen::Vector2d& b) {
  const Eigen::Vector2d ab = b - a;
  const double length2 = ab.squaredNorm();
  const double s = length2 > 0.0 ? std::clamp((p - a).dot(ab) / length2, 0.0, 1.0) : 0.0;
  return (p - (a + s * ab)).norm();
}

/// Whether the ray from uv along +u crosses segment a-b, by the half-open
/// rule (an end counts only when the other end lies strictly above it and
/// this one not), so a closed polygon's crossings are each counted once.
bool ray_crosses(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& uv) {
  if ((a.y() > uv.y()) == (b.y() > uv.y())) return false;
  const double x = a.x() + (uv.y() - a.y()) * (b.x() - a.x()) / (b.y() - a.y());
  return uv.x() < x;
}

/// Chord, box and chord bound of the control points pw[0 .. degree]. With
/// positive weights the piece lies in their convex hull, so within
/// `deviation` of its chord and inside the box.
Piece describe(const Eigen::Vector3d* pw, int degree) {
  Piece piece;
  piece.degree = degree;
  piece.a = cartesian(pw[0]);
  piece.b = cartesian(pw[degree]);
  piece.lo = piece.a.cwiseMin(piece.b);
  piece.hi = piece.a.cwiseMax(piece.b);
  for (int i = 1; i < degree; ++i) {
    const Eigen::Vector2d x = cartesian(pw[i]);
    piece.lo = piece.lo.cwiseMin(x);
    piece.hi = piece.hi.cwiseMax(x);
    piece.deviation = std::max(piece.deviation, segment_distance(x, piece.a, piece.b));
  }
  return piece;
}

/// de Casteljau at s = 1/2 in homogeneous coordinates: the exact halves.
/// left[degree] and right[0] are the same value, so the chords stay chained.
void split_half(const Eigen::Vector3d* pw, int degree, Eigen::Vector3d* left,
                Eigen::Vector3d* right) {
  Hull work;
  std::copy(pw, pw + degree + 1, work.begin());
  left[0] = work[0];
  right[degree] = work[static_cast<std::size_t>(degree)];
  for (int r = 1; r <= degree; ++r) {
    for (int i = 0; i <= degree - r; ++i) {
      const auto k = static_cast<std::size_t>(i);
      work[k] = 0.5 * (work[k] + work[k + 1]);
    }
    left[r] = work[0];
    right[degree - r] = work[static_cast<std::size_t>(degree - r)];
  }
}

/// Crossing parity of the ray from uv with the curve piece pw. The chord
/// gives it whenever uv is outside the piece's hull (then the piece and its
/// chord bound a closed curve that does not wind around uv); otherwise the
/// piece is halved.
bool refined_parity(const Eigen::Vector3d* pw, int degree, const Eigen::Vector2d& uv, int splits) {
  const Piece p = describe(pw, degree);
  if (uv.y() < p.lo.y() || uv.y() > p.hi.y() || uv.x() >= p.hi.x()) return false;
  if (uv.x() < p.lo.x() || p.deviation == 0.0 || splits >= kMaxQuerySplits ||
      segment_distance(uv, p.a, p.b) > p.deviation) {
    return ray_crosses(p.a, p.b, uv);
  }
  Hull left, right;
  split_half(pw, degree, left.data(), right.data());
  return refined_parity(left.data(), degree, uv, splits + 1) !=
         refined_parity(right.data(), degree, uv, splits + 1);
}

/// A curve in Bezier form: every interior knot raised to full multiplicity,
/// so piece e has the homogeneous control points pw[e * degree .. (e + 1) *
/// degree] over [breaks[e], breaks[e + 1]].
struct BezierForm {
  std::vector<Eigen::Vector3d> pw;
  std::vector<double> breaks;
};

BezierForm bezier_form(const BSplineCurve& curve) {
  const int p = curve.degree;
  std::vector<double> interior;
  for (int k = p + 1; k < curve.count(); ++k) {
    if (interior.empty() || curve.knots[k] != interior.back()) interior.push_back(curve.knots[k]);
  }
  BSplineCurve bezier = curve;
  for (const double t : interior) {
    const int m = knot_multiplicity(bezier.knots, t);
    if (m < p) bezier = insert_knot(bezier, t, p - m);
  }
  BezierForm form;
  form.breaks.push_back(curve.domain_start());
  for (const double t : interior) form.breaks.push_back(t);
  form.breaks.push_back(curve.domain_end());
  for (Eigen::Index i = 0; i < bezier.points.rows(); ++i) {
    const double w = bezier.is_rational() ? bezier.weights[i] : 1.0;
    form.pw.emplace_back(w * bezier.points(i, 0), w * bezier.points(i, 1), w);
  }
  return form;
}

/// Corner-to-corner size of a loop's control points in (u, v).
double loop_size(const TrimLoop& loop) {
  Eigen::Vector2d lo = Eigen::Vector2d::Constant(std::numeric_limits<double>::infinity());
  Eigen::Vector2d hi = -lo;
  for (const BSplineCurve& c : loop.curves) {
    lo = lo.cwiseMin(c.points.colwise().minCoeff().transpose().head<2>());
    hi = hi.cwiseMax(c.points.colwise().maxCoeff().transpose().head<2>());
  }
  return (hi - lo).norm();
}

Eigen::Vector2d first_point(const BSplineCurve& c) { return c.points.row(0).transpose(); }
Eigen::Vector2d last_point(const BSplineCurve& c) {
  return c.points.row(c.points.rows() - 1).transpose();
}

/// Every check of validate_trim_loops that needs no pieces.
Status check_structure(const std::vector<TrimLoop>& loops) {
  for (std::size_t l = 0; l < loops.size(); ++l) {
    const std::vector<BSplineCurve>& curves = loops[l].curves;
    if (curves.empty()) return defect("loop ", l, " has no curves");
    for (std::size_t c = 0; c < curves.size(); ++c) {
      const Status s = validate(curves[c]);
      if (!s.ok()) return defect("loop ", l, " curve ", c, ": ", s.message);
      if (curves[c].points.cols() != 2) {
        return defect("loop ", l, " curve ", c, ": points has ", curves[c].points.cols(),
                      " columns, expected 2 (u, v)");
      }
    }
    const double allowed = kMaxTrimGapRatio * loop_size(loops[l]);
    for (std::size_t c = 0; c < curves.size(); ++c) {
      const std::size_t next = (c + 1) % curves.size();
      const Eigen::Vector2d end = last_point(curves[c]);
      const Eigen::Vector2d start = first_point(curves[next]);
      const double gap = (start - end).norm();
      if (!(gap <= allowed)) {
        return defect("loop ", l, " curve ", c, " ends at (u, v) = ", vector_text(end), ", ", gap,
                      " from the start of curve ", next, " at ", vector_text(start),
                      ": gaps must be at most ", limit_text(allowed, LimitSide::upper), " (",
                      kMaxTrimGapRatio, " of the loop's ", approx_text(loop_size(loops[l])),
                      " size in (u, v))");
      }
    }
  }
  return Status::success();
}

/// The cached pieces of all loops and each loop's signed area (of its chords).
struct Pieces {
  std::vector<Piece> pieces;
  std::vector<Eigen::Vector3d> points;
  std::vector<double> area;
};

class PieceBuilder {
 public:
  explicit PieceBuilder(Pieces& out) : out_(out) {}

  void add_loop(const TrimLoop& loop, int l) {
    loop_ = l;
    target_ = kPieceDeviationRatio * loop_size(loop);
    const std::size_t first_piece = out_.pieces.size();
    for (std::size_t c = 0; c < loop.curves.size(); ++c) {
      curve_ = static_cast<int>(c);
      const BezierForm form = bezier_form(loop.curves[c]);
      if (c > 0) close_gap(form.pw.front());
      const int p = loop.curves[c].degree;
      for (std::size_t e = 0; e + 1 < form.breaks.size(); ++e) {
        add(&form.pw[e * static_cast<std::size_t>(p)], p, form.breaks[e], form.breaks[e + 1], 0);
      }
    }
    const Eigen::Vector3d start =
        out_.points[static_cast<std::size_t>(out_.pieces[first_piece].first)];
    close_gap(start);
    double area = 0.0;
    for (std::size_t k = first_piece; k < out_.pieces.size(); ++k) {
      const Piece& piece = out_.pieces[k];
      area += 0.5 * (piece.a.x() * piece.b.y() - piece.a.y() * piece.b.x());
    }
    out_.area.push_back(area);
  }

 private:
  void add(const Eigen::Vector3d* pw, int degree, double t0, double t1, int splits) {
    Piece piece = describe(pw, degree);
    if (piece.deviation > target_ && splits < kMaxBuildSplits) {
      Hull left, right;
      split_half(pw, degree, left.data(), right.data());
      const double mid = 0.5 * (t0 + t1);
      add(left.data(), degree, t0, mid, splits + 1);
      add(right.data(), degree, mid, t1, splits + 1);
      return;
    }
    piece.first = static_cast<int>(out_.points.size());
    piece.loop = loop_;
    piece.curve = curve_;
    piece.t0 = t0;
    piece.t1 = t1;
    out_.points.insert(out_.points.end(), pw, pw + degree + 1);
    out_.pieces.push_back(piece);
    last_ = out_.points.back();
  }

  /// A straight segment from the last piece's end to `next_start` when they
  /// differ, built from the same Cartesian values so the chain stays closed.
  void close_gap(const Eigen::Vector3d& next_start) {
    const Eigen::Vector2d from = cartesian(last_);
    const Eigen::Vector2d to = cartesian(next_start);
    if (from == to) return;
    const std::array<Eigen::Vector3d, 2> segment{Eigen::Vector3d(from.x(), from.y(), 1.0),
                                                 Eigen::Vector3d(to.x(), to.y(), 1.0)};
    const int curve = curve_;
    curve_ = -1;
    add(segment.data(), 1, 0.0, 1.0, 0);
    curve_ = curve;
  }

  Pieces& out_;
  int loop_ = 0;
  int curve_ = 0;
  double target_ = 0.0;
  Eigen::Vector3d last_ = Eigen::Vector3d::Zero();
};

Status check_areas(const std::vector<TrimLoop>& loops, const Pieces& pieces) {
  for (std::size_t l = 0; l < loops.size(); ++l) {
    const double area = pieces.area[l];
    const double size = loop_size(loops[l]);
    // Below this the loop is a sliver of rounding: its side cannot be read.
    if (!(std::abs(area) > 1e-12 * size * size)) {
      return defect("loop ", l, " encloses no area (signed area ", area, " in (u, v))");
    }
    if (loops[l].outer != (area > 0.0)) {
      return defect("loop ", l,
                    loops[l].outer ? " is an outer loop but runs clockwise"
                                   : " is a hole but runs counter-clockwise",
                    " (signed area ", area, " in (u, v)); outer loops run counter-clockwise ",
                    "and holes clockwise: reverse its curves");
    }
  }
  return Status::success();
}

Pieces build_pieces(const std::vector<TrimLoop>& loops) {
  Pieces pieces;
  PieceBuilder builder(pieces);
  for (std::size_t l = 0; l < loops.size(); ++l) builder.add_loop(loops[l], static_cast<int>(l));
  return pieces;
}

}  // namespace

Status validate_trim_loops(const std::vector<TrimLoop>& loops) {
  if (Status s = check_structure(loops); !s.ok()) return s;
  return check_areas(loops, build_pieces(loops));
}

Result<TrimRegion> TrimRegion::create(std::vector<TrimLoop> loops) {
  if (Status s = check_structure(loops); !s.ok()) return s;
  Pieces built = build_pieces(loops);
  if (Status s = check_areas(loops, built); !s.ok()) return s;
  TrimRegion region;
  region.loops_ = std::move(loops);
  region.pieces_ = std::move(built.pieces);
  region.points_ = std::move(built.points);
  if (region.pieces_.empty()) return region;
  region.lo_ = region.pieces_.front().lo;
  region.hi_ = region.pieces_.front().hi;
  for (const Piece& p : region.pieces_) {
    region.lo_ = region.lo_.cwiseMin(p.lo);
    region.hi_ = region.hi_.cwiseMax(p.hi);
  }
  // About two pieces per slab; a flat piece (lo.y == hi.y) never crosses a
  // horizontal ray, so it is listed nowhere.
  const int slabs = static_cast<int>(std::clamp<std::size_t>(region.pieces_.size() / 2, 1, 1024));
  const double height = region.hi_.y() - region.lo_.y();
  region.slab_height_ = height > 0.0 ? height / slabs : 1.0;
  const auto slab_of = [&](double v) {
    return std::clamp(static_cast<int>(std::floor((v - region.lo_.y()) / region.slab_height_)), 0,
                      slabs - 1);
  };
  std::vector<std::vector<int>> lists(static_cast<std::size_t>(slabs));
  for (std::size_t k = 0; k < region.pieces_.size(); ++k) {
    const Piece& p = region.pieces_[k];
    if (!(p.hi.y() > p.lo.y())) continue;
    for (int s = slab_of(p.lo.y()); s <= slab_of(p.hi.y()); ++s)
      lists[static_cast<std::size_t>(s)].push_back(static_cast<int>(k));
  }
  region.slab_start_.push_back(0);
  for (const std::vector<int>& list : lists) {
    region.slab_pieces_.insert(region.slab_pieces_.end(), list.begin(), list.end());
    region.slab_start_.push_back(static_cast<int>(region.slab_pieces_.size()));
  }
  std::vector<int> order(region.pieces_.size());
  for (std::size_t k = 0; k < order.size(); ++k) order[k] = static_cast<int>(k);
  region.build_tree(order, 0, static_cast<int>(order.size()));
  return region;
}

int TrimRegion::build_tree(std::vector<int>& order, int begin, int end) {
  const int id = static_cast<int>(tree_.size());
  tree_.emplace_back();
  Eigen::Vector2d lo = pieces_[static_cast<std::size_t>(order[static_cast<std::size_t>(begin)])].lo;
  Eigen::Vector2d hi = lo;
  Eigen::Vector2d centre_lo = Eigen::Vector2d::Constant(std::numeric_limits<double>::infinity());
  Eigen::Vector2d centre_hi = -centre_lo;
  for (int k = begin; k < end; ++k) {
    const Piece& p = pieces_[static_cast<std::size_t>(order[static_cast<std::size_t>(k)])];
    lo = lo.cwiseMin(p.lo);
    hi = hi.cwiseMax(p.hi);
    centre_lo = centre_lo.cwiseMin(0.5 * (p.lo + p.hi));
    centre_hi = centre_hi.cwiseMax(0.5 * (p.lo + p.hi));
  }
  constexpr int kLeafPieces = 4;
  if (end - begin <= kLeafPieces) {
    tree_[static_cast<std::size_t>(id)] = {lo, hi, static_cast<int>(tree_pieces_.size()),
                                           end - begin};
    tree_pieces_.insert(tree_pieces_.end(), order.begin() + begin, order.begin() + end);
    return id;
  }
  // Median split of the box centres along their longer extent.
  const int axis = (centre_hi - centre_lo).x() >= (centre_hi - centre_lo).y() ? 0 : 1;
  const int mid = (begin + end) / 2;
  std::nth_element(order.begin() + begin, order.begin() + mid, order.begin() + end,
                   [&](int a, int b) {
                     const Piece& pa = pieces_[static_cast<std::size_t>(a)];
                     const Piece& pb = pieces_[static_cast<std::size_t>(b)];
                     return pa.lo[axis] + pa.hi[axis] < pb.lo[axis] + pb.hi[axis];
                   });
  const int left = build_tree(order, begin, mid);
  const int right = build_tree(order, mid, end);
  tree_[static_cast<std::size_t>(id)] = {lo, hi, left, 0};
  tree_[static_cast<std::size_t>(id)].count = -right;  // inner: -(right child)
  return id;
}

bool TrimRegion::piece_parity(const Piece& piece, const Eigen::Vector2d& uv) const {
  if (uv.y() < piece.lo.y() || uv.y() > piece.hi.y() || uv.x() >= piece.hi.x()) return false;
  if (uv.x() < piece.lo.x() || piece.deviation == 0.0 ||
      segment_distance(uv, piece.a, piece.b) > piece.deviation) {
    return ray_crosses(piece.a, piece.b, uv);
  }
  return refined_parity(&points_[static_cast<std::size_t>(piece.first)], piece.degree, uv, 0);
}

bool TrimRegion::contains(const Eigen::Vector2d& uv) const {
  if (loops_.empty()) return true;
  // Outside the box of every loop (NaN included): outside every loop.
  if (!(uv.x() >= lo_.x() && uv.x() <= hi_.x() && uv.y() >= lo_.y() && uv.y() <= hi_.y())) {
    return false;
  }
  const int slabs = static_cast<int>(slab_start_.size()) - 1;
  const int s =
      std::clamp(static_cast<int>(std::floor((uv.y() - lo_.y()) / slab_height_)), 0, slabs - 1);
  bool inside = false;
  for (int k = slab_start_[static_cast<std::size_t>(s)];
       k < slab_start_[static_cast<std::size_t>(s) + 1]; ++k) {
    inside = inside !=
             piece_parity(
                 pieces_[static_cast<std::size_t>(slab_pieces_[static_cast<std::size_t>(k)])], uv);
  }
  return inside;
}

namespace {

bool boxes_touch(const Eigen::Vector2d& lo, const Eigen::Vector2d& hi, const ParamRect& r) {
  return lo.x() <= r.u1 && r.u0 <= hi.x() && lo.y() <= r.v1 && r.v0 <= hi.y();
}

}  // namespace

bool TrimRegion::pieces_touching(const ParamRect& rect, std::vector<int>& out,
                                 std::size_t limit) const {
  if (tree_.empty()) return true;
  const std::size_t start = out.size();
  std::array<int, 128> stack{0};
  int top = 1;
  while (top > 0) {
    const BoxNode& node = tree_[static_cast<std::size_t>(stack[static_cast<std::size_t>(--top)])];
    if (!boxes_touch(node.lo, node.hi, rect)) continue;
    if (node.count > 0) {
      for (int k = node.first; k < node.first + node.count; ++k) {
        const int piece = tree_pieces_[static_cast<std::size_t>(k)];
        const Piece& p = pieces_[static_cast<std::size_t>(piece)];
        if (boxes_touch(p.lo, p.hi, rect)) out.push_back(piece);
        if (out.size() - start > limit) return false;
      }
      continue;
    }
    stack[static_cast<std::size_t>(top++)] = -node.count;
    stack[static_cast<std::size_t>(top++)] = node.first;
  }
  return true;
}

bool TrimRegion::boundary_may_touch(const ParamRect& rect) const {
  if (tree_.empty()) return false;
  std::array<int, 128> stack{0};
  int top = 1;
  while (top > 0) {
    const BoxNode& node = tree_[static_cast<std::size_t>(stack[static_cast<std::size_t>(--top)])];
    if (!boxes_touch(node.lo, node.hi, rect)) continue;
    if (node.count > 0) {
      for (int k = node.first; k < node.first + node.count; ++k) {
        const Piece& p =
            pieces_[static_cast<std::size_t>(tree_pieces_[static_cast<std::size_t>(k)])];
        if (boxes_touch(p.lo, p.hi, rect)) return true;
      }
      continue;
    }
    stack[static_cast<std::size_t>(top++)] = -node.count;
    stack[static_cast<std::size_t>(top++)] = node.first;
  }
  return false;
}

}  // namespace argil
