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

namespace {

/// A leaf on [u0, u0 + 1] x [v0, v0 + 1] whose contact lies at `point`,
/// `depth` deep, at (u, v) (rounded on the leaf's own path: `wobble` in the
/// last bits).
LeafContact leaf_contact(double u0, double v0, const Eigen::Vector3d& point, double depth,
                         double wobble = 0.0) {
  LeafContact l;
  l.rect = ParamRect{u0, u0 + 1.0, v0, v0 + 1.0};
  l.contact.point = point;
  l.contact.depth = depth;
  l.contact.uv_a = Eigen::Vector2d(point.x(), point.y()) * (1.0 + wobble);
  l.contact.uv_b = l.contact.uv_a;
  return l;
}

}  // namespace

TEST_CASE("a contact found by the leaves around a shared corner is kept once") {
  // Four leaves meet at (1, 1): each finds the deepest contact there, the
  // parameters rounded differently; two more leaves find shallower ones.
  std::vector<LeafContact> leaves;
  const Eigen::Vector3d corner(1.0, 1.0, 0.0);
  for (int k = 0; k < 4; ++k) leaves.push_back(leaf_contact(k % 2, k / 2, corner, 0.5, k * 1e-16));
  leaves.push_back(leaf_contact(2.0, 0.0, Eigen::Vector3d(2.5, 0.5, 0.0), 0.25));
  leaves.push_back(leaf_contact(2.0, 1.0, Eigen::Vector3d(2.5, 1.5, 0.0), 0.125));
  for (const int max_contacts : {1, 2, 3, 10}) {
    CAPTURE(max_contacts);
    std::vector<LeafContact> copy = leaves;
    const ContactRegions got = group_regions(copy, max_contacts);
    REQUIRE(got.region_count == 1);
    const std::vector<double> depths = {0.5, 0.25, 0.125};
    REQUIRE(got.contacts.size() == std::min<std::size_t>(3, std::size_t(max_contacts)));
    for (std::size_t i = 0; i < got.contacts.size(); ++i) CHECK(got.contacts[i].depth == depths[i]);
    // The same through rank_regions, on contacts that already carry regions.
    std::vector<Contact> contacts;
    for (const LeafContact& l : leaves) contacts.push_back(l.contact);
    for (Contact& c : contacts) c.region = 0;
    rank_regions(contacts, 1, max_contacts);
    REQUIRE(contacts.size() == got.contacts.size());
    for (std::size_t i = 0; i < contacts.size(); ++i) CHECK(contacts[i].depth == depths[i]);
  }
}

TEST_CASE("copies of a contact rounded apart are kept once, with another between them") {
  // The corner contact found twice, its depth and point rounded apart in the
  // last bits, and a distinct contact whose depth lies between the copies'.
  const Eigen::Vector3d corner(1.0, 1.0, 0.0);
  std::vector<LeafContact> leaves = {
      leaf_contact(0.0, 0.0, corner, 0.5),
      leaf_contact(1.0, 1.0, corner + Eigen::Vector3d(1e-15, 0.0, -1e-15), 0.5 - 2e-16, 1e-16),
      leaf_contact(1.0, 0.0, Eigen::Vector3d(1.5, 0.5, 0.0), 0.5 - 1e-16),
      leaf_contact(0.0, 1.0, Eigen::Vector3d(0.5, 1.5, 0.0), 0.25)};
  const ContactRegions got = group_regions(leaves, 10);
  REQUIRE(got.contacts.size() == 3);
  int at_corner = 0;
  for (const Contact& c : got.contacts) at_corner += (c.point - corner).norm() < 1e-12;
  CHECK(at_corner == 1);
}

TEST_CASE("contacts of equal depth are kept by where they lie, not by their parameters") {
  // Nine contacts of one depth on a 3 x 3 grid of leaves; max_contacts keeps
  // four. With u and v swapped (the same surface, its net transposed) the
  // same four points are kept.
  std::vector<LeafContact> leaves, swapped;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      const Eigen::Vector3d p(i + 0.5, j + 0.5, 0.25 * i - 0.125 * j);
      leaves.push_back(leaf_contact(i, j, p, 1.0));
      LeafContact t = leaf_contact(j, i, p, 1.0);
      t.contact.uv_a = Eigen::Vector2d(p.y(), p.x());
      swapped.push_back(t);
    }
  const ContactRegions a = group_regions(leaves, 4);
  const ContactRegions b = group_regions(swapped, 4);
  REQUIRE(a.contacts.size() == 4);
  REQUIRE(b.contacts.size() == 4);
  for (std::size_t k = 0; k < 4; ++k) CHECK(a.contacts[k].point == b.contacts[k].point);
}

}  // namespace argil
