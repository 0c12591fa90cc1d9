#pragma once
// Where the intersection curve crosses a leaf edge, refined once: the two
// transversal leaf pairs on either side of a shared edge each find that
// crossing, their triangles meeting the edge at the same point up to rounding.

#include <Eigen/Core>
#include <cstdint>
#include <unordered_map>

#include "argil/core/collision/detail/surface_pair_refine.hpp"

namespace argil::detail {

class EdgeCrossings {
 public:
  /// Two starts are one crossing when every parameter differs by at most its
  /// domain's length times 1e-12: the rounding of leaf corners computed on
  /// either side of an edge, far below any leaf's size.
  explicit EdgeCrossings(const SurfacePair& pair);

  /// The crossing kept from a start within rounding of `start` with the same
  /// parameter `fixed` (0 to 3) held at the same value; null when none is.
  const RefinedPair* find(const PairPoint& start, int fixed) const;
  /// Keeps the refinement `refined` of `start` with parameter `fixed` held.
  void keep(const PairPoint& start, int fixed, const RefinedPair& refined);

 private:
  struct Entry {
    Eigen::Vector4d start;  // (u_a, v_a, u_b, v_b)
    int fixed;
    RefinedPair refined;
  };
  Eigen::Vector4d same_;  // see the constructor
  /// The held parameter's index and value: entries on one edge line.
  static std::uint64_t key(const PairPoint& start, int fixed);
  std::unordered_multimap<std::uint64_t, Entry> by_edge_;
};

}  // namespace argil::detail
