#include "argil/core/collision/detail/edge_crossings.hpp"

#include <bit>
#include <cmath>

#include "argil/core/geometry/bspline_surface.hpp"

namespace argil::detail {

namespace {

Eigen::Vector4d params_of(const PairPoint& p) {
  return {p.uv_a[0], p.uv_a[1], p.uv_b[0], p.uv_b[1]};
}

constexpr double kSameStart = 1e-12;

}  // namespace

EdgeCrossings::EdgeCrossings(const SurfacePair& pair) {
  const auto length = [](const BSplineSurface& s, Direction d) {
    return s.domain_end(d) - s.domain_start(d);
  };
  same_ =
      kSameStart * Eigen::Vector4d(length(pair.a(), Direction::u), length(pair.a(), Direction::v),
                                   length(pair.b(), Direction::u), length(pair.b(), Direction::v));
}

std::uint64_t EdgeCrossings::key(const PairPoint& start, int fixed) {
  const double held = params_of(start)[fixed];
  return std::bit_cast<std::uint64_t>(held) * 4 + static_cast<std::uint64_t>(fixed);
}

const RefinedPair* EdgeCrossings::find(const PairPoint& start, int fixed) const {
  const Eigen::Vector4d x = params_of(start);
  const auto [first, last] = by_edge_.equal_range(key(start, fixed));
  for (auto it = first; it != last; ++it) {
    const Entry& e = it->second;
    bool same = e.fixed == fixed && e.start[fixed] == x[fixed];
    for (int k = 0; k < 4 && same; ++k) same = std::abs(e.start[k] - x[k]) <= same_[k];
    if (same) return &e.refined;
  }
  return nullptr;
}

void EdgeCrossings::keep(const PairPoint& start, int fixed, const RefinedPair& refined) {
  by_edge_.emplace(key(start, fixed), Entry{params_of(start), fixed, refined});
}

}  // namespace argil::detail
