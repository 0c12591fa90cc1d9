#pragma once
// IdSlots: a map from dense ids (hierarchy nodes, element blocks) to small
// values, cleared in O(1). Every slot carries the generation that wrote it, so
// clear() only moves the generation on.
//
// Slots live in pages of 512 (4 KB), made when an id in their range is first
// set: a query reads neighbouring ids from one page, as from an array indexed
// by id, but the table never grows in one piece. An array indexed by id
// doubled as a 64 x 64 panel's node pool passed 16,384 during the B-spline
// tool's stroke and wrote 128 KB of fresh pages in one haptic tick: 32 page
// faults, 430 us on the build machine. (A hash table sized by the ids a
// query sets avoided that too, but scattered neighbouring ids over the table:
// a large offline query ran up to 1.45 times slower.)

#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

namespace argil {

class IdSlots {
 public:
  /// The value stored for `id` since the last clear(), or -1.
  int find(std::size_t id) const {
    const std::size_t page = id >> kPageBits;
    if (page >= pages_.size() || !pages_[page]) return -1;
    const Slot& s = (*pages_[page])[id & kPageMask];
    return s.generation == generation_ ? s.value : -1;
  }

  void set(std::size_t id, int value) {
    const std::size_t page = id >> kPageBits;
    if (page >= pages_.size()) pages_.resize(page + 1);
    if (!pages_[page]) pages_[page] = std::make_unique<Page>();
    (*pages_[page])[id & kPageMask] = {generation_, value};
  }

  /// Forgets every id; keeps the storage.
  void clear() {
    if (++generation_ == 0) {  // wrapped: a slot written 2^32 clears ago would match
      for (const std::unique_ptr<Page>& p : pages_)
        if (p) p->fill(Slot{});
      generation_ = 1;
    }
  }

  /// Forgets every id and frees the storage (after a query of millions).
  void release() { std::vector<std::unique_ptr<Page>>().swap(pages_); }

 private:
  struct Slot {
    std::uint32_t generation = 0;  // 0: never written
    int value = -1;
  };

  static constexpr std::size_t kPageBits = 9;
  static constexpr std::size_t kPageMask = (std::size_t{1} << kPageBits) - 1;
  using Page = std::array<Slot, std::size_t{1} << kPageBits>;

  std::vector<std::unique_ptr<Page>> pages_;
  std::uint32_t generation_ = 1;
};

}  // namespace argil
