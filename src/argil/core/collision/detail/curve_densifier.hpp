#pragma once
// Refined points between consecutive refined points of an intersection curve
// until every chord lies within a tolerance of the curve: the leaf segments
// are as long as the flat leaves, and the exact curve bends away from them.

#include <optional>
#include <vector>

#include "argil/core/collision/contact.hpp"
#include "argil/core/collision/detail/surface_pair_refine.hpp"

namespace argil {

struct HermiteArc;  // the curve between two points, from their tangents

class CurveDensifier {
 public:
  CurveDensifier(const SurfacePair& pair, double tolerance) : pair_(pair), tolerance_(tolerance) {}

  /// The curve with refined points inserted between each two consecutive
  /// refined points (`refined[k]`) of one branch; `tangents` holds the
  /// curve's tangent at the points where refinement found it (or is empty).
  IntersectionCurve run(const IntersectionCurve& c, const std::vector<bool>& refined,
                        const std::vector<std::optional<CurveTangent>>& tangents);

  /// The refined points strictly between two refined points of one branch;
  /// nullopt when a point does not refine onto the curve near its chord, or
  /// the chords do not come within the tolerance of the curve.
  std::optional<IntersectionCurve> between(const PairPoint& lo, const PairPoint& hi);

  /// A curve point with the curve's tangent there (see RefinedPair), found
  /// when first needed: most chords are settled without it.
  struct Node {
    PairPoint at;
    std::optional<CurveTangent> tangent;
  };

 private:
  static constexpr int kMaxDepth = 10;  // at most 2^10 halvings per segment

  const CurveTangent& tangent(Node& n) const;
  void push(const PairPoint& p);
  bool fill(Node& lo, Node& hi, int depth);
  bool fill_along(const HermiteArc& arc, const Node* mid, int pieces);
  bool in_domains(const PairPoint& p) const;

  const SurfacePair& pair_;
  double tolerance_;
  IntersectionCurve out_;
};

}  // namespace argil
