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

/// Depths and points closer than this [mm] are the same contact found twice:
/// far above their rounding (1e-13 of a metre-sized model), far below any eps.
constexpr double kEqualDepth = 1e-9;

/// Orders contacts of equal depth by where they lie in the world, then by
/// their parameters: the same on a surface whose u and v are swapped.
bool same_depth_order(const Contact& a, const Contact& b) {
  return std::tie(a.point[0], a.point[1], a.point[2], a.uv_a[0], a.uv_a[1], a.uv_b[0], a.uv_b[1]) <
         std::tie(b.point[0], b.point[1], b.point[2], b.uv_a[0], b.uv_a[1], b.uv_b[0], b.uv_b[1]);
}

/// The same contact: leaves that share an edge or corner find the closest
/// pair on it from each side, at the same point and depth up to rounding
/// (each side refines it on its own path).
bool same_contact(const Contact& a, const Contact& b) {
  return a.region == b.region && std::abs(a.depth - b.depth) <= kEqualDepth &&
         (a.point - b.point).norm() <= kEqualDepth;
}

/// Renumbers regions by their deepest contact (deepest first; ties keep the
/// lower id) and sorts by region, then depth (deepest first), then
/// same_depth_order, so the order is deterministic. `contact_of` gives an item's contact.
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
  // Sorted by index, then permuted in place by swaps: the items are large,
  // and a copy of thousands of them is fresh memory in every haptic tick.
  std::vector<std::size_t> order_of_items(items.size());
  std::iota(order_of_items.begin(), order_of_items.end(), std::size_t{0});
  std::stable_sort(order_of_items.begin(), order_of_items.end(), [&](std::size_t x, std::size_t y) {
    const Contact& a = contact_of(items[x]);
    const Contact& b = contact_of(items[y]);
    if (a.region != b.region) return a.region < b.region;
    if (a.depth != b.depth) return a.depth > b.depth;
    return same_depth_order(a, b);
  });
  // Position i takes items[order_of_items[i]]: each cycle of the
  // permutation is followed once, marked done by pointing at itself.
  for (std::size_t start = 0; start < items.size(); ++start) {
    std::size_t at = start;
    while (order_of_items[at] != start) {
      const std::size_t from = order_of_items[at];
      std::swap(items[at], items[from]);
      order_of_items[at] = at;
      at = from;
    }
    order_of_items[at] = at;
  }
}

/// Which of `contacts` (sorted by region) to keep: every region's deepest
/// (first) contact, then the rest in order up to max_contacts, each contact
/// once. The kept positions come out in order, so they stay grouped by region.
template <class Item, class ContactOf>
std::vector<std::size_t> kept_positions(const std::vector<Item>& items, int max_contacts,
                                        ContactOf contact_of) {
  const std::size_t n = items.size();
  const auto limit = static_cast<std::size_t>(std::max(max_contacts, 0));
  std::vector<bool> keep(n, false);
  std::size_t kept = 0;
  for (std::size_t i = 0; i < n && kept < limit; ++i) {
    if (i == 0 || contact_of(items[i]).region != contact_of(items[i - 1]).region) {
      keep[i] = true;
      ++kept;
    }
  }
  // The rest in order, each contact once: its copies lie among the contacts
  // of its region within kEqualDepth of its depth, just before it. A run of
  // contacts of one region and one depth (to the bit) is in order of x
  // (same_depth_order): in i's own run, from `run_start`, those more than
  // kEqualDepth lower in x are no copies, nor is anything before them in the
  // run. So a curve's crossings (thousands, all at depth 0) are each compared
  // with their few neighbours in x, not with all before.
  const auto found_before = [&](std::size_t i, std::size_t run_start) {
    const Contact& c = contact_of(items[i]);
    for (std::size_t j = i; j-- > 0;) {
      const Contact& before = contact_of(items[j]);
      if (before.region != c.region || before.depth - c.depth > kEqualDepth) return false;
      if (j >= run_start && before.point[0] < c.point[0] - kEqualDepth) {
        j = run_start;  // on to the runs of other depths before it
        continue;
      }
      if (same_contact(before, c)) return true;
    }
    return false;
  };
  std::size_t run_start = 0;
  for (std::size_t i = 1; i < n && kept < limit; ++i) {
    const Contact& a = contact_of(items[i - 1]);
    const Contact& b = contact_of(items[i]);
    if (!(a.region == b.region && a.depth == b.depth)) run_start = i;
    if (!keep[i] && !found_before(i, run_start)) {
      keep[i] = true;
      ++kept;
    }
  }
  std::vector<std::size_t> positions;
  positions.reserve(kept);
  for (std::size_t i = 0; i < n; ++i)
    if (keep[i]) positions.push_back(i);
  return positions;
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

/// Joins (union-find) every two leaves whose closed rectangles touch: leaves
/// on the same rectangle first (a tool lying on a face meets each of the
/// face's leaves with several of its own), then a sweep in u over one leaf
/// per rectangle (only rectangles whose u ranges overlap can touch), handing
/// over to the grid once it has tested kSweepTestsPerLeaf pairs per leaf.
/// Which pairs are joined first does not change the components, and region
/// numbers depend only on them, so the joins before the hand-over stand.
void join_touching(const std::vector<LeafContact>& leaves, std::vector<int>& parent) {
  const std::size_t n = leaves.size();
  if (n < 2) return;
  const auto rect_of = [&](int i) { return leaves[static_cast<std::size_t>(i)].rect; };
  // Rectangles in order of u0 (then the rest, so equal ones are neighbours).
  const auto key = [&](int i) {
    const ParamRect& r = leaves[static_cast<std::size_t>(i)].rect;
    return std::tie(r.u0, r.v0, r.u1, r.v1);
  };
  std::vector<int> by_rect(n);
  std::iota(by_rect.begin(), by_rect.end(), 0);
  std::sort(by_rect.begin(), by_rect.end(), [&](int a, int b) { return key(a) < key(b); });
  // One leaf per distinct rectangle, in order of u0; the others joined to it.
  std::vector<int> distinct;
  for (const int i : by_rect) {
    if (!distinct.empty() && key(i) == key(distinct.back())) {
      parent[static_cast<std::size_t>(find(parent, i))] = find(parent, distinct.back());
      continue;
    }
    distinct.push_back(i);
  }
  const double budget = kSweepTestsPerLeaf * static_cast<double>(distinct.size());
  double tests = 0.0;
  for (std::size_t x = 0; x < distinct.size(); ++x) {
    const ParamRect ri = rect_of(distinct[x]);
    for (std::size_t y = x + 1; y < distinct.size() && rect_of(distinct[y]).u0 <= ri.u1; ++y) {
      if (++tests > budget) {
        join_in_grid(leaves, parent);
        return;
      }
      if (ri.touches(rect_of(distinct[y])))
        parent[static_cast<std::size_t>(find(parent, distinct[x]))] = find(parent, distinct[y]);
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
  const auto contact_of = [](auto& l) -> auto& { return l.contact; };
  rank_and_sort(leaves, regions, contact_of);
  // Only the kept contacts are copied out (a haptic tick keeps 64 of thousands).
  std::vector<Contact> contacts;
  for (const std::size_t i : kept_positions(leaves, max_contacts, contact_of))
    contacts.push_back(leaves[i].contact);
  return {std::move(contacts), regions};
}

void rank_regions(std::vector<Contact>& contacts, int region_count, int max_contacts) {
  const auto contact_of = [](auto& c) -> auto& { return c; };
  rank_and_sort(contacts, region_count, contact_of);
  std::size_t next = 0;
  for (const std::size_t i : kept_positions(contacts, max_contacts, contact_of))
    contacts[next++] = contacts[i];
  contacts.resize(next);
}

}  // namespace argil
