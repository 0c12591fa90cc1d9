#include "support/uniform_refinement.hpp"

#include <cassert>

#include "argil/core/geometry/knot_insertion.hpp"

namespace argil::test {

BSplineSurface halved_spans(BSplineSurface s, int times) {
  for (int k = 0; k < times; ++k) {
    for (const Direction d : {Direction::u, Direction::v}) {
      const Eigen::VectorXd t = s.knots_in(d);
      for (Eigen::Index i = 0; i + 1 < t.size(); ++i) {
        if (!(t[i] < t[i + 1])) continue;
        Result<BSplineSurface> r = insert_knot(s, d, 0.5 * (t[i] + t[i + 1]), 1);
        assert(r.ok());
        s = std::move(r).value();
      }
    }
  }
  return s;
}

}  // namespace argil::test
