#include "argil/core/geometry/local_refinement.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <string>

#include "argil/core/base/number_text.hpp"
#include "argil/core/geometry/degree_elevation.hpp"
#include "argil/core/geometry/evaluate.hpp"
#include "argil/core/geometry/knot_insertion.hpp"

namespace argil {

namespace {

/// Distance from x to the polyline through `path`.
double distance_to_path(const Eigen::Vector3d& x, const std::vector<Eigen::Vector3d>& path) {
  double best = (x - path.front()).norm();
  for (std::size_t k = 1; k < path.size(); ++k) {
    const Eigen::Vector3d a = path[k - 1], ab = path[k] - a;
    const double len2 = ab.squaredNorm();
    const double s = len2 > 0.0 ? std::clamp((x - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
    best = std::min(best, (x - (a + s * ab)).norm());
  }
  return best;
}

/// The distinct non-empty knot spans of a direction, as (start, end).
std::vector<std::pair<double, double>> spans_of(const BSplineSurface& s, Direction d) {
  std::vector<std::pair<double, double>> out;
  const Eigen::VectorXd& t = s.knots_in(d);
  for (int k = s.degree_in(d); k < s.count(d); ++k)
    if (t[k] < t[k + 1]) out.emplace_back(t[k], t[k + 1]);
  return out;
}

/// Longest iso-line length [mm] along d over [a, b], across `region`'s extent
/// in the other direction (polylines of 17 points on 9 iso-lines).
double span_length(const BSplineSurface& s, Direction d, double a, double b,
                   const ParamRect& region) {
  const Direction e = other(d);
  constexpr int kLines = 9, kSamples = 17;
  double longest = 0.0;
  for (int i = 0; i < kLines; ++i) {
    const double w = region.start(e) + region.extent(e) * i / (kLines - 1);
    const auto at = [&](double x) {
      return d == Direction::u ? evaluate(s, x, w) : evaluate(s, w, x);
    };
    double length = 0.0;
    Eigen::Vector3d last = at(a);
    for (int k = 1; k < kSamples; ++k) {
      const Eigen::Vector3d next = at(a + (b - a) * k / (kSamples - 1));
      length += (next - last).norm();
      last = next;
    }
    longest = std::max(longest, length);
  }
  return longest;
}

}  // namespace

std::optional<ParamRect> region_near_path(const BSplineSurface& s,
                                          const std::vector<Eigen::Vector3d>& path, double reach) {
  if (path.empty()) return std::nullopt;
  // A cell of the domain with its corners' surface points (00, 10, 01, 11).
  struct Cell {
    double u0, u1, v0, v1;
    std::array<Eigen::Vector3d, 4> corner;
    int depth;
  };
  const auto at = [&s](double u, double v) { return evaluate(s, u, v); };
  std::array<Eigen::VectorXd, 2> grid;
  for (const Direction d : {Direction::u, Direction::v}) {
    const int n = std::clamp(8 * static_cast<int>(spans_of(s, d).size()), 16, 256);
    grid[static_cast<std::size_t>(index_of(d))] =
        Eigen::VectorXd::LinSpaced(n + 1, s.domain_start(d), s.domain_end(d));
  }
  const Eigen::VectorXd &gu = grid[0], &gv = grid[1];
  std::vector<Eigen::Vector3d> points(static_cast<std::size_t>(gu.size() * gv.size()));
  const auto point = [&](Eigen::Index a, Eigen::Index b) -> Eigen::Vector3d& {
    return points[static_cast<std::size_t>(a * gv.size() + b)];
  };
  for (Eigen::Index a = 0; a < gu.size(); ++a)
    for (Eigen::Index b = 0; b < gv.size(); ++b) point(a, b) = at(gu[a], gv[b]);
  std::vector<Cell> todo;
  for (Eigen::Index a = 0; a + 1 < gu.size(); ++a)
    for (Eigen::Index b = 0; b + 1 < gv.size(); ++b)
      todo.push_back({gu[a],
                      gu[a + 1],
                      gv[b],
                      gv[b + 1],
                      {point(a, b), point(a + 1, b), point(a, b + 1), point(a + 1, b + 1)},
                      0});
  // A surface point of a cell lies within the cell's chord (its longer
  // diagonal) of one of its corners (for a cell as flat as the grid makes
  // it), so a cell with a point within reach has a corner within reach +
  // chord. Such cells are halved along each direction whose side is longer
  // than a quarter of the reach, until no side is, so the region follows the
  // path to that slack, not to the coarse grid's (a 1.1 m rod sampled every
  // 72 mm was "near" a 5 mm ball along 150 mm of its length, and 211 of
  // 11752.stp's faces were refined). A cell wholly within reach is kept
  // whole; past kMaxCells cells looked at, kept cells are no longer split.
  constexpr int kMaxSplits = 12;
  constexpr std::size_t kMaxCells = std::size_t{1} << 16;
  const double fine = 0.25 * reach;
  std::size_t looked = 0;
  std::optional<ParamRect> out;
  while (!todo.empty()) {
    const Cell c = todo.back();
    todo.pop_back();
    ++looked;
    const auto& k = c.corner;
    const double chord = std::max((k[3] - k[0]).norm(), (k[2] - k[1]).norm());
    double nearest = std::numeric_limits<double>::infinity(), farthest = 0.0;
    for (const Eigen::Vector3d& x : k) {
      const double d = distance_to_path(x, path);
      nearest = std::min(nearest, d);
      farthest = std::max(farthest, d);
    }
    if (!(nearest <= reach + chord)) continue;
    const bool split_u = std::max((k[1] - k[0]).norm(), (k[3] - k[2]).norm()) > fine;
    const bool split_v = std::max((k[2] - k[0]).norm(), (k[3] - k[1]).norm()) > fine;
    const bool whole = farthest + chord <= reach;
    if (!whole && (split_u || split_v) && c.depth < kMaxSplits && looked < kMaxCells) {
      const int su = split_u ? 2 : 1, sv = split_v ? 2 : 1;
      const std::array<double, 3> us{c.u0, split_u ? 0.5 * (c.u0 + c.u1) : c.u1, c.u1};
      const std::array<double, 3> vs{c.v0, split_v ? 0.5 * (c.v0 + c.v1) : c.v1, c.v1};
      const auto u_at = [&](int i) { return i == su ? c.u1 : us[static_cast<std::size_t>(i)]; };
      const auto v_at = [&](int j) { return j == sv ? c.v1 : vs[static_cast<std::size_t>(j)]; };
      std::array<std::array<Eigen::Vector3d, 3>, 3> g;  // the children's corners
      for (int i = 0; i <= su; ++i) {
        for (int j = 0; j <= sv; ++j) {
          const bool corner = (i == 0 || i == su) && (j == 0 || j == sv);
          g[static_cast<std::size_t>(i)][static_cast<std::size_t>(j)] =
              corner ? k[static_cast<std::size_t>((i == su ? 1 : 0) + (j == sv ? 2 : 0))]
                     : at(u_at(i), v_at(j));
        }
      }
      for (int i = 0; i < su; ++i) {
        for (int j = 0; j < sv; ++j) {
          const auto a = static_cast<std::size_t>(i), b = static_cast<std::size_t>(j);
          todo.push_back({u_at(i),
                          u_at(i + 1),
                          v_at(j),
                          v_at(j + 1),
                          {g[a][b], g[a + 1][b], g[a][b + 1], g[a + 1][b + 1]},
                          c.depth + 1});
        }
      }
      continue;
    }
    const ParamRect cell{c.u0, c.u1, c.v0, c.v1};
    out = out ? ParamRect{std::min(out->u0, cell.u0), std::max(out->u1, cell.u1),
                          std::min(out->v0, cell.v0), std::max(out->v1, cell.v1)}
              : cell;
  }
  return out;
}

Result<Refinement> refine_region(const BSplineSurface& surface, const ParamRect& region,
                                 const RefinementGoal& goal) {
  if (!(goal.resolution > 0.0) || !std::isfinite(goal.resolution)) {
    return Status::error(StatusCode::invalid_argument,
                         "refinement resolution must be a positive length, got " +
                             number_text(goal.resolution) + " mm");
  }
  Refinement out{surface, {}};
  RefinementReport& report = out.report;
  report.degree_before = surface.degree;
  report.count_before = {surface.count(Direction::u), surface.count(Direction::v)};
  report.resolution = goal.resolution;
  for (const Direction d : {Direction::u, Direction::v}) {
    const int target = std::min(goal.min_degree, kMaxElevatedDegree);
    const int p = out.surface.degree_in(d);
    if (p >= target) continue;
    Result<BSplineSurface> raised = elevate_degree(out.surface, d, target - p);
    if (!raised.ok()) return raised.status();
    out.surface = std::move(raised).value();
  }
  // Spans overlapping the region and longer than the resolution, each split
  // into equal parameter pieces. Length is not even in the parameter, so the
  // pieces are measured again until none is too long (a few passes).
  std::array<double, 2> resolution{goal.resolution, goal.resolution};
  for (int pass = 0; pass < 8; ++pass) {
    bool split = false;
    for (const Direction d : {Direction::u, Direction::v}) {
      double& r = resolution[static_cast<std::size_t>(index_of(d))];
      std::vector<std::pair<double, double>> spans;
      std::vector<double> lengths;
      for (const auto& [a, b] : spans_of(out.surface, d)) {
        if (!(b > region.start(d) && a < region.end(d))) continue;
        spans.emplace_back(a, b);
        lengths.push_back(span_length(out.surface, d, a, b, region));
      }
      const auto pieces = [&](std::size_t k) {
        return std::max(1, static_cast<int>(std::ceil(lengths[k] / r * (1.0 - 1e-12))));
      };
      const auto added = [&]() {
        int n = 0;
        for (std::size_t k = 0; k < spans.size(); ++k) n += pieces(k) - 1;
        return n;
      };
      const int room = std::max(0, goal.max_count - out.surface.count(d));
      if (added() > room) {
        report.capped = true;
        if (pass > 0) continue;            // the first pass set how fine this direction goes
        while (added() > room) r *= 1.05;  // coarsen until the net fits
      }
      for (std::size_t k = 0; k < spans.size(); ++k) {
        const auto [a, b] = spans[k];
        const int n = pieces(k);
        for (int m = 1; m < n; ++m) {
          Result<BSplineSurface> refined = insert_knot(out.surface, d, a + (b - a) * m / n, 1);
          if (!refined.ok()) return refined.status();
          out.surface = std::move(refined).value();
          split = true;
        }
      }
    }
    if (!split) break;
  }
  report.resolution = std::max(resolution[0], resolution[1]);
  report.degree_after = out.surface.degree;
  report.count_after = {out.surface.count(Direction::u), out.surface.count(Direction::v)};
  return out;
}

}  // namespace argil
