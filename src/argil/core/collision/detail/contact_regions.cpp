#include "argil/core/collision/detail/contact_regions.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <span>
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
  // Sorted by index, then moved once: the items are large.
  std::vector<std::size_t> order_of_items(items.size());
  std::iota(order_of_items.begin(), order_of_items.end(), std::size_t{0});
  std::stable_sort(order_of_items.begin(), order_of_items.end(), [&](std::size_t x, std::size_t y) {
    const Contact& a = contact_of(items[x]);
    const Contact& b = contact_of(items[y]);
    if (a.region != b.region) return a.region < b.region;
    if (a.depth != b.depth) return a.depth > b.depth;
    return std::tie(a.uv_a[0], a.uv_a[1]) < std::tie(b.uv_a[0], b.uv_a[1]);
  });
  std::vector<Item> sorted;
  sorted.reserve(items.size());
  for (const std::size_t i : order_of_items) sorted.push_back(std::move(items[i]));
  items = std::move(sorted);
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

/// A grid over the leaves' rectangles, cells about the median leaf's size
/// (at most four cells per leaf), each listing the leaves it meets.
class LeafGrid {
 public:
  explicit LeafGrid(const std::vector<LeafContact>& leaves) {
    std::vector<double> widths, heights;
    widths.reserve(leaves.size());
    heights.reserve(leaves.size());
    for (const LeafContact& l : leaves) {
      u_lo_ = std::min(u_lo_, l.rect.u0);
      u_hi_ = std::max(u_hi_, l.rect.u1);
      v_lo_ = std::min(v_lo_, l.rect.v0);
      v_hi_ = std::max(v_hi_, l.rect.v1);
      widths.push_back(l.rect.u1 - l.rect.u0);
      heights.push_back(l.rect.v1 - l.rect.v0);
    }
    const double cap = 4.0 * static_cast<double>(leaves.size());
    double nu = cells_across(u_hi_ - u_lo_, median(widths), cap);
    double nv = cells_across(v_hi_ - v_lo_, median(heights), cap);
    if (nu * nv > cap) {
      const double shrink = std::sqrt(nu * nv / cap);
      nu = std::max(1.0, std::floor(nu / shrink));
      nv = std::max(1.0, std::floor(nv / shrink));
    }
    nu_ = static_cast<int>(nu);
    nv_ = static_cast<int>(nv);
    // Counting sort of (cell, leaf): one pass to count, one to place.
    start_.assign(static_cast<std::size_t>(nu_ * nv_ + 1), 0);
    for_each_cell(leaves, [&](int cell, int) { ++start_[static_cast<std::size_t>(cell + 1)]; });
    std::partial_sum(start_.begin(), start_.end(), start_.begin());
    leaf_of_.resize(static_cast<std::size_t>(start_.back()));
    std::vector<int> next(start_.begin(), start_.end() - 1);
    for_each_cell(leaves, [&](int cell, int leaf) {
      leaf_of_[static_cast<std::size_t>(next[static_cast<std::size_t>(cell)]++)] = leaf;
    });
  }

  int cell_count() const { return nu_ * nv_; }
  std::span<const int> leaves_in(int cell) const {
    const auto c = static_cast<std::size_t>(cell);
    return {leaf_of_.data() + start_[c], leaf_of_.data() + start_[c + 1]};
  }
  /// The column and row of the cell holding (u, v), each monotone in its
  /// coordinate: a rectangle holding the point is listed in that cell.
  std::pair<int, int> column_and_row(double u, double v) const { return {column(u), row(v)}; }
  std::pair<int, int> column_and_row_of(int cell) const { return {cell / nv_, cell % nv_}; }

 private:
  static double median(std::vector<double>& x) {
    const auto mid = x.begin() + static_cast<long>(x.size() / 2);
    std::nth_element(x.begin(), mid, x.end());
    return *mid;
  }
  static double cells_across(double extent, double size, double cap) {
    if (!(size > 0.0) || !(extent > size)) return 1.0;
    return std::min(cap, std::ceil(extent / size));
  }
  static int index(double x, double lo, double hi, int cells) {
    if (cells == 1) return 0;
    const double at = std::floor((x - lo) / (hi - lo) * cells);
    return static_cast<int>(std::clamp(at, 0.0, static_cast<double>(cells - 1)));
  }
  int column(double u) const { return index(u, u_lo_, u_hi_, nu_); }
  int row(double v) const { return index(v, v_lo_, v_hi_, nv_); }

  template <class Visit>
  void for_each_cell(const std::vector<LeafContact>& leaves, Visit visit) const {
    for (std::size_t i = 0; i < leaves.size(); ++i) {
      const ParamRect& r = leaves[i].rect;
      for (int cu = column(r.u0); cu <= column(r.u1); ++cu)
        for (int cv = row(r.v0); cv <= row(r.v1); ++cv) visit(cu * nv_ + cv, static_cast<int>(i));
    }
  }

  double u_lo_ = std::numeric_limits<double>::infinity();
  double u_hi_ = -std::numeric_limits<double>::infinity();
  double v_lo_ = std::numeric_limits<double>::infinity();
  double v_hi_ = -std::numeric_limits<double>::infinity();
  int nu_ = 1, nv_ = 1;
  std::vector<int> start_;  // cell c lists leaf_of_[start_[c], start_[c + 1])
  std::vector<int> leaf_of_;
};

/// Joins (union-find) every two leaves whose closed rectangles touch, cell by
/// cell of the grid. Two that touch share the point (max u0, max v0), so both
/// are listed in its cell, whose column and row are the larger of theirs (the
/// cell index is monotone): each pair is joined in that cell only.
void join_in_grid(const std::vector<LeafContact>& leaves, std::vector<int>& parent) {
  const LeafGrid grid(leaves);
  std::vector<std::pair<int, int>> low_cell(leaves.size());  // the cell of (u0, v0)
  for (std::size_t i = 0; i < leaves.size(); ++i)
    low_cell[i] = grid.column_and_row(leaves[i].rect.u0, leaves[i].rect.v0);
  for (int cell = 0; cell < grid.cell_count(); ++cell) {
    const std::span<const int> here = grid.leaves_in(cell);
    const std::pair<int, int> at = grid.column_and_row_of(cell);
    for (std::size_t x = 0; x < here.size(); ++x) {
      const auto i = static_cast<std::size_t>(here[x]);
      const ParamRect& a = leaves[i].rect;
      for (std::size_t y = x + 1; y < here.size(); ++y) {
        const auto j = static_cast<std::size_t>(here[y]);
        if (!a.touches(leaves[j].rect)) continue;
        if (std::max(low_cell[i].first, low_cell[j].first) != at.first ||
            std::max(low_cell[i].second, low_cell[j].second) != at.second)
          continue;
        parent[static_cast<std::size_t>(find(parent, here[x]))] = find(parent, here[y]);
      }
    }
  }
}

/// How many rectangle tests per leaf the sweep in u may take before the grid
/// is cheaper: the sweep costs little per test, the grid a pass to list the
/// leaves by cell. The sweep is the cheaper one for the few hundred leaves of
/// a haptic tick's contact; a face lying on another within eps over its whole
/// area (hundreds of thousands of leaves, every one overlapping thousands in u)
/// needs the grid.
constexpr double kSweepTestsPerLeaf = 512.0;

/// Joins (union-find) every two leaves whose closed rectangles touch: a sweep
/// in u (only rectangles whose u ranges overlap can touch), handing over to the
/// grid once it has tested kSweepTestsPerLeaf pairs per leaf. Which pairs are
/// joined first does not change the components, and region numbers depend
/// only on them, so the sweep's joins before the hand-over stand.
void join_touching(const std::vector<LeafContact>& leaves, std::vector<int>& parent) {
  const std::size_t n = leaves.size();
  if (n < 2) return;
  std::vector<int> by_u0(n);
  std::iota(by_u0.begin(), by_u0.end(), 0);
  std::stable_sort(by_u0.begin(), by_u0.end(), [&](int a, int b) {
    return leaves[static_cast<std::size_t>(a)].rect.u0 <
           leaves[static_cast<std::size_t>(b)].rect.u0;
  });
  std::vector<double> u0(n);
  for (std::size_t x = 0; x < n; ++x) u0[x] = leaves[static_cast<std::size_t>(by_u0[x])].rect.u0;
  const double budget = kSweepTestsPerLeaf * static_cast<double>(n);
  double tests = 0.0;
  for (std::size_t x = 0; x < n; ++x) {
    const LeafContact& li = leaves[static_cast<std::size_t>(by_u0[x])];
    for (std::size_t y = x + 1; y < n && u0[y] <= li.rect.u1; ++y) {
      if (++tests > budget) {
        join_in_grid(leaves, parent);
        return;
      }
      if (li.rect.touches(leaves[static_cast<std::size_t>(by_u0[y])].rect))
        parent[static_cast<std::size_t>(find(parent, by_u0[x]))] = find(parent, by_u0[y]);
    }
  }
}

}  // namespace

ContactRegions group_regions(std::vector<LeafContact>& leaves, int max_contacts) {
  const int n = static_cast<int>(leaves.size());
  std::vector<int> parent(static_cast<std::size_t>(n));
  std::iota(parent.begin(), parent.end(), 0);
  join_touching(leaves, parent);
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
