#include "argil/core/collision/detail/contact_regions.hpp"

#include <algorithm>
#include <limits>
#include <numeric>
#include <tuple>
#include <utility>

namespace argil {

namespace {

int find(std::vector<int>& parent, int i) {
  while (parent[static_cast<std::size_t>(i)] != i) {
    parent[static_cast<std::size_t>(i)] =
        parent[static_cast<std::size_t>(parent[static_cast<std::size_t>(i)])];
    i = parent[static_cast<std::size_t>(i)];
  }
  return i;
}

/// Renumbers regions by their deepest contact (deepest first; ties keep the
/// lower id) and sorts by region, then depth (deepest first), then uv_a, so
/// the order is deterministic. `contact_of` gives an item's contact.
template <class Item, class ContactOf>
void rank_and_sort(std::vector<Item>& items, int regions, ContactOf contact_of) {
  std::vector<double> deepest(static_cast<std::size_t>(regions),
                              -std::numeric_limits<double>::infinity());
  for (Item& item : items) {
    const Contact& c = contact_of(item);
    deepest[static_cast<std::size_t>(c.region)] =
        std::max(deepest[static_cast<std::size_t>(c.region)], c.depth);
  }
  std::vector<int> order(static_cast<std::size_t>(regions));
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) {
    return deepest[static_cast<std::size_t>(a)] > deepest[static_cast<std::size_t>(b)];
  });
  std::vector<int> rank(static_cast<std::size_t>(regions));
  for (int r = 0; r < regions; ++r)
    rank[static_cast<std::size_t>(order[static_cast<std::size_t>(r)])] = r;
  for (Item& item : items) {
    Contact& c = contact_of(item);
    c.region = rank[static_cast<std::size_t>(c.region)];
  }
  std::stable_sort(items.begin(), items.end(), [&](const Item& x, const Item& y) {
    const Contact& a = contact_of(x);
    const Contact& b = contact_of(y);
    if (a.region != b.region) return a.region < b.region;
    if (a.depth != b.depth) return a.depth > b.depth;
    return std::tie(a.uv_a[0], a.uv_a[1]) < std::tie(b.uv_a[0], b.uv_a[1]);
  });
}

/// Keeps every region's deepest (first) contact, then fills up to
/// max_contacts in order; the kept contacts stay grouped by region.
void trim(std::vector<Contact>& contacts, int max_contacts) {
  std::vector<bool> keep(contacts.size(), false);
  int kept = 0;
  for (std::size_t i = 0; i < contacts.size() && kept < max_contacts; ++i) {
    if (i == 0 || contacts[i].region != contacts[i - 1].region) {
      keep[i] = true;
      ++kept;
    }
  }
  for (std::size_t i = 0; i < contacts.size() && kept < max_contacts; ++i) {
    if (!keep[i]) {
      keep[i] = true;
      ++kept;
    }
  }
  std::size_t next = 0;
  for (std::size_t i = 0; i < contacts.size(); ++i)
    if (keep[i]) contacts[next++] = contacts[i];
  contacts.resize(next);
}

}  // namespace

ContactRegions group_regions(std::vector<LeafContact>& leaves, int max_contacts) {
  const int n = static_cast<int>(leaves.size());
  std::vector<int> parent(static_cast<std::size_t>(n));
  std::iota(parent.begin(), parent.end(), 0);
  // Sweep in u: only rectangles whose u ranges overlap can touch. Which pairs
  // are joined first does not change the components, and region numbers below
  // depend only on the components, so this matches the all-pairs loop.
  std::vector<int> by_u0(static_cast<std::size_t>(n));
  std::iota(by_u0.begin(), by_u0.end(), 0);
  std::stable_sort(by_u0.begin(), by_u0.end(), [&](int a, int b) {
    return leaves[static_cast<std::size_t>(a)].rect.u0 <
           leaves[static_cast<std::size_t>(b)].rect.u0;
  });
  for (std::size_t x = 0; x < by_u0.size(); ++x) {
    const LeafContact& li = leaves[static_cast<std::size_t>(by_u0[x])];
    for (std::size_t y = x + 1; y < by_u0.size(); ++y) {
      const LeafContact& lj = leaves[static_cast<std::size_t>(by_u0[y])];
      if (lj.rect.u0 > li.rect.u1) break;
      if (li.rect.touches(lj.rect))
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
  rank_and_sort(
      leaves, regions, [](auto& l) -> auto& { return l.contact; });
  std::vector<Contact> contacts;
  contacts.reserve(leaves.size());
  for (const LeafContact& l : leaves) contacts.push_back(l.contact);
  trim(contacts, max_contacts);
  return {std::move(contacts), regions};
}

void rank_regions(std::vector<Contact>& contacts, int region_count, int max_contacts) {
  rank_and_sort(
      contacts, region_count, [](auto& c) -> auto& { return c; });
  trim(contacts, max_contacts);
}

}  // namespace argil
