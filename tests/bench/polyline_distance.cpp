#include "polyline_distance.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "support/polyline_distance.hpp"

namespace argil::bench {
namespace {

constexpr std::size_t kRunLength = 32;

}  // namespace

PolylineDistance::PolylineDistance(const std::vector<Polyline>& lines) {
  for (const Polyline& line : lines) {
    for (std::size_t first = 0; first < line.size(); first += kRunLength) {
      const std::size_t last = std::min(line.size() - 1, first + kRunLength);
      Run run{&line, first, last, line[first], line[first]};
      for (std::size_t k = first; k <= last; ++k) {
        run.lo = run.lo.cwiseMin(line[k]);
        run.hi = run.hi.cwiseMax(line[k]);
      }
      runs_.push_back(run);
      if (last + 1 == line.size()) break;
    }
  }
}

double PolylineDistance::operator()(const Eigen::Vector3d& p) const {
  double best = std::numeric_limits<double>::infinity();
  for (const Run& run : runs_) {
    const Eigen::Vector3d outside =
        (run.lo - p).cwiseMax(p - run.hi).cwiseMax(Eigen::Vector3d::Zero());
    if (outside.norm() >= best) continue;
    const Polyline& line = *run.line;
    if (run.first == run.last) best = std::min(best, (line[run.first] - p).norm());
    for (std::size_t k = run.first; k < run.last; ++k)
      best = std::min(best, test::distance_to_segment(p, line[k], line[k + 1]));
  }
  return best;
}

}  // namespace argil::bench
