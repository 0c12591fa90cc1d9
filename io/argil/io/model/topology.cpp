#include "argil/io/model/topology.hpp"

#include <Eigen/LU>

#include <algorithm>
#include <cmath>
#include <map>
#include <string>

#include "argil/core/base/number_text.hpp"
#include "argil/core/geometry/param_rect.hpp"
#include "argil/io/model/trim_curve.hpp"

namespace argil::io {
namespace {

std::string at(const char* list, std::size_t index) {
  return std::string(list) + "[" + std::to_string(index) + "]";
}

// An index into a list of `size` entries; the message names the field.
Status check_index(std::size_t index, std::size_t size, const std::string& field,
                   const char* what) {
  if (index < size) return Status::success();
  return Status::error(StatusCode::invalid_argument, field + ": " + std::to_string(index) + " of " +
                                                         std::to_string(size) + " " + what);
}

Status check_indices(const std::vector<std::size_t>& indices, std::size_t size,
                     const std::string& field, const char* what) {
  for (std::size_t k = 0; k < indices.size(); ++k) {
    if (Status s = check_index(indices[k], size, at(field.c_str(), k), what); !s.ok()) return s;
  }
  return Status::success();
}

Status check_finite(double value, const std::string& field) {
  if (std::isfinite(value) && value >= 0.0) return Status::success();
  return Status::error(StatusCode::invalid_argument,
                       field + ": " + std::to_string(value) + " is not a finite length");
}

Status check_products(const Topology& t, std::size_t face_count) {
  for (std::size_t p = 0; p < t.products.size(); ++p) {
    const Product& product = t.products[p];
    const std::string field = at("products", p);
    if (product.parent != kNoIndex) {
      if (Status s = check_index(product.parent, p, field + ".parent", "earlier products");
          !s.ok()) {
        return s;  // parents come first, so the tree has no cycle
      }
    }
    if (!product.placement.allFinite()) {
      return Status::error(StatusCode::invalid_argument, field + ".placement: not finite");
    }
    // A rotation and a translation: STEP places parts rigidly, and a mirror or
    // scale would turn a solid inside out or change its size.
    const Eigen::Matrix3d rotation = product.placement.leftCols<3>();
    const double off_orthogonal =
        (rotation.transpose() * rotation - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff();
    if (off_orthogonal > 1e-9 || rotation.determinant() <= 0.0) {
      return Status::error(StatusCode::invalid_argument,
                           field + ".placement: not a rotation and a translation");
    }
    Status s = check_indices(product.solids, t.solids.size(), field + ".solids", "solids");
    if (s.ok()) s = check_indices(product.shells, t.shells.size(), field + ".shells", "shells");
    if (s.ok()) s = check_indices(product.faces, face_count, field + ".faces", "faces");
    if (!s.ok()) return s;
  }
  return Status::success();
}

Status check_edges(const Topology& t, std::size_t face_count) {
  for (std::size_t e = 0; e < t.edges.size(); ++e) {
    const Edge& edge = t.edges[e];
    const std::string field = at("edges", e);
    if (edge.uses.empty()) {
      return Status::error(StatusCode::invalid_argument, field + ".uses: no face uses the edge");
    }
    for (std::size_t u = 0; u < edge.uses.size(); ++u) {
      const std::string use = field + "." + at("uses", u);
      if (Status s = check_index(edge.uses[u].face, face_count, use + ".face", "faces"); !s.ok()) {
        return s;
      }
      if (Status s = validate_trim_curve(edge.uses[u].pcurve); !s.ok()) {
        return Status::error(s.code, use + ".pcurve: " + s.message);
      }
    }
    for (const auto& [vertex, name] :
         {std::pair{edge.start, ".start"}, std::pair{edge.end, ".end"}}) {
      if (vertex == kNoIndex) continue;
      if (Status s = check_index(vertex, t.vertices.size(), field + name, "vertices"); !s.ok()) {
        return s;
      }
    }
    if (Status s = check_finite(edge.tolerance, field + ".tolerance"); !s.ok()) return s;
  }
  return Status::success();
}

std::string use_name(std::size_t edge, std::size_t use) {
  return at("edges", edge) + "." + at("uses", use);
}

// The trim curve's point at fraction s of its parameter range.
Eigen::Vector2d at_fraction(const TrimCurve& c, double s) {
  const double t0 = c.knots[0], t1 = c.knots[c.knots.size() - 1];
  return evaluate_trim_curve(c, t0 + s * (t1 - t0));
}

// How far apart in (u, v) the use's pcurve and the trim curve it stands for
// are, sampled at matching fractions of their ranges (mirrored when the loop
// runs against the edge).
double trace_gap(const EdgeUse& use, const TrimCurve& trim) {
  constexpr int kSamples = 8;
  double gap = 0.0;
  for (int k = 0; k <= kSamples; ++k) {
    const double s = static_cast<double>(k) / kSamples;
    const Eigen::Vector2d on_use = at_fraction(use.pcurve, use.along ? s : 1.0 - s);
    gap = std::max(gap, (on_use - at_fraction(trim, s)).norm());
  }
  return gap;
}

// Where the uses are placed: each face's (loop, curve) slots are taken once,
// without gaps; a trimmed face's slots are its trim curves.
Status check_placement(const Model& model) {
  const Topology& t = model.topology;
  // face -> loop -> curve -> (edge, use)
  std::vector<std::map<std::size_t, std::map<std::size_t, std::pair<std::size_t, std::size_t>>>>
      slots(model.faces.size());
  for (std::size_t e = 0; e < t.edges.size(); ++e) {
    for (std::size_t u = 0; u < t.edges[e].uses.size(); ++u) {
      const EdgeUse& use = t.edges[e].uses[u];
      auto& slot = slots[use.face][use.loop];
      if (slot.count(use.curve) != 0) {
        const auto [e2, u2] = slot.at(use.curve);
        return Status::error(StatusCode::invalid_argument,
                             use_name(e, u) + ": loop " + std::to_string(use.loop) + " curve " +
                                 std::to_string(use.curve) + " of face " +
                                 std::to_string(use.face) + " is taken by " + use_name(e2, u2));
      }
      slot[use.curve] = {e, u};
    }
    // A seam: its face's loop runs along it once and against it once.
    const auto& uses = t.edges[e].uses;
    for (std::size_t a = 0; a < uses.size(); ++a) {
      for (std::size_t b = a + 1; b < uses.size(); ++b) {
        if (uses[a].face == uses[b].face && uses[a].along == uses[b].along) {
          return Status::error(StatusCode::invalid_argument,
                               use_name(e, b) + ": face " + std::to_string(uses[b].face) +
                                   " runs the same way along its seam twice");
        }
      }
    }
  }
  for (std::size_t f = 0; f < model.faces.size(); ++f) {
    const FaceRecord& face = model.faces[f];
    const std::string name = "face " + std::to_string(f);
    std::size_t expected_loop = 0;
    for (const auto& [loop, curves] : slots[f]) {
      if (loop != expected_loop++ || curves.rbegin()->first + 1 != curves.size()) {
        return Status::error(StatusCode::invalid_argument,
                             name + ": its edge uses leave a gap in loop " + std::to_string(loop));
      }
    }
    if (!face.trimmed()) continue;
    if (slots[f].size() != face.loops.size()) {
      return Status::error(StatusCode::invalid_argument,
                           name + ": " + std::to_string(face.loops.size()) + " trim loops, " +
                               "its edge uses make " + std::to_string(slots[f].size()));
    }
    const double tolerance =
        1e-9 * std::max(domain_of(face.surface).width(), domain_of(face.surface).height());
    for (std::size_t l = 0; l < face.loops.size(); ++l) {
      const auto& curves = slots[f].at(l);
      if (curves.size() != face.loops[l].curves.size()) {
        return Status::error(StatusCode::invalid_argument,
                             name + " loop " + std::to_string(l) + ": " +
                                 std::to_string(face.loops[l].curves.size()) +
                                 " trim curves, edge uses for " + std::to_string(curves.size()));
      }
      for (const auto& [k, where] : curves) {
        const EdgeUse& use = t.edges[where.first].uses[where.second];
        if (const double gap = trace_gap(use, face.loops[l].curves[k]); !(gap <= tolerance)) {
          return Status::error(StatusCode::invalid_argument,
                               use_name(where.first, where.second) + ": not the curve of face " +
                                   std::to_string(f) + " loop " + std::to_string(l) + " curve " +
                                   std::to_string(k) + " (" + number_text(gap) +
                                   " apart in (u, v))");
        }
      }
    }
  }
  return Status::success();
}

}  // namespace

TopologyCounts count_topology(const Topology& topology) {
  TopologyCounts c;
  c.products = topology.products.size();
  c.solids = topology.solids.size();
  c.shells = topology.shells.size();
  for (const Shell& shell : topology.shells) c.closed_shells += shell.closed ? 1u : 0u;
  c.edges = topology.edges.size();
  c.vertices = topology.vertices.size();
  for (const Edge& edge : topology.edges) {
    bool distinct = false;
    for (const EdgeUse& use : edge.uses) distinct |= use.face != edge.uses.front().face;
    if (edge.degenerate) {
      ++c.degenerate_edges;
    } else if (distinct) {
      ++c.shared_edges;
    } else if (edge.uses.size() >= 2) {
      ++c.seam_edges;
    } else {
      ++c.free_edges;
    }
  }
  return c;
}

Status validate_topology(const Topology& topology, std::size_t face_count) {
  if (Status s = check_products(topology, face_count); !s.ok()) return s;
  for (std::size_t s = 0; s < topology.solids.size(); ++s) {
    const Solid& solid = topology.solids[s];
    if (solid.shells.empty()) {
      return Status::error(StatusCode::invalid_argument, at("solids", s) + ".shells: none");
    }
    if (Status c = check_indices(solid.shells, topology.shells.size(), at("solids", s) + ".shells",
                                 "shells");
        !c.ok()) {
      return c;
    }
  }
  for (std::size_t s = 0; s < topology.shells.size(); ++s) {
    if (Status c = check_indices(topology.shells[s].faces, face_count, at("shells", s) + ".faces",
                                 "faces");
        !c.ok()) {
      return c;
    }
  }
  if (Status s = check_edges(topology, face_count); !s.ok()) return s;
  for (std::size_t v = 0; v < topology.vertices.size(); ++v) {
    const Vertex& vertex = topology.vertices[v];
    if (!vertex.point.allFinite()) {
      return Status::error(StatusCode::invalid_argument, at("vertices", v) + ".point: not finite");
    }
    if (Status s = check_finite(vertex.tolerance, at("vertices", v) + ".tolerance"); !s.ok()) {
      return s;
    }
  }
  return Status::success();
}

bool uses_placed(const Topology& topology) {
  for (const Edge& edge : topology.edges) {
    for (const EdgeUse& use : edge.uses) {
      if (use.loop == kNoIndex || use.curve == kNoIndex) return false;
    }
  }
  return true;
}

Status validate_topology(const Model& model) {
  if (Status s = validate_topology(model.topology, model.faces.size()); !s.ok()) return s;
  if (model.topology.edges.empty() || !uses_placed(model.topology)) return Status::success();
  for (std::size_t f = 0; f < model.faces.size(); ++f) {
    if (Status s = validate_face(model.faces[f], f); !s.ok()) return s;
  }
  return check_placement(model);
}

}  // namespace argil::io
