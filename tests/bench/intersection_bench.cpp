// Surface-surface intersection against the peers a CAD user would reach for,
// on the same pairs at the same eps: argil::collide with refinement (cold, and
// warm as between haptic ticks), OpenCASCADE GeomAPI_IntSS, and SISL s1859 +
// s1310. Pairs: two crossing panels (16x16 vs 8x8 and 32x32 vs 16x16 poles),
// the wavy pair, and random graph pairs. eps from 1e-3 to 1e-8 of the pair's
// size. Each peer runs in a child process with a time limit (a hang is
// reported, not waited on) and is judged by the same measures: CPU time
// (median of up to 7 runs), whether it returned, its curve count against the
// true count, and its achieved error: the largest distance of its points to
// either surface (OpenCASCADE projection) and the largest distance from the
// oracle's dense curve samples to its curves (coverage; a missed curve shows
// here). SISL is AGPL: linked into this benchmark only.
//
// Usage: bench_intersection [pair,pair,...] [--limit SECONDS] [--peers NAME,NAME]
//                           [--exponents 3,4,...]
// Lines starting "ssi-csv," feed plot_intersection.py.
#include <GeomAPI_ProjectPointOnSurf.hxx>
#include <Precision.hxx>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <map>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "bench_surfaces.hpp"
#include "core/collision/surface_pairs.hpp"
#include "guarded_run.hpp"
#include "intersection_oracle.hpp"
#include "intersection_peers.hpp"
#include "polyline_distance.hpp"

namespace {

using argil::BSplineSurface;
using namespace argil::bench;

struct Pair {
  std::string name;
  BSplineSurface a, b;
  bool graph = false;  // both surfaces are z over the same (x, y): brute-force oracle
  double size = 0.0;   // diagonal of both control-point boxes together [mm]
};

double pair_size(const BSplineSurface& a, const BSplineSurface& b) {
  argil::Box3 box = argil::control_point_box(a);
  const argil::Box3 box_b = argil::control_point_box(b);
  box.min = box.min.cwiseMin(box_b.min);
  box.max = box.max.cwiseMax(box_b.max);
  return box.diagonal();
}

/// Panel n_a crossed by panel n_b turned 70 degrees about a horizontal axis at
/// 30 degrees heading, centred on the middle of panel a.
Pair crossing_pair(int n_a, int n_b) {
  Pair p{"panels" + std::to_string(n_a) + "x" + std::to_string(n_b), bicubic_panel(n_a),
         bicubic_panel(n_b)};
  constexpr double kPi = 3.14159265358979323846;
  const Eigen::Vector3d axis(std::cos(kPi / 6), std::sin(kPi / 6), 0.0);
  const Eigen::Matrix3d r = Eigen::AngleAxisd(70.0 * kPi / 180.0, axis).toRotationMatrix();
  const Eigen::Vector3d t = argil::evaluate(p.a, 0.5, 0.5) - r * argil::evaluate(p.b, 0.5, 0.5);
  p.b = argil::test::moved(p.b, r, t);
  return p;
}

/// Two random polynomial graphs over a 100 mm square (degrees 1 to 5, random
/// non-uniform knots with repeats), z within +-10 mm: curves of any shape and
/// number, closed loops among them.
Pair random_pair(int seed) {
  std::mt19937_64 rng(static_cast<std::uint64_t>(seed));
  Pair p{"random" + std::to_string(seed), argil::test::graph_surface(rng, 100.0, 10.0, 0.0, 5, 8),
         argil::test::graph_surface(rng, 100.0, 10.0, 0.0, 5, 8), true};
  return p;
}

std::vector<Pair> all_pairs() {
  std::vector<Pair> pairs{crossing_pair(16, 8), crossing_pair(32, 16)};
  const auto [wa, wb] = argil::test::wavy_pair();
  pairs.push_back({"wavy", wa, wb, true});
  for (int seed = 1; seed <= 4; ++seed) pairs.push_back(random_pair(seed));
  for (Pair& p : pairs) p.size = pair_size(p.a, p.b);
  return pairs;
}

struct Cell {
  std::string outcome = "returned";
  PeerOutput output;
  double on_surface = 0.0, coverage = 0.0;  // relative to the pair's size
};

std::string relative_text(double v) {
  if (!std::isfinite(v)) return "inf";
  char text[32];
  std::snprintf(text, sizeof text, "%.2g", v);
  return text;
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::string> only;
  std::vector<std::string> peers_only;
  std::vector<int> exponents{3, 4, 5, 6, 7, 8};
  double limit_s = 30.0;
  const auto split = [](const char* text) {
    std::vector<std::string> out;
    std::stringstream items(text);
    for (std::string item; std::getline(items, item, ',');) out.push_back(item);
    return out;
  };
  const char* usage =
      "usage: bench_intersection [pair,pair,...] [--limit SECONDS] [--peers NAME,NAME]\n"
      "                          [--exponents 3,4,...]\n";
  const auto refuse = [&](const std::string& why) {
    std::fprintf(stderr, "bench_intersection: %s\n%s", why.c_str(), usage);
    return 2;
  };
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--help" || arg == "-h") {
      std::printf("%s", usage);
      return 0;
    }
    const bool option = arg == "--limit" || arg == "--peers" || arg == "--exponents";
    if (option && i + 1 == argc) return refuse(arg + " needs a value");
    if (arg == "--limit") {
      char* end = nullptr;
      limit_s = std::strtod(argv[++i], &end);
      if (*end != '\0' || !(limit_s > 0.0))
        return refuse("--limit wants seconds above 0, not '" + std::string(argv[i]) + "'");
    } else if (arg == "--peers") {
      peers_only = split(argv[++i]);
    } else if (arg == "--exponents") {
      exponents.clear();
      for (const std::string& e : split(argv[++i])) {
        char* end = nullptr;
        const long x = std::strtol(e.c_str(), &end, 10);
        if (e.empty() || *end != '\0' || x < 1 || x > 15)
          return refuse("--exponents wants integers 1 to 15, not '" + e + "'");
        exponents.push_back(static_cast<int>(x));
      }
    } else if (arg.rfind("--", 0) == 0) {
      return refuse("unknown option '" + arg + "'");
    } else {
      for (const std::string& name : split(argv[i])) only.push_back(name);
    }
  }
  // A misspelt pair or peer would silently measure nothing.
  const std::vector<Pair> pairs = all_pairs();
  std::string pair_names, peer_names;
  for (const Pair& pair : pairs) pair_names += " " + pair.name;
  for (Peer peer : kPeers) peer_names += " " + peer_name(peer);
  for (const std::string& name : only) {
    if (std::none_of(pairs.begin(), pairs.end(), [&](const Pair& p) { return p.name == name; })) {
      return refuse("unknown pair '" + name + "' (pairs:" + pair_names + ")");
    }
  }
  for (const std::string& name : peers_only) {
    if (std::none_of(std::begin(kPeers), std::end(kPeers),
                     [&](Peer p) { return peer_name(p) == name; })) {
      return refuse("unknown peer '" + name + "' (peers:" + peer_names + ")");
    }
  }
  std::printf(
      "Surface-surface intersection: CPU time (median of up to 7 runs) and achieved error,\n"
      "relative to the pair's size: on-surf = largest distance of the peer's points to either\n"
      "surface; coverage = largest distance from the oracle's curve samples to the peer's\n"
      "curves. Each peer runs in a child process, stopped after %.0f s of CPU time.\n",
      limit_s);
  // (pair, eps exponent) -> peer -> ms, for the peers that returned a result
  // that is not wrong: a missed curve or a failure has no time to compare.
  std::map<std::pair<std::string, int>, std::map<std::string, double>> times;
  for (const Pair& pair : pairs) {
    if (!only.empty() && std::find(only.begin(), only.end(), pair.name) == only.end()) continue;
    const OracleCurves oracle =
        pair.graph ? graph_oracle(pair.a, pair.b, 1000) : occt_oracle(pair.a, pair.b, pair.size);
    std::printf(
        "\n## %s: poles %dx%d / %dx%d, degrees %dx%d / %dx%d, size %.4g mm\n"
        "oracle: %s; %d curve(s), %zu samples, residual %.2g of the size\n",
        pair.name.c_str(), pair.a.count(argil::Direction::u), pair.a.count(argil::Direction::v),
        pair.b.count(argil::Direction::u), pair.b.count(argil::Direction::v), pair.a.degree[0],
        pair.a.degree[1], pair.b.degree[0], pair.b.degree[1], pair.size, oracle.method.c_str(),
        oracle.components, oracle.samples.size(), oracle.residual / pair.size);
    std::printf("%-6s  %-10s  %-22s  %10s  %4s  %6s  %8s  %8s\n", "eps", "peer", "outcome",
                "CPU [ms]", "runs", "curves", "on-surf", "coverage");
    SurfaceDistance to_surfaces(pair.a, pair.b, pair.graph);
    for (int e : exponents) {
      const double eps = std::pow(10.0, -e) * pair.size;
      for (Peer peer : kPeers) {
        if (!peers_only.empty() &&
            std::find(peers_only.begin(), peers_only.end(), peer_name(peer)) == peers_only.end())
          continue;
        Cell cell;
        const GuardedResult run =
            run_guarded([&] { return run_peer(peer, pair.a, pair.b, eps).to_payload(); }, limit_s);
        if (run.outcome == GuardedResult::Outcome::returned) {
          cell.output = PeerOutput::from_payload(run.payload);
          cell.on_surface = to_surfaces.worst(cell.output.polylines) / pair.size;
          const PolylineDistance distance(cell.output.polylines);
          for (const Eigen::Vector3d& q : oracle.samples)
            cell.coverage = std::max(cell.coverage, distance(q));
          cell.coverage /= pair.size;
          if (cell.output.curves < 0) cell.outcome = "returned, failed";
        } else {
          cell.outcome = run.detail;
          cell.on_surface = cell.coverage = HUGE_VAL;
        }
        const bool returned = run.outcome == GuardedResult::Outcome::returned;
        const std::string curves =
            std::to_string(cell.output.curves) + "/" + std::to_string(oracle.components);
        std::printf("1e-%-3d  %-10s  %-22s  %10.4g  %4d  %6s  %8s  %8s\n", e,
                    peer_name(peer).c_str(), cell.outcome.c_str(),
                    returned ? cell.output.cpu_ms : NAN, cell.output.runs,
                    returned ? curves.c_str() : "-", relative_text(cell.on_surface).c_str(),
                    relative_text(cell.coverage).c_str());
        std::printf("ssi-csv,%s,1e-%d,%s,%s,%.6g,%d,%d,%.6g,%.6g\n", pair.name.c_str(), e,
                    peer_name(peer).c_str(), returned ? "returned" : "no-return",
                    returned ? cell.output.cpu_ms : -1.0, returned ? cell.output.curves : -1,
                    oracle.components, cell.on_surface, cell.coverage);
        std::fflush(stdout);
        if (returned && cell.output.curves == oracle.components && std::isfinite(cell.coverage))
          times[{pair.name, e}][peer_name(peer)] = cell.output.cpu_ms;
      }
    }
  }
  std::printf(
      "\nCPU time ratios, same run (> 1: argil slower; '-' where the peer failed, missed a\n"
      "curve or found too many):\n%-12s %6s  %10s  %10s\n",
      "pair", "eps", "argil/occt", "argil/sisl");
  for (const auto& [key, peers] : times) {
    const auto ratio = [&](const char* peer) {
      const auto it = peers.find(peer), ours = peers.find("argil");
      if (it == peers.end() || ours == peers.end()) return std::string("-");
      char text[32];
      std::snprintf(text, sizeof text, "%.3g", ours->second / it->second);
      return std::string(text);
    };
    std::printf("%-12s 1e-%-3d  %10s  %10s\n", key.first.c_str(), key.second, ratio("occt").c_str(),
                ratio("sisl").c_str());
  }
  return 0;
}
