#include "argil/io/mesh/tessellate.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <map>
#include <string>
#include <utility>

#include "argil/core/base/number_text.hpp"
#include "argil/core/geometry/evaluate.hpp"
#include "argil/core/geometry/param_rect.hpp"
#include "argil/core/geometry/trim_region.hpp"
#include "argil/io/mesh/detail/occt_face_mesh.hpp"
#include "argil/io/model/trim_curve.hpp"

namespace argil::io {
namespace {

struct Cell {
  ParamRect rect;
  int depth;
};

// Surface points by exact (u, v): shared cell corners are computed by the same
// midpoint arithmetic on both sides, so exact keys identify them.
class VertexCache {
 public:
  explicit VertexCache(const BSplineSurface& surface) : surface_(surface) {}

  int index(double u, double v) {
    const auto [it, inserted] = index_.try_emplace({u, v}, static_cast<int>(uv_.size()));
    if (inserted) {
      uv_.emplace_back(u, v);
      points_.push_back(evaluate(surface_, u, v));
    }
    return it->second;
  }
  const Eigen::Vector3d& point(int i) const { return points_[static_cast<std::size_t>(i)]; }
  const Eigen::Vector2d& uv(int i) const { return uv_[static_cast<std::size_t>(i)]; }
  std::size_t size() const { return uv_.size(); }
  const BSplineSurface& surface() const { return surface_; }

 private:
  const BSplineSurface& surface_;
  std::map<std::pair<double, double>, int> index_;
  std::vector<Eigen::Vector2d> uv_;
  std::vector<Eigen::Vector3d> points_;
};

// Upper bound of the chord error of the fan (centre, boundary[k], boundary[k+1])
// at the sample points of its triangles, compared with the tolerance.
bool fan_within(VertexCache& cache, int centre, const std::vector<int>& boundary,
                double tolerance) {
  const std::size_t n = boundary.size();
  const auto deviation = [&](const Eigen::Vector2d& uv, const Eigen::Vector3d& linear) {
    return (evaluate(cache.surface(), uv.x(), uv.y()) - linear).norm();
  };
  const Eigen::Vector2d& c_uv = cache.uv(centre);
  const Eigen::Vector3d& c_p = cache.point(centre);
  for (std::size_t k = 0; k < n; ++k) {
    const int a = boundary[k];
    const int b = boundary[(k + 1) % n];
    const Eigen::Vector2d a_uv = cache.uv(a), b_uv = cache.uv(b);
    const Eigen::Vector3d a_p = cache.point(a), b_p = cache.point(b);
    if (deviation(0.5 * (a_uv + b_uv), 0.5 * (a_p + b_p)) > tolerance ||
        deviation(0.5 * (c_uv + a_uv), 0.5 * (c_p + a_p)) > tolerance ||
        deviation((c_uv + a_uv + b_uv) / 3.0, (c_p + a_p + b_p) / 3.0) > tolerance) {
      return false;
    }
  }
  return true;
}

std::array<Cell, 4> split(const Cell& c) {
  const std::array<ParamRect, 4> quarters = c.rect.split();
  const int d = c.depth + 1;
  return {Cell{quarters[0], d}, Cell{quarters[1], d}, Cell{quarters[2], d}, Cell{quarters[3], d}};
}

// Corner parameters of all leaves along every constant-u and constant-v line,
// so a cell can find its neighbours' vertices on its own edges.
struct CornerIndex {
  std::map<double, std::vector<double>> v_on_u_line;
  std::map<double, std::vector<double>> u_on_v_line;

  explicit CornerIndex(const std::vector<Cell>& leaves) {
    for (const Cell& cell : leaves) {
      const ParamRect& c = cell.rect;
      for (double u : {c.u0, c.u1}) {
        v_on_u_line[u].push_back(c.v0);
        v_on_u_line[u].push_back(c.v1);
      }
      for (double v : {c.v0, c.v1}) {
        u_on_v_line[v].push_back(c.u0);
        u_on_v_line[v].push_back(c.u1);
      }
    }
    for (auto* lines : {&v_on_u_line, &u_on_v_line}) {
      for (auto& [key, values] : *lines) {
        std::sort(values.begin(), values.end());
        values.erase(std::unique(values.begin(), values.end()), values.end());
      }
    }
  }

  // Values on line `key` within [lo, hi), ascending.
  static std::vector<double> between(const std::map<double, std::vector<double>>& lines, double key,
                                     double lo, double hi) {
    const std::vector<double>& values = lines.at(key);
    return {std::lower_bound(values.begin(), values.end(), lo),
            std::lower_bound(values.begin(), values.end(), hi)};
  }

  // Boundary vertices of a cell, counter-clockwise in (u, v) from (u0, v0).
  std::vector<int> boundary(const Cell& cell, VertexCache& cache) const {
    const ParamRect& c = cell.rect;
    std::vector<int> out;
    for (double u : between(u_on_v_line, c.v0, c.u0, c.u1)) out.push_back(cache.index(u, c.v0));
    for (double v : between(v_on_u_line, c.u1, c.v0, c.v1)) out.push_back(cache.index(c.u1, v));
    std::vector<double> top = between(u_on_v_line, c.v1, c.u0, c.u1);
    top.push_back(c.u1);
    for (auto it = top.rbegin(); it != top.rend() - 1; ++it) out.push_back(cache.index(*it, c.v1));
    std::vector<double> left = between(v_on_u_line, c.u0, c.v0, c.v1);
    left.push_back(c.v1);
    for (auto it = left.rbegin(); it != left.rend() - 1; ++it) {
      out.push_back(cache.index(c.u0, *it));
    }
    return out;
  }
};

int centre_of(const Cell& c, VertexCache& cache) {
  const Eigen::Vector2d m = c.rect.centre();
  return cache.index(m[0], m[1]);
}

// Unit normal at (u, v), the limit normal on a collapsed edge; where even that
// is undefined (a fully collapsed corner) the normal of a point slightly
// towards the domain centre.
Eigen::Vector3d normal_at(const BSplineSurface& surface, Eigen::Vector2d uv) {
  const Eigen::Vector2d centre = domain_of(surface).centre();
  for (int attempt = 0; attempt < 4; ++attempt) {
    const Eigen::Vector3d n = unit_normal(surface, uv.x(), uv.y());
    if (n.squaredNorm() > 0.0) return n;
    uv += 1e-6 * (centre - uv);
  }
  return Eigen::Vector3d::Zero();
}

// Phase 1: each non-empty knot-span patch split by the flatness of its own
// four-corner fan (`min_depth` levels at least).
std::vector<Cell> flat_cells(VertexCache& cache, const TessellationOptions& options,
                             int min_depth) {
  const BSplineSurface& s = cache.surface();
  std::vector<Cell> stack;
  for (Eigen::Index i = s.degree[0]; i < s.count(Direction::u); ++i) {
    for (Eigen::Index j = s.degree[1]; j < s.count(Direction::v); ++j) {
      const Cell root{{s.knots[0][i], s.knots[0][i + 1], s.knots[1][j], s.knots[1][j + 1]}, 0};
      if (root.rect.width() > 0 && root.rect.height() > 0) stack.push_back(root);
    }
  }
  std::vector<Cell> leaves;
  while (!stack.empty()) {
    const Cell c = stack.back();
    stack.pop_back();
    bool flat = c.depth >= options.max_depth;
    if (!flat && c.depth >= min_depth) {
      std::vector<int> corners;
      for (int k : {0, 1, 3, 2}) {  // counter-clockwise
        const Eigen::Vector2d uv = c.rect.corner(k);
        corners.push_back(cache.index(uv[0], uv[1]));
      }
      flat = fan_within(cache, centre_of(c, cache), corners, options.chord_tolerance_mm);
    }
    if (flat) {
      leaves.push_back(c);
    } else {
      for (const Cell& child : split(c)) stack.push_back(child);
    }
  }
  return leaves;
}

// Leaves whose fans, with their neighbours' vertices on shared edges, are all
// within tolerance, and each leaf's boundary vertices.
struct ConformingCells {
  std::vector<Cell> leaves;
  std::vector<std::vector<int>> boundaries;
};

// Phase 2: re-checks and splits until every fan is within tolerance
// (usually one or two rounds).
ConformingCells conforming_cells(std::vector<Cell> leaves, VertexCache& cache,
                                 const TessellationOptions& options) {
  std::vector<std::vector<int>> boundaries;
  while (true) {
    const CornerIndex corners(leaves);
    boundaries.assign(leaves.size(), {});
    std::vector<Cell> next;
    bool changed = false;
    for (std::size_t k = 0; k < leaves.size(); ++k) {
      boundaries[k] = corners.boundary(leaves[k], cache);
      if (leaves[k].depth < options.max_depth && boundaries[k].size() > 4 &&
          !fan_within(cache, centre_of(leaves[k], cache), boundaries[k],
                      options.chord_tolerance_mm)) {
        for (const Cell& child : split(leaves[k])) next.push_back(child);
        changed = true;
      } else {
        next.push_back(leaves[k]);
      }
    }
    if (!changed) break;
    leaves = std::move(next);
  }
  return {std::move(leaves), std::move(boundaries)};
}

// Phase 3: the fans' triangles whose (u, v) centroid is inside the trim.
std::vector<std::array<int, 3>> trimmed_fans(const FaceRecord& face, const ConformingCells& cells,
                                             VertexCache& cache) {
  // The precondition (validate_trim_loops) accepted the loops, so this succeeds.
  const Result<TrimRegion> trims = TrimRegion::create(face.loops);
  assert(trims.ok());
  const TrimRegion region = trims.ok() ? trims.value() : TrimRegion();
  std::vector<std::array<int, 3>> kept;
  for (std::size_t k = 0; k < cells.leaves.size(); ++k) {
    const int c = centre_of(cells.leaves[k], cache);
    const std::vector<int>& b = cells.boundaries[k];
    for (std::size_t e = 0; e < b.size(); ++e) {
      const std::array<int, 3> t{c, b[e], b[(e + 1) % b.size()]};
      const Eigen::Vector2d centroid = (cache.uv(t[0]) + cache.uv(t[1]) + cache.uv(t[2])) / 3.0;
      if (region.contains(centroid)) kept.push_back(t);
    }
  }
  return kept;
}

// The mesh of the kept triangles, compacted to the vertices they use.
TriangleMesh compact_mesh(const FaceRecord& face, const VertexCache& cache,
                          const std::vector<std::array<int, 3>>& kept, int face_index) {
  std::vector<int> remap(cache.size(), -1);
  int used = 0;
  for (const auto& t : kept) {
    for (int v : t) {
      if (remap[static_cast<std::size_t>(v)] < 0) remap[static_cast<std::size_t>(v)] = used++;
    }
  }
  TriangleMesh mesh;
  mesh.positions.resize(used, 3);
  mesh.normals.resize(used, 3);
  mesh.uv.resize(used, 2);
  mesh.vertex_face.assign(static_cast<std::size_t>(used), face_index);
  const double side = face.reversed ? -1.0 : 1.0;
  for (std::size_t v = 0; v < cache.size(); ++v) {
    const int r = remap[v];
    if (r < 0) continue;
    const int vi = static_cast<int>(v);
    mesh.positions.row(r) = cache.point(vi).transpose();
    mesh.uv.row(r) = cache.uv(vi).transpose();
    mesh.normals.row(r) = side * normal_at(face.surface, cache.uv(vi)).transpose();
  }
  mesh.triangles.resize(static_cast<Eigen::Index>(kept.size()), 3);
  for (std::size_t k = 0; k < kept.size(); ++k) {
    const auto& t = kept[k];
    const auto row = static_cast<Eigen::Index>(k);
    // Counter-clockwise in (u, v) faces S_u x S_v; a reversed face flips the order.
    mesh.triangles(row, 0) = remap[static_cast<std::size_t>(t[0])];
    mesh.triangles(row, 1) = remap[static_cast<std::size_t>(face.reversed ? t[2] : t[1])];
    mesh.triangles(row, 2) = remap[static_cast<std::size_t>(face.reversed ? t[1] : t[2])];
  }
  return mesh;
}

/// The largest chord bound of the triangles: |S(u, v) - linear interpolation|
/// at the interpolated (u, v) of each centroid and edge midpoint.
double worst_chord_bound(VertexCache& cache, const std::vector<std::array<int, 3>>& triangles) {
  static constexpr double kWeights[4][3] = {
      {1.0 / 3, 1.0 / 3, 1.0 / 3}, {0.5, 0.5, 0.0}, {0.0, 0.5, 0.5}, {0.5, 0.0, 0.5}};
  double worst = 0.0;
  for (const std::array<int, 3>& t : triangles) {
    for (const auto& w : kWeights) {
      Eigen::Vector2d uv = Eigen::Vector2d::Zero();
      Eigen::Vector3d linear = Eigen::Vector3d::Zero();
      for (int c = 0; c < 3; ++c) {
        uv += w[c] * cache.uv(t[static_cast<std::size_t>(c)]);
        linear += w[c] * cache.point(t[static_cast<std::size_t>(c)]);
      }
      worst = std::max(worst, (evaluate(cache.surface(), uv.x(), uv.y()) - linear).norm());
    }
  }
  return worst;
}

/// A trimmed face meshed conforming to its trim curves by OpenCASCADE's
/// mesher, its deflection tightened until every triangle passes the chord
/// bound; an error when the mesher fails on the face or does not get there.
Result<TriangleMesh> conforming_trimmed(const FaceRecord& face, const TessellationOptions& options,
                                        int face_index) {
  constexpr int kAttempts = 3;
  const double tolerance = options.chord_tolerance_mm;
  double deflection = tolerance;
  for (int attempt = 0; attempt < kAttempts; ++attempt) {
    const Result<detail::FaceTriangles> mesh = detail::occt_face_triangles(face, deflection);
    if (!mesh.ok()) return mesh.status();
    VertexCache cache(face.surface);
    std::vector<int> index;
    index.reserve(mesh.value().uv.size());
    for (const Eigen::Vector2d& uv : mesh.value().uv) index.push_back(cache.index(uv.x(), uv.y()));
    std::vector<std::array<int, 3>> triangles;
    triangles.reserve(mesh.value().triangles.size());
    for (const std::array<int, 3>& t : mesh.value().triangles) {
      const std::array<int, 3> mapped{index[static_cast<std::size_t>(t[0])],
                                      index[static_cast<std::size_t>(t[1])],
                                      index[static_cast<std::size_t>(t[2])]};
      // Nodes at one (u, v) (a pole's or a seam's) share a vertex: drop what collapses.
      if (mapped[0] == mapped[1] || mapped[1] == mapped[2] || mapped[0] == mapped[2]) continue;
      triangles.push_back(mapped);
    }
    const double worst = worst_chord_bound(cache, triangles);
    if (worst <= tolerance) return compact_mesh(face, cache, triangles, face_index);
    // The mesher's deflection is measured at its own points; ours at every
    // triangle's centroid and edge midpoints: tighten by what was missed.
    deflection *= std::clamp(0.8 * tolerance / worst, 0.25, 0.5);
  }
  return Status::error(StatusCode::numerical_failure,
                       "OpenCASCADE's mesher missed the chord tolerance at deflection " +
                           number_text(deflection / 0.25) + " mm and above");
}

/// The knot-span cells' fans, trimmed by their centroids: every untrimmed
/// face, and a trimmed one OpenCASCADE's mesher fails on.
TriangleMesh grid_tessellation(const FaceRecord& face, const TessellationOptions& options,
                               int face_index) {
  const BSplineSurface& s = face.surface;
  // Bezier patches of degree above 3 can wiggle between the few samples of an
  // unsplit cell; one more forced level makes that aliasing unlikely.
  const int min_depth = std::max(s.degree[0], s.degree[1]) > 3 ? 2 : 1;
  VertexCache cache(s);
  const ConformingCells cells =
      conforming_cells(flat_cells(cache, options, min_depth), cache, options);
  return compact_mesh(face, cache, trimmed_fans(face, cells, cache), face_index);
}

}  // namespace

TriangleMesh tessellate_face(const FaceRecord& face, const TessellationOptions& options,
                             int face_index) {
  if (!face.trimmed()) return grid_tessellation(face, options, face_index);
  Result<TriangleMesh> conforming = conforming_trimmed(face, options, face_index);
  if (conforming.ok()) return std::move(conforming.value());
  TriangleMesh approximate = grid_tessellation(face, options, face_index);
  approximate.warnings.push_back("face " + std::to_string(face_index) +
                                 ": trims approximated by whole triangles (" +
                                 conforming.status().message + ")");
  return approximate;
}

namespace {

/// The chord tolerance's range: positive, finite, and not below what float32
/// mesh files can store for this model.
Status check_chord_tolerance(const Model& model, const TessellationOptions& options) {
  if (!(options.chord_tolerance_mm > 0.0) || !std::isfinite(options.chord_tolerance_mm)) {
    return Status::error(StatusCode::invalid_argument, "chord tolerance " +
                                                           number_text(options.chord_tolerance_mm) +
                                                           " mm must be positive and finite");
  }
  // Mesh files store float32 coordinates (about 6e-8 relative); a finer chord
  // tolerance buys nothing and would subdivide without bound.
  constexpr double kFinestRelativeTolerance = 1e-7;
  const double size = model_box(model).diagonal();
  if (options.chord_tolerance_mm < kFinestRelativeTolerance * size) {
    return Status::error(StatusCode::invalid_argument,
                         "chord tolerance " + number_text(options.chord_tolerance_mm) +
                             " mm is below the smallest this model allows, " +
                             limit_text(kFinestRelativeTolerance * size, LimitSide::lower) +
                             " mm (" + number_text(kFinestRelativeTolerance) + " of its " +
                             approx_text(size) +
                             " mm size): finer than float32 mesh files can store");
  }
  return Status::success();
}

}  // namespace

Result<TriangleMesh> tessellate(const Model& model, const TessellationOptions& options) {
  if (const Status range = check_chord_tolerance(model, options); !range.ok()) return range;
  TriangleMesh all;
  std::vector<TriangleMesh> parts;
  Eigen::Index vertices = 0, triangles = 0;
  for (std::size_t f = 0; f < model.faces.size(); ++f) {
    const Status check = validate_face(model.faces[f], f);
    if (!check.ok()) return check;
    const Status loops = validate_trim_loops(model.faces[f].loops);
    if (!loops.ok())
      return Status::error(loops.code, "face " + std::to_string(f) + " " + loops.message);
    parts.push_back(tessellate_face(model.faces[f], options, static_cast<int>(f)));
    vertices += parts.back().positions.rows();
    triangles += parts.back().triangles.rows();
    if (options.max_triangles > 0 && static_cast<std::size_t>(triangles) > options.max_triangles) {
      return Status::error(
          StatusCode::invalid_argument,
          "chord tolerance " + number_text(options.chord_tolerance_mm) +
              " mm gives more than the limit of " + std::to_string(options.max_triangles) +
              " triangles: " + std::to_string(triangles) + " after " + std::to_string(f + 1) +
              " of " + std::to_string(model.faces.size()) + " faces");
    }
  }
  for (std::size_t f = 0; f < model.faces.size(); ++f) {
    const FaceRecord& face = model.faces[f];
    std::string name = "face " + std::to_string(f);
    if (!face.source_id.empty()) name += " " + face.source_id;
    if (!face.name.empty()) name += " " + face.name;
    all.face_names.push_back(std::move(name));
  }
  all.positions.resize(vertices, 3);
  all.normals.resize(vertices, 3);
  all.uv.resize(vertices, 2);
  all.triangles.resize(triangles, 3);
  Eigen::Index v0 = 0, t0 = 0;
  for (const TriangleMesh& part : parts) {
    const Eigen::Index nv = part.positions.rows(), nt = part.triangles.rows();
    all.positions.middleRows(v0, nv) = part.positions;
    all.normals.middleRows(v0, nv) = part.normals;
    all.uv.middleRows(v0, nv) = part.uv;
    all.vertex_face.insert(all.vertex_face.end(), part.vertex_face.begin(), part.vertex_face.end());
    all.warnings.insert(all.warnings.end(), part.warnings.begin(), part.warnings.end());
    all.triangles.middleRows(t0, nt) = part.triangles.array() + static_cast<int>(v0);
    v0 += nv;
    t0 += nt;
  }
  return all;
}

Result<std::size_t> estimate_triangle_count(const Model& model,
                                            const TessellationOptions& options) {
  if (const Status range = check_chord_tolerance(model, options); !range.ok()) return range;
  const double size = model_box(model).diagonal();
  const double t1 = std::max(options.chord_tolerance_mm, 1e-2 * size);
  const double t2 = std::max(options.chord_tolerance_mm, 0.25 * t1);
  TessellationOptions coarse = options;
  coarse.max_triangles = 0;
  coarse.chord_tolerance_mm = t1;
  const Result<TriangleMesh> m1 = tessellate(model, coarse);
  if (!m1.ok()) return m1.status();
  const auto n1 = static_cast<double>(m1.value().triangles.rows());
  if (t2 == t1) return static_cast<std::size_t>(n1);
  coarse.chord_tolerance_mm = t2;
  const Result<TriangleMesh> m2 = tessellate(model, coarse);
  if (!m2.ok()) return m2.status();
  const auto n2 = static_cast<double>(m2.value().triangles.rows());
  if (t2 == options.chord_tolerance_mm) return static_cast<std::size_t>(n2);
  const double b = std::max(0.0, (n2 - n1) / (1.0 / t2 - 1.0 / t1));
  const double a = std::max(0.0, n2 - b / t2);
  return static_cast<std::size_t>(std::ceil(a + b / options.chord_tolerance_mm));
}

}  // namespace argil::io
