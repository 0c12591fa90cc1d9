#pragma once
// Every node of a hierarchy down to a fixed depth below its roots: what the
// hierarchy bound tests sample.

#include <vector>

#include "argil/core/hierarchy/surface_hierarchy.hpp"

namespace argil::test {

/// Ids of the roots and of every node down to `depth` levels, parents first.
inline std::vector<int> grown_nodes(const SurfaceHierarchy& h, int depth) {
  std::vector<int> ids = h.roots();
  for (std::size_t k = 0; k < ids.size(); ++k) {
    if (h.node(ids[k]).level == depth) continue;
    const int id = ids[k];
    for (int hu = 0; hu < 2; ++hu)
      for (int hv = 0; hv < 2; ++hv) ids.push_back(h.child(id, hu, hv));
  }
  return ids;
}

}  // namespace argil::test
