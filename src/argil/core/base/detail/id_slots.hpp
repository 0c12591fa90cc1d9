#pragma once
// IdSlots: a map from ids (hierarchy nodes, element blocks) to small values,
// cleared in O(1). Every slot carries the generation that wrote it, so clear()
// only moves the generation on.
//
// The ids are hashed into an open-addressing table sized by how many ids one
// query sets, not by the largest id: a table indexed by id grew with the
// hierarchy, and each doubling (a 64 x 64 panel's nodes pass 16,384 during
// the B-spline tool's stroke) wrote 128 KB of fresh pages inside one haptic
// tick: 32 page faults, 430 us on the build machine.

#include <cstddef>
#include <cstdint>
#include <vector>

namespace argil {

class IdSlots {
 public:
  /// The value stored for `id` since the last clear(), or -1.
  int find(std::size_t id) const {
    if (slots_.empty()) return -1;
    for (std::size_t i = home(id);; i = (i + 1) & mask_) {
      const Slot& s = slots_[i];
      if (s.generation != generation_) return -1;  // an empty slot ends the probe
      if (s.id == id) return s.value;
    }
  }

  void set(std::size_t id, int value) {
    if (2 * (count_ + 1) > slots_.size()) grow();
    if (place(id, value)) ++count_;
  }

  /// Forgets every id; keeps the storage.
  void clear() {
    count_ = 0;
    if (++generation_ == 0) {  // wrapped: a slot written 2^32 clears ago would match
      for (Slot& s : slots_) s = Slot{};
      generation_ = 1;
    }
  }

  /// Forgets every id and frees the storage (after a query of millions).
  void release() {
    slots_ = {};
    mask_ = 0;
    count_ = 0;
  }

 private:
  struct Slot {
    std::size_t id = 0;
    std::uint32_t generation = 0;  // 0: never written
    int value = -1;
  };

  static constexpr std::size_t kFirstCapacity = 256;

  /// Fibonacci hashing: consecutive ids (a node's children) spread out.
  std::size_t home(std::size_t id) const {
    return static_cast<std::size_t>((static_cast<std::uint64_t>(id) * 0x9E3779B97F4A7C15ull) >>
                                    32) &
           mask_;
  }

  /// True when `id` was new.
  bool place(std::size_t id, int value) {
    for (std::size_t i = home(id);; i = (i + 1) & mask_) {
      Slot& s = slots_[i];
      if (s.generation != generation_) {
        s = {id, generation_, value};
        return true;
      }
      if (s.id == id) {
        s.value = value;
        return false;
      }
    }
  }

  /// Doubles the table (at most half full, so probes stay short), keeping
  /// the ids of this generation.
  void grow() {
    std::vector<Slot> old = std::move(slots_);
    slots_.assign(old.empty() ? kFirstCapacity : 2 * old.size(), Slot{});
    mask_ = slots_.size() - 1;
    for (const Slot& s : old)
      if (s.generation == generation_) place(s.id, s.value);
  }

  std::vector<Slot> slots_;
  std::size_t mask_ = 0;
  std::size_t count_ = 0;  // ids set since the last clear
  std::uint32_t generation_ = 1;
};

}  // namespace argil
