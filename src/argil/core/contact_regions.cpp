#include "argil/core/contact_regions.hpp"

#include <algorithm>
#include <limits>
#include <numeric>
#include <tuple>

namespace argil {

namespace {

bool rectangles_touch(const LeafContact& a, const LeafContact& b) {
  return a.u0 <= b.u1 && b.u0 <= a.u1 && a.v0 <= b.v1 && b.v0 <= a.v1;
}

int find(std::vector<int>& parent, int i) {
  while (parent[static_cast<std::size_t>(i)] != i) {
    parent[static_cast<std::size_t>(i)] =
        parent[static_cast<std::size_t>(parent[static_cast<std::size_t>(i)])];
    i = parent[static_cast<std::size_t>(i)];
  }
  return i;
}

}  // namespace

void group_regions(std::vector<LeafContact>& leaves, int max_contacts, CollisionResult& out) {
  const int n = static_cast<int>(leaves.size());
  std::vector<int> parent(static_cast<std::size_t>(n));
  std::iota(parent.begin(), parent.end(), 0);
  // Sweep in u: only rectangles whose u ranges overlap can touch. Which pairs
  // are joined first does not change the components, and region numbers below
  // depend only on the components, so this matches the all-pairs loop.
  std::vector<int> by_u0(static_cast<std::size_t>(n));
  std::iota(by_u0.begin(), by_u0.end(), 0);
  std::stable_sort(by_u0.begin(), by_u0.end(), [&](int a, int b) {
    return leaves[static_cast<std::size_t>(a)].u0 < leaves[static_cast<std::size_t>(b)].u0;
  });
  for (std::size_t x = 0; x < by_u0.size(); ++x) {
    const LeafContact& li = leaves[static_cast<std::size_t>(by_u0[x])];
    for (std::size_t y = x + 1; y < by_u0.size(); ++y) {
      const LeafContact& lj = leaves[static_cast<std::size_t>(by_u0[y])];
      if (lj.u0 > li.u1) break;
      if (rectangles_touch(li, lj))
        parent[static_cast<std::size_t>(find(parent, by_u0[x]))] = find(parent, by_u0[y]);
    }
  }
  std::vector<int> region_of_root(static_cast<std::size_t>(n), -1);
  int regions = 0;
  for (int i = 0; i < n; ++i) {
    const int root = find(parent, i);
    if (region_of_root[static_cast<std::size_t>(root)] < 0)
      region_of_root[static_cast<std::size_t>(root)] = regions++;
    leaves[static_cast<std::size_t>(i)].contact.region =
        region_of_root[static_cast<std::size_t>(root)];
  }
  std::vector<double> deepest(static_cast<std::size_t>(regions),
                              -std::numeric_limits<double>::infinity());
  for (const LeafContact& l : leaves)
    deepest[static_cast<std::size_t>(l.contact.region)] =
        std::max(deepest[static_cast<std::size_t>(l.contact.region)], l.contact.depth);
  // Regions by deepest point, then contacts by depth; ties by parameters so the
  // order is deterministic.
  std::vector<int> order(static_cast<std::size_t>(regions));
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) {
    return deepest[static_cast<std::size_t>(a)] > deepest[static_cast<std::size_t>(b)];
  });
  std::vector<int> rank(static_cast<std::size_t>(regions));
  for (int r = 0; r < regions; ++r)
    rank[static_cast<std::size_t>(order[static_cast<std::size_t>(r)])] = r;
  for (LeafContact& l : leaves) l.contact.region = rank[static_cast<std::size_t>(l.contact.region)];
  std::stable_sort(leaves.begin(), leaves.end(), [](const LeafContact& a, const LeafContact& b) {
    if (a.contact.region != b.contact.region) return a.contact.region < b.contact.region;
    if (a.contact.depth != b.contact.depth) return a.contact.depth > b.contact.depth;
    return std::tie(a.contact.uv_a[0], a.contact.uv_a[1]) <
           std::tie(b.contact.uv_a[0], b.contact.uv_a[1]);
  });
  out.region_count = regions;
  // Keep every region's deepest contact, then fill up to max_contacts in
  // order; the kept contacts stay grouped by region.
  std::vector<bool> keep(leaves.size(), false);
  int kept = 0;
  for (std::size_t i = 0; i < leaves.size() && kept < max_contacts; ++i) {
    if (i == 0 || leaves[i].contact.region != leaves[i - 1].contact.region) {
      keep[i] = true;
      ++kept;
    }
  }
  for (std::size_t i = 0; i < leaves.size() && kept < max_contacts; ++i) {
    if (!keep[i]) {
      keep[i] = true;
      ++kept;
    }
  }
  for (std::size_t i = 0; i < leaves.size(); ++i)
    if (keep[i]) out.contacts.push_back(leaves[i].contact);
}

}  // namespace argil
