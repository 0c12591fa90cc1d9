#pragma once
// The intersection peers of bench_intersection, each run on the same pair at
// the same eps: argil (cold: hierarchies built from the surfaces; warm: built
// once, every pole moved between runs, as between haptic ticks), OpenCASCADE
// GeomAPI_IntSS, and SISL s1859 (topology) followed by s1310 (marching) on
// each curve it finds. Each returns its curves as sampled polylines so that
// one error measure applies to all.

#include <Eigen/Core>
#include <string>
#include <vector>

#include "argil/core/geometry/bspline_surface.hpp"

namespace argil::bench {

using Polyline = std::vector<Eigen::Vector3d>;

enum class Peer { argil_cold, argil_warm, occt, sisl };
inline constexpr Peer kPeers[] = {Peer::argil_cold, Peer::argil_warm, Peer::occt, Peer::sisl};
std::string peer_name(Peer peer);

struct PeerOutput {
  double cpu_ms = 0.0;  // median CPU time of one run [ms]
  int runs = 0;
  int curves = 0;                   // curves the peer reports
  std::vector<Polyline> polylines;  // its curves, sampled (argil: its points)

  std::vector<double> to_payload() const;
  static PeerOutput from_payload(const std::vector<double>& payload);
};

/// Runs `peer` on (a, b) at tolerance eps [mm]: repeated up to 7 times or
/// about a second of CPU time, the last run's curves kept. Polynomial
/// surfaces only (SISL is given the polynomial net).
PeerOutput run_peer(Peer peer, const BSplineSurface& a, const BSplineSurface& b, double eps);

}  // namespace argil::bench
