#pragma once
// IdSlots: a map from dense ids (hierarchy nodes, element blocks) to small
// values, cleared in O(1). Every slot carries the generation that wrote it, so
// clear() only moves the generation on. A query that keeps one across calls
// neither fills an array as long as the largest id it sees nor touches fresh
// pages for it again: an id-indexed vector filled with -1 in every query
// cost a 64 x 64 panel's B-spline tool a memset of its node count per side
// and query, and its first stroke up to 70 page faults in one tick.

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace argil {

class IdSlots {
 public:
  /// The value stored for `id` since the last clear(), or -1.
  int find(std::size_t id) const {
    return id < slots_.size() && slots_[id].generation == generation_ ? slots_[id].value : -1;
  }

  void set(std::size_t id, int value) {
    if (id >= slots_.size()) slots_.resize(std::max(id + 1, 2 * slots_.size()));
    slots_[id] = {generation_, value};
  }

  /// Forgets every id; keeps the storage.
  void clear() {
    if (++generation_ == 0) {  // wrapped: a slot written 2^32 clears ago would match
      std::fill(slots_.begin(), slots_.end(), Slot{});
      generation_ = 1;
    }
  }

 private:
  struct Slot {
    std::uint32_t generation = 0;  // 0: never written
    int value = -1;
  };
  std::vector<Slot> slots_;
  std::uint32_t generation_ = 1;
};

}  // namespace argil
