// IdSlots: an id maps to what was set for it since the last clear, -1 before;
// clear forgets every id however large, and ids set after it start clean.
#include <catch2/catch.hpp>

#include <cstddef>

#include "argil/core/base/detail/id_slots.hpp"

namespace {

using argil::IdSlots;

TEST_CASE("id slots hold what was set since the last clear", "[id_slots]") {
  IdSlots slots;
  CHECK(slots.find(0) == -1);
  CHECK(slots.find(1000000) == -1);  // beyond the storage: absent, nothing grown
  slots.set(3, 7);
  slots.set(100000, 0);  // far past the storage: it grows
  slots.set(3, 9);       // set again: the last value counts
  CHECK(slots.find(3) == 9);
  CHECK(slots.find(100000) == 0);
  CHECK(slots.find(2) == -1);
  CHECK(slots.find(4) == -1);
  CHECK(slots.find(99999) == -1);

  slots.clear();
  CHECK(slots.find(3) == -1);
  CHECK(slots.find(100000) == -1);
  slots.set(4, 1);
  CHECK(slots.find(4) == 1);
  CHECK(slots.find(3) == -1);  // still forgotten: its old stamp is not the new one
}

TEST_CASE("id slots forget every id over many clears", "[id_slots]") {
  IdSlots slots;
  for (int query = 0; query < 1000; ++query) {
    const auto id = static_cast<std::size_t>(query % 37);
    CHECK(slots.find(id) == -1);
    CHECK(slots.find(id + 1) == -1);
    slots.set(id, query);
    slots.set(id + 1, -query);
    CHECK(slots.find(id) == query);
    CHECK(slots.find(id + 1) == -query);
    slots.clear();
  }
}

}  // namespace
