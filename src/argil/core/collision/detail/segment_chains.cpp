#include "argil/core/collision/detail/segment_chains.hpp"

#include <algorithm>
#include <tuple>
#include <utility>

namespace argil::detail {

namespace {

/// Segments whose ends agree this closely (relative to eps) are one segment.
constexpr double kRepeatFraction = 1e-3;

/// End point `e` is point e % 2 of segment e / 2.
class SegmentEnds {
 public:
  explicit SegmentEnds(const std::vector<Segment>& segments) : segments_(segments) {}
  int count() const { return static_cast<int>(2 * segments_.size()); }
  const Segment& segment(int e) const { return segments_[static_cast<std::size_t>(e / 2)]; }
  const Eigen::Vector3d& position(int e) const {
    return segment(e).points[static_cast<std::size_t>(e % 2)];
  }
  /// End points e and f (of different segments) coincide: within eps in space
  /// and within half the smaller leaf on each surface in parameters.
  bool coincide(int e, int f, double eps) const {
    const Segment& s = segment(e);
    const Segment& t = segment(f);
    const auto i = static_cast<std::size_t>(e % 2), j = static_cast<std::size_t>(f % 2);
    return (s.points[i] - t.points[j]).norm() <= eps &&
           (s.uv_a[i] - t.uv_a[j]).cwiseAbs().maxCoeff() <= 0.5 * std::min(s.width_a, t.width_a) &&
           (s.uv_b[i] - t.uv_b[j]).cwiseAbs().maxCoeff() <= 0.5 * std::min(s.width_b, t.width_b);
  }

 private:
  const std::vector<Segment>& segments_;
};

/// Pairs of coinciding end points (distance, lower end, higher end), closest
/// first: a sweep along x finds them.
std::vector<std::tuple<double, int, int>> coinciding_ends(const SegmentEnds& ends, double eps) {
  std::vector<int> by_x(static_cast<std::size_t>(ends.count()));
  for (int e = 0; e < ends.count(); ++e) by_x[static_cast<std::size_t>(e)] = e;
  std::sort(by_x.begin(), by_x.end(), [&](int a, int b) {
    return std::make_pair(ends.position(a).x(), a) < std::make_pair(ends.position(b).x(), b);
  });
  std::vector<std::tuple<double, int, int>> candidates;
  for (std::size_t x = 0; x < by_x.size(); ++x) {
    const int e = by_x[x];
    for (std::size_t y = x + 1; y < by_x.size(); ++y) {
      const int f = by_x[y];
      if (ends.position(f).x() - ends.position(e).x() > eps) break;
      if (e / 2 == f / 2) continue;
      if (ends.coincide(e, f, eps))
        candidates.emplace_back((ends.position(e) - ends.position(f)).norm(), std::min(e, f),
                                std::max(e, f));
    }
  }
  std::sort(candidates.begin(), candidates.end());
  return candidates;
}

/// For each end point, the end point it is matched to (-1 when free).
std::vector<int> match_ends(const SegmentEnds& ends, double eps) {
  std::vector<int> next(static_cast<std::size_t>(ends.count()), -1);
  for (const auto& [d, e, f] : coinciding_ends(ends, eps)) {
    if (next[static_cast<std::size_t>(e)] >= 0 || next[static_cast<std::size_t>(f)] >= 0) continue;
    next[static_cast<std::size_t>(e)] = f;
    next[static_cast<std::size_t>(f)] = e;
  }
  return next;
}

/// Walks chains through matched end points, marking segments used.
class ChainWalker {
 public:
  ChainWalker(const SegmentEnds& ends, std::vector<int> next)
      : ends_(ends), next_(std::move(next)), used_(static_cast<std::size_t>(ends.count() / 2)) {}

  bool used(int e) const { return used_[static_cast<std::size_t>(e / 2)]; }
  bool free_end(int e) const { return next_[static_cast<std::size_t>(e)] < 0; }

  /// Walks from end point `start` (its segment not yet used) until the chain
  /// ends or closes.
  void walk(int start) {
    out_.curves.emplace_back();
    out_.reaches.emplace_back();
    out_.pinned.emplace_back();
    out_.tangents.emplace_back();
    append(start);
    int e = start;
    for (;;) {
      used_[static_cast<std::size_t>(e / 2)] = true;
      const int far = e ^ 1;
      const int f = next_[static_cast<std::size_t>(far)];
      if (f < 0 || used(f)) {
        // Closed when the far end meets the start point.
        append(f == start ? start : far);
        break;
      }
      append(far);
      e = f;
    }
  }

  ChainedCurves take() { return std::move(out_); }

 private:
  void append(int e) {
    const Segment& s = ends_.segment(e);
    const auto k = static_cast<std::size_t>(e % 2);
    IntersectionCurve& c = out_.curves.back();
    out_.reaches.back().push_back(s.reach);
    out_.pinned.back().push_back(s.pinned);
    out_.tangents.back().push_back(s.tangents[k]);
    c.points.push_back(s.points[k]);
    c.uv_a.push_back(s.uv_a[k]);
    c.uv_b.push_back(s.uv_b[k]);
  }

  const SegmentEnds& ends_;
  std::vector<int> next_;
  std::vector<bool> used_;
  ChainedCurves out_;
};

/// The segments less repeats: a segment whose ends both lie within `near` of
/// another kept segment's ends (either way round). A curve along an edge two
/// triangles or two leaves share is found once from each side; chaining both
/// copies would fold the curve back on itself. Every point of a dropped
/// segment lies within `near` of the copy kept.
std::vector<Segment> without_repeats(const std::vector<Segment>& segments, double near) {
  std::vector<std::size_t> by_x(segments.size());
  for (std::size_t i = 0; i < segments.size(); ++i) by_x[i] = i;
  const auto low_x = [&](std::size_t i) {
    return std::min(segments[i].points[0].x(), segments[i].points[1].x());
  };
  std::sort(by_x.begin(), by_x.end(), [&](std::size_t a, std::size_t b) {
    return std::make_pair(low_x(a), a) < std::make_pair(low_x(b), b);
  });
  const auto same = [near](const Segment& s, const Segment& t) {
    const auto close = [near](const Eigen::Vector3d& p, const Eigen::Vector3d& q) {
      return (p - q).norm() <= near;
    };
    return (close(s.points[0], t.points[0]) && close(s.points[1], t.points[1])) ||
           (close(s.points[0], t.points[1]) && close(s.points[1], t.points[0]));
  };
  std::vector<bool> dropped(segments.size(), false);
  for (std::size_t x = 0; x < by_x.size(); ++x) {
    if (dropped[by_x[x]]) continue;
    for (std::size_t y = x + 1; y < by_x.size(); ++y) {
      if (low_x(by_x[y]) - low_x(by_x[x]) > near) break;
      if (!dropped[by_x[y]] && same(segments[by_x[x]], segments[by_x[y]])) dropped[by_x[y]] = true;
    }
  }
  std::vector<Segment> kept;
  kept.reserve(segments.size());
  for (std::size_t i = 0; i < segments.size(); ++i)
    if (!dropped[i]) kept.push_back(segments[i]);
  return kept;
}

}  // namespace

ChainedCurves chain_segments(const std::vector<Segment>& all_segments, double eps) {
  const std::vector<Segment> segments = without_repeats(all_segments, kRepeatFraction * eps);
  const SegmentEnds ends(segments);
  ChainWalker walker(ends, match_ends(ends, eps));
  for (int e = 0; e < ends.count(); ++e)  // open chains from their free ends
    if (!walker.used(e) && walker.free_end(e)) walker.walk(e);
  for (int e = 0; e < ends.count(); e += 2)  // what is left are closed loops
    if (!walker.used(e)) walker.walk(e);
  return walker.take();
}

}  // namespace argil::detail
