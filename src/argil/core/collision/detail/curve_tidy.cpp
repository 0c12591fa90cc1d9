#include "argil/core/collision/detail/curve_tidy.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <numeric>
#include <optional>

#include "argil/core/geometry/triangle_distance.hpp"

namespace argil::detail {

namespace {

/// The largest turn at a join, as its cosine: a right angle. Pieces of one
/// branch meet nearly straight; a small closed loop chained from a few leaf
/// segments turns by up to a right angle at each point.
constexpr double kJoinTurnCosine = 0.0;

double distance_to_chord(const Eigen::Vector3d& p, const Eigen::Vector3d& a,
                         const Eigen::Vector3d& b) {
  const Eigen::Vector3d d = b - a;
  const double dd = d.squaredNorm();
  const double t = dd > 0.0 ? std::clamp((p - a).dot(d) / dd, 0.0, 1.0) : 0.0;
  return (a + t * d - p).norm();
}

double distance_to_curve(const Eigen::Vector3d& p, const IntersectionCurve& c) {
  double best = std::numeric_limits<double>::infinity();
  if (c.points.size() == 1) return (c.points[0] - p).norm();
  for (std::size_t k = 0; k + 1 < c.points.size(); ++k)
    best = std::min(best, distance_to_chord(p, c.points[k], c.points[k + 1]));
  return best;
}

void reverse(IntersectionCurve& c) {
  std::reverse(c.points.begin(), c.points.end());
  std::reverse(c.uv_a.begin(), c.uv_a.end());
  std::reverse(c.uv_b.begin(), c.uv_b.end());
}

/// Leaves out a curve's first `k` points.
void drop_front(IntersectionCurve& c, std::size_t k) {
  const auto cut = static_cast<long>(k);
  c.points.erase(c.points.begin(), c.points.begin() + cut);
  c.uv_a.erase(c.uv_a.begin(), c.uv_a.begin() + cut);
  c.uv_b.erase(c.uv_b.begin(), c.uv_b.begin() + cut);
}

/// True when `held` accepts the inner points of the chord from `a` to `b`,
/// taken every `step` at most (its ends are the caller's).
template <class Held>
bool chord_held(const Eigen::Vector3d& a, const Eigen::Vector3d& b, double step, Held&& held) {
  const Eigen::Vector3d d = b - a;
  const double steps = std::ceil(d.norm() / step);
  for (double t = 1.0; t < steps; t += 1.0)
    if (!held(a + (t / steps) * d)) return false;
  return true;
}

/// Appends `tail` to `head`, the meeting points kept once when they coincide.
void append(IntersectionCurve& head, const IntersectionCurve& tail) {
  if (tail.points.empty()) return;
  const std::size_t skip = head.points.back() == tail.points.front() ? 1 : 0;
  head.points.insert(head.points.end(), tail.points.begin() + static_cast<long>(skip),
                     tail.points.end());
  head.uv_a.insert(head.uv_a.end(), tail.uv_a.begin() + static_cast<long>(skip), tail.uv_a.end());
  head.uv_b.insert(head.uv_b.end(), tail.uv_b.begin() + static_cast<long>(skip), tail.uv_b.end());
}

/// The direction a curve leaves its last point (zero when it has no extent).
Eigen::Vector3d out_of_end(const IntersectionCurve& c) {
  for (std::size_t k = c.points.size() - 1; k > 0; --k) {
    const Eigen::Vector3d d = c.points.back() - c.points[k - 1];
    if (d.squaredNorm() > 0.0) return d;
  }
  return Eigen::Vector3d::Zero();
}

/// The direction a curve enters from its first point.
Eigen::Vector3d into_start(const IntersectionCurve& c) {
  for (std::size_t k = 1; k < c.points.size(); ++k) {
    const Eigen::Vector3d d = c.points[k] - c.points.front();
    if (d.squaredNorm() > 0.0) return d;
  }
  return Eigen::Vector3d::Zero();
}

/// True when `head`'s end meets `tail`'s start within eps and the curve runs
/// on in the same direction across the meeting (a curve with no extent runs
/// either way).
bool continues(const IntersectionCurve& head, const IntersectionCurve& tail, double eps) {
  if (!((head.points.back() - tail.points.front()).norm() <= eps)) return false;
  const Eigen::Vector3d out = out_of_end(head), in = into_start(tail);
  const double lengths = out.norm() * in.norm();
  return !(lengths > 0.0) || out.dot(in) >= kJoinTurnCosine * lengths;
}

/// A curve's bounding box grown by eps.
struct Bounds {
  Eigen::Vector3d lo, hi;
  bool holds(const Eigen::Vector3d& p) const {
    return (p.array() >= lo.array()).all() && (p.array() <= hi.array()).all();
  }
  bool meets(const Bounds& o) const {
    return (lo.array() <= o.hi.array()).all() && (o.lo.array() <= hi.array()).all();
  }
};

/// A curve's chords in runs, each with its box grown by `within`, and the
/// runs' boxes merged pairwise, level by level, up to one box: whether a point
/// lies within `within` of a long curve then takes the boxes on the way down
/// to the runs that hold it and those runs' chords, not a pass over every run
/// (covering() asks this every eps/4 along each candidate's chords, and an
/// end's march every 3 eps of its way: 100,000-point curves at 1e-8 have
/// thousands of runs). Consecutive runs lie side by side along the curve, so
/// the merged boxes stay tight.
class ChordRuns {
 public:
  ChordRuns(const IntersectionCurve& c, double within) : c_(c), within_(within) {
    const std::size_t n = c.points.size();
    if (n == 1) add_run(0, 0);
    for (std::size_t first = 0; first + 1 < n; first += kChords)
      add_run(first, std::min(first + kChords, n - 1));
    std::vector<Bounds> level;
    for (const Run& r : runs_) level.push_back(r.box);
    while (level.size() > 1) {
      std::vector<Bounds> up;
      for (std::size_t k = 0; k < level.size(); k += 2)
        up.push_back(k + 1 < level.size() ? merged(level[k], level[k + 1]) : level[k]);
      levels_.push_back(std::move(level));
      level = std::move(up);
    }
    levels_.push_back(std::move(level));
  }

  /// True when some point of the curve lies within `within` of p.
  bool near(const Eigen::Vector3d& p) const {
    // Points asked in turn along a chord (every eps/4) mostly lie by the
    // chord that held the last one: tried first.
    if (last_chord_ + 1 < c_.points.size() &&
        distance_to_chord(p, c_.points[last_chord_], c_.points[last_chord_ + 1]) <= within_)
      return true;
    return any_run(p, p, [&](const Run& r) {
      if (r.first == r.last && (c_.points[r.first] - p).norm() <= within_) return true;
      for (std::size_t k = r.first; k < r.last; ++k)
        if (distance_to_chord(p, c_.points[k], c_.points[k + 1]) <= within_) {
          last_chord_ = k;
          return true;
        }
      return false;
    });
  }

  /// True when some point of the curve lies within `within` of some point of
  /// the segment from p to q.
  bool near_chord(const Eigen::Vector3d& p, const Eigen::Vector3d& q) const {
    const Bounds chord{p.cwiseMin(q), p.cwiseMax(q)};
    return any_run_meeting(chord, [&](const Run& r) {
      if (r.first == r.last) return distance_to_chord(c_.points[r.first], p, q) <= within_;
      for (std::size_t k = r.first; k < r.last; ++k)
        if (segment_segment_distance(p, q, c_.points[k], c_.points[k + 1]) <= within_) return true;
      return false;
    });
  }

  /// True when one chord of the curve lies within `within` of both p and q:
  /// then of every point between them (the distance to a segment is convex).
  bool holds_between(const Eigen::Vector3d& p, const Eigen::Vector3d& q) const {
    return any_run(p, q, [&](const Run& r) {
      for (std::size_t k = r.first; k < r.last; ++k)
        if (distance_to_chord(p, c_.points[k], c_.points[k + 1]) <= within_ &&
            distance_to_chord(q, c_.points[k], c_.points[k + 1]) <= within_)
          return true;
      return false;
    });
  }

 private:
  struct Run {
    Bounds box;
    std::size_t first, last;  // point indices: chords first..last-1
  };

  static Bounds merged(const Bounds& a, const Bounds& b) {
    return {a.lo.cwiseMin(b.lo), a.hi.cwiseMax(b.hi)};
  }

  /// True when `test` accepts a run whose box holds both p and q, tried
  /// down from the top box through the boxes that hold both.
  template <class Test>
  bool any_run(const Eigen::Vector3d& p, const Eigen::Vector3d& q, const Test& test) const {
    return any_run_where([&](const Bounds& box) { return box.holds(p) && box.holds(q); }, test);
  }

  /// True when `test` accepts a run whose box meets `box`.
  template <class Test>
  bool any_run_meeting(const Bounds& box, const Test& test) const {
    return any_run_where([&](const Bounds& b) { return b.meets(box); }, test);
  }

  /// True when `test` accepts a run whose box `keep` accepts, tried down from
  /// the top box through the boxes it accepts.
  template <class Keep, class Test>
  bool any_run_where(const Keep& keep, const Test& test) const {
    if (runs_.empty()) return false;
    // Depth-first, a box's second child waiting: at most one per level.
    std::array<std::pair<std::size_t, std::size_t>, 2 * kMaxLevels> stack;
    std::size_t size = 0;
    stack[size++] = {levels_.size() - 1, 0};
    while (size > 0) {
      const auto [level, index] = stack[--size];
      if (!keep(levels_[level][index])) continue;
      if (level == 0) {
        if (test(runs_[index])) return true;
        continue;
      }
      for (const std::size_t child : {2 * index + 1, 2 * index})
        if (child < levels_[level - 1].size()) stack[size++] = {level - 1, child};
    }
    return false;
  }

  void add_run(std::size_t first, std::size_t last) {
    Bounds b{c_.points[first], c_.points[first]};
    for (std::size_t k = first; k <= last; ++k) {
      b.lo = b.lo.cwiseMin(c_.points[k]);
      b.hi = b.hi.cwiseMax(c_.points[k]);
    }
    // Grown a little more than `within`, so rounding in the box cannot drop
    // a point the distance holds.
    const double grow = within_ * (1.0 + 1e-9) + 1e-300;
    b.lo.array() -= grow;
    b.hi.array() += grow;
    runs_.push_back({b, first, last});
  }

  static constexpr std::size_t kChords = 16;
  static constexpr std::size_t kMaxLevels = 64;  // 2^63 runs
  const IntersectionCurve& c_;
  double within_;
  std::vector<Run> runs_;
  std::vector<std::vector<Bounds>> levels_;  // [0]: the runs' boxes; the last: one box
  mutable std::size_t last_chord_ = 0;
};

Bounds bounds_of(const IntersectionCurve& c, double eps) {
  Bounds b{Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity()),
           Eigen::Vector3d::Constant(-std::numeric_limits<double>::infinity())};
  for (const Eigen::Vector3d& p : c.points) {
    b.lo = b.lo.cwiseMin(p);
    b.hi = b.hi.cwiseMax(p);
  }
  b.lo.array() -= eps;
  b.hi.array() += eps;
  return b;
}

/// The curves (other than `self` and not dropped) that hold every point of
/// curve `self` within `within`, checked at its points and along its chords
/// every `within` / 2 (a stretch of chord whose ends lie within `within` of
/// one chord of a near curve needs no check between them); empty when some
/// point has none near.
/// `runs` are the curves' chord runs built for the same `within`.
std::vector<std::size_t> covering(const std::vector<IntersectionCurve>& curves,
                                  const std::vector<Bounds>& bounds,
                                  const std::vector<ChordRuns>& runs, std::size_t self,
                                  const std::vector<bool>& dropped, double within) {
  std::vector<std::size_t> near;  // the curves whose boxes meet this one's
  for (std::size_t j = 0; j < curves.size(); ++j)
    if (j != self && !dropped[j] && !curves[j].points.empty() && bounds[j].meets(bounds[self]))
      near.push_back(j);
  std::vector<bool> used(curves.size(), false);
  const auto covered = [&](const Eigen::Vector3d& p) {
    for (const std::size_t j : near) {
      if (!bounds[j].holds(p) || !runs[j].near(p)) continue;
      used[j] = true;
      return true;
    }
    return false;
  };
  // A chord whose ends are covered: held by one chord of a near curve, or
  // else its midpoint covered and both halves held, down to within / 2.
  const auto chord_covered = [&](const auto& self_call, const Eigen::Vector3d& p,
                                 const Eigen::Vector3d& q) -> bool {
    if (!((q - p).norm() > 0.5 * within)) return true;
    for (const std::size_t j : near) {
      if (!runs[j].holds_between(p, q)) continue;
      used[j] = true;
      return true;
    }
    const Eigen::Vector3d m = 0.5 * (p + q);
    return covered(m) && self_call(self_call, p, m) && self_call(self_call, m, q);
  };
  const std::vector<Eigen::Vector3d>& points = curves[self].points;
  // Both ends first: cheap, and most curves near others are not covered.
  if (points.empty() || !covered(points.back())) return {};
  for (std::size_t k = 0; k < points.size(); ++k) {
    if (!covered(points[k])) return {};
    if (k + 1 < points.size() && !chord_covered(chord_covered, points[k], points[k + 1])) return {};
  }
  std::vector<std::size_t> out;
  for (std::size_t j = 0; j < curves.size(); ++j)
    if (used[j]) out.push_back(j);
  return out;
}

/// Drops, shortest first, curves no longer than `longest` whose points and
/// chords lie within eps/2 of other kept curves (see tidy_curves()); returns
/// them. `ghosts` are curves an earlier pass dropped: they lean on the curves
/// near them as this pass's drops do.
std::vector<IntersectionCurve> drop_covered(std::vector<IntersectionCurve>& curves,
                                            std::vector<EndReaches>& reaches, double eps,
                                            double longest,
                                            std::vector<IntersectionCurve> ghosts = {}) {
  const std::size_t count = curves.size();
  for (IntersectionCurve& g : ghosts) curves.push_back(std::move(g));
  std::vector<double> lengths(curves.size());
  for (std::size_t i = 0; i < curves.size(); ++i) lengths[i] = curves[i].length();
  // Shortest first, so of two duplicate pieces the longer one stays.
  std::vector<std::size_t> order(count);
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t x, std::size_t y) { return lengths[x] < lengths[y]; });
  std::vector<Bounds> bounds;
  bounds.reserve(curves.size());
  for (const IntersectionCurve& c : curves) bounds.push_back(bounds_of(c, eps));
  const double within = 0.5 * eps;
  std::vector<ChordRuns> runs;
  runs.reserve(curves.size());
  for (const IntersectionCurve& c : curves) runs.emplace_back(c, within);
  std::vector<bool> dropped(curves.size(), false);
  for (std::size_t g = count; g < curves.size(); ++g) dropped[g] = true;
  // A curve that covers a dropped one (its `leaning` pieces) is dropped only
  // when each of those still lies within 3/4 eps of the kept curves (checked
  // likewise, every point then within 15/16 eps); the curves that hold them so
  // are kept (`hard`). So no point of a dropped curve ends up farther than
  // eps from the kept ones. (Two pieces side by side, each covering some of
  // the short pieces along a tangential edge, would otherwise both stay.)
  std::vector<std::vector<std::size_t>> leaning(curves.size());
  std::vector<bool> hard(curves.size(), false);
  std::vector<ChordRuns> loose_runs;  // for 3/4 eps, built when first needed
  const auto loose = [&]() -> const std::vector<ChordRuns>& {
    if (loose_runs.empty())
      for (const IntersectionCurve& c : curves) loose_runs.emplace_back(c, 0.75 * eps);
    return loose_runs;
  };
  for (std::size_t g = count; g < curves.size(); ++g) {
    std::vector<std::size_t> by = covering(curves, bounds, runs, g, dropped, within);
    if (!by.empty()) {
      for (const std::size_t j : by) leaning[j].push_back(g);
      continue;
    }
    // Moved off by the joins since (an overlap left out): held where it is.
    for (const std::size_t j : covering(curves, bounds, loose(), g, dropped, 0.75 * eps))
      hard[j] = true;
  }
  for (const std::size_t i : order) {
    if (curves[i].points.empty()) {
      dropped[i] = true;
      continue;
    }
    if (hard[i] || !(lengths[i] <= longest)) continue;
    // Its points, and its chords every eps/4, within eps/2 of kept curves:
    // every point of it lies within 5/8 eps of them.
    const std::vector<std::size_t> by = covering(curves, bounds, runs, i, dropped, within);
    if (by.empty()) continue;
    dropped[i] = true;
    std::vector<std::size_t> holding;
    bool held = true;
    for (const std::size_t piece : leaning[i]) {
      const std::vector<std::size_t> now =
          covering(curves, bounds, loose(), piece, dropped, 0.75 * eps);
      if (now.empty()) {
        held = false;
        break;
      }
      holding.insert(holding.end(), now.begin(), now.end());
    }
    if (!held) {
      dropped[i] = false;
      continue;
    }
    for (const std::size_t j : holding) hard[j] = true;
    for (const std::size_t j : by) leaning[j].push_back(i);
  }
  std::vector<IntersectionCurve> gone;
  std::size_t kept = 0;
  for (std::size_t i = 0; i < count; ++i) {
    if (dropped[i]) {
      if (!curves[i].points.empty()) gone.push_back(std::move(curves[i]));
      continue;
    }
    if (kept != i) {  // a vector moved onto itself would come out empty
      curves[kept] = std::move(curves[i]);
      reaches[kept] = reaches[i];
    }
    ++kept;
  }
  curves.resize(kept);
  reaches.resize(kept);
  return gone;
}

/// One free end of an open curve: where it is and the direction the curve
/// leaves it by (outward).
struct FreeEnd {
  Eigen::Vector3d point, outward;
};

FreeEnd end_of(const IntersectionCurve& c, bool at_start) {
  return at_start ? FreeEnd{c.points.front(), -into_start(c)}
                  : FreeEnd{c.points.back(), out_of_end(c)};
}

/// Two ends continue each other when they leave in opposite directions, within
/// a right angle (an end with no extent leaves every way).
bool opposite(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  const double lengths = a.norm() * b.norm();
  return !(lengths > 0.0) || -a.dot(b) >= kJoinTurnCosine * lengths;
}

/// Leaves out points within `tiny` of the point kept before them; the last
/// point stays (a closed curve's repeat of its first).
void drop_repeated_points(IntersectionCurve& c, double tiny) {
  if (c.points.size() < 2) return;
  std::size_t kept = 0;
  const std::size_t last = c.points.size() - 1;
  for (std::size_t k = 1; k <= last; ++k) {
    if ((c.points[k] - c.points[kept]).norm() <= tiny) {
      if (k != last) continue;
      if (kept > 0) --kept;  // the last point replaces the one it repeats
    }
    ++kept;
    c.points[kept] = c.points[k];
    c.uv_a[kept] = c.uv_a[k];
    c.uv_b[kept] = c.uv_b[k];
  }
  c.points.resize(kept + 1);
  c.uv_a.resize(kept + 1);
  c.uv_b.resize(kept + 1);
}

/// The first inner point where a curve turns back by more than a right angle
/// (0 when it never does).
std::size_t first_turn_back(const IntersectionCurve& c) {
  for (std::size_t k = 1; k + 1 < c.points.size(); ++k) {
    const Eigen::Vector3d in = c.points[k] - c.points[k - 1], out = c.points[k + 1] - c.points[k];
    if (in.dot(out) < kJoinTurnCosine * in.norm() * out.norm()) return k;
  }
  return 0;
}

/// Leaves out the points before a curve's first turn back when they,
/// and their chords every eps/4, lie within eps/2 of the curve after it: the
/// chain ran out and back along one stretch. (Where a curve runs along a leaf
/// edge that one larger leaf shares with two smaller ones, the larger leaf's
/// segment and the smaller ones' both lie on it, and the chain can start with
/// the first and come back along the others, leaving its neighbour piece a
/// free end at the spike's tip.) Every point left out stays within eps/2 of
/// the curve. Repeats while the new start turns back too.
bool trim_retraced_start(IntersectionCurve& c, double eps) {
  bool trimmed = false;
  for (std::size_t k = first_turn_back(c); k != 0; k = first_turn_back(c)) {
    IntersectionCurve after;
    after.points.assign(c.points.begin() + static_cast<long>(k), c.points.end());
    const double within = 0.5 * eps;
    const ChordRuns after_runs(after, within);
    const auto on_after = [&](const Eigen::Vector3d& p) { return after_runs.near(p); };
    for (std::size_t i = 0; i < k; ++i)
      if (!on_after(c.points[i]) ||
          !chord_held(c.points[i], c.points[i + 1], 0.5 * within, on_after))
        return trimmed;
    drop_front(c, k);
    trimmed = true;
  }
  return trimmed;
}

/// trim_retraced_start() at both ends.
void trim_retraced_ends(IntersectionCurve& c, double eps) {
  if (c.closed()) return;
  trim_retraced_start(c, eps);
  reverse(c);
  trim_retraced_start(c, eps);
  reverse(c);
}

/// A closed curve that runs out along a stretch and back along it encloses
/// nothing: it is the open curve out. (Two segments chained end to end at
/// both ends, pieces of one curve found from either side of a leaf edge; or
/// a larger leaf's segment and its smaller neighbours' along a leaf edge,
/// chained into a loop.) Opened at a point where it turns back, when the
/// stretch from there retraces the rest as trim_retraced_start() asks.
void open_retraced_loop(IntersectionCurve& c, double eps) {
  if (!c.closed()) return;
  const std::size_t n = c.points.size() - 1;  // distinct points; the last repeats the first
  // Such a loop turns back at both its tips, and either will do: only the
  // first two turns are tried (a small loop of a few leaf segments turns by
  // more than a right angle at every point). A loop less than about eps
  // across can pass the test and be opened: at eps it is no loop.
  int turns_tried = 0;
  for (std::size_t k = 0; k < n && turns_tried < 2; ++k) {
    const Eigen::Vector3d in = c.points[k] - c.points[(k + n - 1) % n];
    const Eigen::Vector3d out = c.points[k + 1] - c.points[k];
    if (!(in.dot(out) < kJoinTurnCosine * in.norm() * out.norm())) continue;
    ++turns_tried;
    // The loop from its turn at k, once round, open.
    IntersectionCurve open;
    for (std::size_t i = 0; i <= n; ++i) {
      const std::size_t at = (k + i) % n;
      open.points.push_back(c.points[at]);
      open.uv_a.push_back(c.uv_a[at]);
      open.uv_b.push_back(c.uv_b[at]);
    }
    if (trim_retraced_start(open, eps) && !open.closed()) {
      c = std::move(open);
      return;
    }
  }
}

/// How squarely a free end must face the end it is bridged to: the gap within
/// 60 degrees of the direction each end leaves by. Pieces of one curve leave a
/// gap along the curve; two branches side by side leave one across it.
constexpr double kFacingCosine = 0.5;

bool face_each_other(const FreeEnd& e, const FreeEnd& f) {
  const Eigen::Vector3d gap = f.point - e.point;
  const double le = e.outward.norm() * gap.norm(), lf = f.outward.norm() * gap.norm();
  return le > 0.0 && lf > 0.0 && e.outward.dot(gap) >= kFacingCosine * le &&
         -f.outward.dot(gap) >= kFacingCosine * lf;
}

CurvePoint end_point(const IntersectionCurve& c, bool at_start) {
  const std::size_t k = at_start ? 0 : c.points.size() - 1;
  return {c.points[k], c.uv_a[k], c.uv_b[k]};
}

/// Asks the bridge across a gap once: a failed gap stays failed as curves are
/// joined around it.
class BridgeAsker {
 public:
  explicit BridgeAsker(const GapBridge& bridge) : bridge_(bridge) {}

  std::optional<IntersectionCurve> operator()(const CurvePoint& from, const CurvePoint& to) {
    for (const auto& [p, q] : failed_)
      if ((p == from.point && q == to.point) || (p == to.point && q == from.point))
        return std::nullopt;
    std::optional<IntersectionCurve> between = bridge_(from, to);
    if (!between) failed_.emplace_back(from.point, to.point);
    return between;
  }

 private:
  const GapBridge& bridge_;
  std::vector<std::pair<Eigen::Vector3d, Eigen::Vector3d>> failed_;
};

/// Leaves out the first points of `tail` that lie behind the free end `e`
/// (against the direction it leaves by) and within `reach` of it: where two
/// pieces of one curve overlap, each past the other's end. Returns the length
/// of the chord that led from the last point left out to the new start (0 when
/// none was).
double trim_behind(IntersectionCurve& tail, const FreeEnd& e, double reach) {
  std::size_t behind = 0;
  while (behind < tail.points.size()) {
    const Eigen::Vector3d d = tail.points[behind] - e.point;
    if (!(d.norm() <= reach) || d.dot(e.outward) > 0.0) break;
    ++behind;
  }
  if (behind == 0 || behind == tail.points.size()) return 0.0;
  const double chord = (tail.points[behind] - tail.points[behind - 1]).norm();
  drop_front(tail, behind);
  return chord;
}

/// The points that take `head`'s end on to `tail`'s start across a gap of up
/// to `reach` (after trimming where `tail` overlaps `head` by up to
/// kBridgeReach eps, plus the chord that crossed the end): when the two ends
/// face each other and the bridge runs one branch between them. `tail` comes
/// back trimmed.
std::optional<IntersectionCurve> bridge_gap(const IntersectionCurve& head, IntersectionCurve& tail,
                                            double eps, double reach, BridgeAsker& asker) {
  const FreeEnd e = end_of(head, false);
  const double crossing_chord = trim_behind(tail, e, kBridgeReach * eps);
  if (tail.points.size() < 2) return std::nullopt;
  const FreeEnd f = end_of(tail, true);
  const double gap = (e.point - f.point).norm();
  if (!(gap <= reach + crossing_chord) || !opposite(e.outward, f.outward)) return std::nullopt;
  if (gap > 1e-6 * eps && !face_each_other(e, f)) return std::nullopt;
  return asker(end_point(head, false), end_point(tail, true));
}

/// Joins `tail` on to `head` where the two overlap, each end lying on the
/// other: head's end within eps/2 of a chord of tail that crosses it going on,
/// and tail's points before that chord within eps/2 of head (left out). Where
/// a larger leaf's segment and its smaller neighbours' both lie on one stretch
/// of a curve (a curve along a leaf edge), the chain can split there into two
/// pieces that each run past the other's end.
bool join_overlapping(IntersectionCurve& head, const IntersectionCurve& tail, double eps) {
  const FreeEnd e = end_of(head, false);
  const double within = 0.5 * eps;
  if (tail.points.size() < 2 || !(e.outward.squaredNorm() > 0.0) ||
      !(distance_to_curve(tail.points.front(), head) <= within))
    return false;
  const ChordRuns head_runs(head, within);
  const auto on_head = [&](const Eigen::Vector3d& p) { return head_runs.near(p); };
  for (std::size_t m = 1; m < tail.points.size(); ++m) {
    const Eigen::Vector3d& before = tail.points[m - 1];
    if (!on_head(before)) return false;
    const Eigen::Vector3d chord = tail.points[m] - before;
    if (!((tail.points[m] - e.point).dot(e.outward) > 0.0)) {
      // A chord left out: within eps/2 of head, checked every eps/4.
      if (!chord_held(before, tail.points[m], 0.5 * within, on_head)) return false;
      continue;
    }
    // The chord that passes head's end: it must go on, and pass within eps/2.
    IntersectionCurve crossing;
    crossing.points = {before, tail.points[m]};
    if (!(chord.dot(e.outward) > 0.0) || !(distance_to_curve(e.point, crossing) <= within))
      return false;
    IntersectionCurve rest = tail;
    drop_front(rest, m);
    append(head, rest);
    return true;
  }
  return false;
}

/// How far the bridge may reach across a gap between two ends.
double bridge_reach(double eps, double reach_e, double reach_f) {
  return std::max({kBridgeReach * eps, reach_e, reach_f});
}

double reach_of(const EndReaches& r, bool at_start) { return at_start ? r.front : r.back; }
bool pinned_at(const EndReaches& r, bool at_start) {
  return at_start ? r.front_pinned : r.back_pinned;
}

/// True when a free end of an open curve other than i and j lies nearer to
/// `e` than `gap` and faces it (the two could continue each other).
bool nearer_facing_end(const std::vector<IntersectionCurve>& curves, std::size_t i, std::size_t j,
                       const FreeEnd& e, double gap) {
  for (std::size_t k = 0; k < curves.size(); ++k) {
    if (k == i || k == j || curves[k].closed() || curves[k].points.size() < 2) continue;
    for (const bool at_start : {true, false}) {
      const FreeEnd g = end_of(curves[k], at_start);
      if ((g.point - e.point).norm() < gap && opposite(e.outward, g.outward) &&
          face_each_other(e, g))
        return true;
    }
  }
  return false;
}

/// Joins one pair of open curves that continue each other: ends within eps,
/// or overlapping (join_overlapping()), or with `asker`, ends up to their
/// bridge_reach() apart (or overlapping by up to kBridgeReach eps) through the
/// bridge's points. False when none does.
bool join_one(std::vector<IntersectionCurve>& curves, std::vector<EndReaches>& reaches, double eps,
              BridgeAsker* asker) {
  // An overlap needs each end within eps/2 of the other curve, so inside its box.
  std::vector<Bounds> boxes;
  if (asker == nullptr) {
    boxes.reserve(curves.size());
    for (const IntersectionCurve& c : curves) boxes.push_back(bounds_of(c, 0.5 * eps));
  }
  for (std::size_t i = 0; i < curves.size(); ++i) {
    if (curves[i].closed()) continue;
    for (std::size_t j = i + 1; j < curves.size(); ++j) {
      if (curves[j].closed()) continue;
      // The four ways two open curves can meet: an end of i against an end of j.
      for (int way = 0; way < 4; ++way) {
        const bool i_start = (way & 1) != 0, j_end = (way & 2) != 0;
        const FreeEnd e = end_of(curves[i], i_start), f = end_of(curves[j], !j_end);
        const double gap = (e.point - f.point).norm();
        // The joined curve's ends: i's other end and j's other end.
        const EndReaches joined{reach_of(reaches[i], !i_start), reach_of(reaches[j], j_end),
                                pinned_at(reaches[i], !i_start), pinned_at(reaches[j], j_end)};
        if (asker == nullptr) {
          const bool meet = gap <= eps && opposite(e.outward, f.outward);
          // An overlap needs each end within eps/2 of the other curve.
          if (!meet && !(boxes[i].holds(f.point) && boxes[j].holds(e.point) &&
                         distance_to_curve(f.point, curves[i]) <= 0.5 * eps &&
                         distance_to_curve(e.point, curves[j]) <= 0.5 * eps))
            continue;
          IntersectionCurve head = curves[i], tail = curves[j];
          if (i_start) reverse(head);
          if (j_end) reverse(tail);
          if (meet) {
            append(head, tail);
          } else if (!join_overlapping(head, tail, eps)) {
            continue;
          }
          curves[i] = std::move(head);
        } else {
          const double reach =
              bridge_reach(eps, reach_of(reaches[i], i_start), reach_of(reaches[j], !j_end));
          if (!(gap <= reach)) continue;
          // Within reach only through a pinned end's: the nearest facing ends only.
          const double unpinned_reach = bridge_reach(
              eps, pinned_at(reaches[i], i_start) ? 0.0 : reach_of(reaches[i], i_start),
              pinned_at(reaches[j], !j_end) ? 0.0 : reach_of(reaches[j], !j_end));
          if (gap > unpinned_reach &&
              (nearer_facing_end(curves, i, j, e, gap) || nearer_facing_end(curves, i, j, f, gap)))
            continue;
          IntersectionCurve head = curves[i], tail = curves[j];
          if (i_start) reverse(head);
          if (j_end) reverse(tail);
          const std::optional<IntersectionCurve> between =
              bridge_gap(head, tail, eps, reach, *asker);
          if (!between) continue;
          append(head, *between);
          append(head, tail);
          curves[i] = std::move(head);
        }
        reaches[i] = joined;
        curves.erase(curves.begin() + static_cast<long>(j));
        reaches.erase(reaches.begin() + static_cast<long>(j));
        return true;
      }
    }
  }
  return false;
}

/// Closes an open curve longer than 2 eps whose own ends meet within eps and
/// run on, or with `asker`, whose ends are bridged (as in join_one()) on a
/// curve longer than twice the bridge's reach. A closed curve repeats its first
/// point (replacing a last point within 1e-6 eps of it, as across a periodic
/// face's seam).
void close_if_loop(IntersectionCurve& c, const EndReaches& ends, double eps, BridgeAsker* asker) {
  if (c.closed() || c.points.size() < 3 || !(c.length() > 2.0 * eps)) return;
  if (asker == nullptr) {
    if (!continues(c, c, eps)) return;
  } else {
    // Longer than twice the gap it closes (and than 2 kBridgeReach eps): a
    // loop, not a short arc whose ends the bridge could reach.
    const double gap = (c.points.back() - c.points.front()).norm();
    if (!(gap <= bridge_reach(eps, ends.front, ends.back))) return;
    if (!(c.length() > 2.0 * std::max(kBridgeReach * eps, gap))) return;
    const double reach = bridge_reach(eps, ends.front, ends.back);
    IntersectionCurve trimmed = c;
    const std::optional<IntersectionCurve> between = bridge_gap(c, trimmed, eps, reach, *asker);
    if (!between) return;
    // The loop now starts after the overlap; the bridge leads back to it.
    c = std::move(trimmed);
    append(c, *between);
  }
  if ((c.points.back() - c.points.front()).norm() > 1e-6 * eps) {
    c.points.push_back(c.points.front());
    c.uv_a.push_back(c.uv_a.front());
    c.uv_b.push_back(c.uv_b.front());
  } else {
    c.points.back() = c.points.front();
    c.uv_a.back() = c.uv_a.front();
    c.uv_b.back() = c.uv_b.front();
  }
}

/// A curve no longer than eps: a place where the surfaces meet within eps
/// (open, or a loop less than eps/2 across), not a branch of their
/// intersection.
bool is_touch(const IntersectionCurve& c, double eps) { return !(c.length() > eps); }

/// The curve's points before the stretch of about `length` at its end.
IntersectionCurve before_end(const IntersectionCurve& c, double length) {
  std::size_t k = c.points.size() - 1;
  for (double along = 0.0; k > 0 && along <= length; --k)
    along += (c.points[k] - c.points[k - 1]).norm();
  IntersectionCurve out;
  out.points.assign(c.points.begin(), c.points.begin() + static_cast<long>(k));
  return out;
}

/// Marches each free end of every open curve longer than eps (a touch is no
/// branch: see is_touch()) on (EndMarch), stopping within eps of another curve
/// longer than eps or of its own curve away from the end (a loop, or a march
/// turned back). A march runs over touches: stopped at one, it left the rest
/// of the curve unmarched (bearing.iges faces 160 and 167: 4.2 of 6.1 um).
void march_ends(std::vector<IntersectionCurve>& curves, double eps, const EndMarch& march) {
  // `curves` is not resized here, so the runs' references stay valid; a
  // marched curve's runs are rebuilt.
  std::vector<std::optional<ChordRuns>> runs(curves.size());
  std::vector<bool> touch;
  for (std::size_t i = 0; i < curves.size(); ++i) {
    const IntersectionCurve& c = curves[i];
    runs[i].emplace(c, eps);
    touch.push_back(is_touch(c, eps));
  }
  for (std::size_t i = 0; i < curves.size(); ++i) {
    IntersectionCurve& c = curves[i];
    if (c.closed() || c.points.size() < 2 || touch[i]) continue;
    // The back end, then the front end reversed; reversed back after.
    for (int side = 0; side < 2; ++side) {
      const IntersectionCurve own = before_end(c, 2.0 * eps);
      const ChordRuns own_runs(own, eps);
      const auto stop = [&](const Eigen::Vector3d& from, const Eigen::Vector3d& to) {
        if (own_runs.near_chord(from, to)) return true;
        for (std::size_t j = 0; j < curves.size(); ++j)
          if (j != i && !touch[j] && runs[j]->near_chord(from, to)) return true;
        return false;
      };
      append(c, march(end_point(c, false), end_of(c, false).outward, stop));
      reverse(c);
    }
    runs[i].emplace(c, eps);
  }
}

}  // namespace

std::vector<IntersectionCurve> tidy_curves(std::vector<IntersectionCurve> curves, double eps,
                                           const GapBridge& bridge, std::vector<EndReaches> reaches,
                                           const EndMarch& march) {
  reaches.resize(curves.size());
  for (std::size_t i = 0; i < curves.size(); ++i) {
    IntersectionCurve& c = curves[i];
    drop_repeated_points(c, 1e-6 * eps);
    const bool was_closed = c.closed();
    open_retraced_loop(c, eps);
    // An opened loop's ends are not its chained ends: their reach is unknown.
    if (was_closed && !c.closed()) reaches[i] = {};
    trim_retraced_ends(c, eps);
  }
  // Only short pieces: a longer stretch of a branch that runs within eps/2 of
  // another (a crossing at a small angle) must stay, or the branch splits.
  std::vector<IntersectionCurve> early = drop_covered(curves, reaches, eps, eps);
  while (join_one(curves, reaches, eps, nullptr)) {
  }
  for (std::size_t i = 0; i < curves.size(); ++i)
    close_if_loop(curves[i], reaches[i], eps, nullptr);
  if (bridge) {
    BridgeAsker asker(bridge);
    while (join_one(curves, reaches, eps, &asker)) {
    }
    for (std::size_t i = 0; i < curves.size(); ++i)
      close_if_loop(curves[i], reaches[i], eps, &asker);
  }
  if (march) {
    march_ends(curves, eps, march);
    while (join_one(curves, reaches, eps, nullptr)) {
    }
    for (std::size_t i = 0; i < curves.size(); ++i)
      close_if_loop(curves[i], reaches[i], eps, nullptr);
  }
  // Every curve still no longer than eps is a touch (is_touch()). Then, joined
  // as far as they go, a piece of any length that another curve covers repeats
  // it (a larger leaf's segment beside its smaller neighbours' along a leaf
  // edge). Touches go first, so none is left to cover a longer curve.
  for (std::size_t i = curves.size(); i-- > 0;) {
    if (!is_touch(curves[i], eps)) continue;
    curves.erase(curves.begin() + static_cast<long>(i));
    reaches.erase(reaches.begin() + static_cast<long>(i));
  }
  drop_covered(curves, reaches, eps, std::numeric_limits<double>::infinity(), std::move(early));
  // Pieces joined within eps can meet at points that repeat up to rounding.
  for (IntersectionCurve& c : curves) drop_repeated_points(c, 1e-6 * eps);
  return curves;
}

}  // namespace argil::detail
