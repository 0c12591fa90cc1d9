// Contact regions against all-pairs union-find: leaves whose closed parameter
// rectangles touch (an edge or a corner counts) share a region, and no others,
// on the sweep's sizes (a tool's few hundred leaves) and on the grid's (a face
// lying on another over thousands of leaves that all overlap in u).
#include <catch2/catch.hpp>
#include <limits>
#include <map>
#include <numeric>
#include <random>
#include <utility>
#include <vector>

#include "argil/core/collision/detail/contact_regions.hpp"

namespace argil {
namespace {

int root(std::vector<int>& parent, int i) {
  while (parent[static_cast<std::size_t>(i)] != i) i = parent[static_cast<std::size_t>(i)];
  return i;
}

/// The components of the touching relation, by testing every pair.
std::vector<int> components(const std::vector<ParamRect>& rects) {
  std::vector<int> parent(rects.size());
  std::iota(parent.begin(), parent.end(), 0);
  for (std::size_t i = 0; i < rects.size(); ++i)
    for (std::size_t j = i + 1; j < rects.size(); ++j)
      if (rects[i].touches(rects[j]))
        parent[static_cast<std::size_t>(root(parent, static_cast<int>(i)))] =
            root(parent, static_cast<int>(j));
  std::vector<int> out(rects.size());
  for (std::size_t i = 0; i < rects.size(); ++i) out[i] = root(parent, static_cast<int>(i));
  return out;
}

/// Leaves of random quadtrees over a column of elements [0, 1] x [k, k + 1],
/// each kept with probability `keep` (so regions split apart).
std::vector<ParamRect> random_leaves(std::mt19937& rng, int elements, int max_level, double keep) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<ParamRect> out;
  std::vector<std::pair<ParamRect, int>> open;
  for (int k = 0; k < elements; ++k) open.push_back({ParamRect{0.0, 1.0, double(k), k + 1.0}, 0});
  while (!open.empty()) {
    const auto [r, level] = open.back();
    open.pop_back();
    if (level < max_level && unit(rng) < 0.7) {
      for (const ParamRect& q : r.split()) open.push_back({q, level + 1});
    } else if (unit(rng) < keep) {
      out.push_back(r);
    }
  }
  return out;
}

/// group_regions on one contact per rectangle (uv_a its centre, a random
/// depth) gives the all-pairs components.
void check_regions_match(const std::vector<ParamRect>& rects, std::mt19937& rng) {
  std::uniform_real_distribution<double> depth(-1.0, 1.0);
  std::vector<LeafContact> leaves(rects.size());
  std::map<std::pair<double, double>, std::size_t> index_of;
  for (std::size_t i = 0; i < rects.size(); ++i) {
    leaves[i].rect = rects[i];
    leaves[i].contact.uv_a = rects[i].centre();
    leaves[i].contact.depth = depth(rng);
    index_of[{rects[i].centre()[0], rects[i].centre()[1]}] = i;
  }
  const std::vector<int> expected = components(rects);
  const ContactRegions got = group_regions(leaves, std::numeric_limits<int>::max());
  REQUIRE(got.contacts.size() == rects.size());
  // The same partition: one region per component, both ways.
  std::map<int, int> region_of_component, component_of_region;
  for (const Contact& c : got.contacts) {
    const std::size_t i = index_of.at({c.uv_a[0], c.uv_a[1]});
    const auto [r, new_component] = region_of_component.emplace(expected[i], c.region);
    const auto [k, new_region] = component_of_region.emplace(c.region, expected[i]);
    CHECK(r->second == c.region);
    CHECK(k->second == expected[i]);
  }
  CHECK(got.region_count == static_cast<int>(region_of_component.size()));
}

}  // namespace

TEST_CASE("contact regions are the components of touching leaf rectangles, small and large") {
  std::mt19937 rng(20261127);
  SECTION("a few hundred leaves (the sweep)") {
    for (int trial = 0; trial < 20; ++trial) {
      const std::vector<ParamRect> rects = random_leaves(rng, 2, 5, 0.6);
      INFO("trial " << trial << ", " << rects.size() << " leaves");
      check_regions_match(rects, rng);
    }
  }
  SECTION("thousands of leaves overlapping in u (the grid)") {
    for (int trial = 0; trial < 3; ++trial) {
      const std::vector<ParamRect> rects = random_leaves(rng, 64, 4, 0.6);
      INFO("trial " << trial << ", " << rects.size() << " leaves");
      check_regions_match(rects, rng);
    }
  }
  SECTION("strips across the whole u range, touching at shared edges only") {
    // Abutting strips join; a gap of any width splits.
    std::uniform_int_distribution<int> gap(0, 3);
    std::vector<ParamRect> rects;
    double v = 0.0;
    for (int k = 0; k < 3000; ++k) {
      const double next = v + 1.0;
      rects.push_back({0.0, 1.0, v, next});
      v = next + (gap(rng) == 0 ? 1e-12 * next : 0.0);
    }
    check_regions_match(rects, rng);
  }
}

}  // namespace argil
