#include "argil/io/model/topology.hpp"

#include <cmath>
#include <string>

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

}  // namespace argil::io
